#!/usr/bin/python3
"""check_exports.py - check the trajectory exports of lvsim results folders against the
formats' rules and against the folder's own summary.json and body CSVs.

Usage: check_exports.py OUTDIR...   (each written by lv_export_run with every format)

  mission.czml  json: a document packet first (version, clock: interval = the done phases'
                span from summary.epoch, currentTime, multiplier, range); one "track/<body>/
                <phase>" packet per (body, phase) of the summary with availability = the
                mission interval, position epoch = summary.epoch, samples = the body CSV
                rows of that phase (exact duplicate times dropped) to 1e-9 s / 1e-9 deg /
                1e-6 m (cJSON prints 15 digits when they read back within an ulp or two), each
                child track starting where its parent's ended; "event/<phase>/<k>" markers for
                every phase start and every event of the summary, labelled; "iip/<body>/<k>"
                polylines, one per run of finite IIP rows of the body CSV, equal to it.
  mission.kml   xml.etree: KML 2.2 namespace, one Folder per body, a gx:Track per phase with
                when/gx:coord counts = the body CSV rows of the phase minus duplicates, times
                ISO 8601 and increasing, coordinates equal to the CSV, styles resolvable; a
                body's IIP trace, a LineString per run of finite IIP rows, equal to the CSV.
  <body>.oem    a small CCSDS 502.0-B-2 KVN reader: header and metadata keywords, times
                increasing within START_TIME..STOP_TIME, 7 numbers per data line, |r| within
                Earth radius + 100 km .. + 10000 km, positions and velocities recomputed
                independently from the body CSV (WGS-84; ECI -> ECEF by theta = omega t).
                Flat-world folders must have no .oem file.
Exit status 0 when every check passes.
"""
import csv
import datetime as dt
import glob
import json
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

FAILURES = []

WGS84_A = 6378137.0
WGS84_F = 1.0 / 298.257223563
OMEGA = 7.292115e-5  # rad/s, WGS-84
KML = "{http://www.opengis.net/kml/2.2}"
GX = "{http://www.google.com/kml/ext/2.2}"



# Marker labels, in launcher words (docs/exports.md): a phase that carries fewer stages than
# its parent starts at a separation; events by their names (burnout, impact, ...).
def event_label(e):
    name = e.get("name")
    return name if name else "time event"


def start_label(summary, ph):
    parent = next((p for p in summary["phases"] if p["name"] == ph.get("from")), None)
    if parent is not None and len(ph["stages"]) < len(parent["stages"]):
        return "separation (%s)" % ph["name"]
    return ph["name"] + " start"

def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL: " + what, file=sys.stderr)
    return cond


def parse_iso(text):
    """ISO 8601 UTC ('Z' or no zone) -> aware datetime; None when malformed."""
    if not re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d(\.\d{1,6})?Z?", text):
        return None
    t = dt.datetime.fromisoformat(text.rstrip("Z"))
    return t.replace(tzinfo=dt.timezone.utc)


def at(epoch, t):
    """The instant t seconds after epoch, to the microsecond (lvsim's written resolution).
    Python's datetime knows no leap second: right for the folders checked here (2026, none
    inside them); a span across one is checked by test_export.c (leap_second.yaml)."""
    return epoch + dt.timedelta(microseconds=round(t * 1e6))


class Folder:
    """summary.json and the body CSVs of one results folder."""

    def __init__(self, path):
        self.path = path
        with open(os.path.join(path, "summary.json")) as f:
            self.summary = json.load(f)
        self.epoch = parse_iso(self.summary["epoch"])
        self.phases = {p["name"]: p for p in self.summary["phases"]}
        done = [p for p in self.summary["phases"] if p["state"] == "done"]
        self.t0 = min(p["t_start"] for p in done)
        self.t1 = max(p["t_end"] for p in done)
        self.bodies = {}
        for b in self.summary["bodies"]:
            with open(os.path.join(path, b["trajectory"]), newline="") as f:
                rows = list(csv.reader(f))
            head = [h.split(" [")[0] for h in rows[0]]
            recs = []
            for r in rows[1:]:
                if not r or r[0].startswith("#"):
                    continue
                d = {h: (v if h == "phase" else float(v)) for h, v in zip(head, r)}
                recs.append(d)
            self.bodies[b["name"]] = (b["phases"], recs)

    def phase_rows(self, body, phase):
        """Rows of one body in one phase, of rows with the same time only the last."""
        out = []
        for r in self.bodies[body][1]:
            if r["phase"] != phase:
                continue
            if out and out[-1]["time"] == r["time"]:
                out[-1] = r
            else:
                out.append(r)
        return out

    def iip_runs(self, body):
        """The body's instantaneous impact point trace as the exports draw it: over the rows
        of its phases (of rows with the same time only the last), the runs of at least two
        rows with a finite iip_lat and iip_lon, as [(lon, lat) in degrees]; [] without the
        columns (docs/exports.md)."""
        phs, recs = self.bodies[body]
        if not recs or "iip_lat" not in recs[0]:
            return []
        rows = [r for ph in phs for r in self.phase_rows(body, ph)]
        runs, cur = [], []
        for r in rows + [None]:
            if r is not None and math.isfinite(r["iip_lat"]) and math.isfinite(r["iip_lon"]):
                cur.append((math.degrees(r["iip_lon"]), math.degrees(r["iip_lat"])))
                continue
            if len(cur) >= 2:
                runs.append(cur)
            cur = []
        return runs

    def interval(self):
        return "%s/%s" % (iso(at(self.epoch, self.t0)), iso(at(self.epoch, self.t1)))


def iso(t):
    s = t.strftime("%Y-%m-%dT%H:%M:%S")
    return s + (".%06d" % t.microsecond if t.microsecond else "") + "Z"


def same_instant(text, when):
    t = parse_iso(text) if isinstance(text, str) else None
    return t is not None and t == when


# ------------------------------------------------------------------------------- CZML --

def check_czml(fo):
    name = os.path.join(fo.path, "mission.czml")
    with open(name) as f:
        doc = json.load(f)
    if not check(isinstance(doc, list) and doc, name + ": not a non-empty array of packets"):
        return
    d = doc[0]
    check(d.get("id") == "document", name + ": first packet is not the document")
    check(d.get("version") == "1.0", name + ": document version is not 1.0")
    clock = d.get("clock", {})
    check(clock.get("interval") == fo.interval(),
          "%s: clock interval %r != %r" % (name, clock.get("interval"), fo.interval()))
    check(same_instant(clock.get("currentTime"), at(fo.epoch, fo.t0)), name + ": currentTime")
    check(clock.get("range") in ("UNBOUNDED", "CLAMPED", "LOOP_STOP"), name + ": clock range")
    check(isinstance(clock.get("multiplier"), (int, float)) and clock["multiplier"] > 0,
          name + ": clock multiplier")
    ids = [p.get("id") for p in doc]
    check(len(ids) == len(set(ids)) and None not in ids, name + ": packet ids not unique")
    check(all(p.get("id") != "document" for p in doc[1:]), name + ": second document packet")
    packets = {p["id"]: p for p in doc}

    # Tracks: one per (body, phase).
    want = {"track/%s/%s" % (b, ph) for b, (phs, _) in fo.bodies.items() for ph in phs}
    have = {i for i in ids if i and i.startswith("track/")}
    check(want == have, "%s: track ids %s != %s" % (name, sorted(have), sorted(want)))
    colours = {}
    ends = {}
    for b, (phs, _) in fo.bodies.items():
        for k, ph in enumerate(phs):
            pid = "track/%s/%s" % (b, ph)
            p = packets.get(pid)
            if p is None:
                continue
            check(p.get("availability") == fo.interval(), pid + ": availability is not the "
                  "mission interval")
            pos = p.get("position", {})
            check(same_instant(pos.get("epoch"), fo.epoch), pid + ": position epoch")
            check(pos.get("interpolationAlgorithm") in ("LINEAR", "LAGRANGE", "HERMITE"),
                  pid + ": interpolationAlgorithm")
            check(isinstance(pos.get("interpolationDegree"), int), pid + ": degree")
            check(pos.get("forwardExtrapolationType") == "HOLD", pid + ": forward extrap.")
            check(pos.get("backwardExtrapolationType") == "NONE", pid + ": backward extrap.")
            s = pos.get("cartographicDegrees", [])
            rows = fo.phase_rows(b, ph)
            if not check(len(s) == 4 * len(rows), "%s: %d samples, CSV has %d rows"
                         % (pid, len(s) // 4, len(rows))):
                continue
            ts = s[0::4]
            check(all(x < y for x, y in zip(ts, ts[1:])), pid + ": times not increasing")
            bad = 0
            for i, r in enumerate(rows):
                lon, lat, h = s[4 * i + 1:4 * i + 4]
                bad += not (abs(ts[i] - r["time"]) <= 1e-9
                            and abs(lat - math.degrees(r["lat"])) <= 1e-9
                            and abs(lon - math.degrees(r["lon"])) <= 1e-9
                            and abs(h - r["h"]) <= 1e-6)
            check(bad == 0, "%s: %d samples differ from the body CSV" % (pid, bad))
            ends[(b, ph)] = (s[:4], s[-4:])
            path = p.get("path", {})
            c = path.get("material", {}).get("solidColor", {}).get("color", {}).get("rgba")
            check(isinstance(c, list) and len(c) == 4 and all(0 <= v <= 255 for v in c),
                  pid + ": path colour")
            check(path.get("leadTime") == 0 and path.get("trailTime", 0) >= fo.t1 - fo.t0,
                  pid + ": path lead/trail time")
            check(path.get("width", 0) > 0 and path.get("resolution", 0) > 0, pid + ": path")
            colours.setdefault(ph, set()).add(tuple(c or []))
            last = k == len(phs) - 1
            check(("point" in p and p.get("label", {}).get("text") == b) == last,
                  pid + ": point and label on the body's last phase only")
    for ph, cs in colours.items():
        check(len(cs) == 1, "phase %s: tracks with different colours" % ph)
    # The branch: every child track starts where its parent's track ended (same body).
    for b, (phs, _) in fo.bodies.items():
        for prev, ph in zip(phs, phs[1:]):
            if (b, prev) in ends and (b, ph) in ends:
                e, s = ends[(b, prev)][1], ends[(b, ph)][0]
                check(s[0] == e[0] and max(abs(x - y) for x, y in zip(s[1:3], e[1:3])) < 1e-6
                      and abs(s[3] - e[3]) < 1e-3,
                      "track/%s/%s does not start where %s ended" % (b, ph, prev))

    # Markers: phase starts (k = 0) and every event of the summary (k = 1..n).
    end = at(fo.epoch, fo.t1)
    for ph in fo.summary["phases"]:
        if ph["state"] != "done":
            continue
        marks = [(ph["t_start"], start_label(fo.summary, ph))]
        marks += [(e["t"], event_label(e)) for e in ph.get("events", [])]
        body = next(b for b, (phs, _) in fo.bodies.items() if ph["name"] in phs)
        rows = fo.phase_rows(body, ph["name"])
        for k, (t, text) in enumerate(marks):
            pid = "event/%s/%d" % (ph["name"], k)
            p = packets.get(pid)
            if not check(p is not None, name + ": no packet " + pid):
                continue
            check(p.get("label", {}).get("text") == text, "%s: label %r != %r"
                  % (pid, p.get("label", {}).get("text"), text))
            check("point" in p, pid + ": no point")
            a, _, b_ = p.get("availability", "").partition("/")
            check(same_instant(a, at(fo.epoch, t)) and same_instant(b_, end),
                  pid + ": availability is not event time .. mission end")
            c = p.get("position", {}).get("cartographicDegrees", [])
            if check(len(c) == 3, pid + ": position is not one cartographic point"):
                exact = [r for r in rows if r["time"] == t]
                if exact:
                    r = exact[-1]
                    check(abs(c[0] - math.degrees(r["lon"])) < 1e-9
                          and abs(c[1] - math.degrees(r["lat"])) < 1e-9
                          and abs(c[2] - r["h"]) < 1e-6, pid + ": not at the body's position")
    # The IIP traces: one polyline packet per finite run of each body's iip_lat, iip_lon.
    for b in fo.bodies:
        runs = fo.iip_runs(b)
        have = sorted(i for i in ids if i and i.startswith("iip/%s/" % b))
        check(have == sorted("iip/%s/%d" % (b, k) for k in range(len(runs))),
              "%s: IIP packets of %s: %s, expected %d runs" % (name, b, have, len(runs)))
        for k, run in enumerate(runs):
            p = packets.get("iip/%s/%d" % (b, k), {})
            c = p.get("polyline", {}).get("positions", {}).get("cartographicDegrees", [])
            if not check(len(c) == 3 * len(run), "%s: iip/%s/%d: %d numbers for %d points"
                         % (name, b, k, len(c), len(run))):
                continue
            bad = sum(not (abs(c[3 * j] - lo) < 1e-9 and abs(c[3 * j + 1] - la) < 1e-9
                           and c[3 * j + 2] == 0) for j, (lo, la) in enumerate(run))
            check(bad == 0, "%s: iip/%s/%d: %d points differ from the body CSV" % (name, b, k, bad))
            check(p.get("availability") == fo.interval(),
                  "%s: iip/%s/%d: availability is not the mission interval" % (name, b, k))
    n_events = sum(1 for i in ids if i and i.startswith("event/"))
    n_want = sum(1 + len(p.get("events", [])) for p in fo.summary["phases"]
                 if p["state"] == "done")
    check(n_events == n_want, "%s: %d markers, expected %d" % (name, n_events, n_want))


# -------------------------------------------------------------------------------- KML --

def tick(t):
    return round(t * 1e6)


def check_kml(fo):
    name = os.path.join(fo.path, "mission.kml")
    root = ET.parse(name).getroot()  # raises on XML that is not well-formed
    check(root.tag == KML + "kml", name + ": root is not kml (KML 2.2 namespace)")
    doc = root.find(KML + "Document")
    if not check(doc is not None, name + ": no Document"):
        return
    check(doc.findtext(KML + "name") == fo.summary["mission"], name + ": document name")
    styles = {s.get("id"): s for s in doc.findall(KML + "Style")}
    for s in styles.values():
        c = s.find(KML + "LineStyle/" + KML + "color")
        check(c is not None and re.fullmatch(r"[0-9a-f]{8}", c.text or ""),
              name + ": style colour is not aabbggrr")
    folders = doc.findall(KML + "Folder")
    check([f.findtext(KML + "name") for f in folders] == list(fo.bodies),
          "%s: folders %s != bodies %s" % (name, [f.findtext(KML + "name") for f in folders],
                                          list(fo.bodies)))
    for f in folders:
        body = f.findtext(KML + "name")
        if body not in fo.bodies:
            continue
        phs = fo.bodies[body][0]
        tracks = [pm for pm in f.findall(KML + "Placemark")
                  if pm.find(GX + "Track") is not None]
        check(len(tracks) == len(phs), "%s: folder %s: %d tracks, %d phases"
              % (name, body, len(tracks), len(phs)))
        for pm, ph in zip(tracks, phs):
            check(pm.findtext(KML + "name") == "%s: %s" % (body, ph), name + ": track name")
            check((pm.findtext(KML + "styleUrl") or "#")[1:] in styles,
                  name + ": unresolved styleUrl")
            tr = pm.find(GX + "Track")
            check(tr.findtext(KML + "altitudeMode") == "absolute", name + ": altitudeMode")
            whens = [w.text for w in tr.findall(KML + "when")]
            coords = [c.text.split() for c in tr.findall(GX + "coord")]
            rows, last = [], None
            for r in fo.phase_rows(body, ph):
                if last is None or tick(r["time"]) != last:
                    rows.append(r)
                    last = tick(r["time"])
            where = "%s: %s/%s" % (name, body, ph)
            if not check(len(whens) == len(coords) == len(rows), "%s: %d when, %d coord, %d "
                         "CSV rows" % (where, len(whens), len(coords), len(rows))):
                continue
            ts = [parse_iso(w) for w in whens]
            check(None not in ts, where + ": a when is not ISO 8601")
            check(all(a < b for a, b in zip(ts, ts[1:])), where + ": times not increasing")
            bad = 0
            for t, c, r in zip(ts, coords, rows):
                lon, lat, h = (float(x) for x in c)
                bad += not (t == at(fo.epoch, r["time"])
                            and abs(lon - math.degrees(r["lon"])) < 1e-9
                            and abs(lat - math.degrees(r["lat"])) < 1e-9
                            and abs(h - r["h"]) < 1e-4)
            check(bad == 0, "%s: %d points differ from the body CSV" % (where, bad))
        # the IIP trace: one Placemark with a LineString per finite run, on the ground
        runs = fo.iip_runs(body)
        iips = [pm for pm in f.findall(KML + "Placemark")
                if pm.findtext(KML + "name") == "%s: IIP trace" % body]
        check(len(iips) == (1 if runs else 0), "%s: folder %s: %d IIP placemarks, %d runs"
              % (name, body, len(iips), len(runs)))
        for pm in iips:
            check((pm.findtext(KML + "styleUrl") or "#")[1:] in styles,
                  name + ": unresolved IIP styleUrl")
            lines = pm.findall(KML + "MultiGeometry/" + KML + "LineString")
            if not check(len(lines) == len(runs), "%s: folder %s: %d IIP lines, %d runs"
                         % (name, body, len(lines), len(runs))):
                continue
            for ls, run in zip(lines, runs):
                check(ls.findtext(KML + "altitudeMode") == "clampToGround",
                      name + ": IIP altitudeMode")
                pts = [tuple(float(x) for x in p.split(",")) for p in
                       (ls.findtext(KML + "coordinates") or "").split()]
                bad = len(pts) != len(run) or any(
                    not (abs(p[0] - lo) < 1e-9 and abs(p[1] - la) < 1e-9 and p[2] == 0)
                    for p, (lo, la) in zip(pts, run))
                check(not bad, "%s: folder %s: an IIP line differs from the body CSV" % (name, body))
        labels = {pm.findtext(KML + "name") for pm in f.findall(KML + "Placemark")
                  if pm.find(KML + "Point") is not None}
        for ph in phs:
            p = fo.phases[ph]
            for e in p.get("events", []):
                check(event_label(e) in labels,
                      "%s: folder %s: no event placemark %s" % (name, body, e.get("name")))
            phj = next(p for p in fo.summary["phases"] if p["name"] == ph)
            check(start_label(fo.summary, phj) in labels,
                  "%s: folder %s: no start marker of %s" % (name, body, ph))


# -------------------------------------------------------------------------------- OEM --

HEADER_KEYS = {"CREATION_DATE", "ORIGINATOR", "MESSAGE_ID"}
META_REQUIRED = ["OBJECT_NAME", "OBJECT_ID", "CENTER_NAME", "REF_FRAME", "TIME_SYSTEM",
                 "START_TIME", "STOP_TIME"]
META_OPTIONAL = {"REF_FRAME_EPOCH", "USEABLE_START_TIME", "USEABLE_STOP_TIME",
                 "INTERPOLATION", "INTERPOLATION_DEGREE"}


def read_oem(name):
    """CCSDS 502.0-B-2 KVN OEM -> (header dict, [(meta dict, [(epoch, 6 floats)])])."""
    lines = [l.strip() for l in open(name)]
    lines = [l for l in lines if l]
    kv = re.compile(r"([A-Z_0-9]+)\s*=\s*(.*)")
    m = kv.fullmatch(lines[0]) if lines else None
    check(m is not None and m.group(1) == "CCSDS_OEM_VERS" and m.group(2) == "2.0",
          name + ": first line is not CCSDS_OEM_VERS = 2.0")
    header, blocks, i = {}, [], 1
    while i < len(lines) and lines[i] != "META_START":
        m = kv.fullmatch(lines[i])
        if not lines[i].startswith("COMMENT"):
            check(m is not None and m.group(1) in HEADER_KEYS, name + ": bad header line "
                  + lines[i])
            if m:
                header[m.group(1)] = m.group(2)
        i += 1
    for k in ("CREATION_DATE", "ORIGINATOR"):
        check(k in header, name + ": header lacks " + k)
    while i < len(lines):
        check(lines[i] == "META_START", name + ": expected META_START, found " + lines[i])
        i += 1
        meta, seen_key = {}, False
        while i < len(lines) and lines[i] != "META_STOP":
            if lines[i].startswith("COMMENT"):
                check(not seen_key, name + ": COMMENT after a metadata keyword")
            else:
                m = kv.fullmatch(lines[i])
                ok = m is not None and (m.group(1) in META_REQUIRED or m.group(1) in
                                        META_OPTIONAL)
                check(ok, name + ": bad metadata line " + lines[i])
                if m:
                    meta[m.group(1)] = m.group(2)
                seen_key = True
            i += 1
        i += 1
        for k in META_REQUIRED:
            check(k in meta, name + ": metadata lacks " + k)
        if "INTERPOLATION" in meta:
            check(re.fullmatch(r"\d+", meta.get("INTERPOLATION_DEGREE", "")) is not None,
                  name + ": INTERPOLATION without INTERPOLATION_DEGREE")
        data, seen_data = [], False
        while i < len(lines) and lines[i] != "META_START":
            if lines[i].startswith("COMMENT"):
                check(not seen_data, name + ": COMMENT inside the data")
            else:
                f = lines[i].split()
                if check(len(f) == 7, "%s: %d fields on a data line" % (name, len(f))):
                    data.append((parse_iso(f[0]), [float(x) for x in f[1:]]))
                seen_data = True
            i += 1
        blocks.append((meta, data))
    return header, blocks


def geodetic_to_ecef(lat, lon, h):
    e2 = WGS84_F * (2 - WGS84_F)
    n = WGS84_A / math.sqrt(1 - e2 * math.sin(lat) ** 2)
    return ((n + h) * math.cos(lat) * math.cos(lon), (n + h) * math.cos(lat) * math.sin(lon),
            (n * (1 - e2) + h) * math.sin(lat))


def ecef_velocity(r):
    """v_ecef = R3(theta) (v_eci - w x r_eci), theta = omega t (docs/frames.md F1, F3)."""
    th = OMEGA * r["time"]
    x, y = r["r_eci_x"], r["r_eci_y"]
    vx, vy, vz = r["v_eci_x"] + OMEGA * y, r["v_eci_y"] - OMEGA * x, r["v_eci_z"]
    c, s = math.cos(th), math.sin(th)
    return (c * vx + s * vy, -s * vx + c * vy, vz)


WGS84_A = 6378137.0           # m, NIMA TR8350.2 table 3.1
WGS84_GM = 3.986004418e14     # m^3/s^2, the same


def periapsis_radius(r):
    """The osculating periapsis radius from the row's ECI state, by the eccentricity vector
    e = ((v^2 - GM/r) r - (r.v) v) / GM and the semi-latus rectum p = h^2/GM:
    r_p = p / (1 + |e|) (Vallado, 4th ed., eqs. 2-78, 2-79; independent of lvsim's energy form)."""
    rv = [r["r_eci_x"], r["r_eci_y"], r["r_eci_z"]]
    vv = [r["v_eci_x"], r["v_eci_y"], r["v_eci_z"]]
    rn = math.sqrt(sum(x * x for x in rv))
    v2 = sum(x * x for x in vv)
    rdv = sum(a * b for a, b in zip(rv, vv))
    ev = [((v2 - WGS84_GM / rn) * a - rdv * b) / WGS84_GM for a, b in zip(rv, vv)]
    h = [rv[1] * vv[2] - rv[2] * vv[1], rv[2] * vv[0] - rv[0] * vv[2], rv[0] * vv[1] - rv[1] * vv[0]]
    p = sum(x * x for x in h) / WGS84_GM
    return p / (1.0 + math.sqrt(sum(x * x for x in ev)))


def check_oem(fo):
    files = sorted(glob.glob(os.path.join(fo.path, "*.oem")))
    if fo.summary["world"] == "flat":
        check(not files, fo.path + ": OEM files for a flat-world mission")
        return
    for b, (_, recs) in fo.bodies.items():
        # The rule: the body's rows in time order, one per microsecond, in runs of at least
        # two orbital rows: at or above 100 km geodetic altitude, and the periapsis of the
        # osculating conic above the WGS-84 equatorial radius (docs/exports.md).
        rows, last = [], None
        for r in recs:
            if last is None or tick(r["time"]) > last:
                rows.append(r)
                last = tick(r["time"])
        runs, cur = [], []
        for r in rows + [None]:
            if r is not None and r["h"] >= 100e3 and periapsis_radius(r) > WGS84_A:
                cur.append(r)
            else:
                if len(cur) >= 2:
                    runs.append(cur)
                cur = []
        name = os.path.join(fo.path, b + ".oem")
        if not runs:
            check(not os.path.exists(name), name + ": written, but no orbital rows")
            continue
        if not check(os.path.exists(name), name + ": missing"):
            continue
        header, blocks = read_oem(name)
        check(len(blocks) == len(runs), "%s: %d blocks, %d orbital runs"
              % (name, len(blocks), len(runs)))
        for (meta, data), run in zip(blocks, runs):
            check(meta.get("OBJECT_NAME") == b, name + ": OBJECT_NAME")
            check(meta.get("CENTER_NAME") == "EARTH", name + ": CENTER_NAME")
            check(meta.get("TIME_SYSTEM") == "UTC", name + ": TIME_SYSTEM")
            check(meta.get("REF_FRAME") == "ITRF2000", name + ": REF_FRAME")
            t_a = parse_iso(meta.get("START_TIME", ""))
            t_b = parse_iso(meta.get("STOP_TIME", ""))
            ts = [t for t, _ in data]
            if not check(None not in ts + [t_a, t_b] and data, name + ": bad times"):
                continue
            check(all(x < y for x, y in zip(ts, ts[1:])), name + ": times not increasing")
            check(t_a <= ts[0] and ts[-1] <= t_b, name + ": data outside START..STOP")
            if not check(len(data) == len(run), "%s: %d data lines, %d CSV rows"
                         % (name, len(data), len(run))):
                continue
            for (t, v), r in zip(data, run):
                where = "%s: %s" % (name, t)
                rr = math.sqrt(sum(x * x for x in v[:3]))
                check(6356.752 + 100 - 1e-3 <= rr <= 6378.137 + 10000, where + ": |r| = %.3f km"
                      % rr)
                check(t == at(fo.epoch, r["time"]), where + ": time differs from the CSV")
                pos = geodetic_to_ecef(r["lat"], r["lon"], r["h"])
                check(max(abs(a / 1e3 - b_) for a, b_ in zip(pos, v[:3])) < 2e-6,
                      where + ": position differs from the CSV's lat/lon/h")
                vel = ecef_velocity(r)
                check(max(abs(a / 1e3 - b_) for a, b_ in zip(vel, v[3:])) < 2e-9,
                      where + ": velocity differs from the CSV's ECI state")


def main(argv):
    if len(argv) < 2:
        print(__doc__, file=sys.stderr)
        return 2
    for path in argv[1:]:
        fo = Folder(path)
        check(not glob.glob(os.path.join(path, "*.tmp")), path + ": .tmp files left")
        check_czml(fo)
        check_kml(fo)
        check_oem(fo)
        print("%s: checked (%d bodies, %d phases)" % (path, len(fo.bodies), len(fo.phases)))
    print("check_exports: %d failures" % len(FAILURES))
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
