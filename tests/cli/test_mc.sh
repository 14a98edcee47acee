#!/usr/bin/env bash
# test_mc.sh LVSIM SRC [MPI] - lvsim mc (issue 16): the same campaign gives the same database
# contents (sqlite3 .dump) with -j 1, -j 2 and, with MPI=1, `mpirun -np 2`; a campaign killed
# with SIGKILL and resumed ends with the contents of an uninterrupted one; `lvsim check` and
# `lvsim mc` refuse the same bad dispersions with the same file:line:column; exit codes.
set -u
lvsim="$1"; src="$2"; mpi="${3:-0}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0; pass=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL: $*"; fails=$((fails + 1)); }
dump() { sqlite3 "$1" .dump; }
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

# an existing database: refused without --resume or --force
"$lvsim" mc "$mission" -n 48 -o "$work/j2" --no-stats >"$work/exists.log" 2>&1; rc=$?
[ "$rc" -eq 2 ] && grep -q "exists: continue it with --resume" "$work/exists.log" && ok || bad "existing db: exit $rc"
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
  stored=$(sqlite3 "$work/killed/campaign.db" "SELECT count(*) FROM runs" 2>/dev/null || echo 0)
  [ "${stored:-0}" -ge 500 ] && break
done
kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
stored=$(sqlite3 "$work/killed/campaign.db" "SELECT count(*) FROM runs")
if [ "$stored" -gt 0 ] && [ "$stored" -lt $N ]; then ok; else bad "kill -9 left $stored of $N runs (want some, not all)"; fi
"$lvsim" mc "$isp" -n $N -j 1 -o "$work/killed" --resume --no-stats >"$work/resume.log" 2>&1 || bad "resume"
grep -q "$((N - stored)) this session" "$work/resume.log" && ok || { bad "resume should run the $((N - stored)) missing runs"; cat "$work/resume.log"; }
cmp -s <(dump "$work/full/campaign.db") <(dump "$work/killed/campaign.db") && ok || bad "killed + resumed differs from uninterrupted"

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
