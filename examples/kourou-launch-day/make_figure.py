#!/usr/bin/python3
"""make_figure.py RUN_DIR MC_DIR OUT.png - the README's picture of the launch region (a
developer's script, not part of the build; needs python3-matplotlib):

    build/lvsim run examples/kourou-launch-day/mission.yaml -o build/ld
    build/lvsim mc examples/kourou-launch-day/mission.yaml -n 200 -o build/ld-mc
    /usr/bin/python3 examples/kourou-launch-day/make_figure.py build/ld build/ld-mc \
        docs/img/kourou-launch-day.png

The nominal ground tracks and IIP trace (the phases' CSV files), and the campaign's impact
points and 3-sigma ellipses of the booster, the fairing and the IIP at the listed times
(campaign.db, ellipses.csv; docs/monte-carlo.md).
"""
import csv
import json
import math
import sqlite3
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt

run, mc, out = sys.argv[1:4]
D = 180.0 / math.pi
A, F = 6378137.0, 1.0 / 298.257223563
E2 = F * (2.0 - F)


def rows(phase_file):
    r = list(csv.reader(open(f"{run}/{phase_file}")))
    names = [c.split(" ")[0] for c in r[0]]
    return [dict(zip(names, map(float, x))) for x in r[1:]]


def ellipse(e):
    """The 3-sigma ellipse of ellipses.csv's row e in degrees (its tangent-plane metres mapped
    back with the meridian and prime-vertical radii at the centre, as the campaign does)."""
    lat0 = float(e["centre_lat_deg"]) / D
    w = math.sqrt(1.0 - E2 * math.sin(lat0) ** 2)
    M, N = A * (1.0 - E2) / w ** 3, A / w
    a, b = float(e["semi_major"]), float(e["semi_minor"])
    az = float(e["angle_deg"]) / D  # azimuth of the major axis from north
    xs, ys = [], []
    for k in range(101):
        t = 2.0 * math.pi * k / 100
        u, v = a * math.cos(t), b * math.sin(t)
        east = u * math.sin(az) + v * math.cos(az)
        north = u * math.cos(az) - v * math.sin(az)
        xs.append(float(e["centre_lon_deg"]) + east / (N * math.cos(lat0)) * D)
        ys.append(float(e["centre_lat_deg"]) + north / M * D)
    return xs, ys


summary = json.load(open(f"{run}/summary.json"))
fig, ax = plt.subplots(figsize=(12, 4.6))
colours = {"ascent": "tab:blue", "booster-fall": "tab:red", "upper-burn-1": "tab:blue",
           "fairing-fall": "tab:orange", "upper-burn-2": "tab:green"}
for p in summary["phases"]:
    if p["name"] not in colours:
        continue
    r = [x for x in rows(p["files"]["csv"] if "files" in p else p["result"] + ".csv")
         if x["lon"] * D < -27.0]
    ax.plot([x["lon"] * D for x in r], [x["lat"] * D for x in r], color=colours[p["name"]],
            lw=1.6, label=None if p["name"] == "upper-burn-1" else f"{p['name']} ground track")
    if p["name"] in ("ascent", "upper-burn-1", "upper-burn-2"):
        iip = [x for x in r if not math.isnan(x["iip_lat"]) and x["iip_lon"] * D < -27.0]
        ax.plot([x["iip_lon"] * D for x in iip], [x["iip_lat"] * D for x in iip], color="0.35",
                lw=1.0, ls="--", label="IIP trace" if p["name"] == "ascent" else None)
db = sqlite3.connect(f"{mc}/campaign.db")
for ph, c in (("booster-fall", "tab:red"), ("fairing-fall", "tab:orange")):
    pts = db.execute(f'SELECT lat, lon FROM "phase_{ph}" WHERE state = \'done\'').fetchall()
    ax.scatter([p[1] * D for p in pts], [p[0] * D for p in pts], s=3, color=c, zorder=3,
               label=f"{ph.split('-')[0]} impacts ({len(pts)} runs)")
pts = db.execute("SELECT lat, lon FROM iip WHERE state = 'impact'").fetchall()
ax.scatter([p[1] * D for p in pts], [p[0] * D for p in pts], s=2, color="k", zorder=3,
           label="IIP at T+60, 100, 140, 300, 400 s")
for e in csv.DictReader(open(f"{mc}/ellipses.csv")):
    if e["kind"] in ("impact", "iip") and float(e["centre_lon_deg"]) < -27.0:
        xs, ys = ellipse(e)
        ax.plot(xs, ys, color="k", lw=0.8)
ax.plot([-52.775], [5.236], marker="^", color="k", ms=8, ls="none", label="launch site")
ax.set_xlabel("longitude [deg]")
ax.set_ylabel("latitude [deg]")
ax.set_ylim(4.6, 5.5)
ax.grid(alpha=0.3)
ax.legend(fontsize=8, loc="lower left", ncol=2)
ax.set_title("kourou-launch-day: ground tracks, IIP trace, and 200 dispersed runs' impacts "
             "with 3-sigma ellipses (lines)", fontsize=10)
fig.tight_layout()
fig.savefig(out, dpi=90)
