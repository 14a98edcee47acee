"""sensitivities.py - how the booster's landing point in kourou-rtls-targeted moves with each
boost-back variable, at the converged point: the figures of docs/targeting.md, "A worked
example: closing a booster's return (RTLS)".

    PYTHONPATH=build/python python3 examples/kourou-rtls-targeted/sensitivities.py

Solves the example's targeting section, then perturbs one boost-back parameter at a time by
+- its step (central differences) and runs the booster's branch (boostback to landing) of
each point. The landing point's change is given in metres east (down-range: the return flies
due west) and north (cross-range), on the WGS-84 ellipsoid's radii of curvature at the pad."""
import math
import os
import sys

import lvsim

HERE = os.path.dirname(os.path.abspath(__file__))
A, E2 = 6378137.0, 6.69437999014e-3  # WGS-84 semi-major axis (m), first eccentricity squared

# (run parameter, step): the example's two variables, then the other candidates
VARIABLES = [("boostback.end.target_overshoot", 100.0),        # m
             ("boostback.guidance.target_lat_deg", 0.001),     # deg
             ("boostback.guidance.target_lon_deg", 0.001),     # deg
             ("boostback.guidance.pitch_deg", 1.0),            # deg
             ("boostback.throttle.value", 0.01)]               # 1, where the file writes it


def radii(lat):
    """Meridian and prime-vertical radii of curvature (m) at geodetic latitude lat (rad)."""
    w = 1.0 - E2 * math.sin(lat) ** 2
    return A * (1.0 - E2) / w ** 1.5, A / math.sqrt(w)


def _landing(m, params):
    r = m.run(params=params, phases=["landing"])
    bb = r.result("boostback")
    out = dict(lat=r.final("landing", "lat"), lon=r.final("landing", "lon"),
               burn=bb.t_end - bb.t_start, mass=r.final("landing", "m"),
               v_east=r.final("boostback", "v_east"), v_north=r.final("boostback", "v_north"),
               v_up=-r.final("boostback", "v_down"), h=r.final("boostback", "h"),
               miss=r.final("landing", "target_distance"))
    r.close()
    return out


def sensitivities(path=os.path.join(HERE, "mission.yaml")):
    """(result, base, rows): the targeting result, the landing at the converged point and,
    per variable, a dict of the landing's move east and north (m), the boost-back's duration
    (s), the landing mass (kg) and the boost-back's final velocity east, north and up (m/s),
    each per step (central differences)."""
    with lvsim.Mission(path) as m, m.target() as t:
        res = t.solve()
        x = dict(res.x)
        base = _landing(m, x)
        mer, pv = radii(base["lat"])
        rows = []
        for name, step in VARIABLES:
            try:  # a boost-back with `engines: N` writes no throttle value: left out
                v0 = x[name] if name in x else m.parameter(name).value
            except lvsim.LvsimError:
                continue
            up, dn = (_landing(m, {**x, name: v0 + s * step}) for s in (1.0, -1.0))
            d = {k: (up[k] - dn[k]) / 2.0 for k in up}
            rows.append(dict(name=name, step=step, start=v0,
                             east=d["lon"] * pv * math.cos(base["lat"]), north=d["lat"] * mer,
                             burn=d["burn"], mass=d["mass"], v_east=d["v_east"],
                             v_north=d["v_north"], v_up=d["v_up"]))
    return res, base, rows


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, "mission.yaml")
    res, base, rows = sensitivities(path)
    print(f"converged: {res.converged} ({res.iterations} iterations, {res.phases} phase "
          f"simulations); ends not as assumed: {res.end_mismatches or 'none'}")
    print(f"landing {math.degrees(base['lat']):.7f} N {math.degrees(base['lon']):.7f} E, "
          f"{base['miss'] * 1000:.1f} mm from the pad; boost-back {base['burn']:.3f} s, ends "
          f"{base['h'] / 1000:.1f} km high at {base['v_east']:.1f} m/s east, {base['v_up']:.1f} "
          f"m/s up; landing mass {base['mass']:.0f} kg")
    print(f"{'variable':36} {'step':>6} {'at':>12} {'east m':>9} {'north m':>9} {'burn s':>8} "
          f"{'mass kg':>8} {'dv_E':>7} {'dv_N':>7} {'dv_up':>7}")
    for r in rows:
        print(f"{r['name']:36} {r['step']:>6g} {r['start']:>12.7g} {r['east']:>+9.2f} "
              f"{r['north']:>+9.2f} {r['burn']:>+8.3f} {r['mass']:>+8.1f} {r['v_east']:>+7.3f} "
              f"{r['v_north']:>+7.3f} {r['v_up']:>+7.3f}")


if __name__ == "__main__":
    main()
