#!/usr/bin/python3
"""Draws docs/img/paper-test-case.png from a run of the paper's test case (a developer's
script for the README picture, not part of the build; needs python3-matplotlib):

    build/lvsim run examples/paper-test-case/mission.yaml -o build/paper
    /usr/bin/python3 docs/make_figures.py build/paper

(docs/img/rlv-hthl-fig10.png is build/demo/plots/fig10_normalised.png of `make demo` as
lvsim draws it.)
"""
import csv
import json
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

out = sys.argv[1] if len(sys.argv) > 1 else "build/demo"
summary = json.load(open(f"{out}/summary.json"))
fig, axes = plt.subplots(1, 3, figsize=(13, 3.8))
colors = {"stage1": "tab:red", "stage2": "tab:blue", "stage3": "tab:green"}
for body in summary["bodies"]:
    rows = list(csv.DictReader(open(f"{out}/{body['trajectory']}")))
    t = [float(r["time [s]"]) for r in rows]
    c = colors.get(body["name"], None)
    axes[0].plot(t, [float(r["z [m]"]) / 1e3 for r in rows], color=c, label=body["name"])
    axes[1].plot(t, [float(r["vz [m/s]"]) for r in rows], color=c)
    axes[2].plot(t, [float(r["stage_mass [kg]"]) / 1e3 for r in rows], color=c)
for p in summary["phases"]:
    for ax in axes:
        ax.axvline(p["t_start"], color="0.8", lw=0.8, zorder=0)
axes[0].set_ylabel("altitude z [km]")
axes[1].set_ylabel("vertical velocity [m/s]")
axes[2].set_ylabel("stage mass [t]")
for ax in axes:
    ax.set_xlabel("mission time [s]")
    ax.grid(alpha=0.3)
axes[0].legend()
fig.suptitle("lvsim: the paper's three-stage test case, five phases (grey lines: phase starts)")
fig.tight_layout()
fig.savefig("docs/img/paper-test-case.png", dpi=90)
print("docs/img/paper-test-case.png")
