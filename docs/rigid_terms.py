#!/usr/bin/env python3
"""rigid_terms.py - fly examples/two-stage-6dof with each combination of the switchable
rigid-body terms of its 6-DoF boost (docs/models.md, "Rigid-body terms") and print the table of
docs/models.md, "The two-stage 6-DoF ascent with each combination".

    python3 docs/rigid_terms.py [--lvsim build/lvsim] [--keep DIR]

For each of the 8 combinations of jet_damping (on, off), inertia_rate (on, off) and
rate_damping_frame (air, inertial) it writes a copy of the example with
the booster's `rigid_body: {terms: {...}}` replaced, runs `lvsim run --outputs csv,summary
--no-plots`, and reads the boost's final values (staging) and its rows (the controller's work)
and the upper stage's final values (orbit). Standard library only.
"""
import argparse
import csv
import itertools
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
EXAMPLE = os.path.join(ROOT, "examples", "two-stage-6dof")
DEG = 180.0 / math.pi


def read_rows(path):
    """Columns of an lvsim phase CSV by name (the unit in brackets dropped)."""
    with open(path, newline="") as f:
        rd = csv.reader(f)
        head = [re.sub(r"\s*\[.*\]$", "", h) for h in next(rd)]
        cols = {h: [] for h in head}
        for row in rd:
            for h, v in zip(head, row):
                cols[h].append(float(v))
    return cols


def fly(lvsim, work, jd, ir, fr):
    name = f"jd-{jd}_ir-{ir}_fr-{fr}"
    d = os.path.join(work, name)
    os.makedirs(d)
    for f in ("ca_mach.csv", "cn_alpha.csv", "wind.csv"):
        shutil.copy(os.path.join(EXAMPLE, f), d)
    text = open(os.path.join(EXAMPLE, "mission.yaml")).read()
    terms = f"terms: {{jet_damping: {jd}, inertia_rate: {ir}, rate_damping_frame: {fr}}}"
    text, n = re.subn(r"terms: \{[^}]*\}", terms, text)
    if n != 1:
        sys.exit("rigid_terms.py: the example's `terms: {...}` line not found once")
    mission = os.path.join(d, "mission.yaml")
    open(mission, "w").write(text)
    out = os.path.join(d, "out")
    subprocess.run([lvsim, "run", mission, "-o", out, "--outputs", "csv,summary",
                    "--no-plots", "--quiet"], check=True, stdout=subprocess.DEVNULL)
    s = json.load(open(os.path.join(out, "summary.json")))
    ph = {p["name"]: p for p in s["phases"]}
    b, u = ph["boost"]["final"], ph["upper-burn"]["final"]
    rows = read_rows(os.path.join(out, "phase_2_boost.csv"))
    t = rows["time"]
    q_dyn = rows["q_dyn"]
    return {
        "jd": jd, "ir": ir, "fr": fr,
        "t_stage": b["time"], "h_stage": b["h"] / 1e3, "v_stage": b["v_rel"],
        "fpa_stage": b["fpa"] * DEG, "theta_stage": b["theta"] * DEG,
        "q_stage": b["q"] * DEG,
        "alpha_max": max(abs(a) for a in rows["alpha"]) * DEG,
        "gimbal_max": max(abs(g) for g in rows["gimbal_pitch_in"]) * DEG,
        "err_max": max(abs(e) for e in rows["err_pitch"]) * DEG,
        "q_max": max(abs(q) for q in rows["q"]) * DEG,
        "maxq": max(q_dyn) / 1e3,
        "t_end": u["time"], "peri": u["peri_alt"] / 1e3, "apo": u["apo_alt"] / 1e3,
        "prop_left": u.get("propellant_left", float("nan")),
        "t_rows": (t[0], t[-1]),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--lvsim", default=os.path.join(ROOT, "build", "lvsim"))
    ap.add_argument("--keep", help="keep the runs in this folder (default: a temporary one)")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="lvsim-rigid-terms-")
    if a.keep:
        os.makedirs(work, exist_ok=False)
    res = []
    try:
        for jd, ir, fr in itertools.product(("on", "off"), ("on", "off"), ("air", "inertial")):
            res.append(fly(a.lvsim, work, jd, ir, fr))
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)
    ref = res[0]  # the defaults: on, on, air
    print("| jet_damping | inertia_rate | rate_damping_frame | staging t [s] | h [km] | "
          "v_rel [m/s] | fpa [deg] | theta [deg] | q [deg/s] | boost max abs: alpha [deg] | "
          "gimbal [deg] | pitch error [deg] | q [deg/s] | cut-off t [s] | perigee [km] | "
          "apogee [km] | propellant left [kg] |")
    print("|" + "---|" * 18)
    for r in res:
        print(f"| {r['jd']} | {r['ir']} | {r['fr']} | {r['t_stage']:.3f} | {r['h_stage']:.4f} | "
              f"{r['v_stage']:.3f} | {r['fpa_stage']:.4f} | {r['theta_stage']:.4f} | "
              f"{r['q_stage']:.5f} | {r['alpha_max']:.4f} | {r['gimbal_max']:.4f} | "
              f"{r['err_max']:.4f} | {r['q_max']:.4f} | {r['t_end']:.3f} | {r['peri']:.3f} | "
              f"{r['apo']:.3f} | {r['prop_left']:.1f} |")
    print()
    print("Differences from the defaults (on, on, air):")
    print()
    print("| jet_damping | inertia_rate | rate_damping_frame | d h staging [m] | "
          "d v_rel staging [m/s] | d fpa staging [deg] | d q staging [deg/s] | "
          "d cut-off t [s] | d perigee [m] | d apogee [m] | d propellant left [kg] |")
    print("|" + "---|" * 11)
    for r in res[1:]:
        print(f"| {r['jd']} | {r['ir']} | {r['fr']} | {(r['h_stage'] - ref['h_stage']) * 1e3:+.2f} | "
              f"{r['v_stage'] - ref['v_stage']:+.3f} | {r['fpa_stage'] - ref['fpa_stage']:+.4f} | "
              f"{r['q_stage'] - ref['q_stage']:+.5f} | {r['t_end'] - ref['t_end']:+.3f} | "
              f"{(r['peri'] - ref['peri']) * 1e3:+.1f} | {(r['apo'] - ref['apo']) * 1e3:+.1f} | "
              f"{r['prop_left'] - ref['prop_left']:+.1f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
