"""Independent reference: planar extensible (shear-rigid) elastica cantilever, clamped at s=0.
Rest arc length s in [0, L]; theta' = M/EI (per rest length); x' = (1+N/EA) cos th, y' = (1+N/EA) sin th.
Loads: tip dead load (0,-P) and/or uniform dead load (0,-q) per rest length.
Shooting on theta'(0) so that M(L) = 0, DOP853 rtol=atol=1e-13."""
import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

def rhs_factory(P, q, EI, EA, L):
    def rhs(s, z):
        th, k, x, y = z
        Fy = -(P + q * (L - s))          # internal force transmitted from outboard part: (0, Fy)
        N = Fy * np.sin(th)               # axial (tension +) = F . t
        eps = N / EA if EA is not None else 0.0
        c = (1 + eps) * np.cos(th)
        # EI th'' = dM/ds, M(s) = sum over outboard loads of (x_load - x(s)) * Fy_load
        # => dM/ds = -x'(s) * (total outboard Fy) = -(1+eps) cos th * Fy
        return [k, -c * Fy / EI, c, (1 + eps) * np.sin(th)]
    return rhs

def solve(P=0.0, q=0.0, EI=1.0, EA=None, L=1.0, tol=1e-13):
    rhs = rhs_factory(P, q, EI, EA, L)
    def shoot(k0):
        sol = solve_ivp(rhs, (0, L), [0.0, k0, 0.0, 0.0], method='DOP853', rtol=tol, atol=tol)
        return sol.y[:, -1]
    # linear guess for M(0)/EI = -(P L + q L^2/2)/EI ; bracket
    k_lin = -(P * L + q * L * L / 2) / EI
    f = lambda k: shoot(k)[1]
    a, b = 1.2 * k_lin - 1e-300, 0.0
    # M(0) magnitude is <= linear value (x_L <= L) ... bracket in [1.2 k_lin, 0]
    k0 = brentq(f, a, b, xtol=1e-15, rtol=1e-15, maxiter=500)
    th, k, x, y = shoot(k0)
    return dict(x=x, y=y, th=th, k0=k0, u=L - x, v=-y)

if __name__ == '__main__':
    # inextensible check vs Bisshopp-Drucker PL^2/EI=2: v/L=0.49345748, u/L=0.16064172
    r = solve(P=2.0, EI=1.0, EA=None)
    print('inextensible PL2/EI=2: v=%.10f u=%.10f  (ref 0.49345748, 0.16064172; tests: x=0.839358279174832744, v=0.493457480396711334)' % (r['v'], r['u']))
    for EA in [1e4, 1e6, 1e8, 1e10]:
        r = solve(P=2.0, EI=1.0, EA=EA)
        print('EA/EI=%g: v=%.12f u=%.12f' % (EA, r['v'], r['u']))
    # linear check: v = PL^3/3EI, uniform: qL^4/8EI
    r = solve(P=1e-6, EI=1.0); print('linear tip: v/(PL^3/3EI)=%.12f' % (r['v'] / (1e-6 / 3)))
    r = solve(q=1e-6, EI=1.0); print('linear udl: v/(qL^4/8EI)=%.12f' % (r['v'] / (1e-6 / 8)))
