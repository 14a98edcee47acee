#!/usr/bin/env python3
"""instr_flight.py [BENCH_FLIGHT] [METHOD] - where the instructions of one bench_flight flight go
(issue 24), counted by callgrind (instruction counts are exact and repeatable; wall and CPU
times on a shared machine are not; perf_event_open's instruction counter is not available in
this project's containers).

Two runs of build/bench/bench_flight METHOD 1 1 {norows|rows} under callgrind:
  1. integration only (no sink), collected inside lv_sim_advance: the model's right-hand side
     (dof3_rhs, inclusive: its own instructions) against everything else the integrator does
     per step (stages, error estimate, step control, dense output, event functions, lv_sim's
     loop). Issue 24's goal: instructions per step <= 2 x the right-hand side's own
     (ratio = integration / rhs <= 2).
  2. the whole flight as bench_flight times it (collected inside fly(): create, simulate with
     rows into memory, free), split into the right-hand side on the steps, the output rows
     (emit_row: the row's derivatives and outputs, the sink), the event functions, the dense
     output and the rest.
"""
import os
import re
import subprocess
import sys
import tempfile

here = os.path.dirname(os.path.abspath(__file__))
bench = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "build", "bench",
                                                           "bench_flight")
method = sys.argv[2] if len(sys.argv) > 2 else "auto"


def profile(mode, collect):
    """Runs one flight under callgrind; returns ({function: inclusive Ir}, total, steps, rhs)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cg.out")
        run = subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out,
                              "--toggle-collect=" + collect, bench, method, "1", "1", mode],
                             capture_output=True, text=True, check=True)
        row = [l for l in run.stdout.splitlines() if l.startswith(method + " ")][-1].split()
        steps, rhs = int(row[5]), int(row[6])
        ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out],
                             capture_output=True, text=True, check=True).stdout
    incl, total = {}, None
    for line in ann.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\(\s*[\d.]+%\)\s+(\S+)", line)
        if not m:
            continue
        ir, where = int(m.group(1).replace(",", "")), m.group(2)
        if where == "PROGRAM":
            total = ir
            continue
        fn = where.split(":")[-1]
        incl[fn] = max(incl.get(fn, 0), ir)  # a function listed under two file names
    return incl, total, steps, rhs


incl, total, steps, rhs = profile("norows", "lv_sim_advance")
rhs_ir = incl.get("dof3_rhs", 0)
print(f"# bench_flight {method}: one flight, integration only (no sink), callgrind instructions")
print(f"steps {steps}, rhs evaluations {rhs} ({rhs / steps:.1f} per step)")
print(f"rhs, per evaluation           {rhs_ir / rhs:10.0f}")
print(f"integration, per step         {total / steps:10.0f}")
print(f"  of which the rhs            {rhs_ir / steps:10.0f}")
print(f"  step overhead (the rest)    {(total - rhs_ir) / steps:10.0f}")
for fn in ("sim_g", "dense_eval", "sim_rhs"):
    if fn in incl:
        print(f"    {fn:<26}{incl[fn] / steps:10.0f}   (inclusive)")
print(f"ratio integration / rhs       {total / rhs_ir:10.2f}   (issue 24: <= 2)")

incl, total, steps, rhs = profile("rows", "fly")
print(f"# the whole flight with rows into memory (inside fly()): {total / 1e6:.2f} M instructions")
parts = [("rhs on the steps", incl.get("lv_integ_advance", 0) - incl.get("sim_g", 0) -
          incl.get("dense_eval", 0)),
         ("output rows (emit_row)", incl.get("emit_row", 0)),
         ("event functions (sim_g)", incl.get("sim_g", 0)),
         ("dense output (dense_eval)", incl.get("dense_eval", 0))]
rest = total - sum(v for _, v in parts)
for name, v in parts + [("set-up, finish, free, rest", rest)]:
    print(f"  {name:<28}{v / 1e3:10.0f} k  {100.0 * v / total:5.1f} %")
