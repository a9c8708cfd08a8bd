"""Check the Python model (DER settings) against rodnet's tip positions, node by node."""
import sys, os, json
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import numpy as np, drod, run_rodnet as rr
KAPPA = sys.argv[1] if len(sys.argv) > 1 else 'sin'
worst = 0
for mode in ['tip', 'udl']:
    for lam in [0.01, 1, 2, 5]:
        for N in [10, 20, 40, 80, 160, 320]:
            r = rr.run(N, lam if mode == 'tip' else 0.0, lam if mode == 'udl' else 0.0)
            P = lam * rr.EI if mode == 'tip' else 0.0; q = lam * rr.EI if mode == 'udl' else 0.0
            m = drod.solve(N, P=P, q=q, EI=rr.EI, EA=rr.EA, kappa=KAPPA)
            pr = np.array(r['points'])[:, :2]
            dv = abs(m['v'] - (-pr[-1, 1])) / m['v']; du = abs(m['u'] - (1 - pr[-1, 0])) / m['u']
            dn = np.max(np.abs(m['points'] - pr)) / m['v']
            worst = max(worst, dv)
            print(f'{mode} lam={lam:5} N={N:4}  rel diff tip v {dv:.1e}  u {du:.1e}  max node diff/v {dn:.1e}')
print('worst rel diff in v:', worst)
