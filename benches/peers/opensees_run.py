"""Driving OpenSees (openseespy): static load control with the fewest load steps that converge.

`build()` creates the model, its loads in a Plain pattern on a Linear time series, and returns a
function that reads the result.  The timed solve is everything from `wipe()` to the last
`analyze` (model building through the Python API included, Python import excluded)."""
import math
import time

import openseespy.opensees as ops

SYSTEM, NUMBERER = "UmfPack", "RCM"
TOL, MAX_ITER = 1e-10, 50  # NormDispIncr (m, rad): far below the errors measured
ALGORITHMS = {
    "NewtonLineSearch": ("NewtonLineSearch",),
    "NewtonLineSearch/Bisection": ("NewtonLineSearch", "-type", "Bisection"),
    "Newton": ("Newton",),
    "KrylovNewton": ("KrylovNewton",),
}
STEPS = (1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64)


def quiet():
    """Send OpenSees' messages (warnings of failed attempts while tuning) to out/opensees.log."""
    from common import OUT
    OUT.mkdir(parents=True, exist_ok=True)
    ops.logFile(str(OUT / "opensees.log"), "-noEcho")


def solve(build, algorithm, steps, cap=math.inf):
    """One timed solve: (seconds, value); None if a step fails, "cap" if it runs past `cap` s."""
    t0 = time.perf_counter()
    ops.wipe()
    read = build()
    ops.system(SYSTEM)
    ops.numberer(NUMBERER)
    ops.constraints("Plain")
    ops.test("NormDispIncr", TOL, MAX_ITER)
    ops.algorithm(*ALGORITHMS[algorithm])
    ops.integrator("LoadControl", 1.0 / steps)
    ops.analysis("Static")
    for _ in range(steps):
        if ops.analyze(1) != 0:
            return None
        if time.perf_counter() - t0 > cap:
            return "cap"
    value = read()
    return time.perf_counter() - t0, value


def tune(build, hint=None):
    """(algorithm, steps): for each algorithm the fewest load steps (from STEPS) that converge,
    and of those the fastest.  An algorithm's search stops at its first success, or at a failed
    attempt that took longer than 1.5x the best so far (more steps would not be faster).  With
    the (algorithm, steps) of a coarser level as `hint`, that algorithm is tried first from
    those steps upward (finer models may need more), and the rest of the search is capped."""
    best, tried = None, set()

    def attempt(alg, steps):  # (converged, seconds taken)
        nonlocal best
        tried.add((alg, steps))
        t0 = time.perf_counter()
        r = solve(build, alg, steps, 1.5 * best[0] if best else math.inf)
        if isinstance(r, tuple) and (best is None or r[0] < best[0]):
            best = (r[0], alg, steps)
        return isinstance(r, tuple), time.perf_counter() - t0

    if hint is not None:
        for steps in (s for s in STEPS if s >= hint[1]):
            if attempt(hint[0], steps)[0]:
                break
    for alg in ALGORITHMS:
        for steps in STEPS:
            if best and alg == best[1] and steps >= best[2]:
                break
            if (alg, steps) in tried:
                continue
            ok, took = attempt(alg, steps)
            if ok or (best and took > 1.5 * best[0]):
                break
    if best is None:
        raise RuntimeError("OpenSees: no algorithm converged with up to %d load steps" % STEPS[-1])
    return best[1], best[2]
