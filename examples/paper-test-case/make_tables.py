#!/usr/bin/python3
"""Writes the engine tables of the paper's test case (run once; the outputs are committed).

Thrust F(t) and mass flow mdot(t) of each stage over mission time, with the exhaust velocity
ve = F / mdot = 3000 m/s constant in every row, so the rocket equation v = ve ln(m0/m) - g t
holds through the ramps (tests/unit/test_runner.c checks the phases against it).
Stages 1 and 2 are CSV files, stage 3 a MATLAB v4 .mat file (Modelica CombiTimeTable layout:
columns t, thrust, mdot), as the paper reads its tables from MATLAB files.
"""
import numpy as np
import scipy.io

VE = 3000.0  # m/s

def rows(points):
    return np.array([[t, f, f / VE] for t, f in points])

stage1 = rows([(0.0, 600e3), (60.0, 600e3), (1000.0, 300e3)])   # throttles down after 60 s
stage2 = rows([(0.0, 0.0), (140.0, 0.0), (142.0, 150e3), (2000.0, 150e3)])  # ignites at 140 s
stage3 = rows([(0.0, 0.0), (280.0, 0.0), (282.0, 40.5e3), (5000.0, 40.5e3)])  # at 280 s

for name, tab in (("stage1", stage1), ("stage2", stage2)):
    with open(f"{name}.csv", "w") as f:
        f.write(f"# {name}: thrust and mass flow over mission time, exhaust velocity {VE:g} m/s\n")
        f.write("t [s], thrust [N], mdot [kg/s]\n")
        for t, F, md in tab:
            f.write(f"{t:g}, {F:.10g}, {md:.10g}\n")
scipy.io.savemat("stage3.mat", {"stage3": stage3}, format="4")
