"""The core API: scenes in and out, solves, results, errors."""

import json
import threading
import time

import numpy as np
import pytest

import rodnet


def test_cantilever_matches_the_elastica(networks):
    # Bisshopp & Drucker: P L^2 / EI = 2 gives tip deflection v/L = 0.49345748 and shortening
    # u/L = 0.16064172 (the scene's header); 40 edges leave a discretization error near 1e-4.
    res = rodnet.load_scene(networks / "cantilever.ron").solve()
    assert res.converged and res.residual < 1e-8
    tip = res.points("beam")[-1]
    assert isinstance(tip, np.ndarray)
    assert abs(-tip[1] - 0.49345748) < 2e-3
    assert abs((1.0 - tip[0]) - 0.16064172) < 2e-3
    assert res.points(0).shape == (41, 3)
    assert res.twist("beam").shape == (40,)
    # Equilibrium: the clamp's reaction balances the tip load.
    (r,) = res.reactions
    assert r["rod"] == "beam" and r["vertex"] == 0
    assert np.allclose(r["force"], [0.0, 1.5707963267948966, 0.0], atol=1e-6)


def test_results_dict_is_the_results_json(networks, tmp_path):
    res = rodnet.load_scene(networks / "cantilever.ron").solve()
    d = res.to_dict()
    assert d["converged"] is True and d["iterations"] == res.iterations
    assert d["energy"]["total"] == res.energy
    assert d["rods"][0]["points"] == res.points(0).tolist()
    res.write_json(tmp_path / "r.json")
    assert json.loads((tmp_path / "r.json").read_text()) == d
    res.write_obj(tmp_path / "r.obj")
    vertices = [l for l in (tmp_path / "r.obj").read_text().splitlines() if l.startswith("v ")]
    assert len(vertices) == 41


def test_extrapolated_solve(networks):
    # As `rodnet solve --extrapolate --levels 3`: the results are the finest solve's (4 x 40
    # edges), the extrapolate is at the scene's 41 nodes, its own error estimated far below the
    # finest solve's (6e-8 against 5e-6 m). Against Bisshopp & Drucker's inextensible values the
    # extrapolate is off by the rod's stretch (P/EA L = 5e-5).
    scene = rodnet.load_scene(networks / "cantilever.ron")
    res = scene.solve(extrapolate=3)
    x = res.extrapolation
    assert x == res.to_dict()["extrapolation"]
    assert x["levels"] == 3 and x["subdivide"] == [[40, 160]]
    assert res.points(0).shape == (161, 3) and len(x["rods"][0]["points"]) == 41
    assert x["extrapolate_error_estimate"] < 0.1 * x["error_estimate"]
    tip = x["rods"][0]["points"][-1]
    assert abs(-tip[1] - 0.49345748) < 1e-4 and abs((1.0 - tip[0]) - 0.16064172) < 1e-4
    assert scene.solve(extrapolate=2).to_dict()["extrapolation"]["levels"] == 2
    plain = scene.solve()
    assert plain.extrapolation is None and "extrapolation" not in plain.to_dict()
    with pytest.raises(ValueError, match="extrapolate"):
        scene.solve(extrapolate=4)


def test_scene_round_trips_through_ron_and_dicts(networks, cantilever_dict, tmp_path):
    s = rodnet.Scene.from_dict(cantilever_dict)
    assert s.rods == ["beam"] and s.materials == ["steel"]
    again = rodnet.Scene.from_ron(s.to_ron())
    assert again.to_dict() == s.to_dict()
    s.write_ron(tmp_path / "c.ron")
    assert rodnet.load_scene(tmp_path / "c.ron").to_dict() == s.to_dict()
    assert rodnet.Scene(**cantilever_dict).to_dict() == s.to_dict()
    e1 = s.solve().energy
    e2 = again.solve().energy
    assert e1 == e2 < 0


def test_set_changes_a_parameter_and_the_solution(cantilever_dict):
    s = rodnet.Scene.from_dict(cantilever_dict)
    stiff = s.set("materials.steel.young_modulus", 1e9)
    assert stiff.to_dict()["materials"]["steel"]["young_modulus"] == 1e9
    tip_soft = s.solve().points("beam")[-1][1]
    tip_stiff = stiff.solve().points("beam")[-1][1]
    # Small deflections scale as 1/E.
    assert tip_soft / tip_stiff == pytest.approx(10.0, rel=0.05)
    assert s.set("rods.beam.subdivide", 20).solve().points(0).shape == (21, 3)


def test_settings_and_modes(networks):
    s = rodnet.load_scene(networks / "cantilever.ron")
    capped = s.solve(max_iterations=2)
    assert not capped.converged and capped.iterations <= 2
    res = s.solve(modes=3)
    assert len(res.stability["eigenvalues"]) == 3
    with pytest.raises(TypeError):
        s.solve(tolerence=1e-9)
    with pytest.raises(rodnet.SceneError) as e:
        s.solve(tolerance=-1.0)
    assert e.value.field == "solver.tolerance"


def test_syntax_and_validation_errors_are_located():
    text = 'Scene(\n  rods: [Rod(name: "a", material: "x", points: [(0,0,0), (1,0,0)], subdivide: 2)],\n)'
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.Scene.from_ron(text, path="bad.ron")
    err = e.value
    assert (err.path, err.line, err.field) == ("bad.ron", 2, "rods[0].material")
    assert err.column is not None and str(err).startswith("bad.ron:2:")
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.Scene.from_ron("Scene(rods: [Rod(name: 1)])")
    assert e.value.line == 1 and e.value.path is None
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.load_scene("/nonexistent/scene.ron")
    assert e.value.path == "/nonexistent/scene.ron"


def test_dict_errors_name_the_field(cantilever_dict):
    cantilever_dict["rods"][0]["subdivide"] = 2.5
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.Scene.from_dict(cantilever_dict)
    assert e.value.field == "rods[0].subdivide"
    cantilever_dict["rods"][0]["subdivide"] = 0
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.Scene.from_dict(cantilever_dict)
    assert e.value.field == "rods[0].subdivide"


def test_progress_callback_sees_iterations_and_can_stop_the_solve(networks):
    s = rodnet.load_scene(networks / "cantilever.ron")
    seen = []
    res = s.solve(progress=lambda step, it, residual, energy: seen.append((step, it, residual)))
    assert len(seen) >= res.iterations > 0
    assert seen[-1][2] <= seen[0][2]

    class Enough(Exception):
        pass

    def stop(step, it, residual, energy):
        raise Enough()

    with pytest.raises(Enough):
        s.solve(progress=stop)
    # The module still works after the interrupted solve.
    assert s.solve().converged


def test_solves_release_the_gil():
    done = threading.Event()
    out = {}

    def work():
        out["res"] = rodnet.gridshell.hemisphere(rods=10, subdivide=3)
        done.set()

    t = threading.Thread(target=work)
    t.start()
    ticks = 0
    while not done.is_set():
        ticks += 1
        time.sleep(0.001)
    t.join()
    assert out["res"].converged
    # With the GIL held through the solve this thread would not run until it ended.
    assert ticks >= 3, ticks


def test_hemisphere_has_target_metrics_and_refuses_bad_options():
    res = rodnet.gridshell.hemisphere(rods=6, subdivide=2)
    assert res.converged
    t = res.target
    assert t["shape"] == "sphere" and 0 < t["max_abs_radial_deviation"] < 0.05
    assert res.gridshell["rods_per_family"] == 6
    assert "rods" in rodnet.gridshell.options()
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.gridshell.hemisphere(rods=0)
    assert e.value.field == "rods"
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.gridshell.hemisphere(joint="glue")
    assert e.value.field == "joint"


def test_buckle_matches_euler(networks):
    # networks/euler_column.ron: P_c / P = pi^2 EI / (4 L^2) / 1 mN = 1.937892; with a round
    # section the two bending planes buckle at the same load (a pair of equal factors).
    b = rodnet.load_scene(networks / "euler_column.ron").buckle(modes=2, linear_only=True)
    f = b["critical_load_factors"]
    assert f[0] == pytest.approx(1.937892, rel=2e-3)
    assert f[1] == pytest.approx(f[0], rel=1e-6)
    assert "path" not in b and len(b["modes"]) == 2


def test_indent_gives_the_simply_supported_beams_stiffness():
    # Midspan stiffness of a simply supported beam: 48 EI / L^3 (L = 1 m).
    E, r = 1e9, 0.002
    roller = lambda n: {"rod": "b", "vertex": 2, "kind": {"Roller": {"normal": n}}}
    beam = rodnet.Scene.from_dict(
        {
            "materials": {"m": {"young_modulus": E, "poisson_ratio": 0.3,
                                "section": {"Circle": {"radius": r}}}},
            "rods": [{"name": "b", "material": "m", "subdivide": 16,
                      "points": [[0, 0, 0], [0.5, 0, 0], [1, 0, 0]]}],
            "supports": [{"rod": "b", "vertex": 0, "kind": "Pin"},
                         roller([0, 0, 1]), roller([0, 1, 0])],
        }
    )
    out = beam.indent("b:1", 1e-6, steps=1)
    exact = 48 * E * np.pi * r**4 / 4
    assert out["linear_stiffness"] == pytest.approx(exact, rel=1e-2)
    assert out["complete"] and out["frictionless"]
    depth, force = out["curve"][-1]
    assert force / depth == pytest.approx(out["linear_stiffness"], rel=1e-5)
    with pytest.raises(ValueError):
        beam.indent("nowhere", 1e-3)
