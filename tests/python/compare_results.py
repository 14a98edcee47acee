#!/usr/bin/python3
"""compare_results.py - are two results folders of `lvsim run` the same results?

Usage: compare_results.py OLD NEW

For refactors that must not change a number (docs/architecture.md): every file lvsim wrote in
OLD (its manifest.json's list) must be in NEW and the same - MAT files and the exports
(CZML, KML, OEM: its CREATION_DATE line aside) byte for byte; CSV files value for value to the bit (the numbers' text may be
spelled differently, their doubles may not); summary.json with the run's own times left out
(cpu, wall, started, finished); and NEW must list no file OLD does not. Plots (PNG, SVG) and
index.html are compared by name only (fonts and the renderer are not lvsim's numbers). Prints
one line per difference; exit 0 when there is none.
"""
import csv
import json
import os
import sys

TIMES = {"cpu", "cpu_time", "wall", "started", "finished", "cpu_ms", "time_s", "lvsim"}


def listed(folder):
    with open(os.path.join(folder, "manifest.json")) as f:
        return {e["name"] for e in json.load(f)["files"]}


def strip_times(x):
    if isinstance(x, dict):
        return {k: strip_times(v) for k, v in x.items() if k not in TIMES}
    if isinstance(x, list):
        return [strip_times(v) for v in x]
    return x


def csv_rows(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


def same_csv(a, b):
    ra, rb = csv_rows(a), csv_rows(b)
    if len(ra) != len(rb):
        return "%d rows, now %d" % (len(ra), len(rb))
    for i, (x, y) in enumerate(zip(ra, rb)):
        if len(x) != len(y):
            return "row %d: %d fields, now %d" % (i + 1, len(x), len(y))
        for j, (u, v) in enumerate(zip(x, y)):
            if u == v:
                continue
            try:
                fu, fv = float(u), float(v)
            except ValueError:
                return "row %d field %d: %r, now %r" % (i + 1, j + 1, u, v)
            if fu != fv and not (fu != fu and fv != fv):
                return "row %d field %d: %r, now %r" % (i + 1, j + 1, u, v)
    return None


def main(old, new):
    diffs = []
    a, b = listed(old), listed(new)
    for name in sorted(a - b):
        diffs.append("missing now: %s" % name)
    for name in sorted(b - a):
        diffs.append("new file: %s" % name)
    for name in sorted(a & b):
        pa, pb = os.path.join(old, name), os.path.join(new, name)
        ext = os.path.splitext(name)[1]
        if name.startswith("plots/") or name == "index.html" or name.startswith("viewer/"):
            continue
        if ext == ".csv":
            d = same_csv(pa, pb)
        elif name.endswith(".json"):
            with open(pa) as f:
                ja = strip_times(json.load(f))
            with open(pb) as f:
                jb = strip_times(json.load(f))
            d = None if ja == jb else "differs (times aside)"
        else:
            with open(pa, "rb") as f:
                ba = f.read()
            with open(pb, "rb") as f:
                bb = f.read()
            if ext == ".oem":  # the header's CREATION_DATE is when the file was written
                ba, bb = (b"\n".join(l for l in x.split(b"\n")
                                     if not l.startswith(b"CREATION_DATE")) for x in (ba, bb))
            d = None if ba == bb else "%d bytes, now %d: differs" % (len(ba), len(bb))
        if d is not None:
            diffs.append("%s: %s" % (name, d))
    for d in diffs:
        print("compare_results: %s" % d)
    return 1 if diffs else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[2])
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
