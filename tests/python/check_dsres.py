#!/usr/bin/python3
"""check_dsres.py - read back the dsres MAT v4 files that test_io writes.

Usage: check_dsres.py OK.mat FAILED.mat EMPTY_FAILED.mat

Three independent readings of each file:
  1. the raw MAT v4 headers (order, type codes, sizes: what OpenModelica's
     reader demands);
  2. scipy.io.loadmat;
  3. a small DyMat-style reader that resolves a variable by name through
     dataInfo (matrix, signed column), as Dymola/OpenModelica readers do.
The sample run (same recipe as tests/unit/test_io.c): t_k = k * 0.1,
k = 0..10; h = sin(t), der(h) = cos(t), m = 100 before and 60 after an event
at t = 0.5 (that instant appears twice), C[1,2] = 0.5 t; four parameters.
Exit status 0 when every check passes.
"""
import math
import re
import struct
import sys

import numpy as np
import scipy.io

FAILURES = []


def check(cond, what):
    if not cond:
        FAILURES.append(what)
        print("FAIL: " + what, file=sys.stderr)


NAMES = ["time", "h", "der(h)", "m", "C[1,2]", "mdot", "isp", "g0", "n_stages"]
# dimensionless: "[1]", the unit one (docs/result-files.md, "Units"), also for a model's ""
DESCRIPTIONS = ["Simulation time [s]", "Altitude [m]", "der(Altitude) [m/s]",
                "Vehicle mass [kg]", "Attitude matrix element, body to ECI [1]",
                "Mass flow [kg/s]", "Specific impulse [s]", "Standard gravity [m/s2]",
                "Stage count [1]"]
UNITS = ["s", "m", "m/s", "kg", "1", "kg/s", "s", "m/s2", "1"]
PARAMS = {"mdot": 12.5, "isp": 300.0, "g0": 9.80665, "n_stages": 2.0}
DATAINFO = [[0, 1, 0, -1], [2, 2, 0, -1], [2, 3, 0, -1], [2, 4, 0, -1], [2, 5, 0, -1],
            [1, 2, 0, 0], [1, 3, 0, 0], [1, 4, 0, 0], [1, 5, 0, 0]]


def sample_rows(n):
    """The first n rows of the sample run as (t, h, der(h), m, C[1,2])."""
    rows = []
    for i in range(n):
        k = i if i <= 5 else i - 1
        t = k * 0.1
        rows.append((t, math.sin(t), math.cos(t), 100.0 if i <= 5 else 60.0, 0.5 * t))
    return rows


def raw_headers(path):
    """[(name, type, mrows, ncols)] read from the MAT v4 headers themselves."""
    out = []
    with open(path, "rb") as f:
        while True:
            hdr = f.read(20)
            if not hdr:
                break
            typ, mrows, ncols, imagf, namelen = struct.unpack("<5i", hdr)
            name = f.read(namelen)
            check(name.endswith(b"\0"), path + ": matrix name not NUL-terminated")
            p = (typ // 10) % 10
            elem = {0: 8, 1: 4, 2: 4, 3: 2, 4: 2, 5: 1}[p]
            f.seek(elem * mrows * ncols * (1 + imagf), 1)
            out.append((name[:-1].decode(), typ, mrows, ncols))
    return out


class DsresReader:
    """Minimal Dymola/OpenModelica result reader (the DyMat approach)."""

    def __init__(self, path):
        self.mat = scipy.io.loadmat(path, chars_as_strings=False)
        aclass = ["".join(r).rstrip("\0 ") for r in self.mat["Aclass"]]
        if aclass[0] != "Atrajectory" or aclass[1] != "1.1" or aclass[3] != "binTrans":
            raise ValueError("not a dsres 1.1 binTrans file: %r" % aclass)
        # binTrans: one variable per column
        self.names = ["".join(c).rstrip("\0 ") for c in self.mat["name"].T]
        self.descriptions = ["".join(c).rstrip("\0 ") for c in self.mat["description"].T]
        self.info = self.mat["dataInfo"].T  # row i: [matrix, column, interp, extrap]
        self.index = {n: i for i, n in enumerate(self.names)}

    def unit(self, name):
        m = re.search(r"\[([^\]]*)\]$", self.descriptions[self.index[name]])
        return m.group(1) if m else ""

    def values(self, name):
        """The trajectory of `name` (a parameter gives its two values at t0, tf)."""
        block, col = int(self.info[self.index[name]][0]), int(self.info[self.index[name]][1])
        if block == 0:  # the abscissa: column |col| of the data matrix (time-varying data)
            block = 2
        data = self.mat["data_%d" % block]  # binTrans: one variable per row
        return np.sign(col) * data[abs(col) - 1, :]

    def time(self, block=2):
        return self.mat["data_%d" % block][0, :]


def check_layout(path, nrows, failure):
    hdrs = raw_headers(path)
    want = [("Aclass", 51, 4, 11), ("name", 51, len("n_stages") + 1, 9),
            ("description", 51, len(DESCRIPTIONS[4]) + 1, 9), ("dataInfo", 20, 4, 9),
            ("data_1", 0, 5, 2), ("data_2", 0, 5, nrows)]
    if failure is not None:
        want.append(("lvsim_failure", 51, 1, len(failure)))
    check(hdrs == want, "%s: headers %r, expected %r" % (path, hdrs, want))


def check_scipy(path, nrows, failure):
    m = scipy.io.loadmat(path)  # default: char matrices as arrays of strings
    for key in ("Aclass", "name", "description", "dataInfo", "data_1", "data_2"):
        check(key in m, "%s: scipy sees no %s" % (path, key))
    check([s.rstrip("\0 ") for s in m["Aclass"]] == ["Atrajectory", "1.1", "", "binTrans"],
          "%s: Aclass %r" % (path, m["Aclass"]))
    check(m["dataInfo"].dtype == np.int32, "%s: dataInfo is %s" % (path, m["dataInfo"].dtype))
    check(m["data_2"].dtype == np.float64 and m["data_2"].shape == (5, nrows),
          "%s: data_2 %s %s" % (path, m["data_2"].dtype, m["data_2"].shape))
    if failure is None:
        check("lvsim_failure" not in m, path + ": lvsim_failure in a complete result")
    else:
        got = m.get("lvsim_failure")
        text = str(got[0]) if got is not None and len(got) else None
        check(text == failure, "%s: lvsim_failure %r, expected %r" % (path, text, failure))


def check_reader(path, nrows):
    r = DsresReader(path)
    check(r.names == NAMES, "%s: names %r" % (path, r.names))
    check(r.descriptions == DESCRIPTIONS, "%s: descriptions %r" % (path, r.descriptions))
    check([r.unit(n) for n in NAMES] == UNITS, "%s: units" % path)
    check(r.info.tolist() == DATAINFO, "%s: dataInfo %r" % (path, r.info.tolist()))

    rows = sample_rows(nrows)
    t = r.time()
    check(len(t) == nrows, "%s: %d time points, expected %d" % (path, len(t), nrows))
    check(np.array_equal(r.values("time"), t), path + ": time by name != abscissa")
    for j, name in enumerate(NAMES[:5]):
        want = np.array([row[j] for row in rows])
        got = r.values(name)
        check(got.shape == want.shape and np.allclose(got, want, rtol=1e-15, atol=1e-15),
              "%s: %s = %r, expected %r" % (path, name, got, want))
    for name, value in PARAMS.items():
        got = r.values(name)
        check(list(got) == [value, value], "%s: parameter %s = %r" % (path, name, got))
    t01 = list(r.time(1))
    if nrows > 0:
        check(t01 == [0.0, rows[-1][0]], "%s: data_1 time %r" % (path, t01))
    else:
        check(all(math.isnan(x) for x in t01), "%s: data_1 time %r (no rows)" % (path, t01))
    if nrows > 6:
        # the event at t = 0.5: two rows, before and after
        ev = np.nonzero(t == 0.5)[0]
        m = r.values("m")
        check(list(ev) == [5, 6] and m[5] == 100.0 and m[6] == 60.0,
              "%s: event rows %r, m %r" % (path, list(ev), list(m[4:8])))


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    ok, failed, empty = argv[1:]
    reason = "CVODE error -3 at t = 0.3: repeated error test failures"
    for path, nrows, failure in ((ok, 12, None), (failed, 4, reason),
                                 (empty, 0, "(no reason given)")):
        check_layout(path, nrows, failure)
        check_scipy(path, nrows, failure)
        check_reader(path, nrows)
    print("check_dsres: %d failures" % len(FAILURES))
    return 1 if FAILURES else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
