"""What a solve costs from Python beyond the solve itself (docs/python.md, "Performance").

Times `Scene.solve()` called from Python (scene copy and checks, GIL release, progress hook,
results object) against the same solves run in a loop inside Rust, for a tiny and a small scene.

    python python/bench/overhead.py
"""

import pathlib
import time

import rodnet
from rodnet import _rodnet

ROOT = pathlib.Path(__file__).resolve().parents[2]


def tiny():
    return rodnet.Scene.from_dict(
        {
            "materials": {"m": {"young_modulus": 1e9, "poisson_ratio": 0.3,
                                "section": {"Circle": {"radius": 0.01}}}},
            "rods": [{"name": "b", "material": "m", "points": [[0, 0, 0], [1, 0, 0]],
                      "subdivide": 4}],
            "supports": [{"rod": "b", "vertex": 0, "kind": "Clamp"}],
            "loads": [{"Force": {"rod": "b", "vertex": 1, "force": [0, -0.01, 0]}}],
        }
    )


def best_mean(f, repeat, rounds=7):
    best = float("inf")
    for _ in range(rounds):
        t0 = time.perf_counter()
        for _ in range(repeat):
            f()
        best = min(best, (time.perf_counter() - t0) / repeat)
    return best


for name, scene, repeat in [
    ("tiny beam (4 edges)", tiny(), 2000),
    ("cantilever.ron (40 edges)", rodnet.load_scene(ROOT / "networks" / "cantilever.ron"), 200),
]:
    scene.solve()
    py = best_mean(scene.solve, repeat)
    rust = min(_rodnet._bench_solve(scene, repeat) for _ in range(7))
    print(
        f"{name}: from Python {py * 1e6:9.1f} us, in Rust {rust * 1e6:9.1f} us, "
        f"overhead {(py - rust) * 1e6:7.1f} us per call"
    )
