"""Runs rodnet ($RODNET, default target/release/rodnet) on generated cantilever scenes, one process
at a time, and collects the tip displacements; scenes and results go to $RUNS (default
/tmp/rodnet-accuracy)."""
import json, subprocess, os, sys, math
BIN = os.environ.get('RODNET', os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'target', 'release', 'rodnet'))
E, R, L = 1e8, 0.01, 1.0
EI = E * math.pi * R**4 / 4
EA = E * math.pi * R**2
HERE = os.path.dirname(os.path.abspath(__file__))
RUNS = os.environ.get('RUNS', '/tmp/rodnet-accuracy')

def scene(N, lam=0.0, lam_q=0.0, tol=1e-12):
    P = lam * EI / L**2
    loads = []
    dens = 0.0
    if lam:
        loads.append('Force(rod: "beam", vertex: 1, force: (0.0, %r, 0.0))' % (-P))
    if lam_q:
        q = lam_q * EI / L**3            # q L^3 / EI = lam_q, q = rho g A with g = 1
        dens = q / (math.pi * R**2)
        loads.append('Gravity(g: (0.0, -1.0, 0.0))')
    return f'''Scene(
    materials: {{ "steel": Material(young_modulus: {E!r}, poisson_ratio: 0.5, density: {dens!r}, section: Circle(radius: {R!r})) }},
    rods: [ Rod(name: "beam", material: "steel", points: [(0.0, 0.0, 0.0), ({L!r}, 0.0, 0.0)], subdivide: {N}) ],
    supports: [ Support(rod: "beam", vertex: 0, kind: Clamp) ],
    loads: [ {", ".join(loads)} ],
    solver: Solver(tolerance: {tol!r}, max_iterations: 500, load_steps: 1),
)
'''

def run(N, lam=0.0, lam_q=0.0, tol=1e-12):
    os.makedirs(RUNS, exist_ok=True)
    tag = f'N{N}_P{lam}_Q{lam_q}'
    sp = os.path.join(RUNS, tag + '.ron'); jp = os.path.join(RUNS, tag + '.json')
    open(sp, 'w').write(scene(N, lam, lam_q, tol))
    p = subprocess.run([BIN, 'solve', sp, '--json', jp, '--quiet'], capture_output=True, text=True)
    d = json.load(open(jp))
    pts = d['rods'][0]['points']
    return dict(points=pts, converged=d['converged'], residual=d['residual'], rc=p.returncode,
                stderr=p.stderr.strip(), tip=pts[-1])

if __name__ == '__main__':
    r = run(int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]) if len(sys.argv) > 3 else 0.0)
    print(r['tip'], r['converged'], r['residual'], r['rc'], r['stderr'])
