#!/usr/bin/env python3
"""make_aero.py - writes the notional delta-wing aerodynamic tables of examples/rlv-hthl
(README.md, "Aerodynamics", gives the model and every assumption). Run from this folder:
    python3 make_aero.py
Four 2-D grids over Mach x alpha (CombiTable2D layout, docs/tables.md), reference area
S_ref = 650 m^2 (the main stage's wing):
    cl_ascent.csv, cd_ascent.csv     MS + US, engines burning (ascent, phases 1-3)
    cl_descent.csv, cd_descent.csv   MS alone, engines off (return, phases 5-7)
Model (wind axes), a slender delta wing:
    CL = CLa(M) sin(a) cos(a)^2 + K(M) sin(a)^2 cos(a)  potential + nonlinear (Polhamus' form:
                                                        vortex lift subsonic, Newtonian
                                                        hypersonic)
    CD = CD0(M) + CL tan(a)                            no leading-edge suction: the polar
"""
import math

MACH = [0.0, 0.3, 0.6, 0.8, 0.9, 0.95, 1.0, 1.05, 1.1, 1.2, 1.5, 2.0, 3.0, 4.0, 6.0, 8.0,
        12.0, 25.0]
ALPHA_DEG = [-10, -5, 0, 2, 4, 6, 8, 10, 12, 15, 20, 25, 30, 35, 40, 45, 50, 60, 70, 80]


def kn(m):
    """Nonlinear lift factor: 1.0 up to M = 1 (a vortex lift below Polhamus' K_v ~ pi of a
    sharp slender delta: rounded leading edges and vortex breakdown, giving CL_max ~ 1.26 at
    40 deg), rising linearly to the Newtonian 2 (CN = 2 sin^2 a) at M = 4 and above."""
    return 1.0 if m <= 1.0 else 2.0 if m >= 4.0 else 1.0 + (m - 1.0) / 3.0


def cla(m):
    """Lift-curve slope [1/rad]: 2.5 subsonic (slender delta, aspect ratio ~2: Jones'
    pi A / 2 = 3.1, reduced for thickness and the body), Prandtl-Glauert growth to a
    transonic peak of 3.0 at M = 1, supersonic 4 / sqrt(M^2 - 1) (Ackeret) from M = 1.2, at
    least 0.6 (hypersonic, where the Newtonian term dominates)."""
    if m <= 0.8:
        return 2.5 / math.sqrt(1.0 - 0.5 * m * m) if m > 0 else 2.5
    if m <= 1.0:
        a08 = 2.5 / math.sqrt(1.0 - 0.5 * 0.64)
        return a08 + (3.0 - a08) * (m - 0.8) / 0.2
    if m < 1.2:
        return 3.0  # 4 / sqrt(1.2^2 - 1) = 6.0 is beyond the transonic peak: held at 3.0
    return max(0.6, min(3.0, 4.0 / math.sqrt(m * m - 1.0)))


def cd0(m, base):
    """Zero-lift drag: subsonic 0.018 + base, the transonic drag rise to 2.4 times that at
    M = 1.1, then falling as 1/sqrt(M) to hypersonic values ~0.012 + base/3."""
    sub = 0.018 + base
    if m <= 0.8:
        return sub
    if m <= 1.1:
        return sub * (1.0 + 1.4 * ((m - 0.8) / 0.3) ** 2)
    peak = 2.4 * sub
    return max(0.012 + base / 3.0, peak * math.sqrt(1.1 / m))


def write(name, f, comment):
    with open(name, "w") as out:
        out.write(comment)
        out.write("mach [1] \\ alpha [rad], " +
                  ", ".join("%.6f" % math.radians(a) for a in ALPHA_DEG) + "\n")
        for m in MACH:
            out.write("%g, " % m + ", ".join("%.5f" % f(m, math.radians(a)) for a in ALPHA_DEG)
                      + "\n")


def cl(m, a):
    return (cla(m) * math.sin(a) * math.cos(a) ** 2 +
            kn(m) * math.sin(a) * abs(math.sin(a)) * math.cos(a))


for phase, base, extra in (("ascent", 0.004, 0.006), ("descent", 0.012, 0.0)):
    # ascent: the upper stage on the main stage's back adds 0.006 (its frontal area over
    # S_ref); engines burning fill the base (0.004). descent: dead-engine base drag 0.012.
    head = ("# examples/rlv-hthl %s aerodynamics (make_aero.py; README.md): %s over Mach x "
            "alpha, S_ref = 650 m^2\n")
    write("cl_%s.csv" % phase, cl, head % (phase, "lift coefficient CL"))
    write("cd_%s.csv" % phase, lambda m, a, b=base + extra: cd0(m, b) + cl(m, a) * math.tan(a),
          head % (phase, "drag coefficient CD"))
