#!/usr/bin/python3
"""make_drop_reference.py - writes drop_wgs84_30s.csv, the converged reference of the dropped
sphere with drag over the rotating WGS-84 Earth (issue 24, item 3), for check_defaults.py.

The problem and its equations are those of tests/python/check_drop.py (its own ECI equations of
motion, J2 gravity, US76 troposphere and geodetic conversion; constants cited there): a 10 kg
sphere (CD 0.47, S_ref 0.03 m^2) released at rest relative to the Earth at 10 km geodetic
altitude, 45 deg N, 0 deg E. Integrated by SciPy's DOP853 (an independent implementation of
Hairer's code) at rtol 1e-13, atol 1e-10 m; a second run at rtol 1e-12 differs by less than
1e-6 m in every row (printed), so the stored values are converged far below the 1 mm the check
asks. Run: /usr/bin/python3 tests/data/make_drop_reference.py > tests/data/drop_wgs84_30s.csv
"""
import math
import os
import sys

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import check_drop as cd  # noqa: E402

T_END = 30.0


def solve(rtol, times):
    r0 = cd.geodetic_to_ecef(cd.LAT0, cd.LON0, cd.H0)
    v0 = np.cross(cd.W, r0)
    sol = solve_ivp(cd.rhs, (0.0, T_END), np.concatenate([r0, v0]), method="DOP853",
                    rtol=rtol, atol=1e-10, t_eval=times)
    assert sol.success, sol.message
    rows = []
    for k, t in enumerate(sol.t):
        r, v = sol.y[:3, k], sol.y[3:, k]
        c = cd.rot(cd.OMEGA * t)
        rows.append((t, r, cd.ecef_to_geodetic_h(c @ r), np.linalg.norm(c @ (v - np.cross(cd.W, r)))))
    return rows


def main():
    times = np.arange(0.0, T_END + 0.5, 1.0)
    ref, chk = solve(1e-13, times), solve(1e-12, times)
    worst = max(np.linalg.norm(a[1] - b[1]) for a, b in zip(ref, chk))
    print("# dropped sphere with drag over rotating WGS-84 (tests/data/make_drop_reference.py):")
    print("# SciPy %s DOP853 rtol 1e-13 atol 1e-10; |r(1e-13) - r(1e-12)| <= %.1e m" %
          (__import__("scipy").__version__, worst))
    print("time,r_eci_x,r_eci_y,r_eci_z,h,v_rel")
    for t, r, h, v in ref:
        print("%.1f,%.6f,%.6f,%.6f,%.6f,%.9f" % (t, r[0], r[1], r[2], h, v))


if __name__ == "__main__":
    main()
