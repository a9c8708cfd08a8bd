"""Problem 2: PyElastica's own cantilever, the Timoshenko beam of its examples
(examples/TimoshenkoBeamCase: L = 3 m, r = 0.25 m, E = 1e6 Pa, G = 1e4 Pa, rho = 5000 kg/m^3,
tip force 15 N normal to the rod, time step 0.07 dl).

The beam is short and soft in shear, so the rod theories differ: the shear compliance adds 54 %
to the tip deflection of PyElastica's Cosserat rod; rodnet's Kirchhoff rod has none.  Each code is
therefore measured against the exact solution of its own theory (reference.rod_tip, shooting):
PyElastica against the extensible, shearable rod (shear stiffness 27/28 G A, couple EI k / e^3),
rodnet against the extensible Kirchhoff rod.  Both are the same beam, load and clamp."""
import math

import common
import pyelastica_run
import reference

L, R, RHO, E, G, F = 3.0, 0.25, 5000.0, 1e6, 1e4, 15.0
A, I = math.pi * R**2, math.pi * R**4 / 4
REF_COSSERAT = reference.rod_tip(L, E * I, F, EA=E * A, GA=27 / 28 * G * A, pyelastica=True)
REF_KIRCHHOFF = reference.rod_tip(L, E * I, F, EA=E * A)
DISPLACEMENT = math.hypot(REF_COSSERAT[0] - L, REF_COSSERAT[1])

RODNET_N = (5, 10, 20, 40, 80, 160, 320)
PYELASTICA_N = (25, 50, 100, 200, 400, 800, 1600)
ZETAS = (0.3, 0.6, 0.9, 1.2, 2.4)  # uniform damping constants tried (1/s); omega_1 is about 0.6 rad/s
T_END = 60.0  # simulated seconds per run


def error(tip, ref):
    return math.hypot(tip[0] - ref[0], tip[1] - ref[1]) / math.hypot(ref[0] - L, ref[1])


def rodnet_scene(n):
    return f"""Scene(
    materials: {{ "m": Material(young_modulus: {E}, shear_modulus: {G}, density: {RHO}, section: Circle(radius: {R})) }},
    rods: [ Rod(name: "beam", material: "m", points: [(0.0, 0.0, 0.0), ({L}, 0.0, 0.0)], subdivide: {n}) ],
    supports: [ Support(rod: "beam", vertex: 0, kind: Clamp) ],
    loads: [ Force(rod: "beam", vertex: 1, force: (0.0, {-F}, 0.0)) ],
)"""


def rodnet_runs():
    rows = []
    for n in common.levels(RODNET_N):
        t, times, res = common.repeat(lambda: common.rodnet_solve(f"timoshenko_{n}", rodnet_scene(n)))
        tip = res["rods"][0]["points"][-1]
        rows.append(dict(code="rodnet", n=n, seconds=t, all_seconds=times, value=tip[1], error=error(tip, REF_KIRCHHOFF),
                         note=f'{res["iterations"]} its, own {res["seconds"]:.3g} s'))
    return rows


def pyelastica(n, zeta, t_end=T_END, dt_over_dl=0.07):
    """None if the run goes unstable (the tip strays 3 displacements from the reference)."""
    return pyelastica_run.run(n, L, R, RHO, E, G, (0.0, -F, 0.0), dt_over_dl * L / n, zeta, t_end,
                              blown_up=lambda tip: error(tip, REF_COSSERAT) > 3)


def best_damping(n=50):
    """The damping constant that settles fastest (to 1e-5 of its own final tip) at n = 50."""
    def settle(zeta):
        wall, hist = pyelastica(n, zeta, 2 * T_END)
        final = hist[-1][1]
        return pyelastica_run.settle_time(hist, lambda tip: error(tip, final), 1e-5) / wall
    fractions = {z: settle(z) for z in ZETAS}
    return min(fractions, key=fractions.get), fractions


def pyelastica_runs(zeta):
    """The example's time step 0.07 dl is 0.99 of the axial waves' stability limit dl / c; where
    it goes unstable the level is run with 0.05 dl instead (noted)."""
    rows = []
    for n in common.levels(PYELASTICA_N):
        step = {"dt/dl": 0.07}

        def one():
            run = pyelastica(n, zeta, dt_over_dl=step["dt/dl"])
            if run is None:  # unstable: the failed run is not counted
                step["dt/dl"] = 0.05
                run = pyelastica(n, zeta, dt_over_dl=0.05)
            wall, hist = run
            t, e = pyelastica_run.settled(hist, lambda tip: error(tip, REF_COSSERAT), DISPLACEMENT)
            return t, (t / wall, wall, e, hist[-1][1][1])
        t, times, (frac, wall, e, y) = common.repeat(one)
        steps = round(T_END / (step["dt/dl"] * L / n))
        rows.append(dict(code="PyElastica", n=n, seconds=t, all_seconds=times, value=y, error=e,
                         note=f"settled at {frac:.0%} of a {wall:.3g} s run of {steps} steps"
                              + ("" if step["dt/dl"] == 0.07 else ", dt = 0.05 dl (0.07 dl was unstable)")))
    return rows
