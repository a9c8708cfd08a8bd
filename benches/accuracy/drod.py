"""Independent planar discrete-rod model (step 4).
Unknowns: edge angles th_e and edge lengths l_e (e = 0..N-1); node 0 fixed at the origin, the clamp's
direction is +x.  Node positions x_j = sum_{e<j} l_e (cos th_e, sin th_e).
Energy:
  stretch  sum_e EA (l_e/h - 1)^2 h / 2
  bending  sum_v EI kappa(phi_v)^2 / (2 w_v),  phi_v = th_b - th_a  (turning angle at vertex v)
  loads    -sum_j F_j . x_j  (dead nodal forces; self weight lumped: half of each adjacent edge's weight)
Options:
  kappa  : 'tan' 2tan(phi/2) (DER paper), 'sin' 2sin(phi/2) (what rodnet implements), 'phi' phi,
           'sin4' 4 sin(phi/4) (nodes exactly on the circle under a pure moment)
  clamp  : 'half'  vertex 0 between the clamp direction and edge 0, weight w_0 (default h/2)   [rodnet]
           'edge'  first edge clamped (nodes 0 and 1 fixed: th_0 = 0, l_0 = h), vertices 1..N-1
           'ghost' ghost edge before node 0 (vertex 0 with a full weight h)
  weights: 'voronoi' (h/2 at the clamp, h inside), 'gregory' (5/12, 13/12 at both ends),
           'aes' (alternative extended Simpson 17/48, 59/48, 43/48, 49/48 at both ends),
           'gregory0'/'aes0' (clamp end only), 'gregoryL'/'aesL' (free end only)
  The free end (vertex N) carries no bending energy (M = 0 there); end weights at the free end are
  those of the quadrature nodes N-1, N-2, ... (node N has weight w_N, multiplying M(L) = 0).
"""
import numpy as np

GREG = [5 / 12, 13 / 12]
AES = [17 / 48, 59 / 48, 43 / 48, 49 / 48]

def kfun(kind):
    if kind == 'tan':
        def f(p):
            t = np.tan(p / 2); k = 2 * t; k1 = 1 + t * t; k2 = t * (1 + t * t)
            return k, k1, k2
    elif kind == 'sin':
        def f(p):
            return 2 * np.sin(p / 2), np.cos(p / 2), -0.5 * np.sin(p / 2)
    elif kind == 'sin4':
        def f(p):
            return 4 * np.sin(p / 4), np.cos(p / 4), -0.25 * np.sin(p / 4)
    elif kind.startswith('sinA:'):      # a sin(phi/a): kappa kappa' = phi (1 - 2 phi^2 / (3 a^2) + ...)
        a = float(kind[5:])
        def f(p):
            return a * np.sin(p / a), np.cos(p / a), -np.sin(p / a) / a
    elif kind == 'phi':
        def f(p):
            return p, np.ones_like(p), np.zeros_like(p)
    else:
        raise ValueError(kind)
    return f

def vertex_weights(N, h, weights):
    """Weights of the quadrature nodes 0..N (node i at x = i h); node N unused (M(L) = 0)."""
    w = np.full(N + 1, h); w[0] = h / 2; w[N] = h / 2
    ends = {'gregory': (GREG, GREG), 'aes': (AES, AES), 'gregory0': (GREG, None), 'aes0': (AES, None),
            'gregoryL': (None, GREG), 'aesL': (None, AES), 'voronoi': (None, None)}[weights]
    if ends[0]:
        for k, c in enumerate(ends[0]): w[k] = c * h
    if ends[1]:
        for k, c in enumerate(ends[1]): w[N - k] = c * h
    return w

def solve(N, P=0.0, q=0.0, EI=1.0, EA=4e4, L=1.0, kappa='tan', clamp='half', weights='voronoi',
          steps=None, tol=1e-14, wvec=None):
    h = L / N
    kf = kfun(kappa)
    w = vertex_weights(N, h, weights) if wvec is None else np.asarray(wvec, float)
    # bending vertices: (a, b, weight), a = -1 means the clamp direction (th = 0)
    if clamp == 'half':
        verts = [(-1, 0, w[0])] + [(i - 1, i, w[i]) for i in range(1, N)]
    elif clamp == 'ghost':
        verts = [(-1, 0, h)] + [(i - 1, i, w[i]) for i in range(1, N)]
    elif clamp == 'edge':
        verts = [(i - 1, i, w[i]) for i in range(1, N)]
    else:
        raise ValueError(clamp)
    A = np.array([v[0] for v in verts]); B = np.array([v[1] for v in verts]); W = np.array([v[2] for v in verts])
    # outboard force on each edge: sum of nodal forces at nodes j > e (all along -y)
    Fn = np.zeros(N + 1)          # y-force at nodes
    Fn[N] -= P
    Fn[1:] -= q * h               # lumped weight, half edge each side
    Fn[N] += q * h / 2
    Fout = np.cumsum(Fn[::-1])[::-1][1:]   # Fout[e] = sum_{j >= e+1} Fn[j]
    fixed = np.zeros(2 * N, bool)
    if clamp == 'edge':
        fixed[0] = True; fixed[N] = True
    x = np.concatenate([np.zeros(N), np.full(N, h)])
    free = ~fixed

    def grad_hess(x, lam):
        th, l = x[:N], x[N:]
        g = np.zeros(2 * N); H = np.zeros((2 * N, 2 * N))
        # stretch
        g[N:] += EA * (l - h) / h
        H[np.arange(N, 2 * N), np.arange(N, 2 * N)] += EA / h
        # bending
        tha = np.where(A >= 0, th[np.maximum(A, 0)], 0.0)
        phi = th[B] - tha
        k, k1, k2 = kf(phi)
        d1 = EI * k * k1 / W; d2 = EI * (k1 * k1 + k * k2) / W
        np.add.at(g, B, d1); np.add.at(H, (B, B), d2)
        m = A >= 0
        np.add.at(g, A[m], -d1[m]); np.add.at(H, (A[m], A[m]), d2[m])
        np.add.at(H, (A[m], B[m]), -d2[m]); np.add.at(H, (B[m], A[m]), -d2[m])
        # loads: V = -sum_e l_e sin(th_e) Fy_e   (Fy along y)
        Fy = lam * Fout
        s, c = np.sin(th), np.cos(th)
        e = np.arange(N)
        g[e] += -l * c * Fy; g[N + e] += -s * Fy
        H[e, e] += l * s * Fy; H[e, N + e] += -c * Fy; H[N + e, e] += -c * Fy
        return g, H

    if steps is None:
        lin = (abs(P) * L * L + abs(q) * L ** 3 / 2) / EI
        steps = max(1, int(np.ceil(lin / 0.5)))
    for st in range(1, steps + 1):
        lam = st / steps
        for it in range(100):
            g, H = grad_hess(x, lam)
            gf = g[free]
            dx = np.linalg.solve(H[np.ix_(free, free)], -gf)
            x[free] += dx
            if np.max(np.abs(dx)) < tol:
                break
        else:
            raise RuntimeError('Newton did not converge')
    th, l = x[:N], x[N:]
    pts = np.vstack([np.zeros(2), np.cumsum(np.c_[l * np.cos(th), l * np.sin(th)], axis=0)])
    return dict(points=pts, v=-pts[-1, 1], u=L - pts[-1, 0], th=th, l=l)
