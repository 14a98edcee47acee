#!/usr/bin/python3
"""test_reference_cli.py - an optimiser's trajectory imported as a phase's inputs and reference
(issue 25, item 3; docs/optimal-control.md, "Importing an optimiser's trajectory").

Usage: test_reference_cli.py LVSIM

The references are written here, independently of lvsim: a drag-free coast around a
non-rotating point-mass sphere is a Kepler ellipse, propagated in closed form (Curtis, Orbital
Mechanics for Engineering Students, 3rd ed., sec. 3.4: Kepler's equation M = E - e sin E solved
by Newton's method; position and velocity in the perifocal frame, eq. 2.119-2.121) and turned
into geodetic h, lat, lon (on a sphere: h = r - R, lat = asin(z / r)) and the speed, flight-path
angle and heading of the velocity in the local north-east-up frame. Checked:
- the coast started from the reference's first row flies it: drift (3-D position, velocity
  difference, mass) far below the integration tolerance's scale (tolerance 1e-11: < 1e-4 m);
- the first result row equals the reference's first state (root and child phases);
- a reference perturbed by +100 m in h at its last row drifts by exactly 100 m there;
- a reference over tau gives the same drift as over time, one from a .mat file (MAT v5
  struct, written here) the same as from CSV;
- one control table over mission time, over tau and over mass (a constant mass flow: mass
  falls linearly, m = m0 - mdot t, so alpha(m) is alpha(t(m)) exactly) flies one trajectory;
  a step of alpha at t = 50 s and the same step where the altitude, or the energy
  v^2/2 + g0 h, had its value of t = 50 s fly one trajectory (within 1 mm after 100 s);
- a mid-burn start (reference or set: of m): the burning stage holds the mass beyond the rest,
  burnout where m0 - mdot t reaches the dry mass;
- coasts over the dateline and the pole drift as one along the equator (ECEF comparison; the
  Hermite and linear interpolation errors r th^4/384 and v th^2/8 of a circle);
- time tables with a column named `altitude` / `energy` flown over that variable;
- every bad input is refused by `lvsim check` and `lvsim run` alike, exit 2, file:line:column
  (also a reference starting after the phase's start, one covering none of it, a tau one
  starting after 0, a first mass above the full stack).
"""
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

GM = 3.986004418e14  # m^3/s^2
R = 6371000.0        # m, the sphere's radius
FAILS = []


def check(cond, what):
    if not cond:
        FAILS.append(what)
        print("FAIL:", what)


def kepler(r0, v0, ts):
    """(t, r, v) on the ellipse through (r0, v0) at times ts (closed form, see the docstring)."""
    rn = math.sqrt(sum(x * x for x in r0))
    vn2 = sum(x * x for x in v0)
    h = [r0[1] * v0[2] - r0[2] * v0[1], r0[2] * v0[0] - r0[0] * v0[2],
         r0[0] * v0[1] - r0[1] * v0[0]]
    rv = sum(a * b for a, b in zip(r0, v0))
    e_vec = [((vn2 - GM / rn) * r0[i] - rv * v0[i]) / GM for i in range(3)]
    e = math.sqrt(sum(x * x for x in e_vec))
    a = 1.0 / (2.0 / rn - vn2 / GM)
    n = math.sqrt(GM / a ** 3)
    hn = math.sqrt(sum(x * x for x in h))
    P = [x / e for x in e_vec]
    W = [x / hn for x in h]
    Q = [W[1] * P[2] - W[2] * P[1], W[2] * P[0] - W[0] * P[2], W[0] * P[1] - W[1] * P[0]]
    nu0 = math.atan2(sum(x * y for x, y in zip(Q, r0)) / rn, sum(x * y for x, y in zip(P, r0)) / rn)
    E0 = 2.0 * math.atan(math.sqrt((1 - e) / (1 + e)) * math.tan(nu0 / 2))
    M0 = E0 - e * math.sin(E0)
    out = []
    for t in ts:
        M = M0 + n * t
        E = M
        for _ in range(50):
            E -= (E - e * math.sin(E) - M) / (1 - e * math.cos(E))
        x, y = a * (math.cos(E) - e), a * math.sqrt(1 - e * e) * math.sin(E)
        edot = n / (1 - e * math.cos(E))
        vx, vy = -a * math.sin(E) * edot, a * math.sqrt(1 - e * e) * math.cos(E) * edot
        out.append((t, [x * P[i] + y * Q[i] for i in range(3)],
                    [vx * P[i] + vy * Q[i] for i in range(3)]))
    return out


def geodetic(r, v):
    """h, lat, lon, v, fpa, heading on the sphere (non-rotating: ECI = ECEF)."""
    rn = math.sqrt(sum(x * x for x in r))
    lat, lon = math.asin(r[2] / rn), math.atan2(r[1], r[0])
    up = [x / rn for x in r]
    north = [-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat)]
    east = [-math.sin(lon), math.cos(lon), 0.0]
    vn, ve, vu = (sum(a * b for a, b in zip(v, d)) for d in (north, east, up))
    sp = math.sqrt(vn * vn + ve * ve + vu * vu)
    return [rn - R, lat, lon, sp, math.asin(vu / sp), math.atan2(ve, vn) % (2 * math.pi)]


def start_state(h0, v0, fpa_deg, chi_deg, lat_deg=0.0, lon_deg=0.0):
    """ECI r, v at (lat, lon) for altitude h0, speed v0, flight-path angle, heading (the
    north-east-up frame's axes: up (cos lat cos lon, cos lat sin lon, sin lat), north
    (-sin lat cos lon, -sin lat sin lon, cos lat), east (-sin lon, cos lon, 0))."""
    g, c = math.radians(fpa_deg), math.radians(chi_deg)
    la, lo = math.radians(lat_deg), math.radians(lon_deg)
    up = [math.cos(la) * math.cos(lo), math.cos(la) * math.sin(lo), math.sin(la)]
    north = [-math.sin(la) * math.cos(lo), -math.sin(la) * math.sin(lo), math.cos(la)]
    east = [-math.sin(lo), math.cos(lo), 0.0]
    vu, vn, ve = v0 * math.sin(g), v0 * math.cos(g) * math.cos(c), v0 * math.cos(g) * math.sin(c)
    return ([(R + h0) * u for u in up],
            [vu * up[i] + vn * north[i] + ve * east[i] for i in range(3)])


def write_reference(path, states, axis="time [s]", axis_values=None, mass=1000.0, dh_last=0.0):
    with open(path, "w") as f:
        f.write(axis + ",h [m],lat [rad],lon [rad],v [m/s],fpa [rad],heading [rad],m [kg]\n")
        for i, (t, r, v) in enumerate(states):
            g = geodetic(r, v)
            if i == len(states) - 1:
                g[0] += dh_last
            x = t if axis_values is None else axis_values[i]
            f.write(",".join(repr(float(y)) for y in [x] + g + [mass]) + "\n")


def mat_v5_struct(path, name, fields):
    """A MAT v5 file holding one 1 x 1 struct `name` whose fields (name, values) are row
    vectors of doubles (MathWorks, MAT-File Format, R2018a: the 128-byte header, miMATRIX
    elements of array flags, dimensions, name, field-name length and names, then the fields),
    the layout docs/tables.md reads as a 1-D table: the first field the axis."""
    def el(typ, data):
        return struct.pack("<II", typ, len(data)) + data + b"\0" * ((8 - len(data) % 8) % 8)

    def matrix(nm, cls, dims, body):
        content = (el(6, struct.pack("<II", cls, 0)) + el(5, struct.pack("<%di" % len(dims), *dims))
                   + el(1, nm.encode()) + body)
        return struct.pack("<II", 14, len(content)) + content
    width = 32
    body = (struct.pack("<Ii", (4 << 16) | 5, width)  # small element: field-name length
            + el(1, b"".join(f.encode().ljust(width, b"\0") for f, _ in fields))
            + b"".join(matrix("", 6, [1, len(v)], el(9, struct.pack("<%dd" % len(v), *v)))
                       for _, v in fields))
    head = (b"MATLAB 5.0 MAT-file, lvsim test_reference_cli".ljust(116, b" ") + b"\0" * 8
            + struct.pack("<H", 0x0100) + b"IM")
    with open(path, "wb") as f:
        f.write(head + matrix(name, 2, [1, 1], body))


HEAD = """mission: {name: %s}
environment:
  world: planet
  planet: {name: sphere, radius: 6371000, gm: 3.986004418e14, rotation_rate: 0}
  gravity: pointmass
  atmosphere: none
"""
COAST = HEAD + """stages:
  - {name: cap, dry_mass: 1000, propellant_mass: 0}
phases:
  - name: coast
    model: dof3
    stages: [cap]
    stop_time: 1000
    reference: %s
    integrator: {method: dop853, tolerance: 1e-11, output_interval: 10}
"""


def run(lvsim, mission, out, expect=0, plots=False):
    p = subprocess.run([lvsim, "run", mission, "-o", out] + ([] if plots else ["--no-plots"]),
                       capture_output=True, text=True)
    check(p.returncode == expect, f"lvsim run {mission}: exit {p.returncode}, expected {expect}"
          f"\n{p.stdout}\n{p.stderr}")
    return p


def summary(out):
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def rows(path):
    with open(path) as f:
        lines = f.read().splitlines()
    names = [re.sub(r" \[.*\]$", "", c) for c in lines[0].split(",")]
    return [dict(zip(names, map(float, line.split(",")))) for line in lines[1:]]


def main():
    lvsim = os.path.abspath(sys.argv[1])
    tmp = tempfile.mkdtemp(prefix="lvsim-ref-")
    os.chdir(tmp)
    ts = [10.0 * i for i in range(101)]
    r0, v0 = start_state(200e3, 7800.0, 2.0, 60.0)
    states = kepler(r0, v0, ts)
    write_reference("ref.csv", states)
    write_reference("ref_tau.csv", states, "tau [1]", [t / 1000.0 for t in ts])
    write_reference("ref_100.csv", states, dh_last=100.0)

    # 1. start from the reference, fly it: drift far below the tolerance's scale
    with open("coast.yaml", "w") as f:
        f.write(COAST % ("coast", "{table: ref.csv, start: reference}"))
    p = run(lvsim, "coast.yaml", "o1")
    check("reference: phase" in p.stdout, "run prints the drift table:\n" + p.stdout)
    d = summary("o1")["phases"][0]["reference"]
    print("coast from its reference:", json.dumps(d))
    check(d["rows"] == 101 and d["start"] == "reference" and d["over"] == "time", "rows, start")
    check(d["position"]["max"] < 1e-4, "position drift %g m < 1e-4 m" % d["position"]["max"])
    check(d["velocity"]["max"] < 1e-7, "velocity drift %g m/s < 1e-7" % d["velocity"]["max"])
    check(d["mass"]["max"] == 0.0, "mass drift 0")
    first = rows("o1/phase_1_coast.csv")[0]
    g = geodetic(r0, v0)
    for key, ref, tol in (("h", g[0], 1e-6), ("lat", g[1], 1e-12), ("lon", g[2], 1e-12),
                          ("v_rel", g[3], 1e-9), ("fpa", g[4], 1e-12),
                          ("heading", g[5], 1e-12), ("m", 1000.0, 0.0)):
        check(abs(first[key] - ref) <= tol, f"first row {key} = {first[key]!r}, reference {ref!r}")

    # 1b. the same reference from a .mat file (a MAT v5 struct): the same drift
    pos_csv = d["position"]["max"]
    table = [list(map(float, line.split(","))) for line in open("ref.csv").read().splitlines()[1:]]
    mat_v5_struct("ref.mat", "opt", list(zip(["time", "h", "lat", "lon", "v", "fpa", "heading",
                                              "m"], zip(*table))))
    with open("coast_mat.yaml", "w") as f:
        f.write(COAST % ("coast-mat", "{table: {file: ref.mat, var: opt}, start: reference}"))
    run(lvsim, "coast_mat.yaml", "o1m")
    d = summary("o1m")["phases"][0]["reference"]
    check(d["rows"] == 101 and d["position"]["max"] == pos_csv,
          "from .mat: %r m, from CSV %r m" % (d["position"]["max"], pos_csv))

    # 2. the same reference perturbed by +100 m in h at its last row: exactly that drift there
    with open("coast100.yaml", "w") as f:
        f.write(COAST % ("coast100", "{table: ref_100.csv, start: reference}"))
    run(lvsim, "coast100.yaml", "o2", plots=True)
    d = summary("o2")["phases"][0]["reference"]
    # its rows, figure and report table
    check(d.get("file") == "reference_1_coast.csv",
          "reference.file: " + str(d.get("file")))
    last = rows("o2/reference_1_coast.csv")[-1]
    check(last["time"] == 1000.0 and abs(last["d_position"] - 100.0) < 1e-3 and
          abs(last["h_ref"] - last["h"] - 100.0) < 1e-3, "reference CSV last row: %r" % last)
    check(os.path.getsize("o2/plots/reference_1.png") > 1000, "plots/reference_1.png drawn")
    with open("o2/index.html") as f:
        check("Drift from the reference" in f.read(), "the report's drift table")
    print("perturbed by 100 m:", json.dumps(d))
    check(abs(d["position"]["final"] - 100.0) < 1e-3, "final drift %r m = 100 m" %
          d["position"]["final"])
    check(abs(d["position"]["max"] - 100.0) < 1e-3 and d["position"]["t_max"] == 1000.0,
          "largest drift 100 m at t = 1000 s")
    check(d["velocity"]["max"] < 1e-7, "velocity unaffected")

    # 3. over tau = t / 1000 s: the same drift
    with open("coast_tau.yaml", "w") as f:
        f.write(COAST % ("coast-tau", "{table: ref_tau.csv, start: reference}"))
    run(lvsim, "coast_tau.yaml", "o3")
    d = summary("o3")["phases"][0]["reference"]
    check(d["over"] == "tau" and d["rows"] == 101 and d["position"]["max"] < 1e-4,
          "over tau: " + json.dumps(d))

    # 3b. the phase's end next to the reference's (finding 6): a reference written up to t =
    # 999.9999 s (the ellipse's state then) still compares the phase's last row at 1000 s, the
    # position carried on by the end row's velocity (the step left: a dt^2 / 2 = 9 m/s^2 *
    # 1e-8 s^2 / 2 ~ 4e-8 m)
    ts_e = ts[:-1] + [999.9999]
    write_reference("ref_end.csv", kepler(r0, v0, ts_e))
    with open("coast_end.yaml", "w") as f:
        f.write(COAST % ("coast-end", "{table: ref_end.csv, start: reference}"))
    run(lvsim, "coast_end.yaml", "o3e")
    d = summary("o3e")["phases"][0]["reference"]
    check(d["rows"] == 101 and d["t_final"] == 1000.0 and d["position"]["final"] < 1e-4 and
          d["end"] == {"reference": 999.9999, "phase": 1000.0},
          "reference ending 1e-4 s before the phase: " + json.dumps(d))

    # 3c. a tau reference on a phase that ends before its stop_time (finding 7): said
    with open("coast_tau_early.yaml", "w") as f:
        f.write((COAST % ("coast-tau-early", "{table: ref_tau.csv, start: reference}")).replace(
            "stop_time: 1000", "stop_time: 1000\n    end: [{time: 400}]"))
    p = run(lvsim, "coast_tau_early.yaml", "o3t")
    d = summary("o3t")["phases"][0]["reference"]
    check(abs(d["end"]["phase"] - 0.4) < 1e-12 and "ended at tau = 0.4, before its stop_time"
          in p.stdout, "tau reference, phase ended at 400 s of 1000: " + json.dumps(d) + p.stdout)

    # 4. a child started from its reference (another ellipse, from t = 300 s), not its parent
    r1, v1 = start_state(250e3, 7700.0, -1.0, 45.0)
    ts1 = [300.0 + 10.0 * i for i in range(71)]
    states1 = [(t, r, v) for (t, r, v) in kepler(r1, v1, [t - 300.0 for t in ts1])]
    states1 = [(ts1[i], s[1], s[2]) for i, s in enumerate(states1)]
    write_reference("ref_child.csv", states1, mass=900.0)
    with open("child.yaml", "w") as f:
        f.write((HEAD % "child") + """parameters: {start_h: 200000, start_vel: 7800, start_fpa_deg: 2, start_chi_deg: 60}
stages:
  - {name: cap, dry_mass: 900, propellant_mass: 0}
phases:
  - {name: a, model: dof3, stages: [cap], stop_time: 290}
  - name: b
    model: dof3
    stages: [cap]
    from: a
    stop_time: 1000
    reference: {table: ref_child.csv, start: reference}
    integrator: {method: dop853, tolerance: 1e-11, output_interval: 10}
""")
    run(lvsim, "child.yaml", "o4")
    first = rows("o4/phase_2_b.csv")[0]
    g = geodetic(r1, v1)
    for key, ref, tol in (("time", 300.0, 0.0), ("h", g[0], 1e-6), ("lat", g[1], 1e-12),
                          ("lon", g[2], 1e-12), ("v_rel", g[3], 1e-9), ("fpa", g[4], 1e-12),
                          ("heading", g[5], 1e-12), ("m", 900.0, 0.0)):
        check(abs(first[key] - ref) <= tol, f"child first row {key} = {first[key]!r}, "
              f"reference {ref!r}")
    d = summary("o4")["phases"][1]["reference"]
    check(d["rows"] == 71 and d["position"]["max"] < 1e-4, "child drift " + json.dumps(d))
    # (its parent ended at 290 s: the child starts at the reference's first time, 300 s)
    # a reference that starts before the parent's end (310 s) would fly the bodies back in
    # time: the child fails at run time, naming both times (second breaker pass, finding 4)
    with open("child_back.yaml", "w") as f:
        f.write(open("child.yaml").read().replace("stop_time: 290}", "stop_time: 310}"))
    p = run(lvsim, "child_back.yaml", "o4b", expect=3)
    check(re.search(r"child_back.yaml:\d+:\d+: phase 'b': reference: it starts at t = 300 s, "
                    r"before its parent 'a' ended \(t = 310 s\)", p.stderr + p.stdout) is not None,
          "child before its parent's end: " + p.stderr[-400:])

    # 4b. a mid-burn start (finding 1 of the breaker's report): a stage of 2000 kg dry and 8000
    # kg propellant burning 70 kg/s started from a reference (or a set: of m) of 6000 kg holds
    # 4000 kg: burnout at m0 - mdot t = 2000 kg, t = 4000 / 70 = 57.142857 s, not 8000 / 70
    write_reference("ref_6000.csv", states, mass=6000.0)
    for name, extra in (("ref", "reference: {table: ref_6000.csv, start: reference}"),
                        ("set", "set: {m: 6000}")):
        with open(f"mid_{name}.yaml", "w") as f:
            f.write((HEAD % ("mid-" + name)) + """parameters: {start_h: 200000, start_vel: 7800, start_fpa_deg: 2, start_chi_deg: 60}
stages:
  - {name: s1, dry_mass: 2000, propellant_mass: 8000, engines: [{thrust_vac: 2.0e5, mdot: 70}]}
phases:
  - name: burn
    model: dof3
    stages: [s1]
    stop_time: 100
    end: [burnout]
    %s
    integrator: {method: dop853, tolerance: 1e-11, output_interval: 10}
""" % extra)
        run(lvsim, f"mid_{name}.yaml", "o_mid_" + name)
        last = rows(f"o_mid_{name}/phase_1_burn.csv")[-1]
        ph = summary("o_mid_" + name)["phases"][0]
        print(f"mid-burn start ({name}): burnout at {last['time']!r} s, m = {last['m']!r} kg")
        check(abs(last["time"] - 4000.0 / 70.0) < 1e-6 and abs(last["m"] - 2000.0) < 1e-6,
              f"mid-burn {name}: burnout at {last['time']} s (4000/70), m {last['m']} (2000)")
        check(abs(ph["payload"]) < 1e-9, f"mid-burn {name}: payload {ph['payload']} kg, not 0")

    # 4b'. lvsim's own result CSV as a reference (finding 8): the burnout instant is written
    # twice (before and after the event, one time); the later row is taken. Its columns cut
    # to the reference's (the whole file holds nan where an output is undefined, e.g. the Mach
    # number in vacuum, which no table takes). Re-flown from it: the same trajectory, so the
    # drift is the integration's (< 1e-3 m)
    own = open("o_mid_ref/phase_1_burn.csv").read().splitlines()
    names = [re.sub(r" \[.*\]$", "", c) for c in own[0].split(",")]
    keep = [names.index(c) for c in ("time", "h", "lat", "lon", "v_rel", "fpa", "heading", "m")]
    with open("own.csv", "w") as f:
        for line in own:
            f.write(",".join(line.split(",")[i] for i in keep) + "\n")
    t_rows = [r["time"] for r in rows("own.csv")]
    check(any(a == b for a, b in zip(t_rows, t_rows[1:])), "an event row written twice")
    with open("own.yaml", "w") as f:
        f.write(open("mid_ref.yaml").read().replace("ref_6000.csv", "own.csv")
                .replace("mid-ref", "own"))
    run(lvsim, "own.yaml", "o_own")
    d = summary("o_own")["phases"][0]["reference"]
    print("re-flown from its own result CSV:", json.dumps(d))
    check(d["rows"] >= len(t_rows) - 1 and d["position"]["max"] < 1e-3 and
          d["mass"]["max"] < 1e-6, "re-flown from its own CSV: " + json.dumps(d))

    # 4c. angles that wrap (finding 2): coasts over the dateline and over the north pole,
    # re-flown from their own reference written every 10 s and compared every 1 s, drift as
    # little as one along the equator that crosses nothing. The reference is interpolated in
    # ECEF, the position by cubic Hermite with the reference's own velocity: its error on a
    # circle of radius r stepped by the angle th = w h is r th^4 / 384 (the Hermite remainder
    # f(xi) h^4 / 384 with |f| = r w^4), the velocity's (linear) v th^2 / 8.
    drift = {}
    for name, lat0, lon0, chi in (("zero", 0.0, 0.0, 90.0), ("east", 0.0, 170.0, 90.0),
                                  ("pole", 70.0, 0.0, 0.0)):
        ts_w = [10.0 * i for i in range(61)]
        rr, vv = start_state(200e3, 7790.0, 0.0, chi, lat0, lon0)
        write_reference(f"wrap_{name}.csv", kepler(rr, vv, ts_w))
        with open(f"wrap_{name}.yaml", "w") as f:
            f.write((COAST % ("wrap-" + name, "{table: wrap_%s.csv, start: reference}" % name))
                    .replace("stop_time: 1000", "stop_time: 600")
                    .replace("output_interval: 10", "output_interval: 1"))
        run(lvsim, f"wrap_{name}.yaml", "o_wrap_" + name)
        drift[name] = summary("o_wrap_" + name)["phases"][0]["reference"]
    rc = R + 200e3
    th = 7790.0 / rc * 10.0
    pos_bound, vel_bound = rc * th ** 4 / 384.0, 7790.0 * th ** 2 / 8.0
    for name, d in drift.items():
        print(f"wrap {name}: position {d['position']['max']:.4g} m (r th^4/384 = "
              f"{pos_bound:.4g}), velocity {d['velocity']['max']:.4g} m/s (v th^2/8 = "
              f"{vel_bound:.4g})")
        check(d["rows"] == 601 and d["position"]["max"] < 1.1 * pos_bound and
              d["velocity"]["max"] < 1.1 * vel_bound,
              f"wrap {name}: drift {d['position']['max']} m, {d['velocity']['max']} m/s")
        check(abs(d["position"]["max"] - drift["zero"]["position"]["max"]) < 1e-5,
              f"wrap {name}: {d['position']['max']} m as the equator's "
              f"{drift['zero']['position']['max']} m")

    # 5. one control table over time, tau and mass: one trajectory
    m0, mdot = 10000.0, 70.0
    with open("in_time.csv", "w") as f:
        f.write("time [s],alpha [rad],m [kg]\n")
        for t, a in ((0, 0.0), (25, 0.05), (50, 0.1), (75, 0.025), (100, -0.05)):
            f.write("%r,%r,%r\n" % (float(t), a, m0 - mdot * t))
    finals = {}
    for over in ("time", "tau", "mass", "none"):
        inputs = ("{alpha: 0}" if over == "none" else
                  "{table: in_time.csv, over: %s}" % over)
        with open(f"pw_{over}.yaml", "w") as f:
            f.write((HEAD % ("powered-" + over)) + """parameters: {start_h: 10000, start_vel: 300, start_fpa_deg: 60, start_chi_deg: 90}
stages:
  - name: s1
    dry_mass: 2000
    propellant_mass: 8000
    engines: [{thrust_vac: 2.0e5, mdot: 70}]
phases:
  - name: burn
    model: dof3
    stages: [s1]
    stop_time: 100
    inputs: %s
    integrator: {method: dop853, tolerance: 1e-11, output_interval: 10}
""" % inputs)
        run(lvsim, f"pw_{over}.yaml", "o5" + over)
        finals[over] = rows(f"o5{over}/phase_1_burn.csv")[-1]

    def dist(a, b, pre):
        return math.sqrt(sum((a[pre + c] - b[pre + c]) ** 2 for c in "xyz"))
    for over in ("tau", "mass"):
        dr = dist(finals[over], finals["time"], "r_eci_")
        dv = dist(finals[over], finals["time"], "v_eci_")
        print(f"inputs over {over} vs over time: {dr:.3g} m, {dv:.3g} m/s at t = 100 s")
        check(dr < 1e-3 and dv < 1e-5, f"over {over}: {dr} m, {dv} m/s from over time")
    dr = dist(finals["none"], finals["time"], "r_eci_")
    check(dr > 100.0, f"the inputs act: alpha = 0 ends {dr} m away")

    # 5b. over altitude and over energy: alpha steps from 0 to 0.1 rad within 1 ms at t = 50 s
    # (a time table) or where the altitude / the energy v^2/2 + g0 h had its value of t = 50 s
    # (tables over those variables, their step as wide as the time table's): one trajectory
    def powered(name, inputs):
        with open(name + ".yaml", "w") as f:
            f.write(open("pw_time.yaml").read().replace(
                "{table: in_time.csv, over: time}", inputs).replace("powered-time", name))
        run(lvsim, name + ".yaml", "o_" + name)
        return rows(f"o_{name}/phase_1_burn.csv")
    with open("step_time.csv", "w") as f:
        f.write("time [s],alpha [rad]\n0,0\n50,0\n50.001,0.1\n100,0.1\n")
    a = powered("step-time", "{table: step_time.csv}")
    at50 = next(r for r in a if r["time"] == 50.0)
    up = -at50["v_down"]                              # dh/dt, m/s
    e50 = 0.5 * at50["v_rel"] ** 2 + 9.80665 * at50["h"]
    # dE/dt = v . dv/dt + g0 dh/dt (a non-rotating planet: v_rel is the inertial velocity)
    de = sum(at50["v_eci_" + c] * at50[f"der(v_eci_{c})"] for c in "xyz") + 9.80665 * up
    with open("step_h.csv", "w") as f:
        f.write("altitude [m],alpha [rad]\n0,0\n%r,0\n%r,0.1\n1e7,0.1\n"
                % (at50["h"], at50["h"] + 1e-3 * up))
    with open("step_e.csv", "w") as f:
        f.write("energy [J/kg],alpha [rad]\n0,0\n%r,0\n%r,0.1\n1e9,0.1\n" % (e50, e50 + 1e-3 * de))
    # the same steps from time tables carrying the variable in a column named as the over:
    # word (finding 3: `altitude`, `energy`; re-tabulated over it when loaded)
    with open("step_h_col.csv", "w") as f:
        f.write("time [s],altitude [m],alpha [rad]\n0,0,0\n50,%r,0\n50.001,%r,0.1\n100,1e7,0.1\n"
                % (at50["h"], at50["h"] + 1e-3 * up))
    with open("step_e_col.csv", "w") as f:
        f.write("time [s],energy [J/kg],alpha [rad]\n0,0,0\n50,%r,0\n50.001,%r,0.1\n100,1e9,0.1\n"
                % (e50, e50 + 1e-3 * de))
    for name, table in (("step-h", "{table: step_h.csv, over: altitude}"),
                        ("step-e", "{table: step_e.csv, over: energy}"),
                        ("step-h-col", "{table: step_h_col.csv, over: altitude}"),
                        ("step-e-col", "{table: step_e_col.csv, over: energy}")):
        b = powered(name, table)
        dr = dist(b[-1], a[-1], "r_eci_")
        print(f"inputs over {table}: {dr:.3g} m from the time table at t = 100 s")
        check(dr < 1e-3, f"{name}: {dr} m from the time table")
        check(dist(b[-1], finals["none"], "r_eci_") > 100.0, f"{name}: the step acts")

    # 6. bad inputs: check and run alike, exit 2, file:line:column
    with open("in_up_down.csv", "w") as f:
        f.write("time [s],alpha [rad],h [m]\n0,0,100\n10,0.1,200\n20,0.2,150\n")
    with open("ref_deg.csv", "w") as f:
        f.write(open("ref.csv").read().replace("lat [rad]", "lat [deg]"))
    with open("ref_missing.csv", "w") as f:
        f.write("\n".join(",".join(l.split(",")[:5]) for l in
                          open("ref.csv").read().splitlines()) + "\n")
    write_reference("ref_late.csv", [(t + 10.0, r, v) for t, r, v in states])
    write_reference("ref_after.csv", [(t + 2000.0, r, v) for t, r, v in states[:11]] +
                    [(3000.0, states[11][1], states[11][2])])
    write_reference("ref_tau_late.csv", states[:11], "tau [1]", [0.1 + 0.09 * i for i in range(11)])
    write_reference("ref_heavy.csv", states, mass=1000.5)

    def edit_ref(src, dst, row, col, value):
        """`src` with data row `row` column `col` (0: the axis) set to `value`."""
        lines = open(src).read().splitlines()
        cells = lines[row].split(",")
        cells[col] = value
        lines[row] = ",".join(cells)
        with open(dst, "w") as f:
            f.write("\n".join(lines) + "\n")
    edit_ref("ref.csv", "ref_lat_deg.csv", 1, 2, "52.5")
    edit_ref("ref.csv", "ref_fpa_big.csv", 3, 5, "2.5")
    edit_ref("ref.csv", "ref_lon_deg.csv", 1, 3, "300")
    edit_ref("ref.csv", "ref_neg_v.csv", 2, 4, "-1")
    with open("ref_dup.csv", "w") as f:  # h twice: as h and as altitude
        for i, line in enumerate(open("ref.csv").read().splitlines()):
            c = line.split(",")
            f.write(",".join(c[:2] + (["altitude [m]"] if i == 0 else [c[1]]) + c[2:]) + "\n")
    with open("in_alpha_deg.csv", "w") as f:
        f.write(open("in_time.csv").read().replace("alpha [rad]", "alpha_deg [deg]"))
    # finding 13: a last tau of 1 + 1e-15 (an optimiser's round-off) is its 1: accepted
    write_reference("ref_tau_noisy.csv", states, "tau [1]", [t / 1000.0 for t in ts[:-1]] +
                    [1.0 + 1e-15])
    with open("coast_tau_noisy.yaml", "w") as f:
        f.write(COAST % ("coast-tau-noisy", "{table: ref_tau_noisy.csv, start: reference}"))
    run(lvsim, "coast_tau_noisy.yaml", "o_tau_noisy")
    d = summary("o_tau_noisy")["phases"][0]["reference"]
    check(d["rows"] == 101 and d["position"]["max"] < 1e-4, "tau 1 + 1e-15: " + json.dumps(d))
    pw = open("pw_time.yaml").read()
    coast = open("coast.yaml").read()
    child = open("child.yaml").read()
    bad = {
        # the second breaker's finding 1: a set: of a state (or a separation) with start:
        # reference overrode the reference on a child (a 500 kg drift, payload -500 kg) and
        # was ignored on a root
        "set_child": (child.replace("    reference: {table: ref_child.csv, start: reference}",
                                    "    reference: {table: ref_child.csv, start: reference}\n"
                                    "    set: {m: 850}"),
                      r":\d+:\d+: phase 'b': set: 'm': the phase starts from its reference's "
                      r"first row \(start: reference\)"),
        "set_root_v": (coast.replace("{table: ref.csv, start: reference}\n",
                                     "{table: ref.csv, start: reference}\n    set: {start_vel: 10}\n"),
                       r":\d+:\d+: phase 'coast': set: 'start_vel': the phase starts from its "
                       r"reference's first row"),
        "separation": (child.replace("    reference: {table: ref_child.csv, start: reference}",
                                     "    reference: {table: ref_child.csv, start: reference}\n"
                                     "    separation: {dv: 5}"),
                       r":\d+:\d+: phase 'b', separation: the phase starts from its reference's "
                       r"first row"),
        "nonmonotone": (pw.replace("in_time.csv, over: time", "in_up_down.csv, over: altitude"),
                        r"bad_nonmonotone.yaml:\d+:\d+: phase 'burn', inputs: over: altitude: "
                        r"the variable is not strictly monotone"),
        "nocolumn": (pw.replace("over: time", "over: speed"),
                     r":\d+:\d+: .*over: speed: the table 'in_time' has no column of it"),
        "overword": (pw.replace("over: time", "over: apogee"),
                     r":\d+:\d+: .*over: unknown value 'apogee'"),
        "deg": (coast.replace("ref.csv", "ref_deg.csv"), r":\d+:\d+: .*column 'lat' is in \[deg\]"),
        "missing": (coast.replace("ref.csv", "ref_missing.csv"),
                    r":\d+:\d+: .*lacks the columns fpa, heading, m"),
        "start": (coast.replace("start: reference", "start: launch"),
                  r":\d+:\d+: .*start: unknown value 'launch'"),
        "flat6": ("mission: {name: f}\nstages:\n  - {name: s, dry_mass: 100, propellant_mass: 0}\n"
                  "phases:\n  - {name: c, model: flat6, stages: [s], stop_time: 10, "
                  "reference: ref.csv}\n",
                  r":5:\d+: phase 'c': 'reference' applies to the dof3, dof6 models only"),
        "axis": (coast.replace("ref.csv", "in_time.csv"), r":\d+:\d+: .*lacks the columns"),
        "light": (coast.replace("dry_mass: 1000", "dry_mass: 1200"),
                  r":\d+:\d+: phase 'coast': reference: its first mass m = 1000 kg is less than "
                  r"the dry mass 1200 kg"),
        "ref_late": (coast.replace("ref.csv", "ref_late.csv"),
                     r":\d+:\d+: phase 'coast': reference: table 'ref_late' starts at t = 10 s, "
                     r"but the phase starts at t = 0 s"),
        "ref_outside": (coast.replace("{table: ref.csv, start: reference}", "ref_after.csv"),
                        r":\d+:\d+: phase 'coast': reference: table 'ref_after' covers t = 2000 "
                        r"\.\. 3000 s, no part of the phase's t = 0 \.\. 1000 s"),
        "tau_late": (coast.replace("ref.csv", "ref_tau_late.csv"),
                     r":\d+:\d+: phase 'coast': reference: table 'ref_tau_late' starts at "
                     r"tau = 0.10000000000000001"),
        "heavy": (coast.replace("ref.csv", "ref_heavy.csv"),
                  r":\d+:\d+: phase 'coast': reference: its first mass m = 1000.5 kg is more "
                  r"than the 1000 kg of the stages it carries full"),
        # finding 9: impossible values refused with start: parent too, naming row and column
        "lat_big": (coast.replace("{table: ref.csv, start: reference}", "ref_lat_deg.csv"),
                    r":\d+:\d+: phase 'coast', reference: table 'ref_lat_deg', data row 1 "
                    r"\(time = 0\), column 'lat': 52.5 is not a latitude within \[-pi/2, pi/2\]"),
        "fpa_big": (coast.replace("ref.csv", "ref_fpa_big.csv"),
                    r"data row 3 \(time = 20\), column 'fpa': 2.5 is not a flight-path angle"),
        "lon_deg": (coast.replace("ref.csv", "ref_lon_deg.csv"),
                    r"data row 1 \(time = 0\), column 'lon': 300 is not a longitude within a "
                    r"turn either way"),
        "neg_v": (coast.replace("ref.csv", "ref_neg_v.csv"),
                  r"data row 2 \(time = 10\), column 'v': -1 is not a speed >= 0"),
        # finding 10: two names of one column; an input column in other units under another name
        "dup_alias": (coast.replace("ref.csv", "ref_dup.csv"),
                      r":\d+:\d+: .*table 'ref_dup' has both 'h' and 'altitude', two names of the "
                      r"column h"),
        "alpha_deg": (pw.replace("in_time.csv", "in_alpha_deg.csv"),
                      r":\d+:\d+: phase 'burn', inputs: table 'in_alpha_deg' has a column "
                      r"'alpha_deg' but none 'alpha'"),
        # finding 12: a dispersion or targeting variable of a start value the reference replaces
        "disp_override": (coast.replace("stages:", "parameters: {start_fpa_deg: 2}\nstages:", 1) +
                          "dispersions:\n  parameters:\n    start_fpa_deg: {dist: normal, "
                          "sigma: 0.05}\n",
                          r":\d+:\d+: dispersions: 'start_fpa_deg' has no effect: phase 'coast' "
                          r"starts from its reference \(start: reference\)"),
        "energy": (pw.replace("in_time.csv, over: time", "in_up_down.csv, over: energy"),
                   r":\d+:\d+: .*over: energy: the table 'in_up_down' has no column of it "
                   r"\(`energy`, or `h` and `v`"),
    }
    for name, (text, pattern) in bad.items():
        path = f"bad_{name}.yaml"
        with open(path, "w") as f:
            f.write(text)
        c = subprocess.run([lvsim, "check", path], capture_output=True, text=True)
        r = subprocess.run([lvsim, "run", path, "-o", "obad", "--outputs", "none"],
                           capture_output=True, text=True)
        check(c.returncode == 2 and r.returncode == 2,
              f"{name}: check exit {c.returncode}, run exit {r.returncode}: {c.stderr}{r.stderr}")
        check(re.search(pattern, c.stderr) is not None, f"{name}: check says {c.stderr!r}, "
              f"expected /{pattern}/")
        check(c.stderr.strip() in r.stderr, f"{name}: run says {r.stderr!r}, check {c.stderr!r}")
    shutil.rmtree(tmp)
    print("%d failure(s)" % len(FAILS))
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
