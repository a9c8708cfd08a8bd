"""Shared helpers: running rodnet on generated scenes, timing, errors, tables and CSV."""
import atexit
import csv
import json
import os
import shutil
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
RODNET = os.environ.get("RODNET") or str(
    Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "release" / "rodnet")
OUT = Path(os.environ.get("PEERS_OUT", HERE / "out"))
REPS = int(os.environ.get("PEERS_REPS", "3"))
# PyElastica's cantilever runs take minutes each: PEERS_SKIP_PYELASTICA=1 leaves them out there.
SKIP_PYELASTICA = os.environ.get("PEERS_SKIP_PYELASTICA") == "1"
QUICK = os.environ.get("PEERS_QUICK") == "1"  # smoke test: the first levels of each sequence only
LONG = 60.0  # a run longer than this (s) is not repeated
TARGETS = (1e-3, 1e-4, 1e-5)
TMP = Path(tempfile.mkdtemp(prefix="rodnet-peers-"))  # the generated scenes, removed at exit
atexit.register(shutil.rmtree, TMP, ignore_errors=True)


def levels(seq):
    return seq[:4] if QUICK else seq


def vec(v):
    return "(" + ", ".join(repr(float(c)) for c in v) + ")"


# `rodnet solve --extrapolate --levels 3`: the scene at ×1, ×2 and ×4 its subdivision, the h² and
# h³ terms removed (docs/convergence.md); its series is "rodnet, 3 levels", at the coarse level.
THREE_LEVELS = ("--extrapolate", "--levels", "3")
RODNET_3 = "rodnet, 3 levels"


def rodnet_solve(name, scene, args=()):
    """Write the RON scene, run `rodnet solve` on it (with `args`) and return (wall seconds,
    results dict). The wall time is the whole process: start-up, parsing, the solves and writing
    the JSON."""
    ron, out = TMP / f"{name}.ron", TMP / f"{name}.json"
    ron.write_text(scene)
    t0 = time.perf_counter()
    proc = subprocess.run([RODNET, "solve", str(ron), "--json", str(out), "--quiet", *args],
                          capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode not in (0, 1):
        raise RuntimeError(f"rodnet failed on {ron}: {proc.stderr}")
    return wall, json.loads(out.read_text())


def repeat(run, reps=None):
    """Run `run()` -> (seconds, value) `reps` times (once if it takes over LONG seconds);
    return (median seconds, all seconds, value of the last run)."""
    times, value = [], None
    for _ in range(reps or REPS):
        t, value = run()
        times.append(t)
        if t > LONG:
            break
    return statistics.median(times), times, value


def time_to(errors, times, target):
    """Time to reach a relative error: (log-log interpolation, time of the first run meeting it).
    Runs are in order of refinement; the first run meeting the target is the first from which on
    every finer run meets it too (coarse levels can meet it by a lucky cancellation and lose it
    again).  Interpolated between that run and the one before it.  None when no run reaches it."""
    i = len(errors)
    while i > 0 and errors[i - 1] <= target:
        i -= 1
    if i == len(errors):
        return None, None
    if i == 0:
        return times[0], times[0]
    (e0, t0), (e, t) = (errors[i - 1], times[i - 1]), (errors[i], times[i])
    f = np.log(target / e0) / np.log(e / e0)
    return float(np.exp(np.log(t0) + f * np.log(t / t0))), t


def fmt(x, spec=".3g"):
    return "—" if x is None else format(x, spec)


def table(title, header, rows):
    """Print a Markdown table (so the output can be pasted into docs/performance.md)."""
    print(f"\n### {title}\n")
    print("| " + " | ".join(header) + " |")
    print("|" + "|".join("---" if i == 0 else "---:" for i in range(len(header))) + "|")
    for r in rows:
        print("| " + " | ".join(str(c) for c in r) + " |")


def write_csv(name, header, rows):
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / name, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)
    print(f"\n(wrote {OUT / name})")
