"""Problem 3: square grids of crossing rods sagging under their own weight.

n rods along x (at y = a, 2a, ..., n a) and n along y, span S = (n + 1) a with a = 1 m, joined
rigidly at the n^2 crossings, both ends of every rod pinned.  Rods: circle r = 2 cm, E = 1 GPa,
nu = 0.4, rho = 950 kg/m^3 (a polyethylene-like rod), g = 9.81 m/s^2.  The centre sags 0.197 m
(1.8 % of the span, 10 radii) at n = 10 and 0.470 m (2.2 %, 24 radii) at n = 20: the membrane
regime (the linear bending solution of one rod would sag 18 m and 240 m).  Each bay between crossings has k edges (rodnet
`subdivide`) or k elements (OpenSees corotational elasticBeamColumn, weight lumped at the nodes
as rodnet does).  Quantity: the deflection of a centre crossing (the n/2-th along both families;
the four central crossings are equal by symmetry).  Reference: Richardson extrapolation of each
code's own sequence (from its two finest levels, with the order observed on the last three)."""
import math

import common
import opensees_run

A_BAY, R, E, NU, RHO, GRAV = 1.0, 0.02, 1e9, 0.4, 950.0, 9.81
AREA, I = math.pi * R**2, math.pi * R**4 / 4
G = E / (2 * (1 + NU))

RODNET_K = (1, 2, 4, 8, 16, 32)
RODNET_3_K = (1, 2, 4, 8)  # coarse levels of `--extrapolate --levels 3`
OPENSEES_K = {10: (1, 2, 4, 8), 20: (1, 2, 4, 8, 16)}  # 20x20 is asymptotic from k = 8 only


def rodnet_scene(n, k):
    rods, joints, supports = [], [], []
    for i in range(1, n + 1):
        for fam, at in (("x", lambda s: (s, i * A_BAY, 0.0)), ("y", lambda s: (i * A_BAY, s, 0.0))):
            pts = ", ".join(common.vec(at(j * A_BAY)) for j in range(n + 2))
            rods.append(f'Rod(name: "{fam}{i}", material: "m", points: [{pts}], subdivide: {k})')
            supports += [f'Support(rod: "{fam}{i}", vertex: {v}, kind: Pin)' for v in (0, n + 1)]
        joints += [f'Joint(name: "j{i}_{j}", at: [("x{i}", {j}), ("y{j}", {i})], kind: Rigid)'
                   for j in range(1, n + 1)]
    sep = ",\n        "
    return f"""Scene(
    materials: {{ "m": Material(young_modulus: {E}, poisson_ratio: {NU}, density: {RHO}, section: Circle(radius: {R})) }},
    rods: [
        {sep.join(rods)},
    ],
    joints: [
        {sep.join(joints)},
    ],
    supports: [
        {sep.join(supports)},
    ],
    loads: [ Gravity(g: (0.0, 0.0, {-GRAV})) ],
)"""


def rodnet_runs(n):
    rows = []
    for k in common.levels(RODNET_K):
        t, times, res = common.repeat(lambda: common.rodnet_solve(f"grid{n}_{k}", rodnet_scene(n, k)))
        rod = next(r for r in res["rods"] if r["name"] == f"x{n // 2}")
        rows.append(dict(code="rodnet", n=k, seconds=t, all_seconds=times, value=-rod["points"][(n // 2) * k][2],
                         note=f'{res["iterations"]} its, {"converged" if res["converged"] else "NOT converged"}, '
                              f'own {res["seconds"]:.3g} s'))
    return rows


def rodnet_three_level_runs(n, reference):
    """`--extrapolate --levels 3` from k = 1, 2, 4, 8 edges per bay; errors against `reference`
    (rodnet's own Richardson extrapolate of its plain sequence)."""
    rows = []
    for k in common.levels(RODNET_3_K):
        t, times, res = common.repeat(
            lambda: common.rodnet_solve(f"grid3_{n}_{k}", rodnet_scene(n, k), common.THREE_LEVELS))
        x3 = res["extrapolation"]
        rod = next(r for r in x3["rods"] if r["name"] == f"x{n // 2}")
        w = -rod["points"][(n // 2) * k][2]
        rows.append(dict(code=common.RODNET_3, n=k, seconds=t, all_seconds=times, value=w,
                         error=abs(w - reference) / abs(reference),
                         note=f'{k}/{2 * k}/{4 * k} per bay, {x3["coarse_iterations"]}+{x3["middle_iterations"]}+'
                              f'{x3["fine_iterations"]} its, {"converged" if res["converged"] else "NOT converged"}'))
    return rows


def opensees_build(n, k):
    def build():
        import openseespy.opensees as ops
        ops.model("basic", "-ndm", 3, "-ndf", 6)
        ops.geomTransf("Corotational", 1, 0.0, 0.0, 1.0)
        ops.timeSeries("Linear", 1)
        ops.pattern("Plain", 1, 1)
        m, h = (n + 1) * k, A_BAY / k  # elements per rod, element length
        tags, weight = {}, {}

        def node(ix, iy):  # nodes on a lattice of spacing h; crossings are shared (rigid joints)
            if (ix, iy) not in tags:
                tags[ix, iy] = len(tags) + 1
                ops.node(tags[ix, iy], ix * h, iy * h, 0.0)
            return tags[ix, iy]

        for i in range(1, n + 1):
            for line in ([(s, i * k) for s in range(m + 1)], [(i * k, s) for s in range(m + 1)]):
                nodes = [node(*p) for p in line]
                for end in (nodes[0], nodes[-1]):
                    ops.fix(end, 1, 1, 1, 0, 0, 0)
                for a, b in zip(nodes, nodes[1:]):
                    ops.element("elasticBeamColumn", len(weight) + 1, a, b, AREA, E, G, 2 * I, I, I, 1)
                    weight[len(weight) + 1] = (a, b)
        lumped = {}
        for a, b in weight.values():
            for q in (a, b):
                lumped[q] = lumped.get(q, 0.0) + 0.5 * RHO * AREA * GRAV * h
        for q, f in lumped.items():
            ops.load(q, 0.0, 0.0, -f, 0.0, 0.0, 0.0)
        centre = tags[(n // 2) * k, (n // 2) * k]
        return lambda: -ops.nodeDisp(centre, 3)
    return build


def opensees_runs(n):
    rows, hint = [], None
    for k in common.levels(OPENSEES_K[n]):
        build = opensees_build(n, k)
        alg, steps = hint = opensees_run.tune(build, hint)
        t, times, w = common.repeat(lambda: opensees_run.solve(build, alg, steps))
        rows.append(dict(code="OpenSees", n=k, seconds=t, all_seconds=times, value=w,
                         note=f"{alg}, {steps} load steps"))
    return rows


def richardson(rows):
    """Extrapolate the last level with the order observed on the last three; sets each row's
    relative error against it.  Returns (extrapolate, observed order)."""
    w = [r["value"] for r in rows]
    ratio = k_ratio = rows[-1]["n"] / rows[-2]["n"]
    p = math.log(abs((w[-3] - w[-2]) / (w[-2] - w[-1]))) / math.log(k_ratio)
    w_inf = w[-1] + (w[-1] - w[-2]) / (ratio**p - 1)
    for r in rows:
        r["error"] = abs(r["value"] - w_inf) / abs(w_inf)
    return w_inf, p
