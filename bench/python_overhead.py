#!/usr/bin/python3
"""bench/python_overhead.py - what the Python package (python/lvsim) adds to a run: the same
mission run by `lvsim run --no-plots` as a whole process, and from Python: import, load, execute
(rows kept in memory, no file; with the phase files; without rows), reading every phase's rows
and the bodies into NumPy, and the wrapper's own cost per call (a re-execute that simulates
nothing; a parameter set). Fastest of N repetitions (CPU time where it says so: wall times
scatter on a busy machine). Prints figures; asserts nothing.

    PYTHONPATH=build/python bench/python_overhead.py [--lvsim build/lvsim] [--mission M] [--reps N]
"""
import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def best(fn, reps):
    """(fastest wall, fastest thread CPU) of reps calls of fn, in seconds."""
    walls, cpus = [], []
    for _ in range(reps):
        c0, w0 = time.process_time(), time.perf_counter()
        fn()
        walls.append(time.perf_counter() - w0)
        cpus.append(time.process_time() - c0)
    return min(walls), min(cpus)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lvsim", default=os.path.join(ROOT, "build", "lvsim"))
    ap.add_argument("--mission", default=os.path.join(ROOT, "examples", "rlv-hthl", "mission.yaml"))
    ap.add_argument("--reps", type=int, default=10)
    a = ap.parse_args()

    t0 = time.perf_counter()
    import lvsim  # noqa: E402 - timed
    t_import = time.perf_counter() - t0
    print(f"mission: {a.mission}")
    print(f"import lvsim (numpy, pandas, liblvsim): {t_import * 1e3:.0f} ms, once")

    with tempfile.TemporaryDirectory() as tmp:
        def cli():
            r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
            subprocess.run([a.lvsim, "run", a.mission, "-o", os.path.join(tmp, "cli"),
                            "--no-plots", "--quiet"], check=True, capture_output=True)
            r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
            return (r1.ru_utime + r1.ru_stime) - (r0.ru_utime + r0.ru_stime)
        cpu = []
        walls = []
        for _ in range(a.reps):
            w0 = time.perf_counter()
            cpu.append(cli())
            walls.append(time.perf_counter() - w0)
        print(f"lvsim run --no-plots (whole process: all files, exports): wall {min(walls) * 1e3:.1f} ms, "
              f"CPU {min(cpu) * 1e3:.1f} ms")

        w, c = best(lambda: lvsim.Mission(a.mission).close(), a.reps)
        print(f"Mission(path) + close:                            wall {w * 1e3:.2f} ms, CPU {c * 1e3:.2f} ms")
        m = lvsim.Mission(a.mission)

        def run_mem():
            m.run().close()
        w, c = best(run_mem, a.reps)
        print(f"mission.run(): every phase, rows in memory:       wall {w * 1e3:.2f} ms, CPU {c * 1e3:.2f} ms")

        def run_files():
            m.run(outdir=os.path.join(tmp, "py")).close()
        w, c = best(run_files, a.reps)
        print(f"mission.run(outdir=...): + phase .mat/.csv files: wall {w * 1e3:.2f} ms, CPU {c * 1e3:.2f} ms")

        def run_norows():
            m.run(keep_rows=False).close()
        w, c = best(run_norows, a.reps)
        print(f"mission.run(keep_rows=False): finals only:        wall {w * 1e3:.2f} ms, CPU {c * 1e3:.2f} ms")

        r = m.run()
        n_values = sum(r.result(p.index).values.size for p in m.phases)

        def read_all():
            for p in m.phases:
                r.result(p.index)
            r.bodies()
        w, c = best(read_all, a.reps)
        print(f"every phase's PhaseResult + every body ({n_values} phase values): wall {w * 1e3:.2f} ms, "
              f"CPU {c * 1e3:.2f} ms")
        sim_cpu = sum(r.result(p.index).stats["cpu_time"] for p in m.phases)
        print(f"the phases' own simulation CPU (lv_sim_stats.cpu_time, summed): {sim_cpu * 1e3:.2f} ms")

        n = 2000
        w0 = time.perf_counter()
        for _ in range(n):
            r.execute()  # nothing dirty: the wrapper and lv_run_execute's bookkeeping only
        per = (time.perf_counter() - w0) / n
        print(f"run.execute() with nothing to simulate: {per * 1e6:.1f} us a call")
        w0 = time.perf_counter()
        for i in range(n):
            r.set("us.propellant_mass", 55000.0)
        per = (time.perf_counter() - w0) / n
        print(f"run.set(name, value): {per * 1e6:.1f} us a call")
        r.close()
        m.close()


if __name__ == "__main__":
    sys.exit(main())
