#!/usr/bin/env bash
# test_profile_cli.sh LVSIM SRC - atmosphere and wind profiles in a mission (issue 28, item 1;
# docs/atmosphere.md and docs/wind.md, "Profiles"): a sounding and two forecasts fly in `run`;
# `lvsim atmosphere --profile` reads a level back; bad profile files are refused by `lvsim
# check` and `lvsim run` alike with the profile's file:line:column and exit 2; `lvsim mc`
# disperses a profile wind (environment.wind.scale, .north.bias); gusts and turbulence fly,
# repeat per seed and vary per Monte Carlo run (item 2).
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
cp "$src"/tests/data/profiles/* "$src/examples/dof3-branch/aero_ascent.csv" "$work/"

mission() { # mission ATMOSPHERE WIND [EXTRA]: a vertical climb through the profiles
  cat <<YAML
mission: {name: prof, epoch: "2026-12-03T12:00:00Z"}
environment:
  world: planet
  planet: earth
  gravity: j2
  atmosphere: $1
  wind: $2
parameters: {start_lat_deg: 5.2, start_lon_deg: -52.8, start_h: 100, start_vel: 50, start_fpa_deg: 88, start_chi_deg: 90}
stages:
  - {name: s1, dry_mass: 15000, propellant_mass: 150000, engines: [{name: e, thrust_vac: 3.2e6, isp_vac: 300}]}
phases:
  - {name: P, model: dof3, stages: [s1], stop_time: 40, end: [impact], inputs: {alpha_deg: 0, throttle: 1},
     aero: {s_ref: 10, axes: wind, table: aero_ascent.csv}}
${3:-}
YAML
}
two='{profile: [{file: forecast_t0.csv, t: -600}, {file: forecast_t1.csv, utc: "2026-12-03T13:00:00Z"}], blend: 2000}'
mission "{profile: sounding.txt, blend: 8000}" "$two" > "$work/good.yaml"
expect 0 "is valid: 1 phases" -- "$lvsim" check "$work/good.yaml"
expect 0 "P .* done" -- "$lvsim" run "$work/good.yaml" -o "$work/good" --no-plots
mission "{profile: sounding.txt}" "{profile: sounding.txt}" > "$work/same.yaml"
expect 0 "P .* done" -- "$lvsim" run "$work/same.yaml" -o "$work/same" --no-plots

# bad files: the same message from check and run, at the profile's line and column
printf 'h [m], T [K], p [Pa]\n0, 288, 101325\n1000, 281, 89900\n900, 282, 90000\n' > "$work/order.csv"
printf 'h [m], T [K], p [Pa]\n0, 288, 101325\n1000, nan, 89900\n' > "$work/nan.csv"
printf 'h [m], T [K], p [Pa]\n0, 288, 101325\n1000, , 89900\n' > "$work/gap.csv"
printf 'h [m], T [K]\n0, 288\n1000, 281\n' > "$work/oneT.csv"
printf 'h [m], T [F], p [Pa]\n0, 59, 101325\n1000, 48, 89900\n' > "$work/unit.csv"
printf 'h [m], speed [knot]\n0, 3\n1000, 5\n' > "$work/nodir.csv"
sed 's/^ 1000.0     45$/ 1000.0     45   24.5/' "$work/sounding.txt" > "$work/below.txt"
# lvsim atmosphere --profile: the sounding's 850 hPa level (1440 gpm = 1440.32628 m, 15.0 C):
# 288.15 K, 85000 Pa, rho = 85000 / (287.05307 * 288.15) = 1.0276331 kg/m^3
expect 0 "^1440.3262[0-9]* 288.15 85000 1.027633" -- "$lvsim" atmosphere 1440.3262775 --profile "$work/sounding.txt"
expect 2 "nan.csv:3:7: expected a finite number, found 'nan'" -- "$lvsim" atmosphere 0 --profile "$work/nan.csv"

for c in "order.csv:4:1: breakpoint 900 is not greater" "nan.csv:3:7: expected a finite number, found 'nan'" \
         "gap.csv:3:7: expected a finite number, found ''" "oneT.csv:1:1: profile: one of T, p, rho is not enough" \
         "unit.csv:1:8: profile: column 'T' has unit 'F'" "below.txt:7:8: sounding: a level at 45 m, below the surface"; do
  f="${c%%:*}"
  mission "{profile: $f}" "{north: 1, east: 2}" > "$work/bad.yaml"
  expect 2 "bad.yaml:6:[0-9]+: environment: .*/$c" -- "$lvsim" check "$work/bad.yaml"
  expect 2 "bad.yaml:6:[0-9]+: environment: .*/$c" -- "$lvsim" run "$work/bad.yaml" -o "$work/bad_run" --no-plots
done
mission us76 "{profile: nodir.csv}" > "$work/badw.yaml"
w="badw.yaml:7:[0-9]+: environment: .*/nodir.csv:1:1: profile: a wind speed column needs a direction"
expect 2 "$w" -- "$lvsim" check "$work/badw.yaml"
expect 2 "$w" -- "$lvsim" run "$work/badw.yaml" -o "$work/badw_run" --no-plots
mission us76 "{profile: [{file: forecast_t0.csv, t: 0}, {file: forecast_t1.csv, t: 0}]}" > "$work/badt.yaml"
expect 2 "badt.yaml:7:[0-9]+: environment, wind, profile #2: at t = 0 s, not after the profile before it" -- \
  "$lvsim" check "$work/badt.yaml"
mission us76 "{profile: sounding.txt, file: wind.csv}" > "$work/badk.yaml"
expect 2 "badk.yaml:7:[0-9]+: environment, wind: 'file' does not go with 'profile'" -- "$lvsim" check "$work/badk.yaml"
mission "{profile: sounding.txt, model: exp}" "{north: 1, east: 2}" > "$work/bada.yaml"
expect 2 "bada.yaml:6:[0-9]+: environment, atmosphere: 'model' does not go with 'profile'" -- "$lvsim" check "$work/bada.yaml"
sed 's/, epoch: "2026-12-03T12:00:00Z"//' "$work/good.yaml" > "$work/noepoch.yaml"
expect 2 "noepoch.yaml:7:[0-9]+: environment, wind, profile #2: a profile at a UTC time needs the mission's epoch" -- \
  "$lvsim" run "$work/noepoch.yaml" -o "$work/noepoch" --no-plots

# Monte Carlo: a profile wind scaled per run (environment.wind.scale) and biased
mission "{profile: sounding.txt}" "$two" "dispersions:
  seed: 7
  parameters:
    environment.wind.scale: {dist: uniform, min: 0, max: 3}
    environment.wind.north.bias: {dist: normal, sigma: 5}" > "$work/mc.yaml"
expect 0 "is valid" -- "$lvsim" check "$work/mc.yaml"
expect 0 "4 runs" -- "$lvsim" mc "$work/mc.yaml" -n 4 -j 2 -o "$work/mc" --no-stats
# the dispersed wind reaches the runs: four different final velocities (were the scale and
# bias dropped, the four runs would repeat the nominal one)
if command -v sqlite3 >/dev/null; then
  n=$(sqlite3 "$work/mc/campaign.db" "SELECT count(DISTINCT round(v_east, 6)) FROM phase_P" 2>&1)
  if [ "$n" = 4 ]; then pass=$((pass + 1)); else echo "FAIL: mc: $n distinct final v_east, want 4"; fails=$((fails + 1)); fi
fi

# Gusts and turbulence (docs/wind.md, "Gusts and turbulence"): `lvsim run` flies the same
# realisation every time (the turbulence's seed), another seed another one; `lvsim mc` flies one
# per run even without dispersions; bad values refused by check and run alike.
turb() { # turb TURBULENCE_LINE [GUST]
  local g="${2:-{altitude: 2000, half_width: 200, east: 8\}}"
  sed "s|^  wind: .*|  wind: {profile: sounding.txt}\\n  gust: $g\\n$1|" "$work/same.yaml"
}
turb "  turbulence: {sigma: 2, length: 300, from: 100, to: 15000}" > "$work/turb.yaml"
turb "  turbulence: {sigma: 2, length: 300, from: 100, to: 15000, seed: 2}" > "$work/turb2.yaml"
expect 0 "P .* done" -- "$lvsim" run "$work/turb.yaml" -o "$work/turb_a" --no-plots
expect 0 "P .* done" -- "$lvsim" run "$work/turb.yaml" -o "$work/turb_b" --no-plots
expect 0 "P .* done" -- "$lvsim" run "$work/turb2.yaml" -o "$work/turb_c" --no-plots
if cmp -s "$work/turb_a/phase_1_P.csv" "$work/turb_b/phase_1_P.csv" &&
   ! cmp -s "$work/turb_a/phase_1_P.csv" "$work/turb_c/phase_1_P.csv"; then pass=$((pass + 1))
else echo "FAIL: turbulence: a run must repeat its realisation and another seed change it"; fails=$((fails + 1)); fi
# the wind columns show it: at some row the turbulence's north wind is not 0 (the profile's is)
if awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^wind_down/) c = i } NR > 1 && $c + 0 != 0 { n++ } END { exit !(n > 10) }' \
     "$work/turb_a/phase_1_P.csv"; then pass=$((pass + 1))
else echo "FAIL: turbulence: no vertical wind in wind_down"; fails=$((fails + 1)); fi
expect 0 "3 runs" -- "$lvsim" mc "$work/turb.yaml" -n 3 -o "$work/turb_mc" --no-stats
if command -v sqlite3 >/dev/null; then
  n=$(sqlite3 "$work/turb_mc/campaign.db" "SELECT count(DISTINCT round(v_east, 6)) FROM phase_P" 2>&1)
  if [ "$n" = 3 ]; then pass=$((pass + 1)); else echo "FAIL: mc turbulence: $n distinct final v_east, want 3"; fails=$((fails + 1)); fi
fi
# a resumed campaign must fly the same data: the sounding replaced between two sessions is
# refused (the database's hash covers every file the mission reads), not mixed in
cp "$work/sounding.txt" "$work/sounding.orig"
sed -i 's/^  850.0   1440   15.0   10.0     72   9.10    120     20/  850.0   1440   15.0   10.0     72   9.10    120     60/' "$work/sounding.txt"
expect 2 "made from another mission file or other data files" -- "$lvsim" mc "$work/turb.yaml" -n 4 -o "$work/turb_mc" --resume --no-stats
cp "$work/sounding.orig" "$work/sounding.txt"
expect 0 "4 runs" -- "$lvsim" mc "$work/turb.yaml" -n 4 -o "$work/turb_mc" --resume --no-stats
for c in "turbulence: {length: 300}|environment, turbulence: missing required key 'sigma'" \
         "turbulence: {sigma: 2, from: 9000, to: 100}|'to' must be above 'from'" \
         "turbulence: {sigma: 2, lenght: 300}|unknown key 'lenght'; did you mean 'length'" \
         "turbulence: {sigma: 2}|{altitude: 2000, half_width: -5, east: 3}|gust 1: half_width must be > 0"; do
  IFS='|' read -r tl gl msg <<<"$c"
  [ -z "$msg" ] && { msg="$gl"; gl=""; }
  turb "  $tl" ${gl:+"$gl"} > "$work/badturb.yaml"
  expect 2 "badturb.yaml:[0-9]+:[0-9]+: .*$msg" -- "$lvsim" check "$work/badturb.yaml"
  expect 2 "badturb.yaml:[0-9]+:[0-9]+: .*$msg" -- "$lvsim" run "$work/badturb.yaml" -o "$work/badturb" --no-plots
done

echo "test_profile_cli: $pass passed, $fails failed"
[ "$fails" -eq 0 ]
