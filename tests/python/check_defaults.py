#!/usr/bin/python3
"""check_defaults.py LVSIM WORKDIR [METHOD TOLERANCE] - a mission that sets nothing about its
integration is accurate to the field's references (issue 24, item 3). Every phase below gives
no `integrator:` method or tolerance (only its output grid), so it runs with lvsim's defaults;
METHOD and TOLERANCE instead measure one candidate setting (docs/integration.md, "Defaults").

1. A drag-free circular orbit: 400 km above the equator of a point-mass Earth
   (GM = 3.986004418e14 m^3/s^2, a = 6378137 m, omega = 7.292115e-5 rad/s: the constants of
   docs/gravity.md and check_drop.py), no atmosphere, 10 revolutions. The two-body closed form:
   r(t) = r0 (cos n t, sin n t, 0) in ECI (ECI = ECEF at t = 0), n = sqrt(GM / r0^3). Every
   output row's ECI position within 1 m.
2. The dropped sphere with drag over the rotating WGS-84 Earth (J2, US76; check_drop.py's
   problem) for 30 s: every row's ECI position within 1 mm of tests/data/drop_wgs84_30s.csv,
   SciPy's DOP853 at rtol 1e-13 (tests/data/make_drop_reference.py says how it was made).
3. A torque-free asymmetric rigid body (dof6; I = diag(10, 20, 30) kg m^2, no engines, no
   atmosphere, point-mass gravity acting at the centre of mass: no moment) tumbling from body
   rates (0.2, 0.01, 0.05) rad/s in the orbit of 1. for 3 hours: Euler's equations conserve
   the rotational energy E = (I1 p^2 + I2 q^2 + I3 r^2) / 2 and the angular momentum's
   magnitude |H| = |I w| (Landau & Lifshitz, Mechanics, 33, 36); every output row's E and |H|
   within 1e-8 relative of the start's.
"""
import csv
import math
import os
import subprocess
import sys

GM, A, OMEGA = 3.986004418e14, 6378137.0, 7.292115e-5
H_ORBIT = 400e3

ORBIT = """mission: {{name: orbit}}
environment: {{world: planet, planet: earth, gravity: pointmass, atmosphere: none}}
parameters: {{start_lat_deg: 0, start_lon_deg: 0, start_h: {h}, start_vel: {v},
             start_fpa_deg: 0, start_chi_deg: 90}}
stages: [{{name: sat, dry_mass: 100, propellant_mass: 0}}]
phases:
  - name: coast
    model: dof3
    stages: [sat]
    stop_time: {tf}
    integrator: {{output_interval: {dt}{extra}}}
"""

DROP = """mission: {{name: ball-drop}}
environment: {{world: planet, planet: earth, gravity: j2, atmosphere: us76}}
parameters: {{start_lat_deg: 45, start_lon_deg: 0, start_h: 10000, start_vel: 0}}
stages: [{{name: ball, dry_mass: 10, propellant_mass: 0}}]
phases:
  - name: drop
    model: dof3
    stages: [ball]
    stop_time: 30
    aero: {{s_ref: 0.03, CD: 0.47}}
    integrator: {{output_interval: 1{extra}}}
"""


TUMBLE = """mission: {{name: tumble}}
environment: {{world: planet, planet: earth, gravity: pointmass, atmosphere: none}}
parameters: {{start_lat_deg: 0, start_lon_deg: 0, start_h: {h}, start_vel: {v},
             start_fpa_deg: 0, start_chi_deg: 90, start_p: 0.2, start_q: 0.01, start_r: 0.05}}
stages:
  - name: body
    dry_mass: 100
    propellant_mass: 0
    rigid_body:
      inertia_full: {{xx: 10, yy: 20, zz: 30}}
      inertia_empty: {{xx: 10, yy: 20, zz: 30}}
      cg_full: {{x: -1}}
      cg_empty: {{x: -1}}
phases:
  - name: tumble
    model: dof6
    stages: [body]
    stop_time: 10800
    integrator: {{output_interval: 60{extra}}}
"""
INERTIA = (10.0, 20.0, 30.0)


def run(lvsim, work, name, text, cols=("time", "r_eci_x", "r_eci_y", "r_eci_z")):
    path = os.path.join(work, name + ".yaml")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(work, name)
    subprocess.run([lvsim, "run", path, "-o", out, "--no-plots", "--force", "--quiet"],
                   check=True, stdout=subprocess.DEVNULL)
    phase = [f for f in os.listdir(out) if f.startswith("phase_1_") and f.endswith(".csv")][0]
    with open(os.path.join(out, phase)) as f:
        rows = list(csv.reader(f))
    col = {h.split(" ")[0]: i for i, h in enumerate(rows[0])}
    return [[float(r[col[k]]) for k in cols] for r in rows[1:]]


def main():
    lvsim, work = sys.argv[1], sys.argv[2]
    extra = ""
    if len(sys.argv) > 4:
        extra = ", method: %s, tolerance: %s" % (sys.argv[3], sys.argv[4])
    os.makedirs(work, exist_ok=True)
    fails = 0

    r0 = A + H_ORBIT
    n = math.sqrt(GM / r0 ** 3)
    period = 2.0 * math.pi / n
    v_rel = math.sqrt(GM / r0) - OMEGA * r0          # eastward, relative to the rotating Earth
    rows = run(lvsim, work, "orbit", ORBIT.format(h=H_ORBIT, v=repr(v_rel), tf=repr(10 * period),
                                                   dt=repr(period / 8), extra=extra))
    err = max(math.dist(r[1:], (r0 * math.cos(n * r[0]), r0 * math.sin(n * r[0]), 0.0))
              for r in rows)
    ok = err <= 1.0 and abs(rows[-1][0] - 10 * period) < 1e-6
    fails += not ok
    print("orbit, 10 revolutions: max |r - r_kepler| = %.3e m %s" % (err, "ok" if ok else
                                                                    "FAIL (1 m)"))

    here = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(here, "..", "data", "drop_wgs84_30s.csv")) as f:
        ref = [[float(v) for v in r[:4]] for r in csv.reader(l for l in f if not l.startswith("#"))
               if r[0] != "time"]
    rows = run(lvsim, work, "drop", DROP.format(extra=extra))
    assert len(rows) == len(ref), (len(rows), len(ref))
    err = max(math.dist(a[1:], b[1:]) for a, b in zip(rows, ref))
    ok = err <= 1e-3
    fails += not ok
    print("drop with drag, 30 s: max |r - r_ref| = %.3e m %s" % (err, "ok" if ok else
                                                                 "FAIL (1 mm)"))

    rows = run(lvsim, work, "tumble", TUMBLE.format(h=H_ORBIT, v=repr(v_rel), extra=extra),
               ("time", "p", "q", "r"))
    energy = [0.5 * sum(i * w * w for i, w in zip(INERTIA, r[1:])) for r in rows]
    mom = [math.sqrt(sum((i * w) ** 2 for i, w in zip(INERTIA, r[1:]))) for r in rows]
    de = max(abs(e / energy[0] - 1.0) for e in energy)
    dh = max(abs(h / mom[0] - 1.0) for h in mom)
    ok = de <= 1e-8 and dh <= 1e-8 and rows[-1][0] == 10800.0
    fails += not ok
    print("torque-free body, 3 h: max |dE/E| = %.2e, max |d|H|/|H|| = %.2e %s" %
          (de, dh, "ok" if ok else "FAIL (1e-8)"))
    sys.exit(1 if fails else 0)


if __name__ == "__main__":
    main()
