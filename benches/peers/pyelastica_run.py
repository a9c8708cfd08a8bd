"""Driving PyElastica: damped dynamics (PositionVerlet, AnalyticalLinearDamper) to the static
equilibrium of a cantilever clamped with OneEndFixedBC and loaded by EndpointForces.

The tip is sampled 400 times per run with its wall time since the start of the model set-up
(Python import and numba compilation excluded: `warm_up()` compiles first).  A run's time is
read off that history: the first sample after which the tip stays within 1 % of its final error
of where it ends.  That is an oracle stop, generous to PyElastica: a real run has no such
signal and would have to run on to know it had settled."""
import time

import numpy as np
import elastica as ea


class Cantilever(ea.BaseSystemCollection, ea.Constraints, ea.Forcing, ea.Damping):
    pass


def run(n, length, radius, density, E, G, force, dt, zeta, t_end, samples=400, blown_up=None):
    """Rod along +x from the origin (normal +z), clamped at node 0, dead force `force` at the
    tip from t = 0.  Returns (wall seconds, [(wall s, tip position)]), or None as soon as a
    sample is not finite or `blown_up(tip)` says the run has gone unstable."""
    t0 = time.perf_counter()
    sim = Cantilever()
    rod = ea.CosseratRod.straight_rod(n, np.zeros(3), np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0]),
                                      length, radius, density, youngs_modulus=E, shear_modulus=G)
    sim.append(rod)
    sim.constrain(rod).using(ea.OneEndFixedBC, constrained_position_idx=(0,), constrained_director_idx=(0,))
    sim.add_forcing_to(rod).using(ea.EndpointForces, np.zeros(3), np.asarray(force, float), ramp_up_time=dt)
    sim.dampen(rod).using(ea.AnalyticalLinearDamper, uniform_damping_constant=zeta, time_step=dt)
    sim.finalize()
    stepper, t = ea.PositionVerlet(), 0.0
    steps = int(round(t_end / dt))
    every = max(1, steps // samples)
    history = []
    for i in range(1, steps + 1):
        t = stepper.step(sim, t, dt)
        if i % every == 0 or i == steps:
            tip = rod.position_collection[:, -1]
            if not np.all(np.isfinite(tip)) or (blown_up and blown_up(tip)):
                return None
            history.append((time.perf_counter() - t0, tip.copy()))
    return time.perf_counter() - t0, history


def settle_time(history, error, target):
    """Wall time after which error(tip) stays <= target (None if it ends above)."""
    t = None
    for wall, tip in history:
        e = error(tip)
        if e > target:
            t = None
        elif t is None:
            t = wall
    return t


def settled(history, error, scale):
    """(wall time after which the tip stays within 1 % of its final error of its final position,
    final error): the time this run took to reach the accuracy of its discretization.
    error(tip) is relative to the displacement `scale` (m)."""
    final = history[-1][1]
    e = error(final)
    return settle_time(history, lambda tip: np.linalg.norm(tip - final) / scale, 0.01 * e), e


def warm_up():
    run(4, 1.0, 0.1, 1000.0, 1e6, 1e6, (0.0, -1.0, 0.0), 1e-4, 1.0, 1e-3)
