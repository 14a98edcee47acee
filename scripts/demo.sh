#!/usr/bin/env bash
# make demo: run the default mission (the paper's test case) and say where the results are.
# Usage: scripts/demo.sh BUILD_DIR
set -euo pipefail
build="${1:-build}"
out="$build/demo"
lvsim="$build/lvsim"
mission=examples/paper-test-case/mission.yaml

echo "== lvsim demo: the paper's three-stage test case, five phases with two branches =="
"$lvsim" run "$mission" -o "$out" --quiet
echo
echo "== the same mission as one end-to-end model (the paper's Table 2) =="
"$lvsim" compare "$mission"
echo
"$lvsim" view "$out" --stage-only > /dev/null
echo "report:   $out/index.html (key figures, phases, events, plots)"
echo "viewer:   $lvsim view $out   (3-D globe, offline, on http://127.0.0.1)"
echo "layout:   docs/result-files.md, docs/mission-format.md, docs/visualization.md"
