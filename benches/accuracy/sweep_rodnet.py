"""Step 2: rodnet's tip error constants C = (w_N - w_exact)/w_exact * N^2 (w = v deflection, u shortening)."""
import sys, json, os, math
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import elastica, run_rodnet as rr
Ns = [10, 20, 40, 80, 160, 320]
out = {}
for mode, lams in [('tip', [0.01, 1, 2, 5]), ('udl', [0.01, 1, 2, 5])]:
    for lam in lams:
        if mode == 'tip':
            ref = elastica.solve(P=lam * rr.EI, EI=rr.EI, EA=rr.EA)
        else:
            ref = elastica.solve(q=lam * rr.EI, EI=rr.EI, EA=rr.EA)
        rows = []
        for N in Ns:
            r = rr.run(N, lam if mode == 'tip' else 0.0, lam if mode == 'udl' else 0.0)
            x, y, _ = r['tip']
            v, u = -y, 1.0 - x
            Cv = (v - ref['v']) / ref['v'] * N**2
            Cu = (u - ref['u']) / ref['u'] * N**2
            rows.append(dict(N=N, v=v, u=u, Cv=Cv, Cu=Cu, conv=r['converged'], res=r['residual']))
        out[f'{mode}_{lam}'] = dict(ref=dict(v=ref['v'], u=ref['u']), rows=rows)
        print(f'== {mode} lambda={lam}: v_ref={ref["v"]:.12f} u_ref={ref["u"]:.12f}')
        prev = None
        for row in rows:
            order = '' if prev is None else '%.3f' % math.log2(abs(prev['v'] - ref['v']) / abs(row['v'] - ref['v']))
            print('  N=%4d  v=%.12f  Cv=%+.5f  Cu=%+.5f  order_v=%s  res=%.1e' % (row['N'], row['v'], row['Cv'], row['Cu'], order, row['res']))
            prev = row
json.dump(out, open(os.path.join(rr.RUNS, 'rodnet_constants.json'), 'w'), indent=1)
