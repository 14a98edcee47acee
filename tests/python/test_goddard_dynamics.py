#!/usr/bin/python3
"""test_goddard_dynamics.py - examples/goddard flies Bryson's normalised Goddard rocket exactly.

The Goddard rocket in Bryson's normalisation (A. E. Bryson, Dynamic Optimization, 1999, sec.
10.3; J. T. Betts, Practical Methods for Optimal Control, 2nd ed., 2010; the COPS 3.0 benchmark,
E. D. Dolan, J. J. More, T. S. Munson, ANL/MCS-TM-273, 2004, sec. 10 "Goddard Rocket"):

    dh/dt = v,   dv/dt = (T - D) / m - 1 / h^2,   dm/dt = -T / c,
    D = D_c v^2 exp(-h_c (h - 1)),   0 <= T <= T_max,   m >= m_c,
    h(0) = 1, v(0) = 0, m(0) = 1,
    h_c = 500, v_c = 620, m_c = 0.6, T_c = 3.5, c = 0.5, D_c = 0.5 v_c = 310, T_max = T_c = 3.5

examples/goddard/mission.yaml maps it to SI (length R, time sqrt(R / g0), mass m0, g0 = gm / R^2;
its comments and README.md give the table). This test, independently of lvsim:

1. checks that the file's SI numbers are the mapping's (the scale height R / h_c, the thrust
   T_c m0 g0, the exhaust speed isp g0' = c sqrt(g0 R) with the Isp constant g0' = 9.80665, the
   drag factor rho0 s_ref CD / 2 = m0 D_c / R, the dry and propellant masses, a non-rotating
   point-mass sphere and a vertical start at rest);
2. integrates the normalised ODE above with SciPy (solve_ivp, DOP853, rtol 1e-12, piecewise
   between the table's breakpoints so that no step straddles a kink of the throttle) under the
   file's throttle table, piecewise linear in time, converted to normalised time; the burnout
   at m = m_c (an event, thrust off after it) and the apogee (v = 0, an event) as lvsim has them;
3. runs `lvsim run` on the example (its own tolerance, 1e-10) into a temporary folder and reads
   the phase CSV (docs/result-files.md): the altitude gain h - 1, the vertical speed and the
   mass at several times, at burnout and at the apogee, in normalised units, must agree to
   1e-9 of their scales (altitude gain and speed relative to their largest values along the
   flight, mass relative to m0), and the burnout and apogee times likewise.

Usage: pytest tests/python/test_goddard_dynamics.py with LVSIM=path/to/lvsim in the environment
(ctest test_goddard_dynamics sets it).
"""
import csv
import json
import math
import os
import subprocess
import tempfile

import numpy as np
import pytest
import yaml
from scipy.integrate import solve_ivp

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
EXAMPLE = os.path.join(ROOT, "examples", "goddard")
LVSIM = os.environ.get("LVSIM", os.path.join(ROOT, "build", "lvsim"))

# Bryson's constants (COPS 3.0, sec. 10)
H_C, V_C, M_C, T_C = 500.0, 620.0, 0.6, 3.5
C = 0.5                 # 0.5 sqrt(g0 h0) with g0 = h0 = 1
D_C = 0.5 * V_C         # 0.5 v_c m0 / g0
T_MAX = T_C             # T_c g0 m0
G0_ISP = 9.80665        # m/s^2: lvsim's Isp constant (LV_G0, src/vehicle/engine.c)

TOL = 1e-9              # agreement asked, relative to each quantity's scale (measured: 4e-11)
CHECK_TIMES = (5.0, 20.0, 20.5, 35.0, 50.0, 70.0, 90.0, 120.0, 150.0)  # s, the nearest rows


def load_mission():
    with open(os.path.join(EXAMPLE, "mission.yaml")) as f:
        return yaml.safe_load(f)


def units(mis):
    """R [m], g0 [m/s^2], the time unit [s], the speed unit [m/s], m0 [kg]."""
    pl = mis["environment"]["planet"]
    r, gm = float(pl["radius"]), float(pl["gm"])
    g0 = gm / r ** 2
    st = mis["stages"][0]
    m0 = float(st["dry_mass"]) + float(st["propellant_mass"])
    return r, g0, math.sqrt(r / g0), math.sqrt(g0 * r), m0


def throttle_table():
    with open(os.path.join(EXAMPLE, "throttle_guess.csv")) as f:
        rows = list(csv.reader(f))
    head = [h.strip() for h in rows[0]]
    assert head == ["time [s]", "throttle [1]"], head
    data = np.array([[float(x) for x in r] for r in rows[1:] if r], float)
    return data[:, 0], data[:, 1]


def bryson(t_s, u, tu):
    """Bryson's ODE under the throttle table (t_s [s], u [1]) in normalised time t / tu,
    clamped outside the table as lvsim's table is: the solution on [0, apogee] with the burnout
    time (None if the propellant lasts), the apogee time and a function x(t_norm)."""
    tn = t_s / tu

    def rhs(t, x, on):
        h, v, m = x
        thrust = T_MAX * float(np.interp(t, tn, u)) if on else 0.0
        drag = D_C * v * v * math.exp(-H_C * (h - 1.0))
        return [v, (thrust - drag) / m - 1.0 / (h * h), -thrust / C]

    def burnout(t, x, on):
        return x[2] - M_C
    burnout.terminal, burnout.direction = True, -1

    def apogee(t, x, on):
        return x[1]
    apogee.terminal, apogee.direction = True, -1

    x, t, on, pieces, t_burn = [1.0, 0.0, 1.0], 0.0, True, [], None
    knots = [k for k in tn if k > 0.0] + [10.0]      # the last piece: to the apogee
    for k in knots:
        while t < k:
            # after the burnout only the apogee is watched (the mass stays at m_c)
            sol = solve_ivp(rhs, (t, k), x, args=(on,), method="DOP853", rtol=1e-12,
                            atol=1e-15, dense_output=True,
                            events=[burnout, apogee] if on else [apogee])
            assert sol.success, sol.message
            pieces.append((t, sol.t[-1], sol.sol))
            t, x = sol.t[-1], list(sol.y[:, -1])
            if sol.status == 1 and len(sol.t_events[-1]):         # apogee: done
                def at(tq):
                    for a, b, s in pieces:
                        if a <= tq <= b:
                            return s(tq)
                    raise ValueError(tq)
                return t_burn, t, at
            if sol.status == 1 and len(sol.t_events[0]):          # burnout: thrust off
                t_burn, on = t, False
                x[2] = M_C
    raise AssertionError("no apogee")


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    names = [h.split(" [")[0] for h in rows[0]]
    return names, np.array([[float(x) for x in r] for r in rows[1:]], float)


@pytest.fixture(scope="module")
def flown():
    if not os.access(LVSIM, os.X_OK):
        pytest.fail("lvsim not found at %s (set LVSIM)" % LVSIM)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        r = subprocess.run([LVSIM, "run", os.path.join(EXAMPLE, "mission.yaml"), "-o", out,
                            "--outputs", "csv,summary", "--no-plots", "--quiet"],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        assert r.returncode == 0, r.stdout
        with open(os.path.join(out, "summary.json")) as f:
            summary = json.load(f)
        # the burn to its burnout, then the coast to the apogee: one flight
        names, burn = read_csv(os.path.join(out, "phase_1_burn.csv"))
        names2, coast = read_csv(os.path.join(out, "phase_2_coast.csv"))
        assert names2 == names
        data = np.vstack([burn, coast])
    return summary, names, data


def test_file_is_the_mapping():
    """Every SI number of the file is the normalised problem's, mapped (relative 1e-15)."""
    mis = load_mission()
    r, g0, tu, vu, m0 = units(mis)
    env = mis["environment"]
    assert env["world"] == "planet" and env["gravity"] == "pointmass"
    assert float(env["planet"]["rotation_rate"]) == 0.0
    assert float(env["planet"].get("flattening", 0.0)) == 0.0
    atm = env["atmosphere"]
    assert atm["model"] == "exp"

    def same(a, b, what):
        assert abs(a - b) <= 1e-15 * abs(b), "%s: %r in the file, %r mapped" % (what, a, b)

    same(float(atm["scale_height"]), r / H_C, "scale_height = R / h_c")
    st = mis["stages"][0]
    same(float(st["dry_mass"]), M_C * m0, "dry_mass = m_c m0")
    eng = st["engines"][0]
    assert float(eng.get("exit_area", 0.0)) == 0.0 and "mdot" not in eng and "table" not in eng
    same(float(eng["thrust_vac"]), T_MAX * m0 * g0, "thrust_vac = T_c m0 g0")
    same(float(eng["isp_vac"]) * G0_ISP, C * vu, "isp_vac g0' = c sqrt(g0 R)")
    ph = mis["phases"][0]
    aero = ph["aero"]
    same(0.5 * float(atm["rho0"]) * float(aero["s_ref"]) * float(aero["CD"]), m0 * D_C / r,
         "rho0 s_ref CD / 2 = m0 D_c / R")
    assert set(aero) == {"s_ref", "CD"}                     # no lift, no side force
    p = mis["parameters"]
    assert float(p["start_h"]) == 0.0 and float(p["start_vel"]) == 0.0
    assert float(p["start_fpa_deg"]) == 90.0
    assert ph["inputs"]["over"] == "time" and float(ph["inputs"]["alpha_deg"]) == 0.0
    assert "guidance" not in ph and "throttle" not in ph
    coast = mis["phases"][1]                                # the same air, engine off
    assert coast["from"] == ph["name"] and coast["aero"] == aero
    assert coast["throttle"] in ("off", False) and "guidance" not in coast  # YAML 1.1: off


def test_dynamics_match_bryson(flown):
    summary, names, data = flown
    mis = load_mission()
    r, g0, tu, vu, m0 = units(mis)
    t_s, u = throttle_table()
    t_burn, t_apo, at = bryson(t_s, u, tu)

    col = {n: i for i, n in enumerate(names)}
    t = data[:, col["time"]]
    h = 1.0 + data[:, col["h"]] / r                  # normalised radius
    v = -data[:, col["v_down"]] / vu                 # vertical speed, up positive
    m = data[:, col["m"]] / m0
    # the flight stays vertical: no horizontal speed (non-rotating sphere, zero alpha)
    horiz = np.hypot(data[:, col["v_north"]], data[:, col["v_east"]])
    assert horiz.max() <= 1e-9 * vu, horiz.max()

    ref = np.array([at(tq / tu) for tq in t])
    h_scale = (ref[:, 0] - 1.0).max()
    v_scale = np.abs(ref[:, 1]).max()

    # the events: burnout at m = m_c (the burn's end), apogee at v = 0 (the coast's end)
    ph = summary["phases"][1]
    ev = {"burnout": summary["phases"][0]["t_end"]}
    assert t_burn is not None, "the guess should burn all its propellant"
    d_burn = abs(ev["burnout"] / tu - t_burn) / t_apo
    d_apo = abs(ph["t_end"] / tu - t_apo) / t_apo
    print("burnout t = %.9f s (lvsim) %.9f s (scipy); apogee t = %.9f s (lvsim) %.9f s (scipy);"
          " relative %.1e, %.1e" % (ev["burnout"], t_burn * tu, ph["t_end"], t_apo * tu,
                                    d_burn, d_apo))
    assert d_burn <= TOL and d_apo <= TOL, (d_burn, d_apo)

    # rows at the chosen times, the burnout rows and the last row
    pick = [int(np.argmin(np.abs(t - tq))) for tq in CHECK_TIMES]  # the coast's grid is offset
    pick += list(np.flatnonzero(t == ev["burnout"])) + [len(t) - 1]
    worst = {"h": 0.0, "v": 0.0, "m": 0.0}
    for i in pick:
        x = ref[i]
        if t[i] == ev["burnout"]:          # at the event lvsim's instant is the reference's
            x = at(t_burn)
        dh = abs((h[i] - 1.0) - (x[0] - 1.0)) / h_scale
        dv = abs(v[i] - x[1]) / v_scale
        dm = abs(m[i] - x[2])
        print("t = %9.4f s  h-1 %.10e (%.1e)  v %.10e (%.1e)  m %.12f (%.1e)"
              % (t[i], h[i] - 1.0, dh, v[i], dv, m[i], dm))
        worst = {"h": max(worst["h"], dh), "v": max(worst["v"], dv), "m": max(worst["m"], dm)}
    # final altitude gain, normalised
    print("apogee h = %.12f (lvsim)  %.12f (scipy); worst relative differences %s"
          % (h[-1], at(t_apo)[0], {k: "%.1e" % w for k, w in worst.items()}))
    assert abs(h[-1] - at(t_apo)[0]) <= TOL * h_scale
    assert worst["h"] <= TOL and worst["v"] <= TOL and worst["m"] <= TOL, worst
    # every row, not only the chosen ones (apart from the burnout's two rows)
    ok = t != ev["burnout"]
    assert np.abs((h - ref[:, 0]) / h_scale)[ok].max() <= TOL
    assert np.abs((v - ref[:, 1]) / v_scale)[ok].max() <= TOL
    assert np.abs(m - ref[:, 2])[ok].max() <= TOL


def test_bryson_reference_is_sound():
    """The reference itself: the mass book (the propellant 1 - m_c burnt by the burnout, at the
    rate T/c of the table's throttle integrated in closed form) and a gain below the published
    optimum h(t_f) = 1.01283 (COPS 3.0, sec. 10), which no admissible throttle beats."""
    mis = load_mission()
    _, _, tu, _, _ = units(mis)
    t_s, u = throttle_table()
    t_burn, t_apo, at = bryson(t_s, u, tu)
    tn = t_s / tu
    # propellant burnt to t_burn: integral of T_max u / c, u piecewise linear (trapezoids)
    k = np.searchsorted(tn, t_burn)
    knots = np.append(tn[:k], t_burn)
    uu = np.interp(knots, tn, u)
    burnt = T_MAX / C * np.sum(0.5 * (uu[1:] + uu[:-1]) * np.diff(knots))
    assert abs(burnt - (1.0 - M_C)) <= 1e-10, burnt
    h_f = at(t_apo)[0]
    assert 1.0125 < h_f < 1.01283, h_f
