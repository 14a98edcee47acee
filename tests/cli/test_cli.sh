#!/usr/bin/env bash
# test_cli.sh LVSIM - the command line: outputs, exit codes (0 ok, 2 bad input, 3 simulation
# failure) and messages. Reference values are cited where they appear.
set -u
lvsim="$1"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fails=0
pass=0

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

expect 0 "vertical_ascent" -- "$lvsim" models
expect 0 "^parameter +thrust +N" -- "$lvsim" vars vertical_ascent
expect 2 "unknown model 'nope'" -- "$lvsim" vars nope
expect 2 "unknown command 'fly'" -- "$lvsim" fly
# Free fall from 100 m: impact at sqrt(2 h / g) = 4.51523641 s (g = 9.81)
expect 0 "time += 4.515236" -- "$lvsim" simulate free_fall --stop 10 --tolerance 1e-10 --method dopri5 --final time -o "$work/ff"
[ -f "$work/ff.mat" ] && [ -f "$work/ff.csv" ] && pass=$((pass + 1)) || { echo "FAIL: result files"; fails=$((fails + 1)); }
expect 0 '"ok": true' -- "$lvsim" simulate oscillator --json --format none --final x
expect 2 "did you mean 'thrust'" -- "$lvsim" simulate vertical_ascent --set thrus=1 --format none
expect 2 "is not a finite number" -- "$lvsim" simulate oscillator --stop abc
expect 2 "unknown integration method 'rk45'" -- "$lvsim" simulate oscillator --method rk45 --format none
expect 2 "stopTime -1 s is before startTime 0 s" -- "$lvsim" simulate oscillator --stop -1 --format none
expect 2 "unknown option '--bogus'" -- "$lvsim" simulate oscillator --bogus
# A run that fails in the integrator exits 3 and names model, time and reason.
expect 3 "model 'oscillator': at t = .* too much work" -- "$lvsim" simulate oscillator --stop 1000 --max-steps 50 --format none
# US Standard Atmosphere 1976: sea level 288.15 K, 101325 Pa, 1.2250 kg/m3, 340.294 m/s
expect 0 "^0 288.15 101325 1.22499[0-9]* 340.294" -- "$lvsim" atmosphere 0
expect 0 "^# us76: altitude \[m\]" -- "$lvsim" atmosphere 0 1000
expect 2 "outside the valid range" -- "$lvsim" atmosphere 2e6
expect 2 "'abc' is not an altitude" -- "$lvsim" atmosphere abc
expect 2 "did you mean 'exp'" -- "$lvsim" atmosphere 0 --model exq
# WGS-84 normal gravity at the equator (Somigliana): 9.7803253359 m/s2; the J2 model with
# centrifugal acceleration gives 9.78028 (J4 and higher are missing)
expect 0 "^0 0 9.7802" -- "$lvsim" gravity 0 0 0 --model j2 --effective
expect 2 "did you mean 'zonal'" -- "$lvsim" gravity 45 10 400e3 --model zonl
expect 2 "latitude 95 deg" -- "$lvsim" gravity 95 0 0
expect 2 "expected LAT_DEG LON_DEG ALT_M" -- "$lvsim" gravity 45 x 0
# "sh" reads gravity/egm2008_n20.gfc, found at run time next to the library (build/share/lvsim);
# EGM2008 to degree 4 at 400 km: |g| = 8.69737 m/s2. $LVSIM_DATA comes first.
expect 0 " 8\.69736" -- "$lvsim" gravity 45 10 400e3 --model sh:4
mkdir -p "$work/data/gravity"
printf 'modelname empty\n' > "$work/data/gravity/egm2008_n20.gfc"
expect 2 "$work/data/gravity/egm2008_n20.gfc:1: no end_of_head" -- \
  env LVSIM_DATA="$work/data" "$lvsim" gravity 45 10 400e3 --model sh:4

# Missions: run, check, compare, export; exit codes 0 / 2 / 3 (docs/cli.md)
src="$(cd "$(dirname "$0")/../.." && pwd)"
expect 0 "is valid: 5 phases" -- "$lvsim" check "$src/examples/paper-test-case/mission.yaml"
expect 2 "bad_cycle.yaml:[0-9]+:[0-9]+: phase .*cycle" -- "$lvsim" check "$src/tests/missions/bad_cycle.yaml"
expect 0 "P5 +P2 .* ok" -- "$lvsim" run "$src/examples/paper-test-case/mission.yaml" -o "$work/run"
[ -f "$work/run/summary.json" ] && [ -f "$work/run/mission.czml" ] && [ -f "$work/run/mission.kml" ] \
  && pass=$((pass + 1)) || { echo "FAIL: run outputs"; fails=$((fails + 1)); }
expect 0 '"mission":' -- "$lvsim" run "$src/examples/paper-test-case/mission.yaml" -o "$work/run2" --json
expect 0 "number of states +39 +13" -- "$lvsim" compare "$src/examples/paper-test-case/mission.yaml"
expect 0 "exports written" -- "$lvsim" export "$work/run" --format czml
expect 2 "summary.json: cannot read" -- "$lvsim" export "$work/nothing"
# lvsim view stages with viewer/stage.sh found like any data file ($LVSIM_DATA here), which
# copies from its own folder: web/ and cesium/ (a stand-in for the CesiumJS build)
mkdir -p "$work/data/viewer"
cp -R "$src/viewer/stage.sh" "$src/viewer/web" "$work/data/viewer/"
expect 1 "CesiumJS is missing: no $work/data/viewer/cesium/Cesium.js" -- \
  env LVSIM_DATA="$work/data" "$lvsim" view "$work/run" --stage-only
mkdir -p "$work/data/viewer/cesium/"{Assets,Workers,ThirdParty,Widgets}
echo '// stand-in' > "$work/data/viewer/cesium/Cesium.js"
printf '{\n  "name": "cesium",\n  "version": "0.0.7"\n}\n' > "$work/data/viewer/cesium/package.json"
expect 0 "viewer staged in $work/run/viewer/" -- \
  env LVSIM_DATA="$work/data" "$lvsim" view "$work/run" --stage-only
grep -qx "lvsim viewer, CesiumJS 0.0.7" "$work/run/viewer/VERSION" && [ -f "$work/run/viewer/app.js" ] \
  && [ -f "$work/run/viewer/cesium/Cesium.js" ] && pass=$((pass + 1)) \
  || { echo "FAIL: staged viewer in $work/run/viewer"; fails=$((fails + 1)); }
cat > "$work/fail.yaml" <<YAML
mission: {name: fails}
stages: [{name: a, dry_mass: 100, propellant_mass: 900, engines: [{table: {file: $work/short.csv, extrap: error}}]}]
phases: [{name: p, model: flat6, stages: [a], stop_time: 200}]
YAML
printf 't [s], thrust [N], mdot [kg/s]\n0, 30000, 10\n50, 30000, 10\n' > "$work/short.csv"
expect 3 "phase 'p'.*outside" -- "$lvsim" run "$work/fail.yaml" -o "$work/failrun"

echo "$pass passed, $fails failed"
[ "$fails" -eq 0 ]
