#!/usr/bin/python3
"""Start tables for optimal.yaml: pitch and heading [rad] over mission time, every DT s
(default 5; the shipped tables: 2), of the targeted bilinear tangent laws (lvsim target
mission.yaml -o opt.yaml), in the same inertial frame (frozen at each phase's start):
tan(pitch) = (a + b tau) / (c + d tau), tau = t - t_start (docs/guidance.md).
Usage: optimal_start.py OPT.yaml OUT_DIR [DT]"""
import math, re, sys, os
src, outd = sys.argv[1], sys.argv[2]
dt = float(sys.argv[3]) if len(sys.argv) > 3 else 5.0
# each phase's start and the end of the table (beyond the phase's end: held)
spans = {'six-srb': (0.0, 76.0), 'three-srb': (75.2, 151.0), 'core-alone': (150.4, 262.0),
         'second-stage': (261.0, 1000.0)}
text = open(src).read()
for name, (t0, t1) in spans.items():
    blk = text[text.index('- name: %s\n' % name):]
    g = re.search(r'guidance: \{law: bilinear_tangent, (.*?)\}', blk).group(1)
    k = {kv.split(':')[0].strip(): float(kv.split(':')[1]) for kv in g.split(',')}
    n = int(math.ceil((t1 - t0) / dt))
    with open(os.path.join(outd, 'optimal_start_%s.csv' % name), 'w') as o:
        o.write('time [s],pitch [rad],heading [rad]\n')
        for i in range(n + 1):
            t = min(t0 + i * dt, t1)
            tau = t - t0
            th = math.atan2(k['a'] + k['b'] * tau, k['c'] + k['d'] * tau)
            o.write('%.6f,%.12f,%.12f\n' % (t, th, math.radians(k['heading_deg'])))
