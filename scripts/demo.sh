#!/usr/bin/env bash
# make demo: run the default demonstration and say where the results are.
# Usage: scripts/demo.sh BUILD_DIR
set -euo pipefail
build="${1:-build}"
out="$build/demo"
mkdir -p "$out"
lvsim="$build/lvsim"

echo "== lvsim demo: vertical ascent to apogee (burnout found as a state event) =="
"$lvsim" simulate vertical_ascent --stop 600 --intervals 600 --tolerance 1e-7 \
  --set thrust=30000 --set mdot=10 --set m0=1000 --set m_final=400 --set stop_at_apogee=1 \
  --final time --final h --final v --final m -o "$out/ascent"
echo
echo "results: $out/ascent.mat (Dymola/OpenModelica dsres layout) and $out/ascent.csv"
echo "layout:  docs/result-files.md"
