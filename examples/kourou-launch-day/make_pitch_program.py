#!/usr/bin/env python3
"""make_pitch_program.py OUT_DIR - pitch_program.csv from ../kourou-leo's still-air ascent.

The launch-day ascent flies the attitude history that kourou-leo's gravity turn flies in still
air (its `theta` output: the body x above the local horizon), sampled every 2 s to its MECO,
as an open-loop pitch program: through the day's winds and turbulence the vehicle then keeps
its design attitude and the wind shows as angle of attack (alpha_in) and q alpha, the way a
launch team checks a day's winds against a pre-designed program. OUT_DIR: the results of
`lvsim run examples/kourou-leo/mission.yaml -o OUT_DIR`.
"""
import csv
import math
import sys


def main():
    rows = list(csv.reader(open(sys.argv[1] + "/phase_1_ascent.csv")))
    names = [c.split(" ")[0] for c in rows[0]]
    it, ith = names.index("time"), names.index("theta")
    data = [(float(r[it]), float(r[ith])) for r in rows[1:]]
    t_end = data[-1][0]
    out = ["# examples/kourou-launch-day: pitch program (body x above the local horizon, heading",
           "# 90 deg) over mission time, sampled every 2 s from ../kourou-leo's still-air gravity",
           "# turn (make_pitch_program.py); the last row holds the MECO attitude.",
           "time [s], pitch [rad]"]
    t = 0.0
    while t < t_end:
        th = next(v for (tt, v) in data if tt >= t - 1e-9)
        out.append("%g, %.6f" % (t, th))
        t += 2.0
    out.append("%g, %.6f" % (math.ceil(t_end) + 100.0, data[-1][1]))
    open("pitch_program.csv", "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
