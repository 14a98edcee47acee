#!/usr/bin/env python3
"""check_csv_mat.py LVSIM - every value of every phase CSV reads back to the double in the
phase's .mat file, bit for bit, for all rows and columns (the CSV writes the shortest text
that round-trips: io/numfmt.h). Runs the examples with `lvsim run --no-plots` into a temporary
folder; the .mat data are read with scipy (the dsres layout of docs/result-files.md)."""
import csv
import os
import struct
import subprocess
import sys
import tempfile

import numpy as np
import scipy.io

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def load_mat(path):
    m = scipy.io.loadmat(path, chars_as_strings=False)
    names = ["".join(c).rstrip("\0 ") for c in m["name"].T]
    out = {}
    for i, name in enumerate(names):
        block, col = m["dataInfo"][0, i], m["dataInfo"][1, i]
        if block == 1:
            continue  # a parameter: not in the CSV
        out[name] = np.sign(col) * m["data_2"][abs(col) - 1, :]
    return out


def bits(x):
    return struct.pack("<d", x)


def check(folder):
    files = sorted(f for f in os.listdir(folder) if f.startswith("phase_") and f.endswith(".mat"))
    assert files, "no phase files in " + folder
    n_values = 0
    for f in files:
        mat = load_mat(os.path.join(folder, f))
        with open(os.path.join(folder, f[:-4] + ".csv"), newline="") as fh:
            rows = [r for r in csv.reader(fh) if r and not r[0].startswith("#")]
        header = [h.rsplit(" [", 1)[0] for h in rows[0]]
        data = rows[1:]
        for j, name in enumerate(header):
            ref = mat[name]
            assert len(ref) == len(data), (f, name, len(ref), len(data))
            for i, row in enumerate(data):
                got = float(row[j])
                want = float(ref[i])
                same = bits(got) == bits(want) or (got != got and want != want)
                assert same, "%s row %d %s: CSV %r, MAT %r" % (f, i + 1, name, row[j], want)
                n_values += 1
    return len(files), n_values


def main():
    lvsim = sys.argv[1]
    total_files = total_values = 0
    with tempfile.TemporaryDirectory() as tmp:
        for ex in ("dof3-branch", "paper-test-case"):
            out = os.path.join(tmp, ex)
            mission = os.path.join(ROOT, "examples", ex, "mission.yaml")
            subprocess.run([lvsim, "run", mission, "-o", out, "--no-plots"], check=True,
                           stdout=subprocess.DEVNULL)
            n_f, n_v = check(out)
            total_files += n_f
            total_values += n_v
    print("ok: %d phase files, %d values: CSV == MAT bit for bit" % (total_files, total_values))


if __name__ == "__main__":
    main()
