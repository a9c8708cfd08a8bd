"""Reference solutions for the tip-loaded cantilever, computed independently of every code.

* elastica_tip(p): the inextensible elastica (Bisshopp & Drucker 1945) in closed form with
  elliptic integrals, x_tip / L and y_tip / L for a tip load p = P L^2 / EI normal to the rod.
* rod_tip(...): shooting on the planar rod equations in the rest arc length (scipy DOP853),
  inextensible, extensible (Kirchhoff) or extensible and shearable (PyElastica's Cosserat model,
  shear stiffness 27/28 G A and bending couple EI kappa / e^3).  Used to check the closed form
  and as the reference of each code's own rod theory in the thick PyElastica case.
"""
import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import ellipeinc, ellipe, ellipk, ellipkinc


def elastica_tip(p):
    """Tip of a clamped inextensible elastica of unit length under a unit-EI dead load p
    normal to the rest tangent: returns (x, y) with the load along -y."""
    alpha = np.sqrt(p)

    def parts(theta0):  # tip slope theta0 -> (alpha(theta0), m, phi1)
        m = (1.0 + np.sin(theta0)) / 2.0
        phi1 = np.arcsin(1.0 / np.sqrt(2.0 * m))
        return ellipk(m) - ellipkinc(phi1, m), m, phi1

    theta0 = brentq(lambda t: parts(t)[0] - alpha, 1e-12, np.pi / 2 - 1e-15, xtol=1e-16, rtol=1e-15)
    _, m, phi1 = parts(theta0)
    x = np.sqrt(2.0 * np.sin(theta0)) / alpha
    y = 1.0 - 2.0 / alpha * (ellipe(m) - ellipeinc(phi1, m))
    return x, -y


def rod_tip(L, EI, P, EA=np.inf, GA=np.inf, pyelastica=False):
    """Tip (x, y) of a planar rod clamped at the origin along +x, dead tip force (0, -P).
    EA, GA: axial and shear stiffness (inf: inextensible, unshearable); pyelastica=True uses
    PyElastica's bending law m = EI theta' / e^3."""
    n = np.array([0.0, -P])  # internal force, constant along the rod

    def rhs(s, q):
        x, y, th, mom = q
        d3, d1 = np.array([np.cos(th), np.sin(th)]), np.array([-np.sin(th), np.cos(th)])
        a, b = n @ d3 / EA, n @ d1 / GA
        c = 1.0 - a * a - b * b  # e^2 c - 2 a e - 1 = 0 for the dilatation e (PyElastica)
        e = (a + np.sqrt(a * a + c)) / c if pyelastica else 1.0
        rp = (1.0 + e * a) * d3 + e * b * d1
        return [rp[0], rp[1], (e ** 3 if pyelastica else 1.0) * mom / EI, -(rp[0] * n[1] - rp[1] * n[0])]

    def shoot(m0):
        sol = solve_ivp(rhs, (0.0, L), [0.0, 0.0, 0.0, m0], method="DOP853", rtol=1e-13, atol=1e-16 * (1 + P * L))
        return sol.y[:, -1]

    m0 = brentq(lambda m0: shoot(m0)[3], -1e-3 * P * L, -1.01 * P * L, xtol=1e-16 * P * L, rtol=1e-15)
    x, y, _, _ = shoot(m0)
    return x, y


if __name__ == "__main__":
    for p in (2.0, 5.0):
        xe, ye = elastica_tip(p)
        xs, ys = rod_tip(1.0, 1.0, p)
        print(f"p = {p}: closed form ({xe:.15f}, {ye:.15f}), shooting ({xs:.15f}, {ys:.15f}), "
              f"|diff| = {np.hypot(xe - xs, ye - ys):.1e}")
