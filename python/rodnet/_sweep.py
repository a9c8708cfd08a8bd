"""Parameter sweeps from Python: `rodnet.sweep` (docs/sweep.md)."""

import json
import os

from . import _convert, _rodnet

# Parsed sweeps per worker process, so that an executor's tasks parse each sweep once.
_plans = {}


def _plan(source):
    plan = _plans.get(source)
    if plan is None:
        text, file, base_dir, default_output = source
        plan = _rodnet.Sweep.parse(text, file, base_dir, default_output)
        _plans[source] = plan
    return plan


def run_point(source, index):
    """Solves one point of a sweep unless its results exist (what executors run). `source` is
    `Sweep.source`; returns the point's index, whether it converged and its error, if any."""
    record = _plan(source).run_point(index)
    return {
        "point": index,
        "converged": record.get("converged"),
        "error": record.get("sweep", {}).get("error"),
    }


def _sweep_text(d):
    """A dict sweep as JSON text; a NaN or a value of another type raises `SceneError` naming
    its place (`grid.rods[1]`), not a parse error at a column of the generated text."""
    try:
        return json.dumps(d, default=_convert.plain, allow_nan=False)
    except (TypeError, ValueError):
        found = _convert.locate(d)
        if found is None:
            raise
    field, message = found
    e = _rodnet.SceneError(f"{field}: {message}")
    e.path, e.line, e.column, e.field, e.message = None, None, None, field, message
    raise e


class SweepTable:
    """The merged table of a sweep: `rows` (dicts: point, parameters, converged, iterations,
    seconds, quantities, message), `csv` (the sweep.csv path), `missing` (points without
    results), `parameters` and `quantities` (column names)."""

    def __init__(self, csv, rows, missing, parameters, quantities):
        self.csv = csv
        self.rows = rows
        self.missing = missing
        self.parameters = parameters
        self.quantities = quantities

    def column(self, name):
        """One column as a NumPy array (None where a point has no value becomes NaN)."""
        import numpy as np

        values = [row.get(name) for row in self.rows]
        if all(isinstance(v, (int, float, bool)) or v is None for v in values):
            return np.array([np.nan if v is None else float(v) for v in values])
        return np.array(values, dtype=object)

    def __len__(self):
        return len(self.rows)

    def __repr__(self):
        ok = sum(1 for r in self.rows if r.get("converged"))
        return (
            f"SweepTable({len(self.rows)} points, {ok} converged, "
            f"{len(self.missing)} missing, csv={str(self.csv)!r})"
        )


def sweep(spec, *, executor=None, jobs=None, output=None):
    """Runs a parameter sweep and returns its `SweepTable`.

    `spec` is a sweep file (RON, docs/sweep.md) or the same content as a dict, e.g.
    `{"hemisphere": {"subdivide": 2}, "grid": {"rods": [6, 8], "section_ratio": [0.005, 0.01]},
    "output": "out"}` (a `Scene` may be given as `"scene"`). Points whose results exist are
    kept (resumable). Without `executor`, the points run on `jobs` native threads (default: the
    cores), one solve per thread, with the GIL released; with any
    `concurrent.futures.Executor` (a `ThreadPoolExecutor`, a `ProcessPoolExecutor`, Dask's
    `Client.get_executor()`, a Ray pool), one task per point runs `rodnet._sweep.run_point`
    and writes the point's results file, which must be readable here: a shared file system.

    A wrong parameter path or value raises `SceneError` (its `field` is the parameter) before
    anything is solved; a point that fails is recorded in the table and the others go on.
    """
    if isinstance(spec, (str, os.PathLike)):
        if output is not None:
            raise TypeError("output= applies to dict sweeps; a sweep file names its own")
        plan = _rodnet.Sweep.load(os.fspath(spec))
    elif isinstance(spec, dict):
        d = dict(spec)
        if isinstance(d.get("scene"), _rodnet.Scene):
            d["scene_ron"] = d.pop("scene").to_ron()
        if output is not None:
            d["output"] = os.fspath(output)
        text = _sweep_text(d)
        plan = _rodnet.Sweep.parse(text, "<sweep>", os.getcwd(), None)
    else:
        raise TypeError("spec must be a sweep file path or a dict")
    plan.write_manifest()
    if executor is None:
        plan.run(jobs or os.cpu_count() or 1)
    else:
        futures = [executor.submit(run_point, plan.source, i) for i in plan.pending()]
        for f in futures:
            f.result()
    csv, missing, rows = plan.merge()
    return SweepTable(csv, rows, missing, plan.parameters, plan.quantities)
