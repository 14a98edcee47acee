#!/usr/bin/env bash
# test_dprof_cli.sh LVSIM SRC - dispersed profiles (issue 28, item 3; docs/monte-carlo.md
# "Dispersed profiles"): `lvsim run` flies the nominal (its phase file is byte for byte the one
# of the same mission without the profiles); `lvsim mc` flies a perturbation per run (four runs,
# four different finals; the same campaign again: the same database rows); bad `profiles:`
# entries refused by `lvsim check`, `lvsim run` and `lvsim mc` alike with file:line:column,
# exit 2.
set -u
lvsim="$1"; src="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0; pass=0
expect() { # expect CODE PATTERN -- command...
  local code="$1" pat="$2"; shift 3
  local out rc
  out=$("$@" 2>&1); rc=$?
  if [ "$rc" -ne "$code" ] || ! grep -qE -- "$pat" <<<"$out"; then
    echo "FAIL: $* -> exit $rc (want $code), output:"; echo "$out" | head -5
    echo "      expected pattern: $pat"
    fails=$((fails + 1))
  else
    pass=$((pass + 1))
  fi
}
cp "$src"/tests/data/profiles/sounding.txt "$src/examples/dof3-branch/aero_ascent.csv" "$work/"

mission() { # mission ATMOSPHERE WIND_LINE [DISPERSIONS]: a vertical climb (test_profile_cli's)
  cat <<YAML
mission: {name: dprof}
environment:
  world: planet
  planet: earth
  gravity: j2
  atmosphere: $1
$2
parameters: {start_lat_deg: 5.2, start_lon_deg: -52.8, start_h: 100, start_vel: 50, start_fpa_deg: 88, start_chi_deg: 90}
stages:
  - {name: s1, dry_mass: 15000, propellant_mass: 150000, engines: [{name: e, thrust_vac: 3.2e6, isp_vac: 300}]}
phases:
  - {name: P, model: dof3, stages: [s1], stop_time: 40, end: [impact], inputs: {alpha_deg: 0, throttle: 1},
     aero: {s_ref: 10, axes: wind, table: aero_ascent.csv}}
${3:-}
YAML
}
prof="dispersions:
  seed: 3
  profiles:
    environment.wind: {sigma: 4, correlation_length: 2000}
    environment.atmosphere.density: {sigma: [[0, 0.01], [50000, 0.04], [90000, 0.1]], correlation_length: 6000}"
mission us76 "  wind: {profile: sounding.txt}" > "$work/base.yaml"
mission us76 "  wind: {profile: sounding.txt}" "$prof" > "$work/dprof.yaml"
expect 0 "is valid: 1 phases" -- "$lvsim" check "$work/dprof.yaml"
expect 0 "P .* done" -- "$lvsim" run "$work/base.yaml" -o "$work/base" --no-plots
expect 0 "P .* done" -- "$lvsim" run "$work/dprof.yaml" -o "$work/nom" --no-plots
if cmp -s "$work/base/phase_1_P.csv" "$work/nom/phase_1_P.csv"; then pass=$((pass + 1))
else echo "FAIL: lvsim run must fly the nominal profiles"; fails=$((fails + 1)); fi
expect 0 "4 runs" -- "$lvsim" mc "$work/dprof.yaml" -n 4 -j 2 -o "$work/mc" --no-stats
expect 0 "4 runs" -- "$lvsim" mc "$work/dprof.yaml" -n 4 -o "$work/mc2" --no-stats
# the exp atmosphere and no wind (still air perturbed) fly too
mission exp "" "$prof" > "$work/exp.yaml"
expect 0 "3 runs" -- "$lvsim" mc "$work/exp.yaml" -n 3 -o "$work/mc_exp" --no-stats
if command -v sqlite3 >/dev/null; then
  n=$(sqlite3 "$work/mc/campaign.db" "SELECT count(DISTINCT round(h, 3)) FROM phase_P" 2>&1)
  if [ "$n" = 4 ]; then pass=$((pass + 1)); else echo "FAIL: mc: $n distinct final h, want 4"; fails=$((fails + 1)); fi
  a=$(sqlite3 "$work/mc/campaign.db" "SELECT run, h, v_east, rho FROM phase_P ORDER BY run")
  b=$(sqlite3 "$work/mc2/campaign.db" "SELECT run, h, v_east, rho FROM phase_P ORDER BY run")
  if [ -n "$a" ] && [ "$a" = "$b" ]; then pass=$((pass + 1))
  else echo "FAIL: mc: -j 2 and -j 1 must fly the same profiles run for run"; fails=$((fails + 1)); fi
  n=$(sqlite3 "$work/mc_exp/campaign.db" "SELECT count(DISTINCT round(h, 3)) FROM phase_P" 2>&1)
  if [ "$n" = 3 ]; then pass=$((pass + 1)); else echo "FAIL: mc exp: $n distinct final h, want 3"; fails=$((fails + 1)); fi
fi

# bad entries: the same file:line:column from check, run and mc
for c in "environment.wnd: {sigma: 4, correlation_length: 2000}|16:5|no profile 'environment.wnd'; did you mean 'environment.wind'" \
         "environment.wind: {sigma: -1, correlation_length: 2000}|16:31|sigma must be in \\[0, 100\\] m/s, found -1" \
         "environment.wind: {sigma: 4, correlation_length: 0}|16:54|correlation_length must be in \\[1, 1e6\\] m, found 0" \
         "environment.wind: {sigma: 4}|16:23|missing required key 'correlation_length'" \
         "environment.wind: {sigma: 4, correlation_length: 2000, from: 9000, to: 100}|16:76|'to' \\(100 m\\) must be above 'from'" \
         "environment.wind: {sigma: 4, correlation_lenght: 2000}|16:34|unknown key 'correlation_lenght'; did you mean 'correlation_length'" \
         "environment.atmosphere.density: {sigma: [[0, 0.01], [50000, 0.04], [40000, 0.1]], correlation_length: 6000}|16:73|sigma point 3: altitude 40000 m is not above the previous point's 50000 m" \
         "environment.atmosphere.density: {sigma: [[0, 0.01], [50000, 0.3]], correlation_length: 6000}|16:65|sigma point 2: sigma must be in \\[0, 0.25\\] \\(relative\\), found 0.3" \
         "environment.atmosphere.density: {sigma: [[0, 0.01, 3]], correlation_length: 6000}|16:46|sigma point 1: a pair" \
         "environment.wind: {sigma: 4, correlation_length: 1, to: 1e6}|16:54|correlation lengths deep"; do
  IFS='|' read -r line at msg <<<"$c"
  mission us76 "  wind: {profile: sounding.txt}" "dispersions:
  profiles:
    $line" > "$work/bad.yaml"
  expect 2 "bad.yaml:$at: dispersions: .*$msg" -- "$lvsim" check "$work/bad.yaml"
  expect 2 "bad.yaml:$at: dispersions: .*$msg" -- "$lvsim" run "$work/bad.yaml" -o "$work/bad_run" --no-plots
  expect 2 "bad.yaml:$at: dispersions: .*$msg" -- "$lvsim" mc "$work/bad.yaml" -n 2 -o "$work/bad_mc" --no-stats
done
mission us76 "" "dispersions:
  parameters:
    environment.wind: {dist: normal, sigma: 4}" > "$work/asparam.yaml"
expect 2 "asparam.yaml:16:5: dispersions: 'environment.wind' is a profile, not a parameter: write it under dispersions: profiles:" -- \
  "$lvsim" check "$work/asparam.yaml"
mission none "" "$prof" > "$work/noair.yaml"
expect 2 "noair.yaml:17:5: dispersions: profiles: 'environment.wind': the mission has no atmosphere" -- \
  "$lvsim" check "$work/noair.yaml"
mission us76 "" "dispersions:
  profiles: {}" > "$work/empty.yaml"
expect 2 "empty.yaml:15:13: dispersions: profiles: at least one profile expected" -- "$lvsim" check "$work/empty.yaml"
mission us76 "" "dispersions:
  profiles:
    environment.wind: {sigma: 4, correlation_length: 2000}
  correlations:
    - {parameters: [a, b], rho: 0.5}" > "$work/corr.yaml"
expect 2 "corr.yaml:17:3: dispersions: correlations group dispersed parameters, and there is no 'parameters:'" -- \
  "$lvsim" check "$work/corr.yaml"

echo "test_dprof_cli: $pass passed, $fails failed"
[ "$fails" -eq 0 ]
