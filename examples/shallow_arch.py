#!/usr/bin/env python3
"""Shallow-arch Galerkin model of a clamped-clamped cosine arch: an independent check of the
closed forms in tests/support/shallow_arch.rs and of `rodnet states` / `rodnet indent` on
networks/bistable_arch.ron (docs/stability.md, "A bistable shallow arch").

    w0(x) = (h/2)(1 - cos 2 pi x / L)          rest shape (stress-free)
    E(w)  = EI/2 int (w'' - w0'')^2 + EA/(8L) (int w'^2 - w0'^2)^2

(Euler-Bernoulli bending, the axial strain uniform along the span because the clamps hold the
span.) w is expanded in M clamped-clamped buckling modes, the integrals are taken by Gauss
quadrature (nothing assumes the modes orthogonal), and every stationary point is found by Newton
from many random starts. Needs only NumPy:  python3 examples/shallow_arch.py [Q ...]
"""

import sys

import numpy as np

L, B, T, E = 1.0, 0.01, 0.002, 1e9  # span, width, thickness (in the arch's plane), Young's modulus
EI, EA = E * B * T**3 / 12.0, E * B * T
QUAD = np.polynomial.legendre.leggauss(600)


def antisymmetric_roots(m):
    """N with tan(N/2) = N/2: z = N/2 in (k pi, k pi + pi/2), by bisection on
    sin z - z cos z (continuous, unlike tan z - z)."""
    out = []
    for k in range(1, m + 1):
        lo, hi = k * np.pi + 1e-9, (k + 0.5) * np.pi
        f = lambda z: np.sin(z) - z * np.cos(z)
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if f(mid) * f(lo) > 0.0 else (lo, mid)
        out.append(lo + hi)
    return out


def modes(m):
    """The first m symmetric and m antisymmetric buckling modes: (phi', phi'', phi(L/2)) on
    the quadrature points, and the symmetric flag."""
    xg, wg = QUAD
    x = 0.5 * L * (xg + 1.0)
    w = 0.5 * L * wg
    d1, d2, mid, sym = [], [], [], []
    for k in range(1, m + 1):
        n = 2.0 * np.pi * k
        d1.append(n / L * np.sin(n * x / L))
        d2.append((n / L) ** 2 * np.cos(n * x / L))
        mid.append(1.0 - np.cos(n / 2.0))
        sym.append(True)
    for n in antisymmetric_roots(m):
        # 1 - 2x/L - cos(N x/L) + 2 sin(N x/L)/N
        d1.append(-2.0 / L + n / L * np.sin(n * x / L) + 2.0 / L * np.cos(n * x / L))
        d2.append((n / L) ** 2 * np.cos(n * x / L) - 2.0 * n / L**2 * np.sin(n * x / L))
        mid.append(1.0 - 1.0 - np.cos(n / 2.0) + 2.0 * np.sin(n / 2.0) / n)
        sym.append(False)
    d1, d2 = np.array(d1), np.array(d2)
    G = (d1 * w) @ d1.T  # int phi_i' phi_j'
    Bm = (d2 * w) @ d2.T  # int phi_i'' phi_j''
    return G, Bm, np.array(mid), np.array(sym)


class Arch:
    def __init__(self, q, m=8):
        self.h = q * T
        self.G, self.B, self.mid, self.sym = modes(m)
        self.a0 = np.zeros(2 * m)
        self.a0[0] = self.h / 2.0

    def stretch(self, a):
        return a @ self.G @ a - self.a0 @ self.G @ self.a0

    def energy(self, a):
        da = a - self.a0
        return 0.5 * EI * da @ self.B @ da + EA / (8.0 * L) * self.stretch(a) ** 2

    def gradient(self, a):
        return EI * self.B @ (a - self.a0) + EA / (2.0 * L) * self.stretch(a) * (self.G @ a)

    def hessian(self, a):
        ga = self.G @ a
        return EI * self.B + EA / (2.0 * L) * (self.stretch(a) * self.G + 2.0 * np.outer(ga, ga))

    def axial_force(self, a):
        """Compression P = -EA eps, N."""
        return -EA * self.stretch(a) / (2.0 * L)

    def newton(self, a, tol=1e-13):
        for _ in range(200):
            g = self.gradient(a)
            if np.linalg.norm(g) < tol * np.linalg.norm(EI * self.B @ self.a0):
                return a
            a = a - np.linalg.solve(self.hessian(a), g)
            if not np.all(np.isfinite(a)) or np.abs(a).max() > 50 * self.h:
                return None
        return None

    def stationary_points(self, starts=3000, seed=1):
        rng = np.random.default_rng(seed)
        found = []
        n = len(self.a0)
        # Random starts miss the nearly flat, much compressed state at larger Q: it is also
        # started from its mode-1 amplitude (any a in (0, 1/2) lies in its basin).
        flat = np.zeros(n)
        flat[0] = -0.01 * self.h
        for s in range(starts + 1):
            scale = self.h * rng.uniform(0.05, 1.5) / (1.0 + np.arange(n) % (n // 2))
            a = self.newton(flat if s == starts else rng.normal(size=n) * scale)
            if a is None:
                continue
            if any(np.abs(a - b).max() < 1e-9 * self.h for b in found):
                continue
            found.append(a)
        out = []
        for a in found:
            ev = np.linalg.eigvalsh(self.hessian(a))
            out.append((self.energy(a), int((ev < 0).sum()), a))
        return sorted(out, key=lambda t: t[0])

    def shape(self, a, x):
        """w(x) from the coefficients (for telling symmetric from S-shaped states)."""
        m = len(a) // 2
        w = np.zeros_like(x)
        for k in range(m):
            w += a[k] * (1.0 - np.cos(2.0 * np.pi * (k + 1) * x / L))
        for k, n in enumerate(antisymmetric_roots(m)):
            w += a[m + k] * (1.0 - 2.0 * x / L - np.cos(n * x / L) + 2.0 * np.sin(n * x / L) / n)
        return w

    def held_centre_lowest(self, a):
        """Lowest eigenvalue of the Hessian on the motions that keep w(L/2): the stability of a
        displacement-controlled push at the centre."""
        c = self.mid / np.linalg.norm(self.mid)
        z = np.linalg.svd(np.eye(len(c)) - np.outer(c, c))[0][:, : len(c) - 1]
        return np.linalg.eigvalsh(z.T @ self.hessian(a) @ z)[0]

    def symmetric_push(self, depth):
        """The symmetric equilibrium with the centre pushed down by `depth` (antisymmetric
        coefficients zero): Newton on the equilibrium with a Lagrange multiplier (the force)."""
        s = self.sym
        a = self.a0.copy()
        target = self.mid @ self.a0 - depth
        f = 0.0
        for _ in range(100):
            g = self.gradient(a)[s] - f * self.mid[s]
            c = self.mid[s] @ a[s] - target
            k = np.block(
                [[self.hessian(a)[np.ix_(s, s)], -self.mid[s][:, None]], [self.mid[s][None, :], np.zeros((1, 1))]]
            )
            step = np.linalg.solve(k, -np.concatenate([g, [c]]))
            a[s] += step[:-1]
            f += step[-1]
            if np.abs(step[:-1]).max() < 1e-15 * self.h:
                break
        return a, -f  # the indenter's force, positive down


def main():
    qs = [float(v) for v in sys.argv[1:]] or [5.4, 5.9, 8.0]
    xs = np.linspace(0.0, L, 201)
    for q in qs:
        arch = Arch(q)
        print(f"Q = h/t = {q}: h = {arch.h:.4e} m, EI = {EI:.6e}, EA = {EA:.6e}")
        for e, index, a in arch.stationary_points():
            w = arch.shape(a, xs)
            asym = np.abs(w - w[::-1]).max() / arch.h
            print(
                f"  energy {e:.9e} J  index {index}  crown {w[100]:+.6e} m  "
                f"P {arch.axial_force(a):.6e} N  asymmetry {asym:.3e}"
            )
        # The centre push: depth where the held Hessian's lowest eigenvalue first crosses zero
        # (sampled from the rest state on, then bisected). A point force needs many modes: the
        # depth converges as 1/m^3 (m = 8: 1.0104e-3 m, 32: 1.02071e-3, 64: 1.020858e-3 at Q = 8).
        arch = Arch(q, m=64)
        lam = lambda d: arch.held_centre_lowest(arch.symmetric_push(d)[0])
        grid = np.linspace(0.0, arch.h, 201)
        first = next((k for k, d in enumerate(grid) if lam(d) < 0.0), None)
        if first is not None:
            lo, hi = grid[first - 1], grid[first]
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if lam(mid) > 0.0 else (lo, mid)
            a, f = arch.symmetric_push(lo)
            print(
                f"  centre push: the symmetric path loses stability (held centre) at depth "
                f"{lo:.9e} m, force {f:.9e} N, P {arch.axial_force(a):.9e} N"
            )
        ds = np.linspace(0.0, 2.0 * arch.h, 400)
        fs = [arch.symmetric_push(d)[1] for d in ds]
        k = int(np.argmax(fs))
        print(f"  centre push: symmetric path's largest force {fs[k]:.6e} N at depth {ds[k]:.6e} m")


if __name__ == "__main__":
    main()
