"""Linear limit (lambda = 1e-4): errors of the clamp-end weight corrections (sin measure, as rodnet)."""
import sys, os, math
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np, drod, elastica
E, R = 1e8, 0.01; EI = E * math.pi * R**4 / 4; EA = E * math.pi * R**2
lam = 1e-4
for mode in ['tip', 'udl']:
    P = lam * EI if mode == 'tip' else 0.0; q = lam * EI if mode == 'udl' else 0.0
    ref = elastica.solve(P=P, q=q, EI=EI, EA=EA)
    for wts in ['voronoi', 'gregory0', 'aes0']:
        errs = [(drod.solve(N, P=P, q=q, EI=EI, EA=EA, kappa='sin', weights=wts)['v'] - ref['v']) / ref['v'] for N in [10, 20, 40, 80]]
        print(mode, f'{wts:9s}', ' '.join(f'{e:+.3e}' for e in errs), ' e*N^2 at 80: %+.2e  e*N^3 at 80: %+.3f' % (errs[-1] * 6400, errs[-1] * 80**3))
