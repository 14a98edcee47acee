#!/usr/bin/python3
"""check_key_figures.py - the report's key figures recomputed from the CSV files.

Usage: check_key_figures.py LVSIM SOURCE_DIR

Runs examples/dof3-branch (a planet world: aerodynamic loads, an upper stage on an escape
trajectory, a booster that falls back) and examples/paper-test-case (the flat world), then
recomputes every key figure of every body from summary.json and the phase and body CSV
files with Python's csv and math modules only, following the definitions of
docs/visualization.md ("Key figures"), and compares them with OUTDIR/key_figures.json
(relative 1e-12). It also checks the physics where a closed form exists: the flat world's
axial load factor at burnout is thrust / (m g0) with the stage's own thrust table value,
and a vertical flight lands where it started. And that index.html shows the figures, with
Figure 10 as the first figure and no ground-track map for the vertical flat-world flight.
Exit 0 when every check passes.
"""
import csv
import hashlib
import json
import math
import os
import re
import subprocess
import sys
import tempfile

G0 = 9.80665
R_MEAN = 6371008.8
ATMO_TOP = 1000e3
FAILS = []
CHECKS = [0]


def check(cond, what):
    CHECKS[0] += 1
    if not cond:
        FAILS.append(what)


def close(a, b, what, rel=1e-12):
    CHECKS[0] += 1
    if a is None or b is None:
        if a is not b:
            FAILS.append("%s: %r vs %r" % (what, a, b))
        return
    if not (abs(a - b) <= rel * max(1.0, abs(a), abs(b))):
        FAILS.append("%s: %.17g vs %.17g" % (what, a, b))


def load_csv(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    head = [h.split(" [")[0] for h in rows[0]]
    out = []
    for r in rows[1:]:
        d = {}
        for k, v in zip(head, r):
            try:
                d[k] = float(v)
            except ValueError:
                d[k] = v
        out.append(d)
    return out


def first(row, *names):
    for n in names:
        if n in row:
            return row[n]
    return None


def state(row, phase):
    s = {"phase": phase, "t": row["time"], "h": first(row, "h", "z"),
         "speed": first(row, "v_rel", "speed"), "vehicle_mass": row["m"]}
    for k in ("v_inertial", "fpa"):
        if k in row:
            s[k] = row[k]
    if "lat" in row:
        s["lat"], s["lon"] = row["lat"], row["lon"]
    elif "x" in row:
        s["x"], s["y"] = row["x"], row["y"]
    return s


def compare_state(got, want, what):
    check(got is not None, what + ": missing")
    if got is None:
        return
    for k, v in want.items():
        if isinstance(v, str):
            check(got.get(k) == v, "%s.%s: %r vs %r" % (what, k, got.get(k), v))
        else:
            close(got.get(k), v, "%s.%s" % (what, k))


def heating(names, rows):
    """The heating figures of docs/visualization.md: the largest heat_flux (its time, altitude,
    phase), the heat load, and the first downward crossing of 1135 W/m^2 by heat_flux_fm
    (linear between the rows around it). The heat load: over a phase with the model's heat_load
    column (the integral integrated with the trajectory) its change, last row less first; else
    the trapezoidal rule over the phase's rows. Where the column is, the trapezoidal rule is
    computed too ("trap") and compared at 1 % (its own error over 1 s rows)."""
    hmax, load, fm, trap = None, 0.0, None, 0.0
    any_cols = False
    for pn in names:
        rs = rows[pn]
        if not rs or "heat_flux" not in rs[0]:
            continue
        any_cols = True
        has_load = "heat_load" in rs[0]
        if has_load:
            load += rs[-1]["heat_load"] - rs[0]["heat_load"]
        for i, r in enumerate(rs):
            if hmax is None or r["heat_flux"] > hmax[0]:
                hmax = (r["heat_flux"], r["time"], r["h"], pn)
            if i == 0:
                continue
            p = rs[i - 1]
            step = 0.5 * (r["time"] - p["time"]) * (r["heat_flux"] + p["heat_flux"])
            trap += step
            if not has_load:
                load += step
            if fm is None and p["heat_flux_fm"] >= 1135 and r["heat_flux_fm"] < 1135:
                w = (p["heat_flux_fm"] - 1135) / (p["heat_flux_fm"] - r["heat_flux_fm"])
                fm = (p["time"] + w * (r["time"] - p["time"]), p["h"] + w * (r["h"] - p["h"]), pn)
    return {"max": hmax, "load": load, "trap": trap, "fm": fm} if any_cols else None


def flat_g(summ):
    """The flat world's gravity: environment g of the mission file (the model's 9.81 without)."""
    g = 9.81
    for line in open(summ["file"]):
        m = re.match(r"^\s+g:\s*([-+0-9.eE]+)", line)
        if m:
            g = float(m.group(1))
    return g


def axial(r, g):
    """The axial load factor [g0]: the sensed specific force along the body axis. The model's
    n_axial; in the flat world (thrust along +z) the specific force's z part: without air,
    thrust / m; with air (thrust and drag the only forces besides gravity) der(vz) + g, the
    vertical acceleration with gravity's removed: an account independent of lvsim's (which
    splits the drag from its horizontal parts)."""
    if "n_axial" in r:
        return r["n_axial"]
    if "rho" in r:
        return (r["der(vz)"] + g) / G0
    return r["thrust"] / (r["m"] * G0)


def iip_cutoff(name, names, by_name, rows):
    """The IIP at the end of each powered phase (docs/visualization.md): in each phase of the
    body with the iip_* columns whose bottom stage is the body, the last row with thrust > 0;
    NaN (no impact) as null. None when no phase of the body has the columns."""
    out, any_cols = [], False
    for pn in names:
        rs = rows[pn]
        if not rs or "iip_lat" not in rs[0]:
            continue
        any_cols = True
        if by_name[pn]["stages"][0] != name or "thrust" not in rs[0]:
            continue
        pw = [r for r in rs if r["thrust"] > 0]
        if not pw:
            continue
        r = pw[-1]
        e = {"phase": pn, "t": r["time"], "h": r["h"], "impact": not math.isnan(r["iip_lat"])}
        for k in ("iip_lat", "iip_lon", "iip_tof", "iip_range"):
            e[k] = None if math.isnan(r[k]) else r[k]
        out.append(e)
    return out if any_cols else None


def key_figures(outdir):
    summ = json.load(open(os.path.join(outdir, "summary.json")))
    phases = summ["phases"]
    by_name = {p["name"]: p for p in phases}
    rows = {p["name"]: load_csv(os.path.join(outdir, p["files"]["csv"])) for p in phases}
    flat = summ["world"] == "flat"
    g = flat_g(summ) if flat else None
    bodies = []
    for b in summ["bodies"]:
        name = b["name"]
        traj = load_csv(os.path.join(outdir, b["trajectory"]))
        names = b["phases"]
        q = na = nn = None
        burn, sep, inj = [], [], None
        carried = None  # the last row with thrust > 0 of any phase it flies in, its phase
        for pn in names:
            p, rs = by_name[pn], rows[pn]
            grounded = p["end"].get("event") == "impact"
            for i, r in enumerate(rs):
                h = first(r, "h", "z")
                if "q_dyn" in r and r["rho"] > 0 and h <= ATMO_TOP and (q is None or r["q_dyn"] > q[0]):
                    q = (r["q_dyn"], r["time"], h)
                # the ground contact's row (a phase ended by impact: its last) is no flight load
                if grounded and i == len(rs) - 1:
                    continue
                n = axial(r, g)
                if na is None or abs(n) > abs(na[0]):  # the largest in magnitude, signed
                    na = (n, r["time"])
                if "n_normal" in r and (nn is None or abs(r["n_normal"]) > nn[0]):
                    nn = (abs(r["n_normal"]), r["time"])
            if p["from"] is not None and len(p["stages"]) < len(by_name[p["from"]]["stages"]):
                sep.append(state(rs[0], pn))
            for e in p["events"]:
                if e["kind"] == "state" and e["name"] == "burnout" and p["stages"][0] == name:
                    r = next(r for r in rs if r["time"] == e["t"])
                    burn.append(state(r, pn))
            # the injection: the body's last row with thrust > 0 in a phase its stage burns in
            # (the end of powered flight, whatever event ended it)
            for r in rs:
                if "thrust" in r and r["thrust"] > 0 and "sma" in r:
                    carried = (r, pn)
                if p["stages"][0] == name and r["thrust"] > 0 and "sma" in r:
                    inj = dict(state(r, pn), fpa_inertial=r["fpa_inertial"])
                    inj["orbit"] = {k: r[c] for k, c in (("sma", "sma"), ("ecc", "ecc"), ("inc", "inc"),
                                                          ("peri_alt", "peri_alt"))}
                    above, bound = r["peri_alt"] > 100e3, r["ecc"] < 1
                    inj["trajectory"] = "suborbital" if not above else "orbit" if bound else "escape"
                    inj_phase = pn
        # a body that never burns (a payload) and ends in orbit: the injection of the last
        # stage that carried it, the same row; not one dropped before orbit (a fairing)
        last_row = rows[names[-1]][-1]
        if inj is None and carried is not None and last_row.get("peri_alt", 0) > 100e3 \
                and carried[0]["peri_alt"] > 100e3:
            r, pn = carried
            inj = dict(state(r, pn), fpa_inertial=r["fpa_inertial"])
            inj["orbit"] = {k: r[k] for k in ("sma", "ecc", "inc", "peri_alt")}
            inj["trajectory"] = "orbit" if r["ecc"] < 1 else "escape"
            inj["carried_by"] = by_name[pn]["stages"][0]
            inj_phase = pn
        # a suborbital end of powered flight only where the body coasts up from it, and not a
        # burn that ends on the ground (a landing)
        if inj is not None and inj["trajectory"] == "suborbital":
            lands = inj_phase == names[-1] and by_name[names[-1]]["end"].get("event") == "impact"
            if not (inj["fpa_inertial"] > 0) or lands:
                inj = None
        last = rows[names[-1]][-1]
        final = dict(state(last, names[-1]), stage_mass=traj[-1]["stage_mass"])
        lp = by_name[names[-1]]
        gc = None
        if lp["end"].get("event") == "impact":
            r0 = rows[names[0]][0]
            gc = {"t": last["time"], "speed": first(last, "v_rel", "speed"),
                  "n_axial": axial(last, g)}
            if "n_normal" in last:
                gc["n_normal"] = abs(last["n_normal"])
            gc["kind"] = "landing" if gc["speed"] < 10 else "impact"
            if not flat:
                s1 = math.sin(0.5 * (last["lat"] - r0["lat"]))
                s2 = math.sin(0.5 * (last["lon"] - r0["lon"]))
                a = s1 * s1 + math.cos(r0["lat"]) * math.cos(last["lat"]) * s2 * s2
                gc["distance"] = 2 * R_MEAN * math.asin(min(1.0, math.sqrt(a)))
            else:
                gc["distance"] = math.hypot(last["x"] - r0["x"], last["y"] - r0["y"])
        bodies.append({"name": name, "final": final, "max_q": q, "max_n_axial": na, "max_n_normal": nn,
                       "burnouts": burn, "separations": sep, "injection": inj, "ground_contact": gc,
                       "heating": heating(names, rows),
                       "iip_cutoff": iip_cutoff(name, names, by_name, rows)})
    return summ, bodies


def compare(outdir):
    summ, want = key_figures(outdir)
    got = json.load(open(os.path.join(outdir, "key_figures.json")))
    check([b["name"] for b in got["bodies"]] == [b["name"] for b in want], outdir + ": bodies")
    for g, w in zip(got["bodies"], want):
        n = "%s %s" % (summ["mission"], w["name"])
        compare_state(g["final"], w["final"], n + " final")
        for key in ("max_q", "max_n_axial", "max_n_normal"):
            if w[key] is None:
                check(g[key] is None, "%s %s: %r, expected none" % (n, key, g[key]))
                continue
            close(g[key]["value"], w[key][0], "%s %s" % (n, key), rel=1e-9 if key == "max_n_axial" else 1e-12)
            close(g[key]["t"], w[key][1], "%s %s time" % (n, key))
            if key == "max_q":
                close(g[key]["h"], w[key][2], n + " max_q altitude")
        for key in ("burnouts", "separations"):
            check(len(g[key]) == len(w[key]), "%s %s: %d vs %d" % (n, key, len(g[key]), len(w[key])))
            for i, (gs, ws) in enumerate(zip(g[key], w[key])):
                compare_state(gs, ws, "%s %s[%d]" % (n, key, i))
        if w["injection"] is None:
            check(g["injection"] is None, n + ": injection where none expected")
        else:
            gi, wi = g["injection"], w["injection"]
            check(gi is not None and gi["trajectory"] == wi["trajectory"],
                  "%s injection trajectory: %s vs %s" % (n, gi and gi.get("trajectory"), wi["trajectory"]))
            for k, v in wi["orbit"].items():
                close(gi["orbit"][k], v, "%s orbit %s" % (n, k))
            close(gi["fpa_inertial"], wi["fpa_inertial"], n + " injection fpa_inertial")
            close(gi.get("t"), wi.get("t"), n + " injection t")  # the rows' and the summary's
            for k in ("phase", "carried_by"):
                check(gi.get(k) == wi.get(k), "%s injection %s: %r vs %r" % (n, k, gi.get(k), wi.get(k)))
        gh, wh = g.get("heating"), w["heating"]
        if wh is None:
            check(gh is None, n + ": heating where no phase has heat flux columns")
        else:
            check(gh is not None, n + ": heating missing")
            gh = gh or {"max_heat_flux": {}, "fm_below_1135": None}
            for i, k in enumerate(("value", "t", "h")):
                close(gh["max_heat_flux"].get(k), wh["max"][i], "%s max_heat_flux %s" % (n, k))
            check(gh["max_heat_flux"].get("phase") == wh["max"][3], n + " max_heat_flux phase")
            close(gh.get("heat_load"), wh["load"], n + " heat_load", rel=1e-9)
            close(gh.get("heat_load"), wh["trap"], n + " heat_load against the rows' trapezoids",
                  rel=1e-2)
            if wh["fm"] is None:
                check(gh["fm_below_1135"] is None, n + ": fm_below_1135 where none expected")
            else:
                for i, k in enumerate(("t", "h")):
                    close((gh["fm_below_1135"] or {}).get(k), wh["fm"][i], "%s fm_below_1135 %s" % (n, k),
                          rel=1e-9)
        gi, wi = g.get("iip_cutoff"), w["iip_cutoff"]
        if wi is None:
            check(gi is None, n + ": iip_cutoff where no phase has the iip columns")
        else:
            check(gi is not None and len(gi) == len(wi), "%s iip_cutoff: %r vs %r" % (n, gi, wi))
            for i, (ge, we) in enumerate(zip(gi or [], wi)):
                for k, v in we.items():
                    if isinstance(v, (str, bool)):
                        check(ge.get(k) == v, "%s iip_cutoff[%d].%s: %r vs %r" % (n, i, k, ge.get(k), v))
                    else:
                        close(ge.get(k), v, "%s iip_cutoff[%d].%s" % (n, i, k))
        if w["ground_contact"] is None:
            check(g["ground_contact"] is None, n + ": ground contact where none expected")
        else:
            for k, v in w["ground_contact"].items():
                if isinstance(v, str):
                    check(g["ground_contact"][k] == v, "%s ground contact %s" % (n, k))
                else:
                    close(g["ground_contact"][k], v, "%s ground contact %s" % (n, k), rel=1e-9)
    return summ, got


def same_injection(bodies, payload, carrier, phase):
    """A body that never burns gets its carrier's injection: the same time, phase and orbit."""
    pi, ci = bodies[payload]["injection"], bodies[carrier]["injection"]
    check(pi is not None and ci is not None, "%s injection %r, %s's %r" % (payload, pi, carrier, ci))
    if pi is None or ci is None:
        return
    check(pi.get("carried_by") == carrier and pi["phase"] == ci["phase"] == phase
          and pi["trajectory"] == ci["trajectory"] == "orbit", "%s injection: %r" % (payload, pi))
    check(pi["t"] == ci["t"] and pi["orbit"] == ci["orbit"], "%s orbit %r vs %s's %r"
          % (payload, pi["orbit"], carrier, ci["orbit"]))
    print("%s: injected with %s at t = %.3f s in %s, periapsis %.1f km, apoapsis %.1f km"
          % (payload, carrier, pi["t"], phase, pi["orbit"]["peri_alt"] / 1e3, pi["orbit"]["apo_alt"] / 1e3))


def sounding_rocket(lvsim, out, got, html, tmp):
    """Issue 26's breaker: the flat world in air. The axial load is the sensed specific force
    along the thrust axis (+z), (T + D_z) / (m g0), the drag along the air velocity: here by
    hand from the example's wind (8 m/s east, no vertical part: v_air = (vx - 8, vy, vz)),
    not thrust / (m g0) (10.197 at burnout) and not 0 at the impact (5.8 g of drag)."""
    b = got["bodies"][0]
    def n_hand(r):
        va = math.sqrt((r["vx"] - 8.0) ** 2 + r["vy"] ** 2 + r["vz"] ** 2)
        return (r["thrust"] - r["drag"] * r["vz"] / va) / (r["m"] * G0)
    boost = load_csv(os.path.join(out, "phase_1_boost.csv"))
    tb = b["burnouts"][0]["t"]
    rb = next(r for r in boost if r["time"] == tb)
    want = n_hand(rb)
    print("sounding-rocket: max axial %.6f g0 at burnout t = %.3f s (hand %.6f; T/(m g0) %.6f)"
          % (b["max_n_axial"]["value"], b["max_n_axial"]["t"], want, rb["thrust"] / (rb["m"] * G0)))
    close(b["max_n_axial"]["value"], want, "sounding-rocket max axial = (T + D_z)/(m g0) at burnout", 1e-9)
    check(b["max_n_axial"]["t"] == tb, "sounding-rocket max axial at burnout: %r" % b["max_n_axial"])
    last = load_csv(os.path.join(out, "phase_3_descent.csv"))[-1]
    gc = b["ground_contact"]
    want = n_hand(last)
    print("sounding-rocket: axial load at impact %r g0 (hand %.6f)" % (gc["n_axial"], want))
    close(gc["n_axial"], want, "sounding-rocket axial load at impact", 1e-9)
    check(want > 5.0, "the impact's drag load %r" % want)
    check("axial load factor at contact %.3f" % want in html, "sounding-rocket: contact load not in the report")
    # a model that lacks a column the load needs: null and "not available", never 0
    cut = os.path.join(tmp, "sr-no-drag")
    subprocess.run(["cp", "-r", out, cut], check=True)
    path = os.path.join(cut, "phase_3_descent.csv")
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    k = next(i for i, h in enumerate(rows[0]) if h.split(" [")[0] == "drag")
    with open(path, "w", newline="") as f:
        csv.writer(f).writerows([r[:k] + r[k + 1:] for r in rows])
    # as a model without the column would have written it: the manifest says so
    man_path = os.path.join(cut, "manifest.json")
    man = json.load(open(man_path))
    data = open(path, "rb").read()
    for e in man["files"]:
        if e["name"] == "phase_3_descent.csv":
            e["bytes"], e["sha256"] = len(data), hashlib.sha256(data).hexdigest()
            e.pop("stamp", None)
    json.dump(man, open(man_path, "w"))
    r = subprocess.run([lvsim, "plot", cut], capture_output=True, text=True)
    check(r.returncode == 0, "lvsim plot without drag: %s" % r.stderr)
    kf = json.load(open(os.path.join(cut, "key_figures.json")))["bodies"][0]
    check(kf["ground_contact"]["n_axial"] is None, "no drag column: contact load %r" % kf["ground_contact"]["n_axial"])
    check("axial load factor at contact not available" in open(os.path.join(cut, "index.html")).read(),
          "no drag column: the report does not say 'not available'")


def main():
    lvsim, src = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        for ex in ("dof3-branch", "paper-test-case", "rlv-hthl", "sounding-rocket", "kourou-leo"):
            out = os.path.join(tmp, ex)
            r = subprocess.run([lvsim, "run", os.path.join(src, "examples", ex, "mission.yaml"),
                                "-o", out, "-q"], capture_output=True, text=True)
            check(r.returncode == 0, "lvsim run %s: %s" % (ex, r.stderr))
            if r.returncode != 0:
                continue
            summ, got = compare(out)
            html = open(os.path.join(out, "index.html")).read()
            check('<h2 id="keys">Key figures</h2>' in html, ex + ": no key figures in index.html")
            for b in got["bodies"]:
                check("<h3>%s</h3>" % b["name"] in html, ex + ": body %s not in the report" % b["name"])
                for e in b.get("iip_cutoff") or []:
                    check("IIP at the end of powered flight in %s" % e["phase"] in html,
                          ex + ": %s's IIP at the cut-off of %s not in the report" % (b["name"], e["phase"]))
            imgs = [l for l in html.split("\n") if l.startswith('<img src="plots/')]
            check(imgs and imgs[0].startswith('<img src="plots/fig10_normalised.png"'),
                  ex + ": Figure 10 is not the first figure: %s" % imgs[:1])
            if ex == "paper-test-case":
                check(not os.path.exists(os.path.join(out, "plots", "ground_track.png")),
                      "a vertical flat-world flight got a ground-track map")
                bodies = {b["name"]: b for b in got["bodies"]}
                # stage 1: impact where it started (a vertical flight), at speed: an impact
                gc = bodies["stage1"]["ground_contact"]
                check(gc["kind"] == "impact" and gc["distance"] < 1e-6, "stage1 impact: %r" % gc)
                # flat world: no atmosphere, no dynamic pressure; axial load = thrust / (m g0)
                check(all(b["max_q"] is None for b in got["bodies"]), "max q in the flat world")
                p1 = load_csv(os.path.join(out, "phase_1_P1.csv"))
                r = next(r for r in p1 if r["time"] == bodies["stage1"]["burnouts"][0]["t"])
                check(r["burning"] == 1.0 and r["thrust"] > 0, "P1 burns until its burnout row")
            elif ex == "sounding-rocket":
                sounding_rocket(lvsim, out, got, html, tmp)
            elif ex == "kourou-leo":
                # the payload never burns and ends in orbit: the upper stage's injection, the
                # same row (issue 26's breaker: it had none); the fairing, dropped on the way
                # up, none
                bodies = {b["name"]: b for b in got["bodies"]}
                same_injection(bodies, "payload", "upper", "upper-burn-2")
                check(bodies["fairing"]["injection"] is None, "kourou-leo fairing: %r" % bodies["fairing"]["injection"])
            elif ex == "rlv-hthl":
                # the upper stage's burn ends on its `sma` end, not a burnout: still its
                # injection, into the 200 km orbit of the example's README; the main stage's
                # powered flight ends suborbital (the turn-around)
                bodies = {b["name"]: b for b in got["bodies"]}
                inj = bodies["us"]["injection"]
                check(inj is not None and inj["trajectory"] == "orbit", "rlv us injection: %r" % inj)
                if inj is not None:
                    check(199e3 < inj["orbit"]["peri_alt"] < inj["orbit"]["apo_alt"] < 201e3,
                          "rlv us orbit: %r" % inj["orbit"])
                # the main stage's last burn, the turn-around, ends on the way down (fpa_inertial
                # -1.14 rad): no end of powered flight to report (issue 26: it showed one with a
                # ballistic apoapsis below the ground)
                check(bodies["ms"]["injection"] is None, "rlv ms: %r" % bodies["ms"]["injection"])
                same_injection(bodies, "payload", "us", "us-ascent")
                # the main stage lands (issue 26): the touchdown from the roll-out's file and
                # the flare's last row, the requirement-level facts of the example's README:
                # inside the touchdown zone (the first 3000 ft, 914 m, of the runway: FAA AC
                # 150/5340-1M), the sink rate under the gear's 3.05 m/s, stopped on the 4 km
                # runway
                td = bodies["ms"]["touchdown"]
                ro = load_csv(os.path.join(out, "phase_10_rollout.csv"))
                fl = load_csv(os.path.join(out, "phase_9_flare.csv"))
                check(td is not None and td["status"] == "landed", "rlv ms touchdown: %r" % td)
                if td is not None:
                    close(td["from_threshold"], ro[0]["distance"], "rlv touchdown point", 1e-9)
                    close(td["rollout_distance"], ro[-1]["distance"] - ro[0]["distance"],
                          "rlv roll-out distance", 1e-9)
                    close(td["time_on_runway"], ro[-1]["time"] - ro[0]["time"],
                          "rlv time on the runway", 1e-9)
                    close(td["stop_speed"], ro[-1]["speed"], "rlv stop speed", 1e-9)
                    # the sink rate along the runway plane's normal; the flare's last row gives
                    # it along the local vertical, tilted from it by the distance from the
                    # threshold over the Earth's radius (~1e-4 rad: ~1e-2 m/s at 66 m/s)
                    check(abs(td["sink_rate"] - fl[-1]["v_down"]) < 0.02,
                          "rlv sink rate %r vs v_down %r" % (td["sink_rate"], fl[-1]["v_down"]))
                    check(300.0 < td["from_threshold"] < 914.0, "rlv touchdown zone: %r" % td)
                    check(0.0 < td["sink_rate"] < 3.048, "rlv sink rate: %r" % td)
                    check(td["stop_from_threshold"] < 4000.0, "rlv stops on the runway: %r" % td)
                    check('touchdown</td>' in html and "roll-out" in html, "rlv: no touchdown in the report")
            else:
                bodies = {b["name"]: b for b in got["bodies"]}
                check(bodies["upper"]["injection"]["trajectory"] == "escape",
                      "dof3-branch upper: %r" % bodies["upper"]["injection"]["trajectory"])
                check(bodies["core"]["injection"] is not None
                      and bodies["core"]["injection"]["trajectory"] == "suborbital", "core suborbital")
                check("ballistic apoapsis altitude" in html, "dof3-branch: suborbital end without its apoapsis")
                check(bodies["core"]["ground_contact"]["kind"] == "impact", "core impact")
                q = bodies["core"]["max_q"]
                check(q is not None and q["h"] < 100e3, "core max q below 100 km: %r" % q)
    for f in FAILS:
        print("FAIL: " + f)
    print("%d passed, %d failed" % (CHECKS[0] - len(FAILS), len(FAILS)))
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
