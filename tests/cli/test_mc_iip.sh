#!/usr/bin/env bash
# test_mc_iip.sh LVSIM SRC - the IIP at given times in `lvsim mc` (issue 28, item 5; a phase's
# `iip_at:`, docs/monte-carlo.md "The IIP at given times") on tests/missions/mc/iip_at.yaml:
#  - independent of the IIP code: a body coasting without air or thrust falls along its own
#    drag-free path, so its IIP at any time of its flight is where and when its phase (an
#    integration to `impact`, h = 0) ends: every run's IIP at T+0, T+60 and T+150.5 s within
#    1 m of the phase's own final lat/lon and t + tof within 1 ms of its end time (docs/models.md
#    states the propagation within 0.01 km; measured 1-2 cm, 6 us); the campaign's "IIP at T+60
#    s" ellipse equals the 3-sigma ellipse the test computes itself (numpy-free: the 2 x 2
#    sample covariance's eigenvalues in closed form) from the phase's own final points;
#  - a kept run's IIP at T+10.37 s of a prograde burn (the point moves ~1.5 km/s downrange)
#    against the phase's own result file (0.1 s grid) interpolated linearly at t, within the
#    linear interpolation's bound h^2/8 |f''| (|f''| from the rows' second differences) + 1e-9;
#  - the runs not flying at t (T+5000 s, after every impact) and in orbit (the second phase, at
#    8 km/s) counted as such in the database, outcomes.csv and stats.json, with no ellipse;
#  - the finals of every phase the same with and without `iip_at:` (the stops are the
#    integrator's own interpolation: same steps), within 1e-9 relative;
#  - a jettisoned part (tests/missions/mc/fairing.yaml): kourou-leo's fairing flown to the
#    ground as a phase of its own stage; its impact footprint beside the stages', named by its
#    part; every run on the ground with the dry mass it drew, short of the drag-free IIP at the
#    jettison; the ascent's IIP at T+60 and T+120 s;
#  - bad `iip_at:` refused by `lvsim check` and `lvsim run` alike, file:line:column, exit 2.
set -u
lvsim="$1"; src="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0; pass=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }
mission="$src/tests/missions/mc/iip_at.yaml"

"$lvsim" mc "$mission" -n 40 -j 2 -o "$work/mc" --keep-runs 2 >"$work/mc.log" 2>&1 \
  || { bad "lvsim mc"; cat "$work/mc.log"; }
# the same campaign without iip_at: the same finals
sed '/iip_at:/d' "$mission" > "$work/no_iip.yaml"
"$lvsim" mc "$work/no_iip.yaml" -n 40 -j 2 -o "$work/mc0" --no-stats >/dev/null 2>&1 || bad "mc without iip_at"

python3 - "$work/mc" "$work/mc0" <<'PY' && ok || bad "IIP at given times: values, counts, ellipse, files"
import csv, json, math, sqlite3, sys
d, d0 = sys.argv[1], sys.argv[2]
db = sqlite3.connect(d + "/campaign.db")
fails = []
def check(c, msg):
    if not c:
        fails.append(msg)
A, E2 = 6378137.0, 6.69437999014e-3          # WGS-84
# 1. coasting body: the IIP at t is the phase's own impact point (lat, lon, time)
fall = {r[0]: r[1:] for r in db.execute('SELECT run, t_end, lat, lon, state FROM phase_fall')}
worst_m = worst_s = 0.0
for t in (0.0, 60.0, 150.5):
    rows = db.execute("SELECT run, state, lat, lon, tof FROM iip WHERE phase = 0 AND t = ?",
                      (t,)).fetchall()
    check(len(rows) == 40, f"T+{t}: {len(rows)} rows")
    for run, state, lat, lon, tof in rows:
        t_end, lat1, lon1, st = fall[run]
        check(state == "impact" and st == "done", f"run {run} T+{t}: {state}, phase {st}")
        off = A * math.hypot(lat - lat1, math.remainder(lon - lon1, 2 * math.pi) * math.cos(lat1))
        worst_m = max(worst_m, off)
        worst_s = max(worst_s, abs(t + tof - t_end))
print(f"coasting body: IIP at T+0/60/150.5 s vs the phase's own impact: worst {worst_m:.4f} m, "
      f"{worst_s:.2e} s")
check(worst_m < 1.0 and worst_s < 1e-3, "IIP off the coasting body's impact")
# 2. the ellipse of "IIP at T+60 s (fall)" against the test's own from the phase's end points
def ellipse(pts):
    lat0 = sum(p[0] for p in pts) / len(pts)
    lon0 = sum(p[1] for p in pts) / len(pts)
    s = math.sin(lat0); w = math.sqrt(1 - E2 * s * s)
    M, N = A * (1 - E2) / w**3, A / w
    xs = [(p[1] - lon0) * N * math.cos(lat0) for p in pts]
    ys = [(p[0] - lat0) * M for p in pts]
    n = len(xs); mx = sum(xs) / n; my = sum(ys) / n
    sxx = sum((x - mx)**2 for x in xs) / (n - 1)
    syy = sum((y - my)**2 for y in ys) / (n - 1)
    sxy = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / (n - 1)
    tr, dd = (sxx + syy) / 2, math.sqrt(((sxx - syy) / 2)**2 + sxy**2)
    return 3 * math.sqrt(tr + dd), 3 * math.sqrt(max(tr - dd, 0)), math.degrees(lat0)
a_ref, b_ref, lat_ref = ellipse([(v[1], v[2]) for v in fall.values()])
ell = {r["phase"]: r for r in csv.DictReader(open(d + "/ellipses.csv"))}
e60 = ell.get("IIP at T+60 s (fall)")
check(e60 is not None and e60["kind"] == "iip", "ellipses.csv: no 'IIP at T+60 s (fall)'")
if e60:
    print(f"IIP at T+60 s ellipse: {float(e60['semi_major']):.2f} x {float(e60['semi_minor']):.3f} m;"
          f" the phase's impact points (test): {a_ref:.2f} x {b_ref:.3f} m")
    check(abs(float(e60["semi_major"]) - a_ref) < 1e-4 * a_ref + 1.0, "semi-major")
    check(abs(float(e60["semi_minor"]) - b_ref) < 1e-3 * b_ref + 1.0, "semi-minor")
    check(abs(float(e60["centre_lat_deg"]) - lat_ref) < 1e-6, "centre")
    check(int(e60["n"]) == 40, "n")
check("IIP at T+5000 s (fall)" not in ell and "IIP at T+50 s (orbit)" not in ell,
      "an ellipse of runs not flying / in orbit")
# 3. not flying, in orbit: counted, in the database, outcomes.csv and stats.json
n = db.execute("SELECT count(*) FROM iip WHERE phase = 0 AND t = 5000 AND state = 'not flying'"
               " AND lat IS NULL").fetchone()[0]
check(n == 40, f"T+5000 s: {n} not flying")
n = db.execute("SELECT count(*) FROM iip WHERE phase = 1 AND state = 'in orbit'").fetchone()[0]
check(n == 40, f"orbit: {n} in orbit")
outc = list(csv.DictReader(open(d + "/outcomes.csv")))
check(any(r["phase"] == "IIP at T+5000 s (fall)" and r["outcome"] == "iip" and
          r["cause"] == "not flying" and r["count"] == "40" for r in outc), "outcomes.csv not flying")
check(any(r["phase"] == "IIP at T+50 s (orbit)" and r["cause"] == "in orbit" and
          r["count"] == "40" for r in outc), "outcomes.csv in orbit")
sj = json.load(open(d + "/stats.json"))
iip = {o["name"]: o for o in sj["iip"]}
check(iip["IIP at T+5000 s (fall)"]["not_flying"] == 40 and
      iip["IIP at T+50 s (orbit)"]["in_orbit"] == 40 and
      iip["IIP at T+60 s (fall)"]["impact"] == 40 and
      len(iip["IIP at T+60 s (fall)"]["ellipses"]) == 1, "stats.json counts")
kml = open(d + "/footprint.kml").read()
check("IIP at T+60 s (fall) (instantaneous impact points, 40 runs)" in kml, "footprint.kml")
html = open(d + "/index.html").read()
check("Instantaneous impact point at given times" in html and "IIP at T+150.5 s (fall)" in html,
      "index.html")
# 4. a kept run's IIP at T+10.37 s of the burn against its own rows interpolated at t
for run in (0, 1):
    rows = list(csv.reader(open(f"{d}/runs/run_{run}/phase_3_burn.csv")))
    head = [h.split(" ")[0] for h in rows[0]]
    data = [[float(x) for x in r] for r in rows[1:]]
    it = head.index("time")
    t = 10.37
    i = max(j for j, r in enumerate(data) if r[it] <= t)
    lat, lon, tof, rng = db.execute("SELECT lat, lon, tof, range FROM iip WHERE run = ? AND "
                                    "phase = 2", (run,)).fetchone()
    for name, got in (("iip_lat", lat), ("iip_lon", lon), ("iip_tof", tof), ("iip_range", rng)):
        c = head.index(name)
        t0, t1 = data[i][it], data[i + 1][it]
        f0, f1 = data[i][c], data[i + 1][c]
        lin = f0 + (f1 - f0) * (t - t0) / (t1 - t0)
        d2 = max(abs(data[j + 1][c] - 2 * data[j][c] + data[j - 1][c]) for j in (i - 1, i, i + 1, i + 2))
        bound = 2 * d2 / 8 + 1e-9 * max(1.0, abs(lin))
        print(f"run {run} burn {name} at T+{t}: {got:.12g}, rows interpolated {lin:.12g} "
              f"(bound {bound:.2e})")
        check(abs(got - lin) <= bound, f"run {run} {name}: {got} vs rows {lin}")
# 5. the finals with and without iip_at
db0 = sqlite3.connect(d0 + "/campaign.db")
for tbl in ("phase_fall", "phase_orbit", "phase_burn"):
    a = db.execute(f'SELECT * FROM "{tbl}" ORDER BY run').fetchall()
    b = db0.execute(f'SELECT * FROM "{tbl}" ORDER BY run').fetchall()
    worst = 0.0
    for ra, rb in zip(a, b):
        for x, y in zip(ra[7:], rb[7:]):
            if isinstance(x, float) and isinstance(y, float):
                worst = max(worst, abs(x - y) / max(1.0, abs(y)))
            elif x != y:
                worst = math.inf
    print(f"{tbl}: finals with and without iip_at, worst relative difference {worst:.2e}")
    check(len(a) == len(b) == 40 and worst <= 1e-9, f"{tbl}: finals differ ({worst})")
for f in fails:
    print("  ", f)
sys.exit(1 if fails else 0)
PY

# a jettisoned part (tests/missions/mc/fairing.yaml: kourou-leo's fairing flown to the ground
# as a phase of its own stage from upper-burn-1's end) beside the stages, and the ascent's IIP
"$lvsim" mc "$src/tests/missions/mc/fairing.yaml" -n 30 -j 2 -o "$work/fairing" >"$work/f.log" 2>&1 \
  || { bad "lvsim mc fairing"; cat "$work/f.log"; }
python3 - "$work/fairing" <<'PY' && ok || bad "fairing footprint"
import csv, json, math, sqlite3, sys
d = sys.argv[1]
db = sqlite3.connect(d + "/campaign.db")
fails = []
def check(c, msg):
    if not c:
        fails.append(msg)
# every run: the fairing's phase is done on its impact end, on the ground (h = 0 within 1 m),
# with its own mass: the dry mass this run drew (no propellant, no engines), after the
# jettison (upper-burn-1's end), and short of the drag-free IIP at the jettison (its drag
# takes energy: it lands up-range of the point it would reach in vacuum)
rows = db.execute('SELECT f.run, f.state, f.end_reason, f.h, f.m, f.t_end, u.t_end, f.lon, '
                  'u.iip_lon, r."fairing.dry_mass", u.iip_range, f.downrange, u.downrange '
                  'FROM "phase_fairing-fall" f JOIN "phase_upper-burn-1" u USING (run) '
                  'JOIN runs r USING (run)').fetchall()
check(len(rows) == 30, f"{len(rows)} fairing rows")
short = []
for run, st, end, h, m, tf, tu, lon, iip_lon, dry, rng, dr, dr_u in rows:
    check(st == "done" and end == "impact", f"run {run}: {st} {end}")
    check(abs(h) < 1.0, f"run {run}: h {h}")
    check(m == dry, f"run {run}: mass {m} vs drawn dry mass {dry}")
    check(tf > tu, f"run {run}: impact before the jettison")
    short.append((iip_lon - lon) * 6378137.0 * math.cos(0.09))
    check(lon < iip_lon, f"run {run}: the fairing lands beyond its drag-free IIP")
print(f"fairing: lands {min(short)/1e3:.1f}-{max(short)/1e3:.1f} km short of the drag-free IIP "
      f"at the jettison")
ell = {r["phase"]: r for r in csv.DictReader(open(d + "/ellipses.csv"))}
check(ell.get("fairing-fall", {}).get("kind") == "impact" and ell["fairing-fall"]["n"] == "30",
      "ellipses.csv: the fairing's impact footprint")
for k in ("IIP at T+60 s (ascent)", "IIP at T+120 s (ascent)"):
    check(ell.get(k, {}).get("n") == "30", "ellipses.csv: " + k)
sj = json.load(open(d + "/stats.json"))
ph = {p["name"]: p for p in sj["phases"]}
check(ph["fairing-fall"]["stages"] == "fairing" and ph["fairing-fall"]["done"] == 30,
      "stats.json: the fairing's phase names its part")
kml = open(d + "/footprint.kml").read()
check("fairing-fall (impact points of fairing, 30 runs)" in kml, "footprint.kml: the part")
check("<h2>Phase fairing-fall</h2>\n<p>Carries fairing. 30 runs" in open(d + "/index.html").read(),
      "index.html")
for f in fails:
    print("  ", f)
sys.exit(1 if fails else 0)
PY

# bad iip_at: refused by check and run alike, file:line:column, exit 2
refused() { # NAME PATTERN: check and run of $work/NAME.yaml
  local out rc
  for cmd in check run; do
    if [ "$cmd" = run ]; then out=$("$lvsim" run "$work/$1.yaml" -o "$work/out_$1" 2>&1); rc=$?
    else out=$("$lvsim" check "$work/$1.yaml" 2>&1); rc=$?; fi
    if [ "$rc" -eq 2 ] && grep -qE -- "$2" <<<"$out"; then ok
    else bad "$1 ($cmd): exit $rc, want 2 and /$2/:"; echo "$out" | head -3; fi
  done
}
bad_case() { # NAME SED-EXPR PATTERN
  sed "$2" "$mission" > "$work/$1.yaml"
  refused "$1" "$3"
}
bad_case decreasing 's/iip_at: \[0, 60, 150.5, 5000\]/iip_at: [0, 60, 60]/' \
  "decreasing.yaml:27:21: phase 'fall': iip_at: the times must increase: 60 s after 60 s"
bad_case empty 's/iip_at: \[50\]/iip_at: []/' \
  "empty.yaml:35:13: phase 'orbit': iip_at: a list of mission times in s expected, e.g. \[60, 120\], found an empty list"
bad_case word 's/iip_at: \[10.37\]/iip_at: [soon]/' \
  "word.yaml:43:14: phase 'burn': iip_at: number expected, found 'soon'"
bad_case scalar 's/iip_at: \[10.37\]/iip_at: 10.37/' \
  "scalar.yaml:43:13: phase 'burn': iip_at: a list of mission times in s expected"
# a model without the iip_* outputs: the flat world's (the example's tables beside it)
cp "$src/examples/paper-test-case/"stage*.* "$work/"
sed '0,/^    model: flat6/s//    model: flat6\n    iip_at: [5]/' \
  "$src/examples/paper-test-case/mission.yaml" > "$work/flat.yaml"
refused flat "flat.yaml:[0-9]+:5: phase '[^']+': iip_at: the flat6 model has no impact-point output 'iip_lat'"

echo "test_mc_iip: $pass passed, $fails failed"
[ "$fails" -eq 0 ]
