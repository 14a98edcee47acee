#!/usr/bin/env bash
# make demo: run the default mission (the paper's test case) and say where the results are.
# Usage: scripts/demo.sh BUILD_DIR
set -euo pipefail
build="${1:-build}"
out="$build/demo"
lvsim="$build/lvsim"
mission=examples/paper-test-case/mission.yaml

echo "== lvsim demo: the paper's three-stage test case, five phases with two branches =="
"$lvsim" run "$mission" -o "$out"
echo
echo "== the same mission as one end-to-end model (the paper's Table 2) =="
"$lvsim" compare "$mission"
echo
"$lvsim" view "$out" --stage-only > /dev/null
echo "results:  $out/phase_<k>_<name>.mat (Dymola/OpenModelica dsres) and .csv, one per phase"
echo "          $out/body_<stage>.csv (each stage's trajectory across its phases)"
echo "          $out/summary.json (phase table, events, hand-offs, final states)"
echo "          $out/mission.czml, mission.kml (trajectory exports), $out/plots/ (PNG, SVG)"
echo "report:   $out/index.html"
echo "viewer:   $lvsim view $out   -> http://127.0.0.1:8765/viewer/ (3-D globe, offline)"
echo "layout:   docs/result-files.md, docs/mission-format.md, docs/visualization.md"
