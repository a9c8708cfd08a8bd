"""Problem 1: a clamped cantilever under a transverse dead tip load, P L^2 / EI = 5.

L = 1 m, EI = 1 N m^2 (circle r = 1 mm, E = 4 EI / (pi r^4)), nu = 0.5, P = 5 N along -y.
Reference: the inextensible elastica (Bisshopp & Drucker, reference.py).  r / L = 1e-3 keeps
the rod theories' own departures from it small: extensible Kirchhoff rod 1.1e-6, PyElastica's
extensible and shearable Cosserat rod 3.0e-6 (relative tip errors, printed below).
Quantity: the tip displacement; error |x_tip - x_ref| / |x_ref - x_rest|."""
import math

import numpy as np

import common
import opensees_run
import pyelastica_run
import reference

L, EI, P, R, NU = 1.0, 1.0, 5.0, 1e-3, 0.5
E = 4 * EI / (math.pi * R**4)
G = E / (2 * (1 + NU))
A = math.pi * R**2
RHO = 1000.0  # PyElastica only (statics does not depend on it)
REF = reference.elastica_tip(P * L**2 / EI)

RODNET_N = (10, 20, 40, 80, 160, 320, 640)
RODNET_3_N = (2, 3, 4, 6, 8, 12, 16)  # coarse levels of `--extrapolate --levels 3`
OPENSEES_N = (10, 20, 40, 80, 160, 320)
PYELASTICA_N = (10, 20, 40)


def error(x, y):
    return math.hypot(x - REF[0], y - REF[1]) / math.hypot(REF[0] - L, REF[1])


def rodnet_scene(n):
    return f"""Scene(
    materials: {{ "wire": Material(young_modulus: {E!r}, poisson_ratio: {NU}, section: Circle(radius: {R})) }},
    rods: [ Rod(name: "beam", material: "wire", points: [(0.0, 0.0, 0.0), ({L}, 0.0, 0.0)], subdivide: {n}) ],
    supports: [ Support(rod: "beam", vertex: 0, kind: Clamp) ],
    loads: [ Force(rod: "beam", vertex: 1, force: (0.0, {-P}, 0.0)) ],
)"""


def rodnet_runs():
    rows = []
    for n in common.levels(RODNET_N):
        t, times, res = common.repeat(lambda: common.rodnet_solve(f"cantilever_{n}", rodnet_scene(n)))
        x, y, _ = res["rods"][0]["points"][-1]
        rows.append(dict(code="rodnet", n=n, seconds=t, all_seconds=times, value=y, error=error(x, y),
                         note=f'{res["iterations"]} its, {"converged" if res["converged"] else "NOT converged"}, '
                              f'own {res["seconds"]:.3g} s'))
    return rows


def rodnet_three_level_runs():
    rows = []
    for n in common.levels(RODNET_3_N):
        t, times, res = common.repeat(
            lambda: common.rodnet_solve(f"cantilever3_{n}", rodnet_scene(n), common.THREE_LEVELS))
        x3 = res["extrapolation"]
        x, y, _ = x3["rods"][0]["points"][-1]
        rows.append(dict(code=common.RODNET_3, n=n, seconds=t, all_seconds=times, value=y, error=error(x, y),
                         note=f'{n}/{2 * n}/{4 * n} edges, {x3["coarse_iterations"]}+{x3["middle_iterations"]}+'
                              f'{x3["fine_iterations"]} its, {"converged" if res["converged"] else "NOT converged"}'))
    return rows


def opensees_build(n):
    def build():
        import openseespy.opensees as ops
        ops.model("basic", "-ndm", 3, "-ndf", 6)
        for i in range(n + 1):
            ops.node(i, L * i / n, 0.0, 0.0)
        ops.fix(0, 1, 1, 1, 1, 1, 1)
        ops.geomTransf("Corotational", 1, 0.0, 0.0, 1.0)
        I = math.pi * R**4 / 4
        for i in range(n):
            ops.element("elasticBeamColumn", i + 1, i, i + 1, A, E, G, 2 * I, I, I, 1)
        ops.timeSeries("Linear", 1)
        ops.pattern("Plain", 1, 1)
        ops.load(n, 0.0, -P, 0.0, 0.0, 0.0, 0.0)
        return lambda: (L + ops.nodeDisp(n, 1), ops.nodeDisp(n, 2))
    return build


def opensees_runs():
    rows, hint = [], None
    for n in common.levels(OPENSEES_N):
        build = opensees_build(n)
        alg, steps = hint = opensees_run.tune(build, hint)
        t, times, (x, y) = common.repeat(lambda: opensees_run.solve(build, alg, steps))
        rows.append(dict(code="OpenSees", n=n, seconds=t, all_seconds=times, value=y, error=error(x, y),
                         note=f"{alg}, {steps} load steps"))
    return rows


def pyelastica_runs():
    """Time step 0.9 of PositionVerlet's limit for the fastest mode, the shear-rotation mode of
    an element, dt = r sqrt(rho / (27/28 G)) (the axial limit dl / c is 30x larger here);
    uniform damping 2 omega_1 (critical for the first bending mode of the unloaded cantilever);
    one run per n (each takes minutes), long enough to settle below 1e-5."""
    omega1 = 1.8751**2 * math.sqrt(EI / (RHO * A)) / L**2
    dt = 0.9 * R * math.sqrt(RHO / (27 / 28 * G))
    rows = []
    for n in PYELASTICA_N[:1] if common.QUICK else PYELASTICA_N:
        wall, hist = pyelastica_run.run(n, L, R, RHO, E, G, (0.0, -P, 0.0), dt, 2 * omega1, 14 / omega1)
        t, e = pyelastica_run.settled(hist, lambda tip: error(tip[0], tip[1]), math.hypot(REF[0] - L, REF[1]))
        rows.append(dict(code="PyElastica", n=n, seconds=t, all_seconds=[t], value=hist[-1][1][1], error=e,
                         note=f"settled at {t / wall:.0%} of a {wall:.3g} s run of {round(14 / omega1 / dt)} steps"))
    return rows
