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


def mean_of(f, repeat):
    t0 = time.perf_counter()
    for _ in range(repeat):
        f()
    return (time.perf_counter() - t0) / repeat


for name, scene, repeat in [
    ("tiny beam (4 edges)", tiny(), 1000),
    ("cantilever.ron (40 edges)", rodnet.load_scene(ROOT / "networks" / "cantilever.ron"), 50),
]:
    scene.solve()
    # Rounds alternate between the two so that a change in the machine's load hits both; the
    # fastest round of each is the least disturbed.
    py, rust = float("inf"), float("inf")
    for _ in range(15):
        py = min(py, mean_of(scene.solve, repeat))
        rust = min(rust, _rodnet._bench_solve(scene, repeat))
    print(
        f"{name}: from Python {py * 1e6:9.1f} us, in Rust {rust * 1e6:9.1f} us, "
        f"overhead {(py - rust) * 1e6:7.1f} us per call"
    )
