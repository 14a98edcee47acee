#!/usr/bin/python3
"""check_timeline.py - the bodies' timelines (summary.json bodies[].timeline) against the phase CSVs.

Usage: check_timeline.py LVSIM SOURCE_DIR

Runs examples (planet and flat world, a runway take-off, a jettisoned fairing, a returning
booster, the flat world's doubly logged burnout) and checks every body's timeline with
Python's csv and json modules only, following docs/result-files.md ("timeline"):

- each event once per body (no two rows with the same label and time), in time order;
- every phase the body flies in has one end row whose t, h and speed are the phase CSV's
  last row exactly (and its summary `final` time, `t_end`), labelled by the end's user name
  (`end.label`) or by the label rule (burnout, "altitude 110 km", "stop_time 140 s", ...);
- the first row is the body's start: row 0 of its first phase (lift-off, or a take-off
  roll's start and the runway's lift-off end);
- max-q is the largest q_dyn of the body's phase CSVs where rho > 0 and h <= 1000 km, at its
  first row; none without an atmosphere (the paper's flat world);
- one separation per phase of the body whose children carry fewer stages, with the first
  row of the body's child (the parent's last row for a stage that flies no further),
  labelled by what separates (kourou-leo: the payload's are the booster's and the
  fairing's, as the mission file drops them);
- burnouts within a phase and every named event appear;
- the console table, the report's Timeline section and the key figures' separation labels;
  `lvsim check` and `lvsim run` give the same error for a bad name.
Exit 0 when every check passes.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

ATMO_TOP = 1000e3
FAILS = []
CHECKS = [0]


def check(cond, what):
    CHECKS[0] += 1
    if not cond:
        FAILS.append(what)


def load_csv(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    head = [h.split(" [")[0] for h in rows[0]]
    units = {h.split(" [")[0]: h.split(" [")[1].rstrip("]") if " [" in h else "" for h in rows[0]}
    return [{k: float(v) for k, v in zip(head, r)} for r in rows[1:]], units


def first(row, *names):
    for n in names:
        if n in row:
            return row[n]
    return None


def value_text(v, unit):
    """The label rule's number: metres from 1 km on in km, '%.10g'."""
    if unit == "m" and abs(v) >= 1000:
        return "%.10g km" % (v / 1000)
    if unit in ("", "1", None):
        return "%.10g" % v
    return "%.10g %s" % (v, unit)


def default_label(p, units):
    end = p["end"]
    if end["reason"] == "stop_time":
        return "stop_time " + value_text(end["value"], "s")
    name = end["event"]
    if name == "liftoff":
        return "lift-off"
    v = end.get("value")
    if v is None or name in ("burnout", "apogee") or (name == "impact" and v == 0):
        return name
    unit = {"altitude": "m", "impact": "m", "speed": "m/s", "time": "s"}.get(name, units.get(name, ""))
    return "%s %s" % (name, value_text(v, unit))


def check_run(out, ex):
    summ = json.load(open(os.path.join(out, "summary.json")))
    phases = {p["name"]: p for p in summ["phases"]}
    csvs = {n: load_csv(os.path.join(out, p["files"]["csv"])) for n, p in phases.items()}
    for b in summ["bodies"]:
        who = "%s %s" % (ex, b["name"])
        tl = b.get("timeline")
        check(isinstance(tl, list) and tl, who + ": no timeline")
        if not tl:
            continue
        keys = [(e["label"], e["t"]) for e in tl]
        check(len(keys) == len(set(keys)), who + ": an event listed twice: %r" % keys)
        ts = [e["t"] for e in tl]
        check(ts == sorted(ts), who + ": not in time order")
        for e in tl:  # every value is that of the row it names
            rows = csvs[e["phase"]][0]
            r = rows[e["row"]]
            check(e["t"] == r["time"] and e["h"] == first(r, "h", "z") and
                  e["speed"] == first(r, "v_rel", "speed"),
                  "%s %s: t, h, speed are not those of %s row %d" % (who, e["label"], e["phase"], e["row"]))
        names = b["phases"]
        # the start: row 0 of the first phase
        check(tl[0]["phase"] == names[0] and tl[0]["row"] == 0 and tl[0]["kind"] in ("liftoff", "start"),
              who + ": first row %r" % tl[0])
        for pn in names:
            p = phases[pn]
            rows, units = csvs[pn]
            last = len(rows) - 1
            ends = [e for e in tl if e["phase"] == pn and e["row"] == last and e["kind"] in ("end", "liftoff")]
            check(len(ends) == 1, "%s: %d end rows for phase %s" % (who, len(ends), pn))
            if len(ends) != 1:
                continue
            e = ends[0]
            r = rows[last]
            # the timeline against the phase's finals: the CSV's last row and summary.json,
            # bit for bit (every number in lvsim's JSON files reads back to the same double;
            # cJSON's printer wrote 15 digits, another double for 190.80430311868503)
            check(e["t"] == r["time"] and e["t"] == p["t_end"] and e["t"] == p["final"]["time"],
                  "%s %s: end time" % (who, pn))
            check(e["h"] == first(r, "h", "z") and e["h"] == first(p["final"], "h", "z"),
                  "%s %s: end altitude" % (who, pn))
            check(e["speed"] == first(r, "v_rel", "speed"), "%s %s: end speed" % (who, pn))
            want = p["end"].get("label") or default_label(p, units)
            check(e["label"] == want, "%s %s: label %r, expected %r" % (who, pn, e["label"], want))
            check(e.get("named", False) == ("label" in p["end"]), "%s %s: named" % (who, pn))
            check(e["event"] == p["end"].get("event", p["end"]["reason"]), "%s %s: event %r" % (who, pn, e["event"]))
            # burnouts within the phase and the named events: listed
            for ev in p["events"]:
                at_end = ev["t"] == p["t_end"] and ev["name"] == p["end"].get("event")
                if at_end or not (ev.get("label") or (ev["kind"] == "state" and ev["name"] == "burnout")):
                    continue
                lbl = ev.get("label") or ev["name"]
                check(any(x["label"] == lbl and x["t"] == ev["t"] and x["kind"] == "event" for x in tl),
                      "%s %s: event %s at %r not listed" % (who, pn, lbl, ev["t"]))
            # separations: children that carry fewer stages
            kids = [c for c in summ["phases"] if c["from"] == pn and c["state"] == "done"
                    and len(c["stages"]) < len(p["stages"])]
            seps = [x for x in tl if x["kind"] == "separation" and x["t"] == p["t_end"] and
                    (x["phase"] == pn or phases[x["phase"]]["from"] == pn)]
            check(len(seps) == (1 if kids else 0), "%s %s: %d separations" % (who, pn, len(seps)))
            if kids and seps:
                mine = [c for c in kids if b["name"] in c["stages"]]
                if mine:
                    check(seps[0]["phase"] == mine[0]["name"] and seps[0]["row"] == 0,
                          "%s %s: separation from %r" % (who, pn, seps[0]))
                else:  # the stage flies no further: the parent's last row
                    check(seps[0]["phase"] == pn and seps[0]["row"] == last, "%s %s: dropped" % (who, pn))
        # max-q: the q_dyn column's maximum where the atmosphere model is defined
        best = None
        for pn in names:
            for i, r in enumerate(csvs[pn][0]):
                if "q_dyn" in r and r["rho"] > 0 and first(r, "h", "z") <= ATMO_TOP and r["q_dyn"] > 0 and \
                        (best is None or r["q_dyn"] > best[0]):
                    best = (r["q_dyn"], r["time"], pn, i)
        mq = [e for e in tl if e["kind"] == "max_q"]
        if best is None:  # no air (the paper's flat world): none
            check(not mq, who + ": max-q in a world without air")
        else:
            check(len(mq) == 1 and mq[0]["q"] == best[0] and mq[0]["t"] == best[1] and
                  mq[0]["phase"] == best[2] and mq[0]["row"] == best[3], "%s: max-q %r vs %r" % (who, mq, best))
    return summ


def example_text(src, ex):
    return open(os.path.join(src, "examples", ex, "mission.yaml"), encoding="utf-8").read()


def fly_variant(lvsim, src, tmp, ex, name, text, args=("-q", "--no-plots"), out="out", text_mode=True):
    """Runs `text`, an edited copy of examples/EX/mission.yaml, in TMP/NAME beside links to the
    example's tables: (the results folder, the finished process)."""
    d = os.path.join(tmp, name)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "mission.yaml"), "w", encoding="utf-8") as f:
        f.write(text)
    for fn in os.listdir(os.path.join(src, "examples", ex)):
        if fn.endswith(".csv") and not os.path.exists(os.path.join(d, fn)):
            os.symlink(os.path.join(src, "examples", ex, fn), os.path.join(d, fn))
    o = os.path.join(d, out)
    r = subprocess.run([lvsim, "run", os.path.join(d, "mission.yaml"), "-o", o] + list(args),
                       capture_output=True, text=text_mode)
    return o, r


def labels(summ, body, kind=None):
    b = next(b for b in summ["bodies"] if b["name"] == body)
    return [e["label"] for e in b["timeline"] if kind is None or e["kind"] == kind]


def main():
    lvsim, src = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        runs = {}
        for ex in ("kourou-leo", "kourou-rtls", "rlv-hthl", "paper-test-case", "sounding-rocket",
                   "delta3-gto"):
            out = os.path.join(tmp, ex)
            args = [lvsim, "run", os.path.join(src, "examples", ex, "mission.yaml"), "-o", out, "-q"]
            if ex != "kourou-leo":
                args.append("--no-plots")
            r = subprocess.run(args, capture_output=True, text=True)
            check(r.returncode == 0, "lvsim run %s: %s" % (ex, r.stderr))
            if r.returncode == 0:
                runs[ex] = (check_run(out, ex), r.stdout, out)
        if "kourou-leo" in runs:
            summ, stdout, out = runs["kourou-leo"]
            # the mission drops the booster at the ascent's end, the fairing at upper-burn-1's
            check(labels(summ, "payload", "separation") == ["separation of booster", "separation of fairing"],
                  "kourou-leo payload separations: %r" % labels(summ, "payload", "separation"))
            check(labels(summ, "booster", "separation") == ["separation of booster"],
                  "kourou-leo booster separations: %r" % labels(summ, "booster", "separation"))
            pl = labels(summ, "payload")
            check(pl[0] == "lift-off" and "max-q" in pl and "MECO" in pl and "SECO" in pl and
                  pl.index("MECO") < pl.index("separation of booster") < pl.index("SECO"),
                  "kourou-leo payload: %r" % pl)
            asc = next(p for p in summ["phases"] if p["name"] == "ascent")
            check(asc["end"].get("label") == "MECO" and asc["end"]["event"] == "burnout" and
                  asc["events"][-1].get("label") == "MECO", "kourou-leo ascent end: %r" % asc["end"])
            # the console's compact table: one line per event, with the bodies it concerns
            lines = stdout.split("\ntimeline: event")[-1].split("\nexport")[0].splitlines()[1:]
            meco = [l for l in lines if l.split()[:1] == ["MECO"]]
            seps = [l for l in lines if l.startswith("  separation of fairing")]
            check(len(meco) == 1 and meco[0].rstrip().endswith(" all") and len(seps) == 2 and
                  seps[0].rstrip().endswith("upper, payload") and seps[1].rstrip().endswith("fairing"),
                  "kourou-leo: the run's timeline table: %r" % lines)
            # the exports' event markers carry the user's names (docs/exports.md)
            kml = open(os.path.join(out, "mission.kml")).read()
            czml = json.load(open(os.path.join(out, "mission.czml")))
            texts = [p.get("label", {}).get("text") for p in czml if isinstance(p, dict)]
            check("<name>MECO</name>" in kml and "<name>SECO</name>" in kml and
                  "MECO" in texts and "SECO" in texts, "kourou-leo: exports' markers: %r" %
                  sorted(set(t for t in texts if t)))
            html = open(os.path.join(out, "index.html")).read()
            check('<h2 id="timeline">Timeline</h2>' in html and "separation of fairing" in html,
                  "kourou-leo: no timeline in index.html")
            keys = json.load(open(os.path.join(out, "key_figures.json")))
            kp = next(b for b in keys["bodies"] if b["name"] == "payload")
            check([s.get("label") for s in kp["separations"]] == ["separation of booster", "separation of fairing"],
                  "kourou-leo key figures' separations: %r" % kp["separations"])
        if "rlv-hthl" in runs:
            summ = runs["rlv-hthl"][0]
            ms = labels(summ, "ms")
            check(ms[:2] == ["start of take-off roll", "lift-off"], "rlv-hthl ms: %r" % ms[:3])
            lo = next(p for p in summ["phases"] if p["name"] == "liftoff")
            b = next(b for b in summ["bodies"] if b["name"] == "ms")
            check(b["timeline"][1]["t"] == lo["t_end"] and b["timeline"][1]["kind"] == "liftoff",
                  "rlv-hthl: lift-off at the runway's end")
            # the roll-out's own end (the runway model's stop) named by its end_name
            check(ms[-1] == "wheels stop" and b["timeline"][-1]["event"] == "stop" and
                  b["timeline"][-1]["named"], "rlv-hthl: the roll-out's end: %r" % b["timeline"][-1])
            meco = [e for e in b["timeline"] if e["label"] == "MECO"]
            check(len(meco) == 1 and meco[0]["event"] == "propellant_left", "rlv-hthl MECO: %r" % meco)
        if "kourou-rtls" in runs:
            summ = runs["kourou-rtls"][0]
            bl = labels(summ, "booster")
            check(bl[-1] == "touchdown" and "entry burn shutdown" in bl and "boostback shutdown" in bl,
                  "kourou-rtls booster: %r" % bl)
        if "sounding-rocket" in runs:
            summ = runs["sounding-rocket"][0]
            check(labels(summ, "rocket").count("burnout") == 1, "sounding-rocket: burnout listed %d times"
                  % labels(summ, "rocket").count("burnout"))
        if "paper-test-case" in runs:
            summ = runs["paper-test-case"][0]
            s3 = labels(summ, "stage3")
            check(s3 == ["lift-off", "burnout", "stop_time 140 s", "separation of stage1", "burnout",
                         "stop_time 280 s", "separation of stage2", "burnout", "stop_time 600 s"],
                  "paper-test-case stage3: %r" % s3)
        # a separation named by the child's `separation: {name: ...}` (with an impulse, and
        # alone: a name, no impulse; the flight is the same)
        if "kourou-leo" in runs:
            text = example_text(src, "kourou-leo")
            text = text.replace("separation: {dv: 1} ", "separation: {dv: 1, name: stage separation} ", 1)
            text = text.replace("    from: upper-burn-1\n", "    from: upper-burn-1\n    separation: {name: fairing jettison}\n", 1)
            check("stage separation" in text and "fairing jettison" in text, "named-sep: mission not edited")
            out, r = fly_variant(lvsim, src, tmp, "kourou-leo", "named-sep", text)
            check(r.returncode == 0, "named-sep: %s" % r.stderr)
            if r.returncode == 0:
                summ = check_run(out, "named-sep")
                b = next(b for b in summ["bodies"] if b["name"] == "payload")
                seps = [(e["label"], e.get("named")) for e in b["timeline"] if e["kind"] == "separation"]
                check(seps == [("stage separation", True), ("fairing jettison", True)], "named-sep: %r" % seps)
                ref = runs["kourou-leo"][0]
                check([p["final"] for p in summ["phases"]] == [p["final"] for p in ref["phases"]],
                      "named-sep: a name changed the flight")
        # the fairing flies a phase of its own to its impact: both rows, the payload's and the
        # fairing's, name what leaves the stack (the fairing), not the stack that goes on
        if "kourou-leo" in runs:
            text = example_text(src, "kourou-leo")
            text += ("\n  - {name: fairing-fall, model: dof3, stages: [fairing], from: upper-burn-1,"
                     " stop_time: 3000, end: [impact], throttle: off, aero: {s_ref: 20, CD: 1.2}}\n")
            out, r = fly_variant(lvsim, src, tmp, "kourou-leo", "fairing-fall", text)
            check(r.returncode == 0, "fairing-fall: %s" % r.stderr)
            if r.returncode == 0:
                summ = check_run(out, "fairing-fall")
                check(labels(summ, "payload", "separation") == ["separation of booster", "separation of fairing"],
                      "fairing-fall payload: %r" % labels(summ, "payload", "separation"))
                check(labels(summ, "fairing", "separation") == ["separation of booster", "separation of fairing"],
                      "fairing-fall fairing: %r" % labels(summ, "fairing", "separation"))
        # names of 63 characters (the most, docs/mission-format.md) of 2- and 3-byte UTF-8
        # characters: whole in summary.json, the report and the console (valid UTF-8, strict
        # decoding), the console's columns counted in characters
        if "kourou-leo" in runs:
            meco, seco = "\u00e9" * 63, "a" + "\u5317" * 62
            text = example_text(src, "kourou-leo")
            text = text.replace("end: [{burnout, name: MECO}]", 'end: [{burnout, name: "%s"}]' % meco, 1)
            text = text.replace("end_name: SECO", 'end_name: "%s"' % seco, 1)
            check(meco in text and seco in text, "utf8: mission not edited")
            out, r = fly_variant(lvsim, src, tmp, "kourou-leo", "utf8", text, args=(), text_mode=False)
            check(r.returncode == 0, "utf8: %r" % r.stderr)
            if r.returncode == 0:
                summ = json.loads(open(os.path.join(out, "summary.json"), "rb").read().decode("utf-8", "strict"))
                pl = labels(summ, "payload")
                check(meco in pl and seco in pl, "utf8: labels cut: %r" % pl)
                html = open(os.path.join(out, "index.html"), "rb").read().decode("utf-8", "strict")
                check(meco in html and seco in html, "utf8: names not whole in index.html")
                lines = r.stdout.decode("utf-8", "strict").splitlines()
                row = [l for l in lines if l.startswith("  " + meco)]
                check(len(row) == 1 and row[0][2 + 63:].split()[0] == "153.231" if row else False,
                      "utf8: console row %r" % row)
                ref = [l for l in lines if l.startswith("  max-q")]
                check(len(row) == 1 and len(ref) == 1 and
                      row[0].index(" 153.231") - 63 == ref[0].index("  63.000") - 34,
                      "utf8: console columns: %r / %r" % (row, ref))
        # a name with HTML in it: CZML descriptions are HTML (Cesium renders them): escaped
        if "kourou-leo" in runs:
            text = example_text(src, "kourou-leo").replace("end_name: SECO", "end_name: 'SECO </script><b>&'", 1)
            out, r = fly_variant(lvsim, src, tmp, "kourou-leo", "html-name", text)
            check(r.returncode == 0, "html-name: %s" % r.stderr)
            if r.returncode == 0:
                czml = json.load(open(os.path.join(out, "mission.czml")))
                desc = [p.get("description", "") for p in czml if isinstance(p, dict)]
                hit = [x for x in desc if "SECO" in x]
                check(hit and all("SECO &lt;/script&gt;&lt;b&gt;&amp;" in x and "</script>" not in x for x in hit),
                      "html-name: CZML descriptions: %r" % hit)
        # a touchdown past the end of a 400 m runway crashes: the roll-out is not flown, the
        # body's timeline ends with a "crashed" row at the flare's last row (its touchdown)
        if "rlv-hthl" in runs:
            text = example_text(src, "rlv-hthl")
            i = text.index("heading_deg: 270, length: 4000")
            text = text[:i] + text[i:].replace("length: 4000", "length: 400", 1)
            out, r = fly_variant(lvsim, src, tmp, "rlv-hthl", "crash", text)
            check(r.returncode == 4, "crash: exit %d: %s" % (r.returncode, r.stderr[-300:]))
            summ = json.load(open(os.path.join(out, "summary.json")))
            b = next(b for b in summ["bodies"] if b["name"] == "ms")
            last, td = b["timeline"][-1], b["timeline"][-2]
            fl = next(p for p in summ["phases"] if p["name"] == "flare")
            check(last["kind"] == "crash" and last["label"] == "crashed" and last["event"] == "crashed" and
                  last["phase"] == "flare" and last["t"] == fl["t_end"] and td["label"] == "touchdown" and
                  last["row"] == td["row"], "crash: %r / %r" % (td, last))
            # a 1000 m runway: touchdown 606 m past the threshold, off the end at 1000 m - the
            # roll-out is flown to there (complete files, its rows in the timeline) and crashed
            text = text.replace("length: 400,", "length: 1000,", 1)
            out, r = fly_variant(lvsim, src, tmp, "rlv-hthl", "crash", text, out="out2")
            check(r.returncode == 4 and "crashed at t = " in r.stderr and ": overrun: " in r.stderr,
                  "overrun: exit %d: %s" % (r.returncode, r.stderr[-300:]))
            summ = json.load(open(os.path.join(out, "summary.json")))
            ro = next(p for p in summ["phases"] if p["name"] == "rollout")
            rows, _ = load_csv(os.path.join(out, ro["files"]["csv"]))
            b = next(b for b in summ["bodies"] if b["name"] == "ms")
            end, last = b["timeline"][-2], b["timeline"][-1]
            check(ro["state"] == "crashed" and ro["end"]["event"] == "overrun" and
                  ro["files"]["csv"] == "phase_10_rollout.csv" and abs(rows[-1]["distance"] - 1000) < 1e-6 and
                  end["kind"] == "end" and end["event"] == "overrun" and end["t"] == rows[-1]["time"] and
                  last["kind"] == "crash" and last["phase"] == "rollout" and last["t"] == rows[-1]["time"],
                  "overrun: %r / %r / %r" % (ro.get("end"), end, last))
        # lvsim check = lvsim run: the same message for a bad name
        bad = os.path.join(tmp, "bad.yaml")
        with open(bad, "w") as f:
            f.write("mission: {name: t}\nstages:\n  - {name: s1, dry_mass: 1, propellant_mass: 1}\n"
                    "phases:\n  - {name: P1, model: flat6, stages: [s1], stop_time: 1,\n"
                    "     end: [{burnout, name: X}, {apogee, name: X}]}\n")
        rc = subprocess.run([lvsim, "check", bad], capture_output=True, text=True)
        rr = subprocess.run([lvsim, "run", bad, "-o", os.path.join(tmp, "bad-out")], capture_output=True, text=True)
        check(rc.returncode == 2 and rr.returncode == 2 and "bad.yaml:6:47: phase 'P1': event name 'X' given twice"
              in rc.stderr and rc.stderr.strip().splitlines()[-1] in rr.stderr,
              "check vs run: %r / %r" % (rc.stderr, rr.stderr))
    for f in FAILS:
        print("FAIL: " + f)
    print("%d passed, %d failed" % (CHECKS[0] - len(FAILS), len(FAILS)))
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
