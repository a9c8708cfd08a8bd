"""The example notebook runs as a script and prints what it claims."""

import importlib.util

from conftest import ROOT


def test_tour_notebook_runs(monkeypatch, capsys):
    monkeypatch.setenv("RODNET_ROOT", str(ROOT))
    spec = importlib.util.spec_from_file_location(
        "run_notebook", ROOT / "examples" / "python" / "run_notebook.py"
    )
    runner = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(runner)
    env = runner.run(str(ROOT / "examples" / "python" / "tour.ipynb"))
    out = capsys.readouterr().out
    assert "tip deflection v/L = 0.49" in out
    table = env["table"]
    assert len(table) == 12 and not table.missing
    assert all(row["converged"] for row in table.rows)
