#!/usr/bin/python3
"""Error against work of lvsim's integration methods on two example missions (issue 24):
docs/img/error-work.png and its data, docs/img/error-work.csv (docs/integration.md, "Error
against work"). A developer's script, not part of the build; needs python3-matplotlib.

    PYTHONPATH=build/python /usr/bin/python3 docs/make_error_work.py          # measure + draw
    /usr/bin/python3 docs/make_error_work.py --plot                           # draw the CSV

The missions: examples/sounding-rocket (flat6: boost, coast to apogee, descent to impact) and
examples/kourou-leo (dof3: ascent, two upper-stage burns to a 200 km orbit, one revolution),
each flown with one method at one tolerance in every phase (`Run.execute(method=,
tolerance=)`), as written otherwise.

Error: the largest distance, over the mission's phases, between a phase's final position
(summary.json's finals: ECI r for dof3, flat-world x, y, z for flat6) and the same phase's in
tests/data/examples_reference.json (dopri5, ARKODE, at 1e-13 in every phase, checked by
cvode-adams at 1e-13 to 6e-7 m and 2e-3 m on these two missions: tests/python/check_examples.py).

Work: CPU per flight, measured in-process: the Python package flies the mission REPEAT times in
one process (Run.invalidate(), Run.execute(keep_rows=False, threads=1): no result rows, the
integrator still stops at each phase's output grid) and the figure shows the median over the
repetitions of the sum of the phases' `stats["cpu_time"]` (each phase's thread CPU time from
lv_simulate, as summary.json's `cpu_time`), i.e. the integration and the model without Python.
The machine is a shared 2-core one: expect +-30 %.
"""
import csv
import json
import math
import os
import statistics
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
CSV = os.path.join(ROOT, "docs", "img", "error-work.csv")
PNG = os.path.join(ROOT, "docs", "img", "error-work.png")
MISSIONS = ("sounding-rocket", "kourou-leo")
METHODS = ("dassl", "dopri5", "dp5", "dop853")
TOLERANCES = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
REPEAT = 41


def position(final):
    if "r_eci_x" in final:
        return [final[k] for k in ("r_eci_x", "r_eci_y", "r_eci_z")]
    return [final[k] for k in ("x", "y", "z")]


def measure():
    import lvsim
    with open(os.path.join(ROOT, "tests", "data", "examples_reference.json")) as f:
        ref = json.load(f)["examples"]
    rows = []
    for name in MISSIONS:
        mission = lvsim.Mission(os.path.join(ROOT, "examples", name, "mission.yaml"))
        for method in METHODS:
            for tol in TOLERANCES:
                run = mission.create_run()
                cpu, rhs, steps, err, why = [], 0, 0, None, None
                for _ in range(REPEAT):
                    run.invalidate()
                    run.execute(method=method, tolerance=tol, keep_rows=False, threads=1,
                                check=False)
                    if not run.ok:
                        why = run.failed
                        break
                    res = run.results()
                    cpu.append(sum(r.stats["cpu_time"] for r in res.values()))
                    rhs = sum(r.stats["rhs_evals"] for r in res.values())
                    steps = sum(r.stats["steps"] for r in res.values())
                    err = max(math.dist(position(r.finals), position(ref[name][p]["final"]))
                              for p, r in res.items())
                run.close()
                if err is None:
                    print("%s %s %g: failed: %s" % (name, method, tol, why),
                          file=sys.stderr)
                    continue
                rows.append({"mission": name, "method": method, "tolerance": "%g" % tol,
                             "error_m": "%.3e" % err,
                             "cpu_ms": "%.4f" % (1e3 * statistics.median(cpu)),
                             "cpu_min_ms": "%.4f" % (1e3 * min(cpu)), "rhs": rhs,
                             "steps": steps})
                print(" ".join(str(v) for v in rows[-1].values()), file=sys.stderr)
        mission.close()
    with open(CSV, "w", newline="") as f:
        f.write("# docs/make_error_work.py: error = largest final-position distance over the "
                "phases from tests/data/examples_reference.json (dopri5 at 1e-13); cpu = median "
                "over %d in-process flights of the phases' summed thread CPU (keep_rows=False); "
                "rhs, steps: summed over the phases\n" % REPEAT)
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


def plot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    with open(CSV) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    style = {"dassl": ("tab:red", "s"), "dopri5": ("tab:blue", "^"),
             "dp5": ("tab:green", "v"), "dop853": ("black", "o")}
    label = {"dassl": "dassl (CVODE BDF)", "dopri5": "dopri5 (ARKODE DP5)",
             "dp5": "dp5 (lvsim)", "dop853": "dop853 (lvsim; auto when not stiff)"}
    title = {"sounding-rocket": "sounding-rocket (flat6, 3 phases, 329 s)",
             "kourou-leo": "kourou-leo (dof3, 4 phases, ascent + one orbit)"}
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    for ax, name in zip(axes, MISSIONS):
        for method in METHODS:
            sel = [r for r in rows if r["mission"] == name and r["method"] == method]
            x = [float(r["cpu_ms"]) for r in sel]
            y = [max(float(r["error_m"]), 1e-7) for r in sel]
            c, mk = style[method]
            ax.loglog(x, y, marker=mk, color=c, label=label[method])
            for r, xi, yi in zip(sel, x, y):
                ax.annotate("%.0e" % float(r["tolerance"]), (xi, yi), fontsize=6.5, color=c,
                            textcoords="offset points", xytext=(4, 3))
        ax.axhline(1.0, color="0.6", lw=0.8, ls="--")
        ax.text(ax.get_xlim()[0], 1.15, " 1 m", color="0.4", fontsize=8)
        ax.set_title(title[name], fontsize=10)
        ax.set_xlabel("CPU per flight [ms] (median of in-process repetitions)")
        ax.set_ylabel("largest final-position error vs 1e-13 reference [m]")
        ax.grid(True, which="both", alpha=0.25)
    axes[0].legend(fontsize=8, loc="lower left")
    fig.suptitle("lvsim: error against work, tolerance beside each point "
                 "(data: docs/img/error-work.csv; docs/make_error_work.py)", fontsize=10)
    fig.tight_layout()
    fig.savefig(PNG, dpi=90)
    print(PNG)


if __name__ == "__main__":
    if "--plot" not in sys.argv[1:]:
        measure()
    plot()
