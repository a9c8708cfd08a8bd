"""Probe rodnet's discrete moment-curvature law from its equilibrium: at vertex i the moment of the
tip load, M_i = P (x_N - x_i), against the turning angle phi_i (clamp vertex: angle to +x)."""
import sys, os
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np, run_rodnet as rr
N, lam = 10, 5.0
r = rr.run(N, lam)
p = np.array(r['points'])[:, :2]
e = np.diff(p, axis=0); th = np.arctan2(e[:, 1], e[:, 0]); l = np.linalg.norm(e, axis=1)
P = lam * rr.EI; h = 1.0 / N
phis = np.diff(np.concatenate([[0.0], th]))
for i in range(N):
    M = P * (p[N, 0] - p[i, 0])
    w = h / 2 if i == 0 else h
    phi = phis[i]
    t = np.tan(phi / 2)
    print(f'i={i} phi={phi:+.6f}  M w/EI={-M*w/rr.EI:+.9f}  tan:kk\'={2*t*(1+t*t):+.9f}  sin:{2*np.sin(phi/2)*np.cos(phi/2):+.9f}  phi:{phi:+.9f}  l/h-1={l[i]/h-1:.3e}')
