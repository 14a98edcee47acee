#!/usr/bin/env python3
"""bench/whole_process.py - what a user waits for: `lvsim check`, `lvsim run --no-plots` and
`lvsim run` as whole processes (loader, mission load, simulation, result files, exports,
plots), and the cost per output row at 10^3..10^5 rows, each beside the simulation's own CPU
time, so the share outside the simulation is visible (issue 11).

    bench/whole_process.py [--lvsim build/lvsim] [--reps N] [--quick]

Figures: wall time and CPU time (user + system, of the process and its children) from
wait4(), the fastest of N repetitions (a quiet machine is not guaranteed; the fastest run is
the least disturbed one). "sim" is the sum of the phases' own CPU time as lvsim reports it
(summary.json, or the run table when no summary is written): integration, events and the
phase's result rows. With an lvsim that has `run --outputs`, the script also runs
`--outputs none` (nothing written) and the per-row runs with the MAT and CSV files alone.
Prints figures; asserts nothing. Issue 11 quotes OpenTsiolkovsky's sample mission at
50-70 ms as a whole process with its CSV output (not measured here)."""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def run_once(argv):
    """(wall s, CPU s (user + system, from wait4), stdout, stderr, exit code) of one process."""
    with tempfile.TemporaryFile() as fo, tempfile.TemporaryFile() as fe:
        t0 = time.perf_counter()
        p = subprocess.Popen(argv, stdout=fo, stderr=fe)
        _, status, ru = os.wait4(p.pid, 0)
        wall = time.perf_counter() - t0
        p.returncode = os.waitstatus_to_exitcode(status)
        fo.seek(0)
        fe.seek(0)
        return (wall, ru.ru_utime + ru.ru_stime, fo.read().decode(), fe.read().decode(),
                p.returncode)


class Timer:
    """Fastest wall and CPU of N runs of a command."""

    def __init__(self, reps):
        self.reps = reps

    def measure(self, argv, before=None):
        best_wall, best_cpu, out = float("inf"), float("inf"), ""
        for _ in range(self.reps):
            if before:
                before()
            wall, cpu, out, err, rc = run_once(argv)
            if rc != 0:
                sys.exit("whole_process: %s failed (%d):\n%s%s" % (" ".join(argv), rc, out, err))
            best_wall = min(best_wall, wall)
            best_cpu = min(best_cpu, cpu)
        return best_wall, best_cpu, out


def sim_cpu_from(outdir, stdout):
    """Sum of the phases' CPU time [s]: summary.json, else the run table's cpu [ms] column."""
    path = os.path.join(outdir, "summary.json")
    if os.path.exists(path):
        with open(path) as f:
            d = json.load(f)
        return sum(p.get("stats", {}).get("cpu_time", 0.0) for p in d["phases"])
    total = 0.0
    for line in stdout.splitlines():
        m = re.match(r"^\d+\s+\S+\s+\S+\s+[-\d.]+\s+[-\d.]+\s+\S+\s+\d+\s+\d+\s+\d+\s+\d+\s+([\d.]+)\s", line)
        if m:
            total += float(m.group(1)) * 1e-3
    return total


def rows_from(outdir):
    path = os.path.join(outdir, "summary.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        d = json.load(f)
    return sum(p.get("stats", {}).get("rows", 0) for p in d["phases"])


def dir_bytes(d):
    return sum(os.path.getsize(os.path.join(r, f)) for r, _, fs in os.walk(d) for f in fs)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lvsim", default=os.path.join(ROOT, "build", "lvsim"))
    ap.add_argument("--reps", type=int, default=5, help="repetitions of each fast command")
    ap.add_argument("--quick", action="store_true", help="fewer repetitions, rows to 10^4")
    a = ap.parse_args()
    lvsim = os.path.abspath(a.lvsim)
    reps = 2 if a.quick else a.reps
    help_text = subprocess.run([lvsim, "run", "--help"], capture_output=True, text=True).stdout
    has_outputs = "--outputs" in help_text
    tmp = tempfile.mkdtemp(prefix="lvsim-bench-")
    fast, slow = Timer(reps * 4), Timer(reps)

    print("# whole process, %s; fastest of N runs; ms" % lvsim)
    print("# sim = the phases' own CPU (integration, events, their rows); outside = CPU - sim")
    print("%-16s %-26s %9s %9s %9s %9s" % ("mission", "command", "wall", "CPU", "sim", "outside"))
    missions = [
        ("one-phase", os.path.join(HERE, "missions", "one-phase.yaml")),
        ("paper-test-case", os.path.join(ROOT, "examples", "paper-test-case", "mission.yaml")),
        ("dof3-branch", os.path.join(ROOT, "examples", "dof3-branch", "mission.yaml")),
    ]
    for name, path in missions:
        out = os.path.join(tmp, name)
        rows = [("check", [lvsim, "check", path], fast, False)]
        if has_outputs:
            rows.append(("run --outputs none", [lvsim, "run", path, "-o", out, "--outputs", "none"],
                         fast, True))
        rows.append(("run --no-plots", [lvsim, "run", path, "-o", out, "--no-plots"], fast, True))
        rows.append(("run", [lvsim, "run", path, "-o", out], slow, True))
        for label, argv, timer, is_run in rows:
            wipe = (lambda o=out: shutil.rmtree(o, ignore_errors=True))
            wall, cpu, stdout = timer.measure(argv, before=wipe)
            sim = sim_cpu_from(out, stdout) if is_run else 0.0
            print("%-16s %-26s %9.1f %9.1f %9.1f %8.0f%%" % (name, label, 1e3 * wall, 1e3 * cpu,
                                                           1e3 * sim, 100 * (cpu - sim) / cpu))
            sys.stdout.flush()

    # cost per row: the one-phase mission on finer grids (100 s of flight)
    print()
    print("# per output row: one-phase mission, `run --no-plots` (all of today's files) ")
    print("# us/row = (CPU - CPU at 101 rows) / (rows - 101); sim/row likewise from the phases' CPU")
    print("%-26s %8s %9s %9s %9s %9s %8s %10s" % ("command", "rows", "wall ms", "CPU ms", "sim ms",
                                               "us/row", "sim/row", "MB files"))
    base = open(missions[0][1]).read()
    grids = [1.0, 0.1, 0.01] + ([] if a.quick else [0.001])
    variants = [("run --no-plots", ["--no-plots"])]
    if has_outputs:
        variants += [("run --outputs mat,csv", ["--outputs", "mat,csv"]),
                     ("run --outputs none", ["--outputs", "none"])]
    for label, extra in variants:
        ref = None
        for dt in grids:
            mpath = os.path.join(tmp, "grid_%g.yaml" % dt)
            with open(mpath, "w") as f:
                f.write(base.replace("output_interval: 1.0", "output_interval: %r" % dt))
            out = os.path.join(tmp, "grid_out")
            timer = slow if dt < 0.01 else fast
            wall, cpu, stdout = timer.measure([lvsim, "run", mpath, "-o", out] + extra,
                                              before=lambda: shutil.rmtree(out, ignore_errors=True))
            sim = sim_cpu_from(out, stdout)
            n = int(round(100.0 / dt)) + 1
            mb = dir_bytes(out) / 1e6 if os.path.isdir(out) else 0.0
            if ref is None:
                ref = (n, cpu, sim)
                per, sper = float("nan"), float("nan")
            else:
                per = 1e6 * (cpu - ref[1]) / (n - ref[0])
                sper = 1e6 * (sim - ref[2]) / (n - ref[0])
            print("%-26s %8d %9.1f %9.1f %9.1f %9.2f %8.2f %10.2f" % (label, n, 1e3 * wall, 1e3 * cpu,
                                                                1e3 * sim, per, sper, mb))
            sys.stdout.flush()
    shutil.rmtree(tmp, ignore_errors=True)
    print("# issue 11 targets: check a few ms; <= 1 us CPU per row per 50 columns for CSV + MAT;")
    print("# plots <= 0.2 s; OpenTsiolkovsky's sample mission 50-70 ms whole process (issue's figure)")


if __name__ == "__main__":
    main()
