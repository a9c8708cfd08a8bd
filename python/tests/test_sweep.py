"""rodnet.sweep: local threads, resumability, bad input, and a real Dask cluster."""

import csv
import os

import pytest

import rodnet


def scene_sweep(cantilever_dict, **extra):
    spec = {
        "scene": rodnet.Scene.from_dict(cantilever_dict),
        "grid": {"materials.steel.young_modulus": [1e8, 2e8, 4e8]},
        "zip": {"rods.beam.subdivide": [4, 8]},
        "output": "out",
    }
    spec.update(extra)
    return spec


def test_scene_sweep_table_resume_and_units(cantilever_dict, tmp_path):
    table = rodnet.sweep(scene_sweep(cantilever_dict), jobs=2)
    assert len(table) == 6 and not table.missing
    assert all(r["converged"] for r in table.rows)
    # Stiffer rods store less energy under the same load (|E| ~ P^2 L^3 / EI).
    e = table.column("energy.total").reshape(3, 2)
    assert (abs(e[0]) > abs(e[1])).all() and (abs(e[1]) > abs(e[2])).all()
    header = next(csv.reader(open(table.csv)))
    assert "materials.steel.young_modulus [Pa]" in header and "energy.total [J]" in header
    assert "seconds [s]" in header and "converged" in header
    files = sorted(p for p in (tmp_path / "out").iterdir() if p.name.startswith("materials"))
    assert len(files) == 6
    stamps = [p.stat().st_mtime_ns for p in files]
    again = rodnet.sweep(scene_sweep(cantilever_dict), jobs=2)
    assert [p.stat().st_mtime_ns for p in files] == stamps
    assert again.column("energy.total").tolist() == table.column("energy.total").tolist()


def test_bad_parameter_is_refused_before_any_solve(cantilever_dict, tmp_path):
    spec = scene_sweep(cantilever_dict, grid={"materials.steel.young_modulas": [1e8]})
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.sweep(spec)
    assert e.value.field == "materials.steel.young_modulas"
    spec = scene_sweep(cantilever_dict, grid={"rods.beam.subdivide": ["many"]}, zip={})
    with pytest.raises(rodnet.SceneError) as e:
        rodnet.sweep(spec)
    assert e.value.field == "rods.beam.subdivide"
    assert not (tmp_path / "out").exists()


def test_a_failing_point_is_recorded_and_the_others_finish(cantilever_dict):
    spec = scene_sweep(cantilever_dict, grid={"solver.max_iterations": [1, 200]}, zip={})
    table = rodnet.sweep(spec, jobs=2)
    bad, good = table.rows
    assert bad["converged"] is False and bad["message"]
    assert good["converged"] is True and good["message"] is None


def test_sweep_on_a_dask_local_cluster(tmp_path):
    distributed = pytest.importorskip("distributed")
    spec = {
        "hemisphere": {"subdivide": 2},
        "grid": {"rods": [4, 6], "section_ratio": [0.005, 0.01]},
        "output": "dask",
    }
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address=None,
    ) as cluster, distributed.Client(cluster) as client:
        table = rodnet.sweep(spec, executor=client.get_executor())
        workers = len(client.scheduler_info()["workers"])
    assert workers == 2
    assert len(table) == 4 and all(r["converged"] for r in table.rows)
    local = rodnet.sweep(dict(spec, output="local"))
    for a, b in zip(table.rows, local.rows):
        assert a["target.max_abs_radial_deviation"] == pytest.approx(
            b["target.max_abs_radial_deviation"], rel=1e-8
        )
    # The dome is closer to the sphere with more rods.
    dev = table.column("target.max_abs_radial_deviation").reshape(2, 2)
    assert (dev[1] < dev[0]).all()


def test_thread_pool_executor_runs_points(cantilever_dict):
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(2) as pool:
        table = rodnet.sweep(scene_sweep(cantilever_dict), executor=pool)
    assert len(table) == 6 and all(r["converged"] for r in table.rows)
    assert os.path.exists(table.csv)
