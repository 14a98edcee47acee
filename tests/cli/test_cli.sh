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
# the mission model types too, and their variables: the names of set:, end: and the files
expect 0 "^dof3 +3-DoF .*\(planet world\)" -- "$lvsim" models
expect 0 "^flat6 +point mass with the paper.s 13 states .*\(flat world\)" -- "$lvsim" models
expect 0 "^state +r_eci_x +m " -- "$lvsim" vars dof3
expect 0 "^output +q_dyn +Pa " -- "$lvsim" vars dof3
expect 0 "^mission +start_lat +rad " -- "$lvsim" vars dof3
expect 0 "^# end conditions \('end:'\): burnout altitude speed apogee impact" -- "$lvsim" vars dof3
expect 0 "^# phase keys of its own: inputs aero" -- "$lvsim" vars dof3
expect 0 "^state +z +m " -- "$lvsim" vars flat6
expect 0 "^derivative +der\(vz\) +m/s2 " -- "$lvsim" vars flat6
# the registered types as `lvsim models` lists them (no list of names kept by hand here)
types=$("$lvsim" models | awk '/^# built-in/ { exit } !/^#/ { printf "%s%s", s, $1; s = " " }')
expect 2 "unknown model 'dof4'; mission model types: $types; built-in models: vertical_ascent" -- "$lvsim" vars dof4
expect 0 "^parameter +thrust +N" -- "$lvsim" vars vertical_ascent
expect 2 "unknown model 'nope'" -- "$lvsim" vars nope
# lvsim laws: the registered laws with their keys (lv_laws_get), and the types that take them
expect 0 "^# 'guidance:' laws \('lvsim laws'\): attitude gravity_turn linear_tangent" -- "$lvsim" vars dof3
expect 0 "^# 'throttle:' laws \('lvsim laws'\): nominal landing off" -- "$lvsim" vars dof3
expect 0 "^gravity_turn: vertical rise" -- "$lvsim" laws
expect 0 "^  kick\[_deg\] +rad +\[0, 90\] deg +required " -- "$lvsim" laws gravity_turn
expect 0 "^  q_gain +1/s +\(0, 100\] 1/s +1 1/s .*\(with q_max\)" -- "$lvsim" laws nominal
expect 0 "^\| \| .bank_max. \(._deg.\) \| rad \| \(0, 90\] deg \| 45 deg \|" -- "$lvsim" laws --markdown
expect 2 "unknown law 'gravity'; the laws: inputs attitude gravity_turn" -- "$lvsim" laws gravity
expect 2 "laws takes at most one law name" -- "$lvsim" laws heading off
expect 2 "unknown command 'fly'" -- "$lvsim" fly
# Free fall from 100 m: impact at sqrt(2 h / g) = 4.51523641 s (g = 9.81)
expect 0 "time += 4.515236" -- "$lvsim" simulate free_fall --stop 10 --tolerance 1e-10 --method dopri5 --final time -o "$work/ff"
[ -f "$work/ff.mat" ] && [ -f "$work/ff.csv" ] && pass=$((pass + 1)) || { echo "FAIL: result files"; fails=$((fails + 1)); }
# result files that exist (lvsim cannot prove it wrote them: a Dymola dsres.mat, say) are
# refused, untouched, unless --force
before=$(sha256sum < "$work/ff.mat")
expect 2 "ff.mat' exists: lvsim does not replace a file it cannot prove it wrote" -- "$lvsim" simulate free_fall --stop 1 -o "$work/ff"
[ "$before" = "$(sha256sum < "$work/ff.mat")" ] && pass=$((pass + 1)) || { echo "FAIL: a refused simulate changed ff.mat"; fails=$((fails + 1)); }
expect 0 "result: $work/ff.mat, $work/ff.csv" -- "$lvsim" simulate free_fall --stop 1 -o "$work/ff" --force
expect 0 '"ok":[[:space:]]*true' -- "$lvsim" simulate oscillator --json --format none --final x
expect 2 "did you mean 'thrust'" -- "$lvsim" simulate vertical_ascent --set thrus=1 --format none
expect 2 "is not a finite number" -- "$lvsim" simulate oscillator --stop abc
# counts as --max-rows takes them: 1e1 runs, 1e9 steps (issue 22's breaker)
expect 0 "ok at t = 1 s" -- "$lvsim" simulate free_fall --max-steps 1e9 --format none
expect 2 "--max-steps: '3e9' is not a whole count from 1 to 2147483647" -- "$lvsim" simulate free_fall --max-steps 3e9 --format none
expect 2 "-n needs a whole run count >= 1, got '1.5'" -- "$lvsim" mc "$(dirname "$0")/../../examples/dof3-branch/mission.yaml" -n 1.5 -o "$work/mcn"
# view of a folder that is no run's names what it is, suggesting no command lvsim refuses
expect 2 "'/etc' is not a results folder \(no summary.json\): give the folder of a run" -- "$lvsim" view /etc
# numbers as written: strtod's hexadecimal ("0x10" = 16) and leading blanks are refused
expect 2 "is not a finite number" -- "$lvsim" simulate oscillator --stop 0x10 --format none
expect 2 "is not a finite number" -- "$lvsim" simulate oscillator --stop " 1" --format none
# a start a hair above the ground is an impact at the start, not a fall through it (CVODE
# resolves no root that close to t0: issue 22's breaker, F1; h(t) = h0 - g t^2/2 crosses 0
# at t = 4.5e-151 s)
expect 0 "ok at t = 0 s \(impact\)" -- "$lvsim" simulate free_fall --set h=1e-300 --format none
# a refused --set names the option, not Dymola's initialNames[k], and prints no report
out=$("$lvsim" simulate free_fall --set h=-1 --format none 2>&1); rc=$?
[ "$rc" -eq 2 ] && grep -q "h = -1 m is below its lower bound 0 m" <<<"$out" && ! grep -q "initialNames\|steps" <<<"$out" \
  && pass=$((pass + 1)) || { echo "FAIL: simulate --set h=-1: exit $rc: $out"; fails=$((fails + 1)); }
expect 2 "--method needs an integration method \(dassl, cvode-adams, dopri5, rk4, euler, dp5, dop853, auto\), got .rk45." -- "$lvsim" simulate oscillator --method rk45 --format none
expect 2 "stopTime -1 s is before startTime 0 s" -- "$lvsim" simulate oscillator --stop -1 --format none
expect 2 "unknown option '--bogus'" -- "$lvsim" simulate oscillator --bogus
# A run that fails in the integrator exits 3 and names model, time and reason.
expect 3 "model 'oscillator': at t = .* too much work" -- "$lvsim" simulate oscillator --stop 1000 --max-steps 50 --format none
# simulate bounded and stoppable (issue 22's breaker: --interval 1e-12 wrote 82 GB until the
# disk was full, -o "" and -o /dev/null were taken): a model without events is refused beyond
# --max-rows before it runs, one with events stopped there with its files marked failed
expect 2 "give a file path without extension" -- "$lvsim" simulate free_fall -o ""
# -o names a stem: a folder or a name with the extension is refused, not turned into
# "..mat" or "x.mat.mat" (issue 22's breaker)
expect 2 "'\.' is a folder: give a file path without extension in it" -- "$lvsim" simulate free_fall -o .
expect 2 "give the path without its extension \('$work/x'\)" -- "$lvsim" simulate free_fall -o "$work/x.mat"
[ ! -e "$work/x.mat.mat" ] && [ ! -e ..mat ] && pass=$((pass + 1)) || { echo "FAIL: simulate wrote x.mat.mat or ..mat"; fails=$((fails + 1)); }
expect 2 "'/dev/null' is a device, pipe or socket" -- "$lvsim" simulate free_fall -o /dev/null
[ ! -e /dev/null.mat ] && pass=$((pass + 1)) || { echo "FAIL: simulate wrote /dev/null.mat"; fails=$((fails + 1)); }
expect 2 "model 'oscillator' would write 1e\+10 rows \(10 s at the --interval\) - more than the limit of 1000000 rows" -- "$lvsim" simulate oscillator --interval 1e-9 --stop 10
expect 3 "stopped at t = 1e-06 s by the row limit: 1000 output rows" -- "$lvsim" simulate free_fall --interval 1e-9 --stop 10 --max-rows 1000 -o "$work/ffrows"
[ -e "$work/ffrows.failed.mat" ] && pass=$((pass + 1)) || { echo "FAIL: the row limit left no ffrows.failed.mat"; fails=$((fails + 1)); }
"$lvsim" simulate free_fall --interval 1e-7 --stop 100 --max-rows 1e12 --format none > "$work/ffint.out" 2>&1 &
pid=$!
sleep 0.5
t0=$(date +%s.%N); kill -INT $pid; wait $pid; rc=$?
dt=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
echo "simulate: SIGINT: exit $rc after $dt s"
if [ "$rc" -eq 130 ] && awk -v d="$dt" 'BEGIN { exit !(d < 1.0) }' && grep -q "cancelled at t =" "$work/ffint.out"; then
  pass=$((pass + 1))
else
  echo "FAIL: simulate interrupted: exit $rc after $dt s (want 130 within 1 s)"; cat "$work/ffint.out"; fails=$((fails + 1))
fi
# a command stuck where it cannot see the signal (SUNDIALS on an absurd scale: issue 22's
# breaker, F2) still ends within the 5 s grace of the first SIGINT, exit 130
"$lvsim" simulate free_fall --format none --stop 1e300 --set h=1e300 > "$work/ffstuck.out" 2>&1 &
pid=$!
sleep 0.3
t0=$(date +%s.%N); kill -INT $pid; wait $pid; rc=$?
dt=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
if [ "$rc" -eq 130 ] && awk -v d="$dt" 'BEGIN { exit !(d < 7.0) }'; then
  pass=$((pass + 1))
else
  echo "FAIL: a stuck simulate: exit $rc after $dt s (want 130 within the 5 s grace)"; cat "$work/ffstuck.out"; fails=$((fails + 1))
fi
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
expect 0 "^5 +P5 +P2 .* done$" -- "$lvsim" run "$src/examples/paper-test-case/mission.yaml" -o "$work/run"
[ -f "$work/run/summary.json" ] && [ -f "$work/run/mission.czml" ] && [ -f "$work/run/mission.kml" ] \
  && pass=$((pass + 1)) || { echo "FAIL: run outputs"; fails=$((fails + 1)); }
expect 0 '"mission":' -- "$lvsim" run "$src/examples/paper-test-case/mission.yaml" -o "$work/run2" --json
expect 0 "number of states +39 +13" -- "$lvsim" compare "$src/examples/paper-test-case/mission.yaml"
expect 0 "^export czml: wrote $work/run/mission.czml$" -- "$lvsim" export "$work/run" --format czml
expect 2 "'$work/nothing' is not a results folder" -- "$lvsim" export "$work/nothing"
expect 2 "^lvsim: --format: unknown export 'xczml' \(known: czml, kml, oem(, [a-z0-9]+)*\)$" -- "$lvsim" export "$work/run" --format xczml
expect 0 "^export kml: wrote $work/run/mission.kml$" -- "$lvsim" export "$work/run" --format oem,kml
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
# lvsim view: a busy --port exits 2 naming it (no Python traceback); without --port it serves
# on a free port and says where, with its token (the server is python3 on lvsim's own socket;
# the server itself: tests/viewer/test_view_server.py)
/usr/bin/python3 -c 'import socket, sys, time
s = socket.socket(); s.bind(("127.0.0.1", 0)); s.listen(1)
print(s.getsockname()[1], flush=True); time.sleep(20)' > "$work/busy.port" &
busy_pid=$!
for _ in $(seq 100); do [ -s "$work/busy.port" ] && break; sleep 0.05; done
busy=$(cat "$work/busy.port")
out=$(env LVSIM_DATA="$work/data" "$lvsim" view "$work/run" --port "$busy" 2>&1); rc=$?
[ "$rc" -eq 2 ] && grep -q "port $busy on 127.0.0.1 is busy" <<<"$out" && ! grep -q Traceback <<<"$out" \
  && pass=$((pass + 1)) || { echo "FAIL: view on a busy port: exit $rc: $out"; fails=$((fails + 1)); }
kill "$busy_pid" 2> /dev/null; wait "$busy_pid" 2> /dev/null
env LVSIM_DATA="$work/data" "$lvsim" view "$work/run" > "$work/view.out" 2>&1 &
view_pid=$!
for _ in $(seq 100); do grep -q "^lvsim view: http" "$work/view.out" && break; sleep 0.05; done
url=$(sed -n 's|^lvsim view: \(http://127.0.0.1:[0-9]*/[0-9a-f]*\)/viewer/ .*|\1|p' "$work/view.out")
code=$(/usr/bin/python3 -c "import sys, urllib.request, time
for i in range(50):
    try:
        print(urllib.request.urlopen(sys.argv[1] + '/summary.json', timeout=2).status); break
    except OSError: time.sleep(0.1)" "$url" 2>&1)
[ -n "$url" ] && [ "$code" = "200" ] && pass=$((pass + 1)) \
  || { echo "FAIL: lvsim view serves: url '$url', status '$code': $(cat "$work/view.out")"; fails=$((fails + 1)); }
kill -INT "$view_pid" 2> /dev/null # Ctrl-C: the server ends quietly
for _ in $(seq 100); do kill -0 "$view_pid" 2> /dev/null || break; sleep 0.05; done
kill -9 "$view_pid" 2> /dev/null && { echo "FAIL: lvsim view did not end at SIGINT"; fails=$((fails + 1)); }
wait "$view_pid" 2> /dev/null
grep -q Traceback "$work/view.out" && { echo "FAIL: lvsim view printed a traceback"; fails=$((fails + 1)); } \
  || pass=$((pass + 1))
cat > "$work/fail.yaml" <<YAML
mission: {name: fails}
stages: [{name: a, dry_mass: 100, propellant_mass: 900, engines: [{table: {file: $work/short.csv, extrap: error}}]}]
phases: [{name: p, model: flat6, stages: [a], stop_time: 200}]
YAML
printf 't [s], thrust [N], mdot [kg/s]\n0, 30000, 10\n50, 30000, 10\n' > "$work/short.csv"
expect 3 "phase 'p'.*outside" -- "$lvsim" run "$work/fail.yaml" -o "$work/failrun"


# lvsim vars TYPE lists exactly the columns of that type's phase files (time aside)
"$lvsim" run "$src/examples/dof3-branch/mission.yaml" -o "$work/d3" -q --no-plots > /dev/null 2>&1
for pair in "dof3 $work/d3/phase_1_ascent.csv" "flat6 $work/run/phase_1_P1.csv"; do
  set -- $pair
  want=$(head -1 "$2" | tr ',' '\n' | sed 's/ \[.*//' | grep -v '^time$' | sort)
  got=$("$lvsim" vars "$1" | awk '$1 == "state" || $1 == "derivative" || $1 == "output" {print $2}' | sort)
  [ -n "$want" ] && [ "$want" = "$got" ] && pass=$((pass + 1)) \
    || { echo "FAIL: lvsim vars $1 and the columns of $2 differ:"; diff <(echo "$want") <(echo "$got") | head; fails=$((fails + 1)); }
done
set -- "$lvsim"
# Bounded output: check and run estimate each phase's rows and refuse beyond --max-rows
mission="$src/examples/paper-test-case/mission.yaml"
expect 0 "^1 +P1 +281 +33 " -- "$lvsim" check "$mission"
# every phase over the limit named (its children at least from its stop time: 140 .. 280 s and
# 280 .. 600 s at 0.5 s), and a limit that allows them all (issue 22's breaker)
expect 2 "phase 1 'P1' would write up to 281 rows .*limit of 100 rows per phase.*phases 2 'P2' \\(281 rows\\), 3 'P3' \\(641 rows\\) are over it too.*--max-rows 641" -- \
  "$lvsim" check "$mission" --max-rows 100
expect 0 "is valid" -- "$lvsim" check "$mission" --max-rows 1251
expect 2 "phase 1 'P1' would write up to 281 rows" -- "$lvsim" run "$mission" -o "$work/limited" --max-rows 100
[ ! -e "$work/limited" ] && pass=$((pass + 1)) || { echo "FAIL: a refused run wrote $work/limited"; fails=$((fails + 1)); }
cp -R "$src/examples/paper-test-case" "$work/huge"
sed -i 's/output_interval: 0.5/output_interval: 1.0e-7/' "$work/huge/mission.yaml"
expect 2 "phase 1 'P1' would write up to 1.4e\\+09 rows .*370 GB of .mat, 1.02 TB of .csv.*--max-rows 3.21e\\+09\\)" -- "$lvsim" check "$work/huge/mission.yaml"
expect 2 "--max-rows needs a whole number from 1 to 1e15, got '1.5'" -- "$lvsim" check "$mission" --max-rows 1.5
# a generous stop_time with end: [burnout] (issue 22): the stop time bounds nothing worth
# refusing, the end comes first; check and run accept it (dof3-branch's ascent burns out at
# 137.9 s whatever its stop time), the table says the limit holds as it runs
cp -R "$src/examples/dof3-branch" "$work/generous"
sed -i 's/stop_time: 400/stop_time: 1.0e30/; s/stop_time: 2000/stop_time: 2.0e30/; s/stop_time: 3000/stop_time: 3.0e30/' "$work/generous/mission.yaml"
expect 0 "^1 +ascent +1e\+30 +[0-9]+ .*an end event: rows limited as it runs" -- "$lvsim" check "$work/generous/mission.yaml"
expect 0 "^1 +ascent +- +0.000 +137.906 +burnout " -- "$lvsim" run "$work/generous/mission.yaml" -o "$work/generous_out" --no-plots
# ... and a phase whose end never fires is stopped at the row limit as it runs: no gravity
# to speak of, at rest, an altitude end 1e9 m up; a row every second: stopped at t = 1000 s
# with 1000 rows, files kept as *.failed.*, exit 3
cat > "$work/never.yaml" <<'YAML'
mission: {name: never}
environment: {world: flat, g: 1.0e-9}
stages:
  - {name: s, dry_mass: 100, propellant_mass: 0}
phases:
  - {name: coast, model: flat6, stages: [s], stop_time: 1.0e30, end: [{altitude: 1.0e9}],
     integrator: {output_interval: 1.0}}
YAML
expect 0 "^1 +coast +1e\+30 " -- "$lvsim" check "$work/never.yaml" --max-rows 1000
expect 3 "phase 'coast': stopped at t = 1000 s by the row limit: 1000 output rows \(max_rows\) and no end of the run reached.*--max-rows" -- \
  "$lvsim" run "$work/never.yaml" -o "$work/never_out" --max-rows 1000 --no-plots
rows=$(($(grep -vc '^#' "$work/never_out/phase_1_coast.failed.csv") - 1))  # header, comments: no rows
[ "$rows" -eq 1000 ] && pass=$((pass + 1)) || { echo "FAIL: the stopped phase's file has $rows rows (want 1000)"; fails=$((fails + 1)); }

# A throttle law that cannot be followed (issue 27): one engine of two whose minimum throttle
# 0.85 is more than the landing law comes to ask (tests/unit/test_engines.c: at 9.307 s): a
# warning names the phase, the event and the time; `check` and `run` accept the same file and
# refuse the same bad count (file:line:column)
cat > "$work/sat.yaml" <<'YAML'
mission: {name: landing-min}
environment:
  world: planet
  planet: {name: flatland, radius: 1.0e10, gm: 9.80665e20, rotation_rate: 0}
  atmosphere: none
parameters: {start_h: 2000, start_vel: 181, start_fpa_deg: -90}
stages: [{name: s, dry_mass: 20000, propellant_mass: 10000,
          engines: [{name: m1, count: 2, thrust_vac: 600000, isp_vac: 300, throttle_min: 0.85}]}]
phases:
  - {name: land, model: dof3, stages: [s], stop_time: 40, engines: 1,
     end: [impact, {speed: 1, direction: falling}],
     guidance: {law: retrograde}, throttle: {landing: {altitude: 0, speed: 2}}}
YAML
expect 0 "is valid: 1 phases" -- "$lvsim" check "$work/sat.yaml"
expect 0 "warning: phase 'land': the commanded throttle asked for less than the running engines' minimum throttle from t = 9.307 s" -- \
  "$lvsim" run "$work/sat.yaml" -o "$work/sat_out" --no-plots
# slower at the start (150 m/s): saturated from the first row, where no crossing is logged
sed 's/start_vel: 181/start_vel: 150/' "$work/sat.yaml" > "$work/sat0.yaml"
expect 0 "warning: phase 'land': the commanded throttle asked for less than the running engines' minimum throttle from t = 0.000 s \(the phase's start\)" -- \
  "$lvsim" run "$work/sat0.yaml" -o "$work/sat0_out" --no-plots
sed 's/engines: 1,/engines: 3,/' "$work/sat.yaml" > "$work/sat3.yaml"
expect 2 "sat3.yaml:10:68: phase 'land': engines: 3 engines cannot run: stage 's' has 2 of engine 'm1'" -- \
  "$lvsim" check "$work/sat3.yaml"
expect 2 "sat3.yaml:10:68: phase 'land': engines: 3 engines cannot run" -- \
  "$lvsim" run "$work/sat3.yaml" -o "$work/sat3_out" --no-plots

# Progress: not on a terminal one line per post-processing step on stderr; --quiet: none; on
# a terminal (script(1) gives one) a live line that is redrawn in place
"$lvsim" run "$mission" -o "$work/prog" > "$work/prog.out" 2> "$work/prog.err"
grep -qE "^lvsim: plots and index.html \([0-9.]+ s\)$" "$work/prog.err" && ! grep -q "lvsim: " "$work/prog.out" \
  && pass=$((pass + 1)) || { echo "FAIL: progress lines: $(cat "$work/prog.err")"; fails=$((fails + 1)); }
"$lvsim" run "$mission" -o "$work/prog" --quiet > /dev/null 2> "$work/prog.err"
# (LeakSanitizer's report of its suppressions may be there under ASan: not lvsim's)
! grep -qE "^lvsim: |running " "$work/prog.err" && pass=$((pass + 1)) \
  || { echo "FAIL: --quiet printed: $(cat "$work/prog.err")"; fails=$((fails + 1)); }
if command -v script > /dev/null; then
  script -qec "$lvsim run $mission -o $work/prog" /dev/null > "$work/tty.out" 2>&1
  grep -q $'\r\033\[Kplots and index.html \.\.\.' "$work/tty.out" \
    && grep -qE $'\r\033\[Krunning P1 t = [0-9.]+ s \\(limit 140 s\\)' "$work/tty.out" && pass=$((pass + 1)) \
    || { echo "FAIL: no live progress line on a terminal: $(head -c 300 "$work/tty.out" | od -c | head -5)"; fails=$((fails + 1)); }
fi
# the phase table in run order (1..5), whatever order the branches finish in
"$lvsim" run "$mission" -o "$work/order" --threads 4 -q | awk '/^[0-9]+ +P/ {print $1}' | tr '\n' ' ' | grep -qx "1 2 3 4 5 " \
  && pass=$((pass + 1)) || { echo "FAIL: phase table not in run order"; fails=$((fails + 1)); }


# Usage and help come from the command table (cli/cli.h): every command, including those that
# take no arguments, answers --help, -h and `lvsim help CMD` with exit 0 and its own usage line,
# on stdout; `lvsim help` lists every command with its one-line summary.
mission="$src/examples/paper-test-case/mission.yaml"
commands="models vars laws simulate run check params compare export formats plot view atmosphere gravity help version"
for c in $commands; do
  expect 0 "^usage: lvsim $c( |\$)" -- "$lvsim" "$c" --help
  expect 0 "^usage: lvsim $c( |\$)" -- "$lvsim" "$c" -h
  expect 0 "^usage: lvsim $c( |\$)" -- "$lvsim" help "$c"
  expect 0 "^  $c +[^ ]" -- "$lvsim" help
  expect 0 "^  $c +[^ ]" -- "$lvsim" --help
done
"$lvsim" run --help 2> /dev/null | grep -q "^  -o OUTDIR .*(default lvsim-out)" && pass=$((pass + 1)) \
  || { echo "FAIL: run --help on stdout lists -o with its default"; fails=$((fails + 1)); }
# --help anywhere among the arguments wins: nothing is checked, run or written
expect 0 "^usage: lvsim check MISSION.yaml" -- "$lvsim" check "$src/tests/missions/bad_cycle.yaml" --help
expect 0 "^usage: lvsim run MISSION.yaml" -- "$lvsim" run "$mission" -o "$work/helprun" --help
[ ! -e "$work/helprun" ] && pass=$((pass + 1)) || { echo "FAIL: run --help wrote $work/helprun"; fails=$((fails + 1)); }
expect 0 "^usage: lvsim simulate MODEL" -- "$lvsim" simulate oscillator --stop 1 --help
expect 2 "unknown command 'nope'" -- "$lvsim" help nope
expect 2 "help takes at most one command name" -- "$lvsim" help run check
expect 2 "usage: lvsim COMMAND" -- "$lvsim"
expect 0 "^lvsim [0-9]+\.[0-9]+\.[0-9]+$" -- "$lvsim" version
expect 0 "^lvsim [0-9]+\.[0-9]+\.[0-9]+$" -- "$lvsim" --version
# unknown commands: did you mean, among the command names (typos and abbreviations)
expect 2 "unknown command 'simulat'; did you mean 'simulate'\?" -- "$lvsim" simulat
expect 2 "unknown command 'plto'; did you mean 'plot'\?" -- "$lvsim" plto
expect 2 "unknown command 'param'; did you mean 'params'\?" -- "$lvsim" param
expect 2 "did you mean 'atmosphere'" -- "$lvsim" atmo
# an unknown option is named, with the command's help to see
for c in models vars laws run check params compare export formats plot view atmosphere gravity version; do
  expect 2 "unknown option '--bogus'" -- "$lvsim" "$c" --bogus
  expect 2 "^\(see 'lvsim help $c'\)" -- "$lvsim" "$c" --bogus
done
expect 2 "^\(see 'lvsim help simulate'\)" -- "$lvsim" simulate oscillator --bogus
expect 2 "unexpected argument 'extra'" -- "$lvsim" run "$mission" extra
expect 2 "models takes no arguments; got 'extra'" -- "$lvsim" models extra
# lvsim formats: the registered result formats and exports (one table each in the libraries)
expect 0 "^  csv +\.csv +CSV" -- "$lvsim" formats results
expect 0 "^  oem +<stage>\.oem +CCSDS OEM" -- "$lvsim" formats
expect 2 "expected 'results' or 'exports', got 'pdf'" -- "$lvsim" formats pdf

# lvsim params: the run parameters, with their values and lines in the mission file; angles
# in rad (start_fpa_deg: 90 -> pi/2); per-phase defaults the file does not write.
line_prop=$(grep -n "propellant_mass: 27000" "$mission" | head -1 | cut -d: -f1)
line_stop=$(grep -n "stop_time: 140 " "$mission" | head -1 | cut -d: -f1)
expect 0 "^stage1\.propellant_mass +27000 +kg +>= 0 +$line_prop\$" -- "$lvsim" params "$mission"
expect 0 "^P1\.stop_time +140 +s +[^ ].* $line_stop\$" -- "$lvsim" params "$mission"
expect 0 "^start_fpa +1\.570796327 +rad " -- "$lvsim" params "$mission"
expect 0 "^environment\.g +9\.81 +m/s2 +> 0 " -- "$lvsim" params "$mission"
expect 0 "^P[0-9]\.[a-z_.]+ +[-0-9.e+]+ +[^ ]+ +.* default\$" -- "$lvsim" params "$mission"
expect 0 "^# mission 'paper-test-case' .*: [0-9]+ parameters" -- "$lvsim" params "$mission"
expect 2 "bad_cycle.yaml:[0-9]+:[0-9]+: phase .*cycle" -- "$lvsim" params "$src/tests/missions/bad_cycle.yaml"
expect 2 "nothing.yaml: cannot open" -- "$lvsim" params "$work/nothing.yaml"
expect 2 "params needs a mission file" -- "$lvsim" params
# check, run and params read a mission with the same call: the same file, the same answer
expect 2 "bad_cycle.yaml:[0-9]+:[0-9]+: phase .*cycle" -- "$lvsim" run "$src/tests/missions/bad_cycle.yaml" -o "$work/cyc"
[ ! -e "$work/cyc" ] && pass=$((pass + 1)) || { echo "FAIL: run of a bad mission wrote $work/cyc"; fails=$((fails + 1)); }

# JSON documents (built with cJSON) parse, with their keys and value types
json_ok() { # json_ok WHAT FILE PYTHON-ASSERTIONS (d: the document)
  if python3 -c "import json,sys; d=json.load(open(sys.argv[1])); $3" "$2" 2> "$work/json.err"; then
    pass=$((pass + 1))
  else
    echo "FAIL: $1: $(tail -1 "$work/json.err")"; head -c 400 "$2"; echo; fails=$((fails + 1))
  fi
}
num='lambda v: isinstance(v, (int, float)) and not isinstance(v, bool)'
"$lvsim" simulate oscillator --json --format none --final x --final time > "$work/sim.json"; rc=$?
[ "$rc" -eq 0 ] && pass=$((pass + 1)) || { echo "FAIL: simulate --json exit $rc"; fails=$((fails + 1)); }
json_ok "simulate --json" "$work/sim.json" "n=$num
assert list(d) == ['model', 'ok', 'method', 'tolerance', 'end_time', 'stop', 'stats', 'final'], list(d)
assert d['model'] == 'oscillator' and d['ok'] is True and d['method'] == 'dassl' and d['stop'] == 'stop_time'
assert n(d['tolerance']) and n(d['end_time']) and abs(d['end_time'] - 1) < 1e-12
assert set(d['stats']) == {'states', 'steps', 'rhs_evals', 'rhs_evals_steps', 'rhs_evals_output', 'row_evals', 'jac_evals', 'state_events', 'time_events', 'restarts', 'rows', 'cpu_time'}
assert d['stats']['rhs_evals'] == d['stats']['rhs_evals_steps'] + d['stats']['rhs_evals_output']
assert all(n(v) for v in d['stats'].values()) and d['stats']['states'] == 2 and d['stats']['rows'] == 501
assert list(d['final']) == ['x', 'time'] and n(d['final']['x']) and d['final']['time'] == 1"
"$lvsim" simulate oscillator --json --stop 1000 --max-steps 50 --format none > "$work/simfail.json" 2> /dev/null; rc=$?
[ "$rc" -eq 3 ] && pass=$((pass + 1)) || { echo "FAIL: failed simulate --json exit $rc (want 3)"; fails=$((fails + 1)); }
json_ok "failed simulate --json" "$work/simfail.json" "
assert d['ok'] is False and 'too much work' in d['error'] and d['stop'] == 'failed' and d['final'] == {}
assert d['stats']['steps'] == 50"
"$lvsim" compare "$mission" --json > "$work/cmp.json"; rc=$?
[ "$rc" -eq 0 ] && pass=$((pass + 1)) || { echo "FAIL: compare --json exit $rc"; fails=$((fails + 1)); }
json_ok "compare --json" "$work/cmp.json" "n=$num
assert list(d) == ['mission', 'output_interval', 'end_to_end', 'sequential', 'bodies'], list(d)
assert d['mission'].endswith('mission.yaml') and d['output_interval'] == 1
for s in ('end_to_end', 'sequential'):
    assert list(d[s]) == ['method', 'tolerance', 'states', 'state_events', 'time_events', 'steps', 'rhs_evals', 'rhs_evals_steps', 'rhs_evals_output', 'jac_evals', 'cpu_time'], list(d[s])
    assert d[s]['rhs_evals'] == d[s]['rhs_evals_steps'] + d[s]['rhs_evals_output']
    assert d[s]['method'] == 'dassl' and abs(d[s]['tolerance'] - 1e-7) < 1e-20
    assert all(n(v) for k, v in d[s].items() if k != 'method')
assert d['end_to_end']['states'] == 39 and d['sequential']['states'] == 13
assert [b['name'] for b in d['bodies']] == ['stage1', 'stage2', 'stage3']
for b in d['bodies']:
    assert list(b) == ['name', 'common_times', 'max_dpos', 'max_dvel', 'max_dmass'] and all(n(b[k]) for k in list(b)[1:])
    assert b['common_times'] > 100 and 0 <= b['max_dpos'] < 100"
# one vocabulary in summary.json: run status, phase states, end reasons, time events named by
# their source (the stage's thrust-table breakpoint at the event's own time)
json_ok "run summary.json words" "$work/run/summary.json" "import re
assert d['status'] == 'ok' and [p['index'] for p in d['phases']] == [1, 2, 3, 4, 5]
assert [p['name'] for p in d['phases']] == ['P1', 'P2', 'P3', 'P4', 'P5']
assert all(p['state'] == 'done' and p['end']['reason'] in ('stop_time', 'event') for p in d['phases'])
tev = [(p, e) for p in d['phases'] for e in p['events'] if e['kind'] == 'time']
assert len(tev) == 3, tev
for p, e in tev:
    m = re.fullmatch(r\"stage '(\\w+)' thrust table breakpoint t = ([0-9.]+) s\", e['name'])
    assert m and m.group(1) == p['stages'][0] and float(m.group(2)) == e['t'], e
assert all(e['name'] in ('burnout', 'impact') for p in d['phases'] for e in p['events'] if e['kind'] == 'state')"
"$lvsim" params "$mission" --json > "$work/params.json"; rc=$?
[ "$rc" -eq 0 ] && pass=$((pass + 1)) || { echo "FAIL: params --json exit $rc"; fails=$((fails + 1)); }
n_text=$("$lvsim" params "$mission" | grep -vc '^#')
json_ok "params --json" "$work/params.json" "n=$num
assert isinstance(d, list) and len(d) == $n_text, len(d)
assert all(list(p) == ['name', 'value', 'unit', 'rule', 'line'] and n(p['value']) for p in d)
p = {q['name']: q for q in d}
assert p['stage1.propellant_mass'] == {'name': 'stage1.propellant_mass', 'value': 27000, 'unit': 'kg', 'rule': '>= 0', 'line': $line_prop}, p['stage1.propellant_mass']
assert p['P1.stop_time']['value'] == 140 and p['P1.stop_time']['unit'] == 's' and p['P1.stop_time']['line'] == $line_stop
assert any(q['line'] is None for q in d) and all(q['line'] is None or q['line'] > 0 for q in d)"

# --outputs: only what is asked for is written; 'none' writes nothing, not even the folder;
# the exports need the files they read; unknown names are refused
expect 0 "manifest.json, summary.json, 5 phase files" -- "$lvsim" run "$mission" -o "$work/out_some" --outputs csv,summary
files=$(cd "$work/out_some" && ls | tr '\n' ' ')
[ "$files" = "manifest.json phase_1_P1.csv phase_2_P2.csv phase_3_P3.csv phase_4_P4.csv phase_5_P5.csv summary.json " ] \
  && pass=$((pass + 1)) || { echo "FAIL: --outputs csv,summary wrote: $files"; fails=$((fails + 1)); }
grep -q '"mat"' "$work/out_some/summary.json" || grep -q '"trajectory"' "$work/out_some/summary.json" \
  && { echo "FAIL: summary.json names files that were not written"; fails=$((fails + 1)); } || pass=$((pass + 1))
expect 0 "nothing written" -- "$lvsim" run "$mission" -o "$work/out_none" --outputs none
[ ! -e "$work/out_none" ] && pass=$((pass + 1)) || { echo "FAIL: --outputs none made $work/out_none"; fails=$((fails + 1)); }
expect 0 "manifest.json, mission.kml, summary.json" -- "$lvsim" run "$mission" -o "$work/out_kml" --outputs body,summary,kml --no-plots
[ -f "$work/out_kml/mission.kml" ] && [ ! -e "$work/out_kml/mission.czml" ] && [ ! -e "$work/out_kml/phase_1_P1.mat" ] \
  && pass=$((pass + 1)) || { echo "FAIL: --outputs body,summary,kml"; fails=$((fails + 1)); }
expect 2 "czml, kml(, [a-z0-9]+)* and [a-z0-9]+ read summary and body" -- "$lvsim" run "$mission" -o "$work/out_bad" --outputs czml
# format lists take exact names (one parser, cli/common.c): the error names the option and
# lists the known names, in the order of the library's tables (later ones may follow)
expect 2 "^lvsim: --outputs: unknown output 'pdf' \(known: mat, csv(, [a-z0-9]+)*, body, summary, czml, kml, oem(, [a-z0-9]+)*, none\)$" -- "$lvsim" run "$mission" -o "$work/out_bad" --outputs mat,pdf
expect 2 "unknown output 'xmatx'" -- "$lvsim" run "$mission" -o "$work/out_bad" --outputs xmatx
expect 2 "unknown output ''" -- "$lvsim" run "$mission" -o "$work/out_bad" --outputs mat,,csv
expect 2 "^lvsim: --format: unknown format 'xmatx' \(known: mat, csv(, [a-z0-9]+)*, none\)$" -- "$lvsim" simulate oscillator --format xmatx
expect 2 "^lvsim: --format: 'none' stands alone, not in a list 'mat,none'$" -- "$lvsim" simulate oscillator --format mat,none
expect 0 "^  result: $work/osc_csv.csv$" -- "$lvsim" simulate oscillator -o "$work/osc_csv" --format csv
[ -f "$work/osc_csv.csv" ] && [ ! -e "$work/osc_csv.mat" ] && pass=$((pass + 1)) \
  || { echo "FAIL: simulate --format csv wrote: $(ls "$work"/osc_csv*)"; fails=$((fails + 1)); }
expect 2 "--json prints summary.json" -- "$lvsim" run "$mission" --json --outputs mat

# PLplot is loaded only when a figure is drawn (liblvsim_post dlopens lvsim_plot.so): not by
# check or run --no-plots, by plot
loaded() { LD_DEBUG=files "$@" 2>&1 >/dev/null | grep -c "file=libplplot" || true; }
[ "$(loaded "$lvsim" check "$mission")" -eq 0 ] && [ "$(loaded "$lvsim" run "$mission" -o "$work/ld1" --no-plots)" -eq 0 ] \
  && pass=$((pass + 1)) || { echo "FAIL: PLplot loaded without a plot"; fails=$((fails + 1)); }
# libmatio (and the ~40 libraries of its HDF5 build) only when a MAT file is read: result
# files are written without it (the MAT v4 sink streams its own bytes)
matio() { LD_DEBUG=files "$@" 2>&1 >/dev/null | grep -c "file=libmatio" || true; }
d3="$src/examples/dof3-branch/mission.yaml"
[ "$(matio "$lvsim" check "$d3")" -eq 0 ] && [ "$(matio "$lvsim" run "$d3" -o "$work/ld2" --outputs csv,summary)" -eq 0 ] \
  && [ "$(matio "$lvsim" run "$d3" -o "$work/ld3" --outputs mat)" -eq 0 ] && [ -f "$work/ld3/phase_1_ascent.mat" ] \
  && [ "$(matio "$lvsim" check "$mission")" -gt 0 ] \
  && pass=$((pass + 1)) || { echo "FAIL: libmatio loaded without a MAT file to read, or not with one"; fails=$((fails + 1)); }
[ "$(loaded "$lvsim" plot "$work/ld1")" -gt 0 ] && [ -f "$work/ld1/plots/altitude.png" ] \
  && pass=$((pass + 1)) || { echo "FAIL: lvsim plot did not load PLplot or draw"; fails=$((fails + 1)); }

# dof6 inputs from a table: the values held to the constants' ranges, no column unread, no
# input given twice (check refuses what run would)
dof6_yaml() { # dof6_yaml TABLE [INPUT-KEYS]
  cat <<YAML
mission: {name: r}
environment: {world: planet, planet: earth, gravity: j2, atmosphere: none}
parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 1000, start_vel: 1, start_fpa_deg: 89, start_chi_deg: 90}
stages:
  - {name: s1, dry_mass: 20000, propellant_mass: 100000, engines: [{name: e, thrust_vac: 2.0e6, isp_vac: 300}],
     rigid_body: {inertia_full: {xx: 2.0e5, yy: 8.0e6, zz: 8.0e6}, engine_position: {x: -30}}}
phases:
  - {name: P, model: dof6, stages: [s1], stop_time: 2, attitude: {psi_deg: 90, theta_deg: 89}, inputs: {table: $1${2:-}}}
YAML
}
printf 'time [s],throttle\n0,3\n10,3\n' > "$work/thr3.csv"
printf 'time [s],gimbal_pitch [rad]\n0,3\n10,3\n' > "$work/gim3.csv"
printf 'time [s],gimbal_pitch [rad],gimbal_roll [rad]\n0,0,0\n10,0,0\n' > "$work/roll.csv"
printf 'time [s],gimbal_pitch [rad]\n0,0.01\n10,0.01\n' > "$work/gim.csv"
dof6_yaml thr3.csv > "$work/d6a.yaml"; dof6_yaml gim3.csv > "$work/d6b.yaml"
dof6_yaml gim.csv ", gimbal_pitch_deg: 5" > "$work/d6c.yaml"
# a table's throttle beyond the engines' range is clamped and logged, as dof3's (issue 27, M4):
# `check` accepts it and `run` warns from the phase's start; a constant is refused at its value
expect 0 "is valid: 1 phases" -- "$lvsim" check "$work/d6a.yaml"
expect 0 "warning: phase 'P': the commanded throttle asked for more than the running engines' maximum throttle from t = 0.000 s \(the phase's start\)" -- \
  "$lvsim" run "$work/d6a.yaml" -o "$work/d6a" --no-plots
sed 's/inputs: {table: thr3.csv}/inputs: {throttle: 3}/' "$work/d6a.yaml" > "$work/d6k.yaml"
expect 2 "d6k.yaml:8:[0-9]+: phase 'P': inputs: throttle = 3 is outside the throttle range \[0, 1\] of engine 'e'" -- "$lvsim" check "$work/d6k.yaml"
expect 2 "d6k.yaml:8:[0-9]+: phase 'P': inputs: throttle = 3 is outside the throttle range \[0, 1\] of engine 'e'" -- \
  "$lvsim" run "$work/d6k.yaml" -o "$work/d6k" --no-plots
expect 2 "gimbal_pitch = 3 rad at time 0 s is outside \[-pi/2, pi/2\]" -- "$lvsim" run "$work/d6b.yaml" -o "$work/d6b" --no-plots
expect 2 "'gimbal_pitch' is also a column of table 'gim': give it once" -- "$lvsim" check "$work/d6c.yaml"
dof6_yaml roll.csv > "$work/d6d.yaml"
expect 2 "column 'gimbal_roll' is not an input \(gimbal_pitch, gimbal_yaw, throttle\)" -- "$lvsim" check "$work/d6d.yaml"

# a 6-DoF retrograde burn braked to tens of m/s: the command turns faster than the gimbal
# follows and the body tumbles (docs/models.md, "Lost pointing"): run says so, exit 0
cat > "$work/d6tumble.yaml" <<YAML
mission: {name: tumble}
environment: {world: planet, planet: earth, gravity: j2, atmosphere: us76}
parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 20000, start_vel: 300, start_fpa_deg: 0, start_chi_deg: 90}
stages:
  - {name: s1, dry_mass: 1000, propellant_mass: 9000, engines: [{thrust_vac: 200000, isp_vac: 300}],
     rigid_body: {inertia_full: {xx: 1.0e3, yy: 5.0e4, zz: 5.0e4}, cg_full: {x: -5}, engine_position: {x: -10}}}
phases:
  - {name: p, model: dof6, stages: [s1], stop_time: 60, attitude: {psi_deg: 270},
     guidance: {law: retrograde}, end: [impact],
     controller: {pitch: {kp: 1.5, kd: 1.2}, yaw: {kp: 1.5, kd: 1.2}, limit_deg: 6, rate_limit_deg: 20}}
YAML
expect 0 "warning: phase 'p': the pointing error passed 90 deg at t = " -- "$lvsim" run "$work/d6tumble.yaml" -o "$work/d6tumble" --no-plots -q

# lvsim target (issue 13): a drag-free shot over flat ground that must land 800 m away; the
# closed form gives gamma = asin(800 g / v^2) / 2 = 25.8387 deg for 100 m/s
shot() { # shot RANGE: the mission with its targeting section
  cat <<YAML
mission: {name: shot}
environment:
  world: planet
  planet: {name: flatland, radius: 1.0e10, gm: 9.80665e20, rotation_rate: 0}
  atmosphere: none
parameters: {start_h: 0, start_vel: 100, start_fpa_deg: 20, start_chi_deg: 90}  # the gun
stages: [{name: ball, dry_mass: 1, propellant_mass: 0}]
phases:
  - {name: flight, model: dof3, stages: [ball], stop_time: 100, end: [impact],
     integrator: {tolerance: 1.0e-10}}
targeting:
  variables: [{name: start_fpa_deg, min: 5, max: 60, scale: 1}]
  constraints: [{final: flight.downrange, equal: $1, tolerance: 0.001}]
YAML
}
shot 800 > "$work/shot.yaml"
expect 0 "^converged: every constraint met" -- "$lvsim" target "$work/shot.yaml" -o "$work/shot_conv.yaml"
expect 0 "start_fpa_deg += 25\.8387" -- "$lvsim" target "$work/shot.yaml" -q
expect 0 "^ +1  newton  accepted" -- "$lvsim" target "$work/shot.yaml"
# an existing -o file: refused before the solve, untouched; replaced with --force; the
# mission (or a data file) itself never, by any spelling, also with --force
before=$(sha256sum < "$work/shot_conv.yaml")
expect 2 "shot_conv.yaml' exists: lvsim does not replace a file it cannot prove it wrote" -- "$lvsim" target "$work/shot.yaml" -o "$work/shot_conv.yaml"
[ "$before" = "$(sha256sum < "$work/shot_conv.yaml")" ] && pass=$((pass + 1)) || { echo "FAIL: a refused target -o changed the file"; fails=$((fails + 1)); }
cp "$work/shot.yaml" "$work/shot.keep"
expect 2 "it is the mission's file" -- "$lvsim" target "$work/shot.yaml" -o "$work/shot.yaml" --force
expect 2 "it is the mission's file" -- "$lvsim" target "$work/shot.yaml" -o "$work/../$(basename "$work")/shot.yaml"
cmp -s "$work/shot.yaml" "$work/shot.keep" && pass=$((pass + 1)) || { echo "FAIL: target -o changed its mission"; fails=$((fails + 1)); }
expect 0 "reproduces the targeted finals" -- "$lvsim" target "$work/shot.yaml" -o "$work/shot_conv.yaml" --force
grep -q "start_fpa_deg: 25\.838.*start_chi_deg: 90}  # the gun" "$work/shot_conv.yaml" \
  && pass=$((pass + 1)) || { echo "FAIL: the converged file"; fails=$((fails + 1)); }
expect 0 "mission 'shot': 1 phases" -- "$lvsim" run "$work/shot_conv.yaml" -o "$work/shot_out" --no-plots
expect 0 "converged: every constraint is met at the start point" -- "$lvsim" target "$work/shot_conv.yaml"
# 2000 m is out of reach (at most v^2 / g = 1019.7 m): exit 3, the failing constraint named
shot 2000 > "$work/far.yaml"
expect 3 "^failing constraints: flight.downrange" -- "$lvsim" target "$work/far.yaml" -o "$work/far_conv.yaml"
[ ! -e "$work/far_conv.yaml" ] && pass=$((pass + 1)) || { echo "FAIL: a file for an unmet target"; fails=$((fails + 1)); }
expect 3 "^NOT MET: " -- "$lvsim" target "$work/far.yaml" -q
# the section is checked when the mission is loaded: check refuses what target would
sed 's/start_fpa_deg, min/start_fpa_dg, min/' "$work/shot.yaml" > "$work/bad.yaml"
expect 2 "bad.yaml:12:22: targeting: variable 'start_fpa_dg': mission 'shot' has no parameter" -- "$lvsim" check "$work/bad.yaml"
expect 2 "bad.yaml:12:22: targeting: variable 'start_fpa_dg'" -- "$lvsim" target "$work/bad.yaml"
expect 2 "the mission has no \`targeting:\` section" -- "$lvsim" target "$src/examples/dof3-branch/mission.yaml"
expect 2 "--method: auto, newton, slsqp or cobyla expected, got 'simplex'" -- "$lvsim" target "$work/shot.yaml" --method simplex
expect 0 "^usage: lvsim target MISSION.yaml" -- "$lvsim" target --help
# -o is checked before the solve; the counts take the file's ranges
expect 2 "'$work/no-such-dir' does not exist" -- "$lvsim" target "$work/shot.yaml" -o "$work/no-such-dir/c.yaml"
# a symbolic link is the user's, dangling or not: never replaced by an output (issue 22's
# breaker: target, fmu and simulate turned a dangling link into a regular file, exit 0)
ln -s "$work/nowhere.yaml" "$work/dang.yaml"
expect 2 "'$work/dang.yaml' is a symbolic link: lvsim does not replace it" -- "$lvsim" target "$work/shot.yaml" -o "$work/dang.yaml" --force
ln -s "$work/nowhere.mat" "$work/dsim.mat"
expect 2 "'$work/dsim.mat' is a symbolic link" -- "$lvsim" simulate free_fall --stop 1 -o "$work/dsim" --format mat
[ -L "$work/dang.yaml" ] && [ -L "$work/dsim.mat" ] && pass=$((pass + 1)) || { echo "FAIL: a dangling link was replaced"; fails=$((fails + 1)); }
touch "$work/plain.yaml"
expect 2 "'$work/plain.yaml' is a file, not a folder" -- "$lvsim" target "$work/shot.yaml" -o "$work/plain.yaml/c.yaml"
expect 2 "not a folder" -- "$lvsim" target "$work/shot.yaml" -o "$work"
expect 2 "\-\-restarts needs an integer from 0 to 100, got '101'" -- "$lvsim" target "$work/shot.yaml" --restarts 101
expect 0 "^converged" -- "$lvsim" target "$work/shot.yaml" --max-iter 1e3 -q
expect 0 "^converged: slsqp" -- "$lvsim" target "$work/shot.yaml" --method slsqp -q
# a variable the constraint does not depend on (the heading, over a non-rotating planet); with
# cvode-adams, whose round-off noise in the downrange (~1e-6 m on this 1e10 m planet) lets
# Newton's step reach a scale: with auto's dop853 the noise keeps the trust region below one,
# and the diagnosis needs a move of a scale or more (target.c). Which method's noise walks far
# enough is chance: dassl's did until the heat-load quadrature states (two more components in
# the SUNDIALS error weights) changed its round-off; cvode-adams' does since
sed -e 's/start_fpa_deg, min: 5, max: 60, scale: 1/start_chi_deg, min: 0, max: 180/' \
    -e 's/integrator: {tolerance/integrator: {method: cvode-adams, tolerance/' "$work/shot.yaml" > "$work/chi.yaml""
expect 3 "the constraints do not depend on the variables" -- "$lvsim" target "$work/chi.yaml" -q
# a converged value that breaks a cross-phase load rule: the file is not written
# (the parent ends at its apogee, ~3.5 s, long before its stop_time 50 s: the child's stop
# time 5 s runs, but the loader refuses a child stop_time before the parent's)
cat > "$work/two.yaml" <<'YAML'
mission: {name: two}
environment: {world: planet, atmosphere: none}
parameters: {start_h: 0, start_vel: 100, start_fpa_deg: 20, start_chi_deg: 90}
stages: [{name: ball, dry_mass: 1, propellant_mass: 0}]
phases:
  - {name: up, model: dof3, stages: [ball], stop_time: 50, end: [apogee]}
  - {name: down, model: dof3, stages: [ball], from: up, stop_time: 100, end: [impact]}
targeting:
  variables: [{name: down.stop_time, min: 1, max: 100, start: 6}]
  constraints: [{final: down.time, equal: 5, tolerance: 0.01}]
YAML
expect 2 "the converged values make a mission that does not load, not written" -- "$lvsim" target "$work/two.yaml" -o "$work/two_conv.yaml"
[ ! -e "$work/two_conv.yaml" ] && [ ! -e "$work/two_conv.yaml.tmp" ] && pass=$((pass + 1)) || { echo "FAIL: an unloadable converged file was left"; fails=$((fails + 1)); }

# Issue 27, item 2: a converged point where the constrained phase ended by another end than the
# one its constraints assume (the first written, altitude) is reported. A vertical hop over
# flat6's flat ground (g = 9.81, no air): a final time of 5 s is met only by a burnout at 5 s
# (m_p = 5 F / (Isp g0) = 169.95 kg; the altitude end fires at 7.24 s or later, the closed form
# of the rocket equation in tests/unit/test_target.c (i)).
cat > "$work/hop.yaml" <<'YAML'
mission: {name: hop}
stages:
  - {name: s, dry_mass: 1000, propellant_mass: 2000,
     engines: [{name: e, thrust_vac: 100000, isp_vac: 300}]}
phases:
  - {name: burn, model: flat6, stages: [s], stop_time: 100,
     end: [{altitude: 2000, direction: rising}, burnout], integrator: {tolerance: 1.0e-10}}
targeting:
  variables: [{name: s.propellant_mass, min: 10, max: 3000, scale: 100}]
  constraints: [{final: burn.time, equal: 5, tolerance: 0.001}]
YAML
expect 0 "^warning: at the converged point phase 'burn' ended by burnout at t = 4\.99.* s, not by altitude, the end its constraints assume" -- "$lvsim" target "$work/hop.yaml" -o "$work/hop_conv.yaml"
expect 0 "^# lvsim target: WARNING: phase 'burn' ended by burnout at t = 4\.99.* s, not by altitude" -- head -3 "$work/hop_conv.yaml"
expect 0 "^ +s\.propellant_mass += 169\.95" -- "$lvsim" target "$work/hop.yaml" -q
expect 0 "note: phase 'burn' ended by burnout at t = " -- "$lvsim" target "$work/hop.yaml"
expect 3 "lvsim: --strict: converged onto a point where 1 phase\(s\) ended otherwise than the constraints assume \(above\); nothing written" -- "$lvsim" target "$work/hop.yaml" --strict -o "$work/hop_strict.yaml"
[ ! -e "$work/hop_strict.yaml" ] && pass=$((pass + 1)) || { echo "FAIL: target --strict wrote a file"; fails=$((fails + 1)); }
# the end named on the constraint: no warning, and --strict is content
sed 's/tolerance: 0.001}/tolerance: 0.001, end: burnout}/' "$work/hop.yaml" > "$work/hop_named.yaml"
out=$("$lvsim" target "$work/hop_named.yaml" --strict -q 2>&1); rc=$?
[ "$rc" -eq 0 ] && ! grep -q "warning" <<<"$out" && pass=$((pass + 1)) || { echo "FAIL: target with end: burnout -> exit $rc: $out"; fails=$((fails + 1)); }
expect 2 "hop_bad.yaml:10:69: targeting: constraint on 'burn.time': end 'burnot': phase 'burn' has no such end; did you mean 'burnout'\?" -- sh -c "sed 's/tolerance: 0.001}/tolerance: 0.001, end: burnot}/' '$work/hop.yaml' > '$work/hop_bad.yaml' && '$lvsim' check '$work/hop_bad.yaml'"
# the examples converge with every constrained phase ended as assumed: no warning, --strict exit 0
for ex in kourou-leo-targeted kourou-rtls-targeted; do
  out=$("$lvsim" target "$src/examples/$ex/mission.yaml" --strict 2>&1); rc=$?
  [ "$rc" -eq 0 ] && ! grep -q "warning" <<<"$out" && ! grep -q "ended by" <<<"$out" && pass=$((pass + 1)) || { echo "FAIL: target --strict $ex -> exit $rc"; fails=$((fails + 1)); }
done

# Issue 22, item 6: no silent wrong answer from the known classes. Each refusal names the
# file:line:column (a mission file) or the option (the command line) and exits 2; check and
# run refuse the same files.
mission="$src/examples/paper-test-case/mission.yaml"
refused() { # refused PATTERN MISSION: check and run both exit 2 with PATTERN; run writes nothing
  expect 2 "$1" -- "$lvsim" check "$2"
  rm -rf "$work/refused"
  expect 2 "$1" -- "$lvsim" run "$2" -o "$work/refused" -q --no-plots
  [ ! -e "$work/refused" ] && pass=$((pass + 1)) || { echo "FAIL: run of refused $2 wrote"; fails=$((fails + 1)); }
}
# (4) a system error names the system's reason (lv_strerror, the one helper), never "error 2"
ln -s "$work/nowhere/x" "$work/dangling"
expect 2 "results folder '$work/dangling' is a link that leads nowhere: No such file or directory$" -- \
  "$lvsim" run "$mission" -o "$work/dangling" -q --no-plots
cp -R "$src/examples/sounding-rocket" "$work/sr"
touch "$work/sr/plain"
sed 's|CD: cd_mach.csv|CD: plain/cd_mach.csv|' "$work/sr/mission.yaml" > "$work/sr/under_file.yaml"
line=$(grep -n "CD: plain/cd_mach.csv" "$work/sr/under_file.yaml" | cut -d: -f1)
refused "under_file.yaml:$line:[0-9]+: .*cannot read '$work/sr/plain/cd_mach.csv': Not a directory$" "$work/sr/under_file.yaml"
if [ "$(id -u)" -ne 0 ]; then
  mkdir "$work/ro" && chmod 0500 "$work/ro"
  expect 2 "cannot write in '$work/ro' \(the lock file .*\): Permission denied$" -- \
    "$lvsim" run "$mission" -o "$work/ro/out" -q --no-plots
  chmod 0700 "$work/ro"
  chmod 000 "$work/sr/cd_mach.csv"
  refused "cd_mach.csv: cannot open: Permission denied" "$work/sr/mission.yaml"
  chmod 0600 "$work/sr/cd_mach.csv"
else
  echo "skip: as root, file permissions do not stop lvsim: the read-only results parent and the unreadable table are not tried"
fi
# (1) tolerances within [1e-14, 0.1] (lv_sim.h) wherever they enter: a phase (the reproduction:
# tolerance 10 put the sounding rocket's apogee 5 times too high), and every option
sed 's/integrator: {output_interval: 0.5}/integrator: {output_interval: 0.5, tolerance: 10}/' \
  "$src/examples/sounding-rocket/mission.yaml" > "$work/sr/tol10.yaml"
line=$(grep -n "tolerance: 10}" "$work/sr/tol10.yaml" | cut -d: -f1)
refused "tol10.yaml:$line:[0-9]+: phase 'boost', integrator: tolerance must be >= 1e-14 and <= 0.1, found 10$" "$work/sr/tol10.yaml"
expect 0 "^boost\.integrator\.tolerance +1e-09 +1 +>= 1e-14 and <= 0\.1 +default$" -- "$lvsim" params "$src/examples/sounding-rocket/mission.yaml"
for t in 0 -1 10 1e-15; do
  expect 2 "^lvsim: --tolerance needs a relative tolerance from 1e-14 to 0.1 .*, got '$t'$" -- "$lvsim" compare "$mission" --tolerance "$t"
  expect 2 "^lvsim: --tolerance needs a relative tolerance from 1e-14 to 0.1 .*, got '$t'$" -- "$lvsim" simulate free_fall --tolerance "$t" --format none
done
mc_mission="$src/tests/missions/mc/correlated.yaml"
expect 2 "^lvsim: --tolerance needs a relative tolerance from 1e-14 to 0.1 .*, got '10'$" -- "$lvsim" mc "$mc_mission" -n 2 -o "$work/mc" --tolerance 10
expect 2 "^lvsim: --method needs an integration method \(dassl, cvode-adams, dopri5, rk4, euler, dp5, dop853, auto\), got 'rk45'$" -- "$lvsim" mc "$mc_mission" -n 2 -o "$work/mc" --method rk45
expect 2 "^lvsim: --method needs an integration method .*, got 'rk45'$" -- "$lvsim" compare "$mission" --method rk45
expect 2 "^lvsim: --output-interval needs seconds > 0, got '0'$" -- "$lvsim" mc "$mc_mission" -n 2 -o "$work/mc" --output-interval 0
expect 2 "^lvsim: --interval needs seconds > 0, got '-1'$" -- "$lvsim" compare "$mission" --interval -1
[ ! -e "$work/mc" ] && pass=$((pass + 1)) || { echo "FAIL: a refused mc wrote $work/mc"; fails=$((fails + 1)); }
expect 2 "^lvsim: --interval: '-1' s must be >= 0" -- "$lvsim" simulate free_fall --interval -1 --format none
expect 0 "tolerance 0.1: ok" -- "$lvsim" simulate free_fall --tolerance 0.1 --format none
# (2) every angle has the range of its kind (docs/mission-format.md, "Angle ranges"): the
# reproduction's theta_deg: 1e300, as a parameter and as a phase's set:
cp -R "$src/examples/paper-test-case" "$work/ang"
sed 's/start_theta_deg: 0$/start_theta_deg: 1e300/' "$src/examples/paper-test-case/mission.yaml" > "$work/ang/theta.yaml"
line=$(grep -n "start_theta_deg: 1e300" "$work/ang/theta.yaml" | cut -d: -f1)
refused "theta.yaml:$line:20: parameters: start_theta_deg must be >= -90 and <= 90 deg, found 1e\+300$" "$work/ang/theta.yaml"
sed 's/    from: P1$/    from: P1\n    set: {theta_deg: 1e300}/' "$src/examples/paper-test-case/mission.yaml" > "$work/ang/set.yaml"
line=$(grep -n "theta_deg: 1e300" "$work/ang/set.yaml" | head -1 | cut -d: -f1)
refused "set.yaml:$line:22: phase 'P2', set: theta_deg must be >= -720 and <= 720 deg, found 1e\+300$" "$work/ang/set.yaml"
expect 0 "^start_fpa +1\.570796327 +rad +>= -1\.570796327 and <= 1\.570796327 +31$" -- "$lvsim" params "$mission"
# (3) no start under the ground: a built-in model's domain (h >= 0) and a phase's impact end
expect 2 "^lvsim: model 'free_fall': the start state at t = 0 s is outside the model's domain: h = -1 m is below its lower bound 0 m" -- \
  "$lvsim" simulate free_fall --set h=-1 --format none
expect 2 "h = -3 m is below its lower bound 0 m" -- "$lvsim" simulate vertical_ascent --set h0=-3 --format none
# a start the model cannot take says why, as bad input (exit 2, not a solver failure)
expect 2 "model 'vertical_ascent': initialisation failed at t = 0 s: the mass m must be > 0 kg" -- \
  "$lvsim" simulate vertical_ascent --set m=-5 --format none
expect 2 "model 'kepler': start values cannot be computed from the parameters: the eccentricity e must be >= 0 and < 1" -- \
  "$lvsim" simulate kepler --set e=1.5 --format none
# a start on the ground, falling: the impact at t = 0 (not a fall through the ground)
expect 0 "ok at t = 0 s \(impact\)" -- "$lvsim" simulate free_fall --set h=0 --stop 3 --format none
shot 800 | sed 's/start_h: 0,/start_h: -1,/' > "$work/under.yaml"
line=$(grep -n "name: flight" "$work/under.yaml" | cut -d: -f1)
refused "under.yaml:$line:5: phase 'flight': initialisation failed at t = 0 s: the start altitude h = -1 m is below the level 0 m of its end 'impact'" "$work/under.yaml"
# (5) names: a 10 MB mission name was copied into 7 result files; at most 256 bytes now
python3 -c "print('mission: {name: ' + 'x' * 10485760 + '}')" > "$work/bigname.yaml"
sed -n '/^stages:/,$p' "$mission" | sed "s|table: stage1.csv|table: $src/examples/paper-test-case/stage1.csv|; s|table: stage2.csv|table: $src/examples/paper-test-case/stage2.csv|; s|file: stage3.mat|file: $src/examples/paper-test-case/stage3.mat|" >> "$work/bigname.yaml"
refused "bigname.yaml:1:17: mission: name of 10485760 bytes: at most 256 \(it is copied into every result file\)$" "$work/bigname.yaml"
# (6) a targeting scale within [1e-4, 1] x (max - min): 1e-9 gave a false NOT MET
shot 800 | sed 's/scale: 1}/scale: 1.0e-9}/' > "$work/scale.yaml"
expect 2 "scale.yaml:12:61: targeting: variable 'start_fpa_deg': scale 1e-09 is outside \[0.0055, 55\]" -- "$lvsim" check "$work/scale.yaml"
expect 2 "scale.yaml:12:61: targeting: variable 'start_fpa_deg': scale 1e-09 is outside \[0.0055, 55\]" -- "$lvsim" target "$work/scale.yaml"
# (7) every numeric option held to its range, refused (not replaced) naming the option
expect 2 "^lvsim: --threads needs a count from 1 to 16 \(the most a run uses\), got '17'$" -- "$lvsim" run "$mission" -o "$work/thr" --threads 17
[ ! -e "$work/thr" ] && pass=$((pass + 1)) || { echo "FAIL: a refused run wrote $work/thr"; fails=$((fails + 1)); }
expect 2 "^lvsim: --max-rows needs a whole number from 1 to 1e15, got '0'$" -- "$lvsim" check "$mission" --max-rows 0
expect 2 "^lvsim: -j needs a thread count 1..256, got '0'$" -- "$lvsim" mc "$mc_mission" -n 2 -o "$work/mc" -j 0
expect 2 "^lvsim: --restarts needs an integer from 0 to 100, got '-1'$" -- "$lvsim" target "$work/shot.yaml" --restarts -1
expect 2 "^lvsim: --max-steps: '0' is not a whole count from 1 to 2147483647$" -- "$lvsim" simulate free_fall --max-steps 0 --format none
expect 2 "outside the valid range" -- "$lvsim" atmosphere -6000
expect 2 "latitude 91 deg must be within \[-90, 90\]" -- "$lvsim" gravity 91 0 0
expect 2 "longitude 400 deg within \[-360, 360\]" -- "$lvsim" gravity 0 400 0
# target interrupted inside a long evaluation (issue 22): the Monte Carlo test's long runs
# (about 2.7 s of CPU an evaluation) with a Newton problem; SIGINT 0.3 s into the first
# sensitivity evaluation stops it within a second with the start as the best point, exit
# 130, nothing evaluated again. (Its solution, for the record: vz at 320 s is
# Isp g0 ln(m0 / m_f) - g 320 s, so vz = 1600 m/s at Isp = 4739.2 / (9.80665 ln 5) = 300.269 s.)
sed '/^dispersions:/,$d' "$src/tests/missions/mc/long_run.yaml" > "$work/tlong.yaml"
cat >> "$work/tlong.yaml" <<'YAML'
targeting:
  method: newton
  variables:
    - {name: e1.isp_vac, min: 280, max: 320, scale: 1}
  constraints:
    - {final: coast2.vz, equal: 1600, tolerance: 0.01}
YAML
"$lvsim" target "$work/tlong.yaml" > "$work/tlong.out" 2> "$work/tlong.err" &
pid=$!
for _ in $(seq 1 600); do
  sleep 0.05
  grep -qE "^ +0 +start +start" "$work/tlong.out" && break
done
sleep 0.3
t0=$(date +%s.%N); kill -INT $pid; wait $pid; rc=$?
dt=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')
echo "target: SIGINT inside an evaluation: exit $rc after $dt s"
if [ "$rc" -eq 130 ] && awk -v d="$dt" 'BEGIN { exit !(d < 1.0) }' \
   && grep -q "^best point:" "$work/tlong.out" && grep -qE "^  e1.isp_vac += 300 s$" "$work/tlong.out" \
   && grep -q "cancelled at iteration 0: the best point so far" "$work/tlong.out" \
   && grep -q "lvsim: interrupted: the best point so far above" "$work/tlong.err"; then
  pass=$((pass + 1))
else
  echo "FAIL: target interrupted: exit $rc after $dt s (want 130 within 1 s, the best point):"
  cat "$work/tlong.out" "$work/tlong.err"; fails=$((fails + 1))
fi

# An end on an output the model cannot evaluate (q_dyn above a table atmosphere's top, 10 km):
# the phase fails with the model's reason, not only "event function failed" (exit 3)
mkdir -p "$work/evf"
printf 'h [m], T [K], p [Pa], rho [kg/m3]\n0, 288.15, 101325, 1.225\n5000, 255.65, 54019.9, 0.736116\n10000, 223.252, 26436.3, 0.412707\n' > "$work/evf/atm.csv"
cat > "$work/evf/m.yaml" <<'EOF2'
mission: {name: evf}
environment: {world: planet, planet: earth, gravity: j2, atmosphere: {table: atm.csv}}
parameters: {start_lat_deg: 5, start_lon_deg: -52, start_h: 100, start_vel: 100, start_fpa_deg: 89, start_chi_deg: 90}
stages: [{name: s, dry_mass: 1000, propellant_mass: 4000, engines: [{name: e, thrust_vac: 120000, isp_vac: 250}]}]
phases:
  - {name: up, model: dof3, stages: [s], stop_time: 60, end: [{q_dyn: 1.0e9}], aero: {s_ref: 1, CD: 0.3}}
EOF2
expect 3 "event functions .* cannot be evaluated at t = 30\.3.*atmosphere model 'table' .*altitude 10000\.[0-9]+ m is above the table's range 0 m to 10000 m \(by [0-9.e-]+ m\)" -- \
  "$lvsim" run "$work/evf/m.yaml" -o "$work/evf/out" --no-plots -q

# An end on a heat load that can never fire: refused by check and run alike (exit 2)
for end in "{heat_load: -1}|heat_load must be > 0 J/m2, found -1" \
           "{heat_load_fm: 0}|heat_load_fm must be > 0 J/m2, found 0" \
           "{heat_load: 3.0e7, direction: falling}|heat_load never decreases"; do
  sed -e "s/end: \[{q_dyn: 1.0e9}\]/end: [${end%%|*}]/" -e 's/{table: atm.csv}/us76/' \
    "$work/evf/m.yaml" > "$work/evf/h.yaml"
  for cmd in check run; do
    expect 2 "h.yaml:6:[0-9]+: phase 'up'.*${end#*|}" -- "$lvsim" $cmd "$work/evf/h.yaml" \
      $([ $cmd = run ] && echo "-o $work/evf/hout --no-plots")
  done
done

# A heat-load end on a child whose parent's load is already past it: rising by default, so the
# phase fails as "already passed" (exit 3) instead of never firing and ending otherwise
sed -e 's/{table: atm.csv}/us76/' -e 's/, end: \[{q_dyn: 1.0e9}\]//' -e 's/stop_time: 60/stop_time: 20/' \
  "$work/evf/m.yaml" > "$work/evf/h2.yaml"
echo "  - {name: up2, model: dof3, stages: [s], from: up, stop_time: 60, end: [{heat_load: 1}], aero: {s_ref: 1, CD: 0.3}}" >> "$work/evf/h2.yaml"
expect 3 "phase 'up2': the end 'heat_load' is already passed at the start t = 20 s: it fires when heat_load rises through 1" -- \
  "$lvsim" run "$work/evf/h2.yaml" -o "$work/evf/h2out" --no-plots

echo "$pass passed, $fails failed"
[ "$fails" -eq 0 ]
