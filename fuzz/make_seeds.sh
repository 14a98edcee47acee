#!/usr/bin/env bash
# fuzz/make_seeds.sh LVSIM - (re)writes the seed corpora of the fuzz targets other than the
# mission parser's (fuzz/corpus/mission is written by hand) from files of the source tree and,
# for the results folder, from runs of LVSIM (a built lvsim). Each seed is in its target's
# input format (the header comment of fuzz/fuzz_<target>.c). Regression inputs of fixed bugs
# live beside them as regress-*, written by hand; this script leaves them alone.
set -euo pipefail
lvsim=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
src=$(cd "$(dirname "$0")/.." && pwd)
c=$src/fuzz/corpus
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$c/tables" "$c/results" "$c/fmu" "$c/cli"
rm -f "$c"/tables/seed-* "$c"/results/seed-* "$c"/fmu/seed-* "$c"/cli/seed-*

# ---- tables: byte 0 reader | MAT << 3 | PCHIP << 4 | extrap << 5, byte 1 variant, [var\n] ----
seed() { # seed NAME BYTE0 BYTE1 FILE [VAR]
  local out=$c/tables/seed-$1
  printf "\\x$(printf %02x "$2")\\x$(printf %02x "$3")" > "$out"
  [ $# -ge 5 ] && printf '%s\n' "$5" >> "$out"
  head -c 6000 "$4" >> "$out"
}
R_TABLE=0 R_ATMO=1 R_WIND=2 R_GRAVITY=3 R_ENGINE=4 R_AERO=5 R_ENV=6 R_CONTROL=7
MAT=8 PCHIP=16 CLAMP=32 LINEAR=64 DEFAULT=96
for f in "$src"/tests/data/tables/*.csv "$src"/tests/missions/data/*.csv; do
  seed "table-$(basename "$f" .csv)" $((R_TABLE | CLAMP)) 0 "$f"
done
seed table-cd-grid-pchip $((R_TABLE | PCHIP | LINEAR)) 0 "$src/tests/data/tables/cd_grid.csv"
seed table-stage2-mat $((R_TABLE | MAT)) 0 "$src/tests/missions/data/stage2.mat" stage2
seed table-stage3-mat $((R_TABLE | MAT | PCHIP)) 0 "$src/examples/paper-test-case/stage3.mat" stage3
cat > "$work/atmo.csv" <<'CSV'
# US76 values (docs/atmosphere.md)
h [m],  T [K],    p [Pa],    rho [kg/m3],  a [m/s],  mu [Pa s]
0,      288.15,   101325,    1.2250,       340.29,   1.7894e-5
1000,   281.651,  89874.6,   1.11164,      336.43,   1.7579e-5
11000,  216.65,   22632.1,   0.363918,     295.07,   1.4216e-5
20000,  216.65,   5474.89,   0.0880349,    295.07,   1.4216e-5
CSV
printf 'rho [kg/m3], p [Pa], h [m], T [K]\n1.225, 101325, 0, 288.15\n0.4, 26000, 10000, 223\n' \
  > "$work/atmo_cols.csv"
seed atmo-us76 $R_ATMO 0 "$work/atmo.csv"
seed atmo-columns $R_ATMO 0 "$work/atmo_cols.csv"
seed wind-dof3-branch $((R_WIND | CLAMP)) 0 "$src/examples/dof3-branch/wind.csv"
seed wind-6dof $((R_WIND | LINEAR)) 0 "$src/examples/two-stage-6dof/wind.csv"
seed wind-one-row $((R_WIND | DEFAULT)) 0 "$src/tests/missions/data/wind_one_row.csv"
# profiles (an odd variant): a sounding text list and the CSV forecasts of tests/data/profiles
seed atmo-profile-sounding $R_ATMO 1 "$src/tests/data/profiles/sounding.txt"
seed atmo-profile-csv $R_ATMO 3 "$src/tests/data/profiles/forecast_t1.csv"
seed wind-profile-sounding $R_WIND 3 "$src/tests/data/profiles/sounding.txt"
seed wind-profile-csv $R_WIND 1 "$src/tests/data/profiles/forecast_t0.csv"
head -n 60 "$src/data/gravity/egm2008_n20.gfc" > "$work/egm.gfc" # the header and n <= 6
seed gravity-egm2008-n6 $R_GRAVITY 6 "$work/egm.gfc"
seed gravity-egm2008-n4x2 $R_GRAVITY $((4 | 2 << 5)) "$work/egm.gfc"
seed gravity-egm2008-n3x0 $R_GRAVITY $((3 | 7 << 5)) "$work/egm.gfc"
seed engine-stage1-flat $((R_ENGINE | DEFAULT)) 0 "$src/tests/missions/data/stage1.csv"
seed engine-stage1-dof3 $((R_ENGINE | CLAMP | PCHIP)) 1 "$src/examples/paper-test-case/stage1.csv"
seed engine-stage2-mat $((R_ENGINE | MAT | DEFAULT)) 0 "$src/tests/missions/data/stage2.mat" stage2
seed aero-kourou-wind $((R_AERO | DEFAULT)) 0 "$src/examples/kourou-leo/aero_ascent.csv"
seed aero-two-body $((R_AERO | CLAMP)) 1 "$src/tests/missions/data/aero_two.csv"
seed aero-rlv-cl $((R_AERO | DEFAULT)) 1 "$src/examples/rlv-hthl/cl_ascent.csv"
seed aero-cd-mach-flat6 $((R_AERO | CLAMP)) 2 "$src/examples/sounding-rocket/cd_mach.csv"
seed aero-badaxis $((R_AERO | DEFAULT)) 0 "$src/tests/missions/data/aero_badaxis.csv"
seed env-wind $((R_ENV | DEFAULT)) 0 "$src/examples/dof3-branch/wind.csv"
seed env-wind-planet $((R_ENV | DEFAULT)) 2 "$src/examples/dof3-branch/wind.csv"
seed env-atmo $R_ENV 1 "$work/atmo.csv"
seed env-atmo-planet $R_ENV 3 "$work/atmo.csv"
printf 'time [s], alpha [rad], throttle [1]\n0, 0, 1\n5, 0.05, 0.8\n10, 0.02, 0.6\n' \
  > "$work/in3.csv"
printf 'time [s], gimbal_pitch [rad], gimbal_yaw [rad]\n0, 0, 0\n5, 0.01, -0.01\n' > "$work/in6.csv"
printf 'mach [1], Cm [1], Cn [1]\n0, -0.02, 0\n2, -0.04, 0.001\n5, -0.03, 0\n' > "$work/mom.csv"
seed control-dof3 $((R_CONTROL | DEFAULT)) 0 "$work/in3.csv"
seed control-dof3-pitch $((R_CONTROL | DEFAULT)) 0 "$src/tests/missions/data/pitch_program.csv"
seed control-dof6 $((R_CONTROL | DEFAULT)) 1 "$work/in6.csv"
seed control-moments $((R_CONTROL | CLAMP)) 2 "$work/mom.csv"

# ---- results: summary.json, NUL, a CSV (written under every name the summary gives) --------
result_seed() { # result_seed NAME MISSION [CSV in OUTDIR]
  local o=$work/run-$1
  "$lvsim" run "$2" -o "$o" --no-plots -q > /dev/null 2>&1 || true
  local csv=${3:-$(cd "$o" && ls body_*.csv | head -1)}
  { cat "$o/summary.json"; printf '\0'; head -n 20 "$o/$csv"; } > "$c/results/seed-$1"
}
result_seed minimal "$src/tests/missions/minimal.yaml"
result_seed planet-dof3 "$src/tests/missions/planet_dof3.yaml"
result_seed paper-test-case "$src/examples/paper-test-case/mission.yaml"
result_seed sounding-phase "$src/examples/sounding-rocket/mission.yaml" phase_1_boost.csv
result_seed sounding-body "$src/examples/sounding-rocket/mission.yaml"
cat > "$work/fail.yaml" <<'YAML'
mission: {name: fails}
stages: [{name: s, dry_mass: 100, propellant_mass: 0}]
phases:
  - {name: p1, model: flat6, stages: [s], stop_time: 5, integrator: {method: rk4, fixed_step: 1e-9}}
  - {name: p2, model: flat6, stages: [s], from: p1, stop_time: 10}
YAML
result_seed failed "$work/fail.yaml" phase_1_p1.failed.csv

# ---- fmu: byte 0 (bit 0 Co-Simulation, bit 1 logging), then calls: op, who, arguments ------
# (fuzz_fmu.c one_call), for the FMU fuzz.cmake exports: the standard's calling sequences
"$lvsim" fmu "$src/examples/sounding-rocket/mission.yaml" --phase boost -o "$work/f.fmu" > /dev/null
unzip -q -o "$work/f.fmu" resources/lvsim-fmu.txt -d "$work/fmu"
python3 - "$work/fmu/resources/lvsim-fmu.txt" "$c/fmu" <<'PY'
import sys
cfg = dict(l.split(' ', 1) for l in open(sys.argv[1]).read().splitlines() if ' ' in l)
nx, ni = int(cfg['states']), int(cfg['event_indicators'])
# reals: an index into fuzz_fmu.c's table (0: 0, 1: 1, 4: 1e-9, 7: 10, 8: 30, 9: 60, 21: 0.1),
# or 22 + 4 k for k seconds
R = {0: 0, 1: 1, 1e-9: 4, 10: 7, 30: 8, 60: 9, 0.1: 21}
def real(x): return [R[x]] if x in R else [22 + int(4 * x)]
def setup(who=0): return [2, who, 1, *real(1e-9), *real(0), 1, *real(60)]
def step(t, h, who=0): return [26, who, *real(t), *real(h), 1]
ENTER, EXIT, TERM, FREE = 3, 4, 5, 1
def op(code, who=0, *args): return [code, who, *args]
cosim = [1] + setup() + op(ENTER) + op(EXIT)
for k in range(5):
    cosim += step(k, 1)
cosim += op(7, 0, 3, 0, 1, 2) + op(29, 0, 2, 1) + op(TERM) + op(FREE)
me = [0] + op(8, 0, 2, 0, 2 * nx, *real(60), *real(1)) + setup() + op(ENTER) + op(EXIT)
me += op(16, 0, 0) + op(17)
for t in (0.1, 0.5):
    me += op(19, 0, *real(t)) + op(20, 0, 0, *([0] * nx)) + op(21, 0, 0, 0) + op(22, 0, 0, 0)
    me += op(18, 0, 0) + op(23, 0, 0, 0)
me += op(15) + op(16, 0, 0) + op(17) + op(TERM)
states = [3] + setup() + op(ENTER) + op(EXIT) + op(10, 0) + step(0, 2) + op(11, 0)
states += op(33, 0, *real(0.1), *real(0)) + op(12, 0, 0) + op(7, 0, 2, 0, 1) + op(TERM)
two = [2] + op(30, 0, 3, 0, 3, 1, 3) + setup() + op(ENTER) + op(EXIT) + op(10, 2)
two += op(0, 1, 1) + setup(1) + op(10, 1) + op(11, 3) + op(11, 0) + op(FREE, 0)
two += op(7, 0, 1, 0) + op(6, 1) + op(29, 1, 0, 2) + op(FREE, 1) + op(3, 1)
for name, b in (('cosim', cosim), ('me', me), ('cosim-states', states), ('two', two)):
    open('%s/seed-%s' % (sys.argv[2], name), 'wb').write(bytes(b))
PY

# ---- cli: one argument per line ------------------------------------------------------------
cli() { local name=$1; shift; printf '%s\n' "$@" | head -c -1 > "$c/cli/seed-$name"; }
cli check check m.yaml
cli check-rows check m.yaml --max-rows 10 -q
cli run-none run m.yaml --outputs none
cli run-none-json run m.yaml --outputs none --json --threads 2
cli run-outdir run m.yaml -o res --outputs mat,csv,summary --max-rows 1e6 --no-plots
cli simulate simulate vertical_ascent --stop 10 --format none --final time
cli simulate-set simulate oscillator --set omega=2 --method rk4 --fixed-step 0.01 --json
cli simulate-kepler simulate kepler --method dopri5 --tolerance 1e-8 --intervals 50 -o k
cli mc mc m.yaml -n 10 -o mc -j 2 --seed 3 --no-plots
cli target target m.yaml -o converged.yaml --method slsqp --max-iter 5
cli params params m.yaml --json
cli compare compare e.yaml --interval 0.5 --json
cli compare-air compare m.yaml --method rk4 --tolerance 1e-6
cli export export out --format czml,kml
cli plot plot out
cli view view out --port 8765
cli view-stage view out --stage-only
cli fmu fmu m.yaml --phase burn -o x.fmu --model-identifier fz
cli atmosphere atmosphere 0 1000 86000 --model us76
cli gravity gravity 45 10 1000 --model sh:4 --planet earth
cli gravity-moon gravity -10 370 0 --model j2 --planet moon --effective
cli models models
cli vars vars dof3
cli help help run
cli version --version
cli typo simulat
cli help-flag run m.yaml --help
echo "seeds written under $c"
