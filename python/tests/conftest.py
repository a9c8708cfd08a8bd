import os
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def networks():
    return ROOT / "networks"


@pytest.fixture
def cantilever_dict():
    """A small cantilever (tip load), as Python data shaped like the RON text."""
    return {
        "materials": {
            "steel": {
                "young_modulus": 1e8,
                "poisson_ratio": 0.5,
                "section": {"Circle": {"radius": 0.01}},
            }
        },
        "rods": [
            {
                "name": "beam",
                "material": "steel",
                "points": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
                "subdivide": 10,
            }
        ],
        "supports": [{"rod": "beam", "vertex": 0, "kind": "Clamp"}],
        "loads": [{"Force": {"rod": "beam", "vertex": 1, "force": [0.0, -0.1, 0.0]}}],
    }


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    os.environ.setdefault("RAYON_NUM_THREADS", "2")
