#!/bin/sh
# bench_optimize.sh - `lvsim optimize` as a user runs it: the whole process's wall and CPU time,
# IPOPT's iterations, the NLP's size and each iteration's cost broken down (the Jacobian's
# column groups, the points IPOPT asks for, IPOPT's own work), for the examples with known
# answers: the linear tangent law (21 nodes), the Goddard rocket (16 nodes) and Betts' Delta III
# with free pitch and heading (examples/delta3-gto/optimal.yaml).
# Usage: bench/bench_optimize.sh [BUILD_DIR] [THREADS]   (default build, 2)
set -eu
B=${1:-build}
J=${2:-2}
D=$(mktemp -d)
trap 'rm -rf "$D"' EXIT
cat > "$D/lt.yaml" <<'YAML'
mission: {name: lt-ocp}
environment:
  world: planet
  planet: {name: flatland, radius: 1.0e10, gm: 9.80665e20, rotation_rate: 0}
  atmosphere: none
parameters: {start_h: 1000, start_vel: 100, start_fpa_deg: 80, start_chi_deg: 90}
stages: [{name: s, dry_mass: 1000, propellant_mass: 100,
          engines: [{thrust_vac: 21574.63, isp_vac: 1.0e9}]}]
phases:
  - {name: climb, model: dof3, stages: [s], stop_time: 60, inputs: {alpha_deg: 0}}
optimal_control:
  phases: [{name: climb, controls: [{name: alpha_deg, min: -60, max: 60}], nodes: 21}]
  constraints:
    - {final: climb.h, equal: 11000, tolerance: 0.01}
    - {final: climb.v_down, equal: 0, tolerance: 1.0e-4}
  cost: {maximize: climb.v_east}
YAML
cp -r "$(dirname "$0")/../examples/goddard" "$D/goddard"
cp -r "$(dirname "$0")/../examples/delta3-gto" "$D/delta3-gto"
for m in "$D/lt.yaml" "$D/goddard/mission.yaml" "$D/delta3-gto/optimal.yaml"; do
  echo "== $(basename "$(dirname "$m")")/$(basename "$m") (--threads $J)"
  /usr/bin/time -f "process: %e s wall, %U s user + %S s system" \
    "$B/lvsim" optimize "$m" -q --threads "$J" 2>&1 | grep -v "^  VIOLATED"
done
