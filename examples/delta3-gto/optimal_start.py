#!/usr/bin/python3
"""Sample alpha_in, mu_in of a run of the targeted Delta III (bilinear tangent) into one start
table per phase: time [s], alpha [rad], mu [rad]. Usage: optimal_start.py RUN_DIR OUT_DIR [DT]"""
import sys, os
import numpy as np
run, outd = sys.argv[1], sys.argv[2]
dt = float(sys.argv[3]) if len(sys.argv) > 3 else 2.0
phases = [(1, 'six-srb'), (2, 'three-srb'), (3, 'core-alone'), (4, 'second-stage')]
for k, n in phases:
    f = os.path.join(run, 'phase_%d_%s.csv' % (k, n))
    hdr = open(f).readline().strip().split(',')
    col = {h.split(' ')[0]: i for i, h in enumerate(hdr)}
    d = np.genfromtxt(f, delimiter=',', skip_header=1)
    t, a, mu = d[:, col['time']], d[:, col['alpha_in']], d[:, col['mu_in']]
    if k == 1:          # at rest (t = 0) alpha is 0: the first moving row's instead
        a[0], mu[0] = a[1], mu[1]
    # the later of two rows at one time (an event), then rows every dt and the last
    keep = np.r_[np.diff(t) > 0, True]
    t, a, mu = t[keep], a[keep], mu[keep]
    tt = np.r_[np.arange(t[0], t[-1], dt), t[-1]]
    if tt[-1] - tt[-2] < 0.5 * dt:
        tt = np.delete(tt, -2)
    tt[0] = np.floor(t[0] * 1e3) / 1e3                  # a little before the phase's start
    tt[-1] = (np.floor(t[-1]) + 1.0) if k < 4 else 1000.0   # and beyond its end: held
    with open(os.path.join(outd, 'optimal_start_%s.csv' % n), 'w') as o:
        o.write('time [s],alpha [rad],mu [rad]\n')
        for ti in tt:
            o.write('%.6f,%.9f,%.9f\n' % (ti, np.interp(ti, t, a), np.interp(ti, t, mu)))
    print(n, len(tt), 'rows', tt[0], tt[-1])
