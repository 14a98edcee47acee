#!/usr/bin/env bash
# make demo: run the default mission (examples/rlv-hthl: the paper's section 4.2, a winged
# two-stage reusable launcher, seven phases) and say where the results, plots and 3-D view are.
# The paper's three-stage test case stays an example: examples/paper-test-case.
# Usage: scripts/demo.sh BUILD_DIR
set -euo pipefail
build="${1:-build}"
out="$build/demo"
lvsim="$build/lvsim"
mission=examples/rlv-hthl/mission.yaml

echo "== lvsim demo: a winged two-stage reusable launcher, horizontal take-off and landing =="
echo "   (the paper's section 4.2: seven phases, one separation state seeding two branches)"
"$lvsim" run "$mission" -o "$out" --quiet
echo
"$lvsim" view "$out" --stage-only > /dev/null
echo "report:   $out/index.html (key figures, phases, events, plots)"
echo "plots:    $out/plots/fig10_normalised.png (the paper's Figure 10), altitude, mach,"
echo "          dynamic_pressure, load_factor, ground_track, ground_track_site (.png, .svg)"
echo "3-D view: $lvsim view $out   (a track per stage: main stage, upper stage, payload, on one path until the separation;"
echo "          3-D globe, offline, on http://127.0.0.1; data: $out/mission.czml)"
echo "more:     $lvsim run examples/paper-test-case/mission.yaml -o out   (the paper's test case;"
echo "          $lvsim compare examples/paper-test-case/mission.yaml: its Table 2)"
echo "          $lvsim run examples/two-stage-6dof/mission.yaml -o out6   (a 6-DoF first stage under attitude control)"
echo "          $lvsim fmu examples/two-stage-6dof/mission.yaml --phase boost -o boost.fmu   (FMI 2.0: docs/fmi.md)"
echo "python:   PYTHONPATH=build/python /usr/bin/python3 -c 'import lvsim'   (docs/python.md, examples/notebook.ipynb)"
echo "layout:   docs/result-files.md, docs/mission-format.md, docs/visualization.md"
