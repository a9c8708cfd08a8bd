"""Runs a notebook's code cells in order as one script, printing each cell's output; with
--write, stores that output (text) in the notebook's cells, as Jupyter would have. Used by the
Python tests (python/tests/test_notebook.py) without Jupyter.

    python examples/python/run_notebook.py examples/python/tour.ipynb [--write]
"""

import contextlib
import io
import json
import sys


def run(path, write=False):
    nb = json.load(open(path))
    env = {"__name__": "__main__"}
    for k, cell in enumerate(nb["cells"]):
        if cell["cell_type"] != "code":
            continue
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            exec(compile("".join(cell["source"]), f"{path} cell {k}", "exec"), env)
        text = out.getvalue()
        sys.stdout.write(text)
        cell["outputs"] = (
            [{"name": "stdout", "output_type": "stream", "text": text.splitlines(True)}]
            if text
            else []
        )
    if write:
        with open(path, "w") as f:
            json.dump(nb, f, indent=1, ensure_ascii=False)
            f.write("\n")
    return env


if __name__ == "__main__":
    run(sys.argv[1], write="--write" in sys.argv[2:])
