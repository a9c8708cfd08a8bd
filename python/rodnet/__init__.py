"""rodnet: Discrete Elastic Rods statics for rod networks and elastic gridshells.

    import rodnet
    scene = rodnet.load_scene("networks/cantilever.ron")
    res = scene.solve()
    print(res.converged, res.iterations, res.energy)
    xyz = res.points(0)            # NumPy (n, 3) array, m

Scenes are the RON scene files of the command-line tool (docs/scene-format.md); results are
its results JSON (docs/contract.md). See docs/python.md.
"""

from ._rodnet import (
    Results,
    Scene,
    SceneError,
    SolveError,
    __version__,
    load_scene,
)
from . import gridshell
from ._sweep import SweepTable, sweep

__all__ = [
    "Results",
    "Scene",
    "SceneError",
    "SolveError",
    "SweepTable",
    "__version__",
    "gridshell",
    "load_scene",
    "sweep",
]
