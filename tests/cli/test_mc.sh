#!/usr/bin/env bash
# test_mc.sh LVSIM SRC [MPI] - lvsim mc (issue 16): the same campaign gives the same database
# contents (sqlite3 .dump) with -j 1, -j 2 and, with MPI=1, `mpirun -np 2`; a campaign killed
# with SIGKILL and resumed ends with the contents of an uninterrupted one; `lvsim check` and
# `lvsim mc` refuse the same bad dispersions with the same file:line:column; exit codes.
# Issue 22: dense grids and run counts refused or estimated before anything runs; SIGINT and
# SIGTERM end a campaign within a second inside a long run, and --resume completes it.
set -u
lvsim="$1"; src="$2"; mpi="${3:-0}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0; pass=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }
dump() { sqlite3 "$1" .dump; }
# runs stored so far in a campaign's database being written; read-only, so that the probe
# never creates the file before lvsim does (it would then be "an existing database")
stored_runs() { [ -s "$1" ] && sqlite3 -readonly -cmd ".timeout 200" "$1" "SELECT count(*) FROM runs" 2>/dev/null || echo 0; }
mission="$src/examples/dof3-branch/mission.yaml"
isp="$src/tests/missions/mc/isp_scatter.yaml"

if [ "$mpi" = 1 ]; then
  # mpirun as root needs --allow-run-as-root (CI runs as root); 2 ranks on any machine
  extra=()
  [ "$(id -u)" -eq 0 ] && extra+=(--allow-run-as-root)
  "$lvsim" mc "$mission" -n 48 -j 1 -o "$work/j1" --no-stats >/dev/null 2>&1 || bad "mc -j 1"
  mpirun "${extra[@]}" --oversubscribe -np 2 "$lvsim" mc "$mission" -n 48 -j 1 -o "$work/np2" \
    --no-stats >"$work/np2.log" 2>&1 || { bad "mpirun -np 2 lvsim mc"; cat "$work/np2.log"; }
  grep -q "2 ranks" "$work/np2.log" && ok || bad "mpirun: no '2 ranks' line"
  if cmp -s <(dump "$work/j1/campaign.db") <(dump "$work/np2/campaign.db"); then ok
  else bad "mpirun -np 2 and -j 1 databases differ"; fi
  # SIGINT on rank 0 inside long runs (issue 22): rank 0 stops handing out work and tells the
  # other rank, whose run is cancelled; the ranks end within a second, mpirun (OpenMPI aborts a
  # job whose rank exits non-zero) about a second after; the database is consistent and
  # --resume completes it as an uninterrupted campaign
  long="$src/tests/missions/mc/long_run.yaml"
  "$lvsim" mc "$long" -n 4 -j 2 -o "$work/long_full" --no-stats >/dev/null 2>&1 || bad "long runs, uninterrupted"
  mpirun "${extra[@]}" --oversubscribe -np 2 "$lvsim" mc "$long" -n 4 -j 1 -o "$work/long_np2" \
    --no-stats >"$work/long_np2.log" 2>&1 &
  mp=$!
  for _ in $(seq 1 600); do  # the first chunks stored, the next runs under way
    sleep 0.05
    # rank 0's progress line says a run is done even when the probe finds the database
    # busy (a full suite on a loaded machine once saw neither before the campaign ended)
    grep -q "mc: [1-3]/4 runs" "$work/long_np2.log" 2>/dev/null && break
    stored=$(stored_runs "$work/long_np2/campaign.db")
    [ "${stored:-0}" -ge 1 ] && break
  done
  sleep 0.3
  r0=""
  for c in $(pgrep -P $mp); do  # rank 0: the child of mpirun whose environment says so
    tr '\0' '\n' < "/proc/$c/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=0" && r0=$c
  done
  t0=$(date +%s.%N)
  [ -n "$r0" ] && kill -INT "$r0"
  wait $mp; rc=$?
  dt=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
  echo "SIGINT on rank 0 ($r0): mpirun exit $rc after $dt s"
  [ -n "$r0" ] && [ "$rc" -eq 130 ] && awk -v d="$dt" 'BEGIN { exit !(d < 5.0) }' && ok \
    || { bad "SIGINT on rank 0: mpirun exit $rc after $dt s (want 130)"; cat "$work/long_np2.log"; }
  grep -q "lvsim: campaign stopped (continue with --resume)" "$work/long_np2.log" && ok || { bad "rank 0 did not stop cleanly"; cat "$work/long_np2.log"; }
  [ "$(sqlite3 "$work/long_np2/campaign.db" "PRAGMA integrity_check")" = ok ] && ok || bad "database not consistent"
  "$lvsim" mc "$long" -n 4 -j 2 -o "$work/long_np2" --resume --no-stats >"$work/long_np2.resume.log" 2>&1 || { bad "resume after mpirun"; cat "$work/long_np2.resume.log"; }
  cmp -s <(dump "$work/long_full/campaign.db") <(dump "$work/long_np2/campaign.db") && ok || bad "stopped under mpirun + resumed differs from uninterrupted"
  echo "test_mc (mpi): $pass passed, $fails failed"
  [ "$fails" -eq 0 ]; exit
fi

# -j 1 and -j 2: the same rows, run for run, bit for bit
"$lvsim" mc "$mission" -n 48 -j 1 -o "$work/j1" --no-stats >/dev/null 2>&1 || bad "mc -j 1"
"$lvsim" mc "$mission" -n 48 -j 2 -o "$work/j2" >"$work/j2.log" 2>&1 || bad "mc -j 2"
if cmp -s <(dump "$work/j1/campaign.db") <(dump "$work/j2/campaign.db"); then ok
else bad "-j 1 and -j 2 databases differ"; fi
n=$(sqlite3 "$work/j2/campaign.db" "SELECT count(*) FROM runs WHERE status = 'ok'")
[ "$n" = 48 ] && ok || bad "48 runs expected, $n stored"
n=$(sqlite3 "$work/j2/campaign.db" "SELECT count(*) FROM phase_booster WHERE end_reason = 'impact'")
[ "$n" = 48 ] && ok || bad "the booster should impact in every run ($n)"
for f in stats.json stats.csv ellipses.csv outcomes.csv sensitivity.csv footprint.kml index.html; do
  [ -s "$work/j2/$f" ] && ok || bad "missing $f"
done
grep -q '^"booster",impact,east_m,north_m,48,' "$work/j2/ellipses.csv" && ok || bad "booster impact ellipse"
grep -q "<coordinates>" "$work/j2/footprint.kml" && ok || bad "KML coordinates"

# Impacts are outcomes, not failures (issue 27): 300 runs of the README's campaign, in which a
# few dispersed upper stages are too slow to reach orbit and fall back before burnout. The
# same mission with the upper stage's `end: [burnout]` alone (as before issue 27) leaves the
# model's domain in exactly those runs: an independent account of which runs fell. With
# `end: [burnout, impact]` they are `impact` (state, status, outcomes.csv, stats.json, the
# CLI's count), their final altitude is the ground's (the impact end's h = 0, within the
# event location's 1 m), no run failed, and the orbit statistics cover the burnout runs only.
cp -r "$src/examples/dof3-branch" "$work/fall"
sed -i 's/^    end: \[burnout, impact\]$/    end: [burnout]/' "$work/fall/mission.yaml"
grep -c '^    end: \[burnout\]$' "$work/fall/mission.yaml" | grep -qx 2 && ok || bad "the copy without the impact end"
"$lvsim" mc "$work/fall/mission.yaml" -n 300 -j 2 -o "$work/fall_old" --no-plots >/dev/null 2>&1
"$lvsim" mc "$mission" -n 300 -j 2 -o "$work/fall_new" --no-plots >"$work/fall_new.log" 2>&1 || bad "mc: impacts must not fail the campaign (exit $?)"
q() { sqlite3 "$1" "$2" | tr '\n' ' '; }
old=$(q "$work/fall_old/campaign.db" "SELECT run FROM \"phase_upper-burn\" WHERE state = 'failed' AND error LIKE '%left the model''s domain: h fell%' ORDER BY run")
new=$(q "$work/fall_new/campaign.db" "SELECT run FROM \"phase_upper-burn\" WHERE state = 'impact' AND end_reason = 'impact' ORDER BY run")
runs=$(q "$work/fall_new/campaign.db" "SELECT run FROM runs WHERE status = 'impact' ORDER BY run")
nimp=$(wc -w <<<"$new")
echo "impacts: $nimp runs ($new); without the impact end they failed: $old"
[ "$nimp" -ge 1 ] && [ "$new" = "$old" ] && [ "$runs" = "$new" ] && ok || bad "impact runs '$new' (runs table '$runs') differ from the domain exits without the end '$old'"
n=$(q "$work/fall_new/campaign.db" "SELECT count(*) FROM runs WHERE status NOT IN ('ok', 'impact')")
[ "$n" = "0 " ] && ok || bad "$n runs failed"
n=$(q "$work/fall_new/campaign.db" "SELECT count(*) FROM \"phase_upper-burn\" WHERE state = 'impact' AND abs(h) > 1")
[ "$n" = "0 " ] && ok || bad "$n impact runs do not end on the ground"
grep -q "0 with a failed phase or an input out of range, $nimp with a phase that fell to the ground" "$work/fall_new.log" && ok || { bad "mc's counts"; tail -3 "$work/fall_new.log"; }
grep -qx "\"upper-burn\",impact,\"impact\",$nimp,.*" "$work/fall_new/outcomes.csv" && ! grep -q ',failed,' "$work/fall_new/outcomes.csv" && ok || { bad "outcomes.csv"; cat "$work/fall_new/outcomes.csv"; }
python3 - "$work/fall_new/stats.json" "$nimp" <<'PY' && ok || bad "stats.json: impacts counted apart, orbit statistics over the burnout runs"
import json, sys
ph = {p["name"]: p for p in json.load(open(sys.argv[1]))["phases"]}["upper-burn"]
n = int(sys.argv[2])
assert ph["impact"] == n and ph["failed"] == 0 and ph["done"] == 300 - n, ph
assert ph["finals"]["peri_alt"]["n"] == 300 - n and "impact" not in ph["ends"], ph["ends"]
PY

# Runway phases and crashes (issue 26's breaker): examples/rlv-hthl with landing-gear limits on
# the main stage and its sink-rate limit dispersed around the demo's touchdown sink rate. The
# runway phases end by their own events (the take-off roll by `liftoff`, the roll-out by `stop`:
# summary.json's end.event of a plain run), never `stop_time`; a run crashes exactly when its
# drawn limit is below the touchdown's sink rate (summary.json's handoff.absorbed of the plain
# run: the flight before the touchdown is the same in every run), and the crashed runs are
# counted in the CLI's progress and final lines, stats.json, outcomes.csv and index.html (the
# campaign's line and the roll-out's phase line) - also after --resume.
cp -r "$src/examples/rlv-hthl" "$work/rlv"
python3 - "$work/rlv/mission.yaml" <<'PY'
import sys
p = sys.argv[1]
s = open(p).read()
geo = "    geometry: {length: 60, diameter: 7, span: 32}\n"
assert s.count(geo) == 1
s = s.replace(geo, geo + "    landing_gear: {}\n")
s += ("\ndispersions:\n  seed: 7\n  parameters:\n"
      "    ms.landing_gear.sink_rate_max: {dist: uniform, min: 0.3, max: 0.9}\n")
open(p, "w").write(s)
PY
"$lvsim" run "$work/rlv/mission.yaml" -o "$work/rlv_run" -q >/dev/null 2>&1 || bad "rlv with landing gear: plain run"
"$lvsim" mc "$work/rlv/mission.yaml" -n 10 -j 2 -o "$work/rlv_mc" >"$work/rlv_mc.log" 2>&1 || bad "rlv mc (exit $?)"
"$lvsim" mc "$work/rlv/mission.yaml" -n 20 -j 2 -o "$work/rlv_mc" --resume >"$work/rlv_mc2.log" 2>&1 || bad "rlv mc --resume (exit $?)"
python3 - "$work/rlv_run" "$work/rlv_mc" "$work/rlv_mc.log" "$work/rlv_mc2.log" <<'PY' && ok || bad "rlv mc: runway ends and crashes"
import csv, json, os, sqlite3, sys
run, mc, log1, log2 = sys.argv[1:5]
summ = json.load(open(os.path.join(run, "summary.json")))
ph = {p["name"]: p for p in summ["phases"]}
sink = ph["rollout"]["handoff"]["absorbed"]["sink_rate"]
db = sqlite3.connect(os.path.join(mc, "campaign.db"))
draws = dict(db.execute('SELECT run, "ms.landing_gear.sink_rate_max" FROM runs'))
assert len(draws) == 20, draws
want = sorted(r for r, lim in draws.items() if lim < sink)
first = sum(1 for r in want if r < 10)
print("touchdown sink rate %.6f m/s; crashes expected in runs %s" % (sink, want))
assert 0 < len(want) < 20, (sink, draws)
got = sorted(r for (r,) in db.execute("SELECT run FROM runs WHERE status = 'crashed'"))
assert got == want, (got, want)
assert [r for (r,) in db.execute("SELECT run FROM runs WHERE status NOT IN ('ok', 'crashed')")] == []
# the plain run's ends: liftoff and stop, events of the runway type itself
assert ph["liftoff"]["end"] == {"reason": "event", "event": "liftoff"}, ph["liftoff"]["end"]
assert ph["rollout"]["end"]["event"] == "stop", ph["rollout"]["end"]
ends = db.execute("SELECT DISTINCT state, end_reason FROM phase_liftoff").fetchall()
assert ends == [("done", "liftoff")], ends
ends = sorted(db.execute("SELECT state, end_reason, count(*) FROM phase_rollout GROUP BY 1, 2"))
assert ends == sorted([("crashed", "crashed", len(want)), ("done", "stop", 20 - len(want))]), ends
# no phase of any run ends by stop_time (each ends by an event of its own)
for (tbl,) in db.execute("SELECT tbl FROM phases"):
    n = db.execute('SELECT count(*) FROM "%s" WHERE end_reason = \'stop_time\'' % tbl).fetchone()[0]
    assert n == 0, (tbl, n)
out = list(csv.reader(open(os.path.join(mc, "outcomes.csv"))))
assert ["liftoff", "end", "liftoff", "20", "1"] in out, out
assert ["rollout", "crashed", "crashed", str(len(want)), "%.6g" % (len(want) / 20)] in out, out
assert ["rollout", "end", "stop", str(20 - len(want)), "%.6g" % ((20 - len(want)) / 20)] in out, out
st = json.load(open(os.path.join(mc, "stats.json")))
assert st["campaign"]["crashed"] == len(want) and st["campaign"]["failed"] == 0, st["campaign"]
ro = {p["name"]: p for p in st["phases"]}["rollout"]
assert ro["crashed"] == len(want) and ro["failed"] == 0 and ro["ends"] == {"stop": 20 - len(want)}, ro
html = open(os.path.join(mc, "index.html")).read()
assert "0 with a failed phase, 0 with a phase that fell to the ground, %d crashed" % len(want) in html
i = html.index("<h2>Phase rollout</h2>")
line = html[i:html.index("</p>", i)]
assert "%d done" % (20 - len(want)) in line and "%d crashed (a touchdown" % len(want) in line, line
assert "Ends and failures: " in line and "crashed %d" % len(want) in line and "other" not in line, line
# the CLI: this session's final line, the resumed one counts the stored runs too
for log, n, c in ((log1, 10, first), (log2, 20, len(want))):
    text = open(log).read()
    assert "0 with a failed phase or an input out of range, 0 with a phase that fell to the " \
           "ground (an impact end other than its first), %d crashed" % c in text, text
    assert "%d/%d runs" % (n, n) in text and "crashed %d, failed 0" % c in text, text
PY

# an existing database: refused without --resume or --force, the folder left as it was (its
# manifest too: issue 22's breaker saw a refused mc mark a finished campaign 'incomplete')
man_before=$(sha256sum < "$work/j2/manifest.json")
"$lvsim" mc "$mission" -n 48 -o "$work/j2" --no-stats >"$work/exists.log" 2>&1; rc=$?
[ "$rc" -eq 2 ] && grep -q "exists: continue it with --resume" "$work/exists.log" && ok || bad "existing db: exit $rc"
[ "$man_before" = "$(sha256sum < "$work/j2/manifest.json")" ] && ok || bad "a refused mc changed the manifest"
# a campaign grows, it is not cut short on resume (its statistics would leave runs out)
"$lvsim" mc "$mission" -n 20 -o "$work/j2" --resume --no-stats >"$work/shrink.log" 2>&1; rc=$?
[ "$rc" -eq 2 ] && grep -q "holds runs up to run 47: resume with -n 48 or more" "$work/shrink.log" && ok || { bad "resume with fewer runs: exit $rc"; cat "$work/shrink.log"; }
[ "$man_before" = "$(sha256sum < "$work/j2/manifest.json")" ] && ok || bad "a refused resume changed the manifest"
# export and plot of a campaign folder (no summary.json) fail and leave it as it was
"$lvsim" export "$work/j2" >"$work/exp.log" 2>&1; rc=$?
"$lvsim" plot "$work/j2" >>"$work/exp.log" 2>&1; rc2=$?
[ "$rc" -eq 2 ] && [ "$rc2" -eq 2 ] && [ "$man_before" = "$(sha256sum < "$work/j2/manifest.json")" ] && ok || { bad "failed export/plot: exit $rc $rc2 or the manifest changed"; cat "$work/exp.log"; }
# resuming a complete campaign runs nothing and changes nothing
"$lvsim" mc "$mission" -n 48 -o "$work/j1" --resume --no-stats >/dev/null 2>&1 || bad "resume complete"
cmp -s <(dump "$work/j1/campaign.db") <(dump "$work/j2/campaign.db") && ok || bad "resume changed a complete db"
# another seed: refused on resume
"$lvsim" mc "$mission" -n 48 -o "$work/j1" --resume --seed 5 --no-stats >"$work/seed.log" 2>&1; rc=$?
[ "$rc" -eq 2 ] && grep -q "has seed 20260301, not 5" "$work/seed.log" && ok || bad "resume with another seed: exit $rc"

# kill -9 in the middle, then --resume: the contents of an uninterrupted campaign
N=6000
"$lvsim" mc "$isp" -n $N -j 2 -o "$work/full" --no-stats >/dev/null 2>&1 || bad "uninterrupted"
"$lvsim" mc "$isp" -n $N -j 2 -o "$work/killed" --no-stats >/dev/null 2>&1 &
pid=$!
stored=0
for _ in $(seq 1 400); do
  sleep 0.05
  stored=$(stored_runs "$work/killed/campaign.db")
  [ "${stored:-0}" -ge 500 ] && break
done
kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
stored=$(sqlite3 "$work/killed/campaign.db" "SELECT count(*) FROM runs")
if [ "$stored" -gt 0 ] && [ "$stored" -lt $N ]; then ok; else bad "kill -9 left $stored of $N runs (want some, not all)"; fi
"$lvsim" mc "$isp" -n $N -j 1 -o "$work/killed" --resume --no-stats >"$work/resume.log" 2>&1 || bad "resume"
grep -q "$((N - stored)) this session" "$work/resume.log" && ok || { bad "resume should run the $((N - stored)) missing runs"; cat "$work/resume.log"; }
cmp -s <(dump "$work/full/campaign.db") <(dump "$work/killed/campaign.db") && ok || bad "killed + resumed differs from uninterrupted"

# Bounds before anything runs (issue 22): a dense output grid on a phase only its stop time
# ends is refused with the rows in readable form, before DIR is made; on phases with an end
# event it is estimated, and a phase that reaches --max-rows fails in that run (an outcome)
sed 's/    end: \[burnout\]//; s/stop_time: 200/stop_time: 100/' "$isp" > "$work/open.yaml"
out=$("$lvsim" mc "$work/open.yaml" --output-interval 1e-9 -n 10 -o "$work/dense" 2>&1); rc=$?
[ "$rc" -eq 2 ] && grep -q "lvsim: mc: phase 1 'burn' would write up to 1e+11 rows (100 s of mission time, a row every 1e-09 s; .*more than the limit of 1000000 rows per phase" <<<"$out" \
  && [ ! -e "$work/dense" ] && ok || bad "dense grid on an open phase: exit $rc: $out"
out=$("$lvsim" mc "$mission" --output-interval 1e-9 -n 2 -o "$work/dense2" --no-stats 2>&1); rc=$?
[ "$rc" -eq 0 ] && grep -q "mc: estimate: up to 3000000 output rows a run (5.4e+12 by the stop times)" <<<"$out" \
  && grep -q "a phase with an end event that does not fire within --max-rows 1000000 rows fails there" <<<"$out" \
  && ok || bad "dense grid with end events: exit $rc: $out"
n=$(sqlite3 "$work/dense2/campaign.db" "SELECT count(*) FROM phase_ascent WHERE state = 'failed' AND error LIKE '%by the row limit: 1000000 output rows%'")
[ "$n" = 2 ] && ok || bad "the dense runs should fail at the row limit ($n of 2)"
# a run count whose database cannot fit: refused with the sizes, exit 2, nothing made
out=$("$lvsim" mc "$mission" -n 99999999999 -o "$work/huge" 2>&1); rc=$?
[ "$rc" -eq 2 ] && grep -q "lvsim: mc -n 99999999999: a campaign of 1e+11 runs is too large; its database would need about .* TB (.* kB a run) and the file system of .* has .* free; its statistics would need .* TB of memory .* and this machine has .*: run fewer (-n), or skip the statistics (--no-stats)" <<<"$out" \
  && [ ! -e "$work/huge" ] && ok || bad "-n 99999999999: exit $rc: $out"

# Ctrl-C and SIGTERM inside a run of several seconds (long_run.yaml: about 2.7 s of CPU a run,
# start and end rows only): the campaign ends within a second (130), the runs done are
# stored, the one cut short is not, the database is consistent, and --resume ends with the
# contents of an uninterrupted campaign
long="$src/tests/missions/mc/long_run.yaml"
"$lvsim" mc "$long" -n 3 -j 2 -o "$work/long_full" --no-stats >/dev/null 2>&1 || bad "long runs, uninterrupted"
now() { date +%s.%N; }
for sig in INT TERM; do
  d="$work/long_$sig"
  "$lvsim" mc "$long" -n 3 -j 1 -o "$d" --no-stats >"$d.log" 2>&1 &
  pid=$!
  stored=0
  for _ in $(seq 1 600); do  # the first run stored, the second under way
    sleep 0.05
    stored=$(stored_runs "$d/campaign.db")
    [ "${stored:-0}" -ge 1 ] && break
  done
  sleep 0.3
  t0=$(now); kill -$sig $pid; wait $pid; rc=$?; t1=$(now)
  dt=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')
  echo "SIG$sig: exit $rc after $dt s"
  [ "$rc" -eq 130 ] && awk -v d="$dt" 'BEGIN { exit !(d < 1.0) }' && ok || bad "SIG$sig: exit $rc after $dt s (want 130 within 1 s)"
  grep -q "lvsim: campaign stopped: 1 of 3 runs stored (the database is consistent: resume it to continue)" "$d.log" && ok || bad "SIG$sig: $(tail -1 "$d.log")"
  [ "$(sqlite3 "$d/campaign.db" "PRAGMA integrity_check")" = ok ] && ok || bad "SIG$sig: database not consistent"
  for t in runs phase_burn phase_coast1 phase_coast2 events; do  # only whole runs, as stored uninterrupted
    extra=$(sqlite3 "$d/campaign.db" "ATTACH '$work/long_full/campaign.db' AS f; SELECT count(*) FROM (SELECT * FROM main.\"$t\" EXCEPT SELECT * FROM f.\"$t\")")
    [ "$extra" = 0 ] && ok || bad "SIG$sig: $extra rows of $t differ from the uninterrupted campaign"
  done
  n=$(sqlite3 "$d/campaign.db" "SELECT count(*) FROM phase_coast2")
  [ "$n" = 1 ] && ok || bad "SIG$sig: $n runs' phases stored (want the 1 run done)"
  "$lvsim" mc "$long" -n 3 -j 2 -o "$d" --resume --no-stats >"$d.resume.log" 2>&1 || bad "SIG$sig: resume"
  grep -q "2 this session" "$d.resume.log" && ok || bad "SIG$sig: resume should run the 2 missing runs: $(tail -1 "$d.resume.log")"
  cmp -s <(dump "$work/long_full/campaign.db") <(dump "$d/campaign.db") && ok || bad "SIG$sig: stopped + resumed differs from uninterrupted"
done

# bad dispersions: check and mc say the same, with the position
cat > "$work/bad.yaml" <<'YAML'
mission: {name: bad}
environment: {world: flat}
stages:
  - {name: s1, dry_mass: 100, propellant_mass: 10, engines: [{name: e1, thrust_vac: 5000, isp_vac: 200}]}
phases:
  - {name: p, model: flat6, stages: [s1], stop_time: 10}
dispersions:
  parameters:
    e1.isp_vac: {dist: normal, sigma: -2}
YAML
c1=$("$lvsim" check "$work/bad.yaml" 2>&1); r1=$?
c2=$("$lvsim" mc "$work/bad.yaml" -n 3 -o "$work/bad" 2>&1); r2=$?
[ "$r1" -eq 2 ] && [ "$r2" -eq 2 ] && ok || bad "bad dispersions: exits $r1, $r2 (want 2, 2)"
grep -q "bad.yaml:9:39: dispersions: 'e1.isp_vac': sigma must be >= 0, found -2" <<<"$c1" && ok || bad "check: $c1"
[ "$c1" = "$c2" ] && ok || bad "check and mc differ: '$c1' vs '$c2'"
# no dispersions, usage
"$lvsim" mc "$src/tests/missions/minimal.yaml" -n 3 -o "$work/none" >"$work/none.log" 2>&1; rc=$?
[ "$rc" -eq 2 ] && grep -q "no 'dispersions:' section" "$work/none.log" && ok || bad "no dispersions: exit $rc"
"$lvsim" mc "$mission" >"$work/u.log" 2>&1; rc=$?
[ "$rc" -eq 2 ] && grep -q "mc needs the run count" "$work/u.log" && ok || bad "missing -n: exit $rc"

echo "test_mc: $pass passed, $fails failed"
[ "$fails" -eq 0 ]
