"""Issue 39 from Python: bad values in Python data raise `SceneError` at their field, scenes and
results pickle bit for bit (process pools, Dask), process pools of the "fork" start method work
after the parent has solved, and Ctrl-C stops a solve while it runs."""

import os
import pickle
import signal
import subprocess
import sys
import textwrap
from concurrent.futures import ProcessPoolExecutor

import multiprocessing

import numpy as np
import pytest

import rodnet



# --- NaN and wrong types in Python data --------------------------------------------------------


@pytest.mark.parametrize(
    "edit, field",
    [
        (lambda d: d["rods"][0]["points"][1].__setitem__(0, float("nan")), "rods[0].points[1][0]"),
        (lambda d: d["rods"][0].__setitem__("points", np.array([[0, 0, 0], [1, np.inf, 0]])),
         "rods[0].points[1][1]"),
        (lambda d: d["materials"]["steel"].__setitem__("young_modulus", np.float64("nan")),
         "materials.steel.young_modulus"),
        (lambda d: d["materials"]["steel"].__setitem__("poisson_ratio", {0.5}),
         "materials.steel.poisson_ratio"),
        (lambda d: d["loads"][0]["Force"].__setitem__("force", [0.0, object(), 0.0]),
         "loads[0].Force.force[1]"),
    ],
)
def test_a_value_json_cannot_carry_is_a_scene_error_at_its_field(cantilever_dict, edit, field):
    edit(cantilever_dict)
    for make in (rodnet.Scene.from_dict, lambda d: rodnet.Scene(**d)):
        with pytest.raises(rodnet.SceneError) as e:
            make(cantilever_dict)
        assert e.value.field == field, str(e.value)
        assert str(e.value).startswith(field + ": "), str(e.value)
        assert "line 1 column" not in str(e.value)
        assert e.value.path is None and e.value.line is None


def test_scene_set_and_dict_sweeps_name_a_nan_by_its_path(cantilever_dict):
    scene = rodnet.Scene.from_dict(cantilever_dict)
    with pytest.raises(rodnet.SceneError) as e:
        scene.set("materials.steel.young_modulus", float("inf"))
    assert e.value.field == "materials.steel.young_modulus", str(e.value)
    with pytest.raises(rodnet.SceneError) as e:
        scene.set("rods[0].points", [[0, 0, 0], [float("nan"), 0, 0]])
    assert e.value.field == "rods[0].points[1][0]", str(e.value)
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.sweep(
            {"scene": scene, "grid": {"materials.steel.young_modulus": [1e8, float("nan")]}},
            output="out",
        )
    assert e.value.field == "grid.materials.steel.young_modulus[1]", str(e.value)
    assert not os.path.exists("out"), "a refused sweep wrote its folder"


# --- pickling ------------------------------------------------------------------------------------


def test_scenes_pickle_to_the_same_scene(networks, cantilever_dict):
    for scene in (
        rodnet.load_scene(networks / "cantilever.ron"),
        rodnet.Scene.from_dict(cantilever_dict).set("materials.steel.young_modulus", 0.1 + 0.2),
    ):
        back = pickle.loads(pickle.dumps(scene))
        assert isinstance(back, rodnet.Scene)
        assert back.to_ron() == scene.to_ron()
        assert back.to_dict() == scene.to_dict()
        assert back.path == scene.path
    # 0.1 + 0.2 is not 0.3: the modulus comes back to the last bit.
    assert back.to_dict()["materials"]["steel"]["young_modulus"] == 0.1 + 0.2


def test_results_pickle_bit_for_bit(networks):
    res = rodnet.load_scene(networks / "cantilever.ron").solve(modes=2)
    back = pickle.loads(pickle.dumps(res))
    assert isinstance(back, rodnet.Results)
    assert back.to_json() == res.to_json()
    a, b = res.points("beam"), back.points("beam")
    assert a.tobytes() == b.tobytes()
    assert back.energy == res.energy and back.converged == res.converged
    assert back.stability == res.stability and back.reactions == res.reactions


def test_gridshell_results_pickle_with_their_block():
    res = rodnet.gridshell.hemisphere(rods=4, subdivide=2)
    back = pickle.loads(pickle.dumps(res))
    assert back.gridshell == res.gridshell and back.gridshell is not None
    assert back.target == res.target
    assert back.to_json() == res.to_json()


def test_scenes_and_results_cross_a_spawned_process_pool(networks):
    scene = rodnet.load_scene(networks / "cantilever.ron")
    here = scene.solve()
    ctx = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(1, mp_context=ctx) as pool:
        there = pool.submit(rodnet.Scene.solve, scene).result(timeout=120)
    assert isinstance(there, rodnet.Results)
    # Same scene, same code, bit-identical across processes (docs/reliability.md).
    assert there.points("beam").tobytes() == here.points("beam").tobytes()
    assert there.energy == here.energy


# --- fork after rayon's threads ------------------------------------------------------------------


FORKED = textwrap.dedent(
    """
    import multiprocessing, sys
    from concurrent.futures import ProcessPoolExecutor
    import rodnet

    scene = rodnet.load_scene(sys.argv[1])
    here = scene.solve()                      # starts rayon's pool in the parent
    ctx = multiprocessing.get_context("fork")
    with ProcessPoolExecutor(2, mp_context=ctx) as pool:
        there = pool.submit(rodnet.Scene.solve, scene).result()
        table = rodnet.sweep(
            {"scene": scene, "grid": {"materials.steel.young_modulus": [1e8, 2e8]}},
            executor=pool, output=sys.argv[2])
    assert there.energy == here.energy, (there.energy, here.energy)
    assert len(table.rows) == 2 and not table.missing
    assert all(r["converged"] for r in table.rows)
    print("ok")
    """
)


@pytest.mark.skipif(
    "fork" not in multiprocessing.get_all_start_methods(), reason="no fork on this platform"
)
def test_fork_pools_solve_after_the_parent_has_solved(networks, tmp_path):
    script = tmp_path / "forked.py"
    script.write_text(FORKED)
    try:
        out = subprocess.run(
            [sys.executable, str(script), str(networks / "cantilever.ron"), str(tmp_path / "s")],
            capture_output=True, text=True, timeout=120,
        )
    except subprocess.TimeoutExpired:
        pytest.fail("a fork-context process pool hung after the parent had solved")
    assert out.returncode == 0 and out.stdout.strip() == "ok", out.stdout + out.stderr


# --- Ctrl-C ------------------------------------------------------------------------------------

# 20 cantilevers of 2000 edges: Newton stops after one iteration (max_iterations=1), then the
# 100 lowest modes take about a minute with no iteration, and so no progress call, in between.
# The progress callback sends SIGINT at the last iteration: a check in the progress hook alone
# would see it only when the solve returns.
INTERRUPTED = textwrap.dedent(
    """
    import os, signal, sys
    import rodnet

    d = {
        "materials": {"steel": {"young_modulus": 1e8, "poisson_ratio": 0.5,
                                "section": {"Circle": {"radius": 0.01}}}},
        "rods": [{"name": f"b{i}", "material": "steel", "subdivide": 2000,
                  "points": [[0.0, 0.0, 0.1 * i], [1.0, 0.0, 0.1 * i]]} for i in range(20)],
        "supports": [{"rod": f"b{i}", "vertex": 0, "kind": "Clamp"} for i in range(20)],
        "loads": [{"Force": {"rod": f"b{i}", "vertex": 1, "force": [0.0, -1.5, 0.0]}}
                  for i in range(20)],
    }

    def progress(step, iteration, residual, energy):
        if iteration == 1:
            print("interrupting", flush=True)
            os.kill(os.getpid(), signal.SIGINT)

    try:
        rodnet.Scene.from_dict(d).solve(max_iterations=1, modes=100, progress=progress)
        print("solved")
    except KeyboardInterrupt:
        print("interrupted")
    """
)


def test_ctrl_c_stops_a_solve_between_its_iterations(tmp_path):
    script = tmp_path / "interrupted.py"
    script.write_text(INTERRUPTED)
    # A hang guard, not a timing: the interrupt comes within 50 ms of the signal, while the
    # solve would go on for about a minute on the 2-core CI machine.
    try:
        out = subprocess.run(
            [sys.executable, str(script)], capture_output=True, text=True, timeout=20
        )
    except subprocess.TimeoutExpired:
        pytest.fail("Ctrl-C did not stop the solve")
    assert out.stdout.split() == ["interrupting", "interrupted"], out.stdout + out.stderr


def test_a_callbacks_exception_still_stops_the_solve(cantilever_dict):
    class Enough(Exception):
        pass

    seen = []

    def progress(step, iteration, residual, energy):
        seen.append(iteration)
        if iteration == 2:
            raise Enough()

    with pytest.raises(Enough):
        rodnet.Scene.from_dict(cantilever_dict).solve(progress=progress)
    assert seen == [0, 1, 2]


LIMITED = textwrap.dedent(
    """
    import resource, sys
    import rodnet
    # A process allowed 768 MiB of data: its solves take half of it, as the CLI's --max-memory
    # default does, and a gridshell estimated above that is refused before it is allocated.
    cap = 768 << 20
    resource.setrlimit(resource.RLIMIT_DATA, (cap, resource.getrlimit(resource.RLIMIT_DATA)[1]))
    try:
        rodnet.gridshell.hemisphere(rods=100, subdivide=8)
        print("solved")
    except (rodnet.SceneError, rodnet.SolveError) as e:
        print("refused", e)
    """
)


def test_python_solves_take_the_processs_memory_limit(tmp_path):
    script = tmp_path / "limited.py"
    script.write_text(LIMITED)
    out = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, timeout=120
    )
    assert out.returncode == 0, out.stdout + out.stderr
    assert out.stdout.startswith("refused"), out.stdout + out.stderr
    assert "memory" in out.stdout, out.stdout
