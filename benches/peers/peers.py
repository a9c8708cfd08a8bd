"""rodnet beside OpenSees and PyElastica on the same problems: runs, errors, time to accuracy.

    python peers.py [cantilever] [timoshenko] [grid10] [grid20]     (default: all four)
    python peers.py --from out/runs.csv                             (the tables of a past run)

Prints Markdown tables and writes out/runs.csv and out/summary.csv (PEERS_OUT to move them)."""
import csv
import os
import platform
import sys
import time
from importlib.metadata import version

import common
from common import TARGETS, fmt

RUN_HEADER = ["problem", "code", "level", "seconds", "seconds_all", "value", "error", "note"]
SUMMARY_HEADER = ["problem", "code", "target", "seconds_interpolated", "seconds_first_run", "rodnet_over_code_interpolated"]


def cantilever():
    import cantilever as c
    import reference
    for name, kw in (("extensible Kirchhoff", dict(EA=c.E * c.A)),
                     ("PyElastica Cosserat", dict(EA=c.E * c.A, GA=27 / 28 * c.G * c.A, pyelastica=True))):
        x, y = reference.rod_tip(c.L, c.EI, c.P, **kw)
        print(f"cantilever: the {name} rod's tip differs from the elastica's by {c.error(x, y):.2e} (relative)")
    print(f"cantilever: elastica tip ({c.REF[0]:.12f}, {c.REF[1]:.12f}) m")
    runs = {"rodnet": c.rodnet_runs(), common.RODNET_3: c.rodnet_three_level_runs(), "OpenSees": c.opensees_runs()}
    if not common.SKIP_PYELASTICA:
        runs["PyElastica"] = c.pyelastica_runs()
    return runs


def timoshenko():
    import timoshenko as t
    print("timoshenko: tip of the Cosserat rod ({:.12f}, {:.12f}) m, of the Kirchhoff rod ({:.12f}, {:.12f}) m"
          .format(*t.REF_COSSERAT, *t.REF_KIRCHHOFF))
    zeta, fractions = t.best_damping()
    print("timoshenko: PyElastica damping constant -> settling time / run time at n = 50: "
          + ", ".join(f"{z}: {f:.3f}" for z, f in fractions.items()) + f"; using {zeta}")
    return {"rodnet": t.rodnet_runs(), "PyElastica": t.pyelastica_runs(zeta)}


def grid(n):
    import grid as g
    runs = {"rodnet": g.rodnet_runs(n), "OpenSees": g.opensees_runs(n)}
    w = {}
    for code, rows in runs.items():
        w[code], p = g.richardson(rows)
        print(f"grid {n}x{n}: {code} Richardson extrapolate {w[code]:.10f} m (observed order {p:.2f})")
    print(f"grid {n}x{n}: extrapolates differ by {abs(w['rodnet'] - w['OpenSees']) / w['OpenSees']:.1e} (relative)")
    runs[common.RODNET_3] = g.rodnet_three_level_runs(n, w["rodnet"])
    return runs


def report(problem, runs, run_rows, summary_rows):
    rows = []
    for code, rs in runs.items():
        for r in rs:
            rows.append([code, r["n"], fmt(r["seconds"], ".4g"), " ".join(format(t, ".3g") for t in r["all_seconds"]),
                         fmt(r.get("value"), ".10g"), fmt(r["error"], ".2e"), r["note"]])
            run_rows.append([problem, code, r["n"], r["seconds"], " ".join(f"{t:.6g}" for t in r["all_seconds"]),
                             r.get("value"), r["error"], r["note"]])
    common.table(f"{problem}: runs", ["code", "level", "s (median)", "s (each)", "value", "rel. error", "note"], rows)
    times = {code: [common.time_to([r["error"] for r in rs], [r["seconds"] for r in rs], e) for e in TARGETS]
             for code, rs in runs.items()}
    rows = []
    ours = [c for c in times if c.startswith("rodnet")]
    for code, tt in times.items():
        # A peer's row compares it with each rodnet series (plain, and 3 levels when run).
        for mine in ours if not code.startswith("rodnet") else [None]:
            ratios = [None if mine is None or a is None or b is None else a / b
                      for a, b in zip((t[0] for t in times.get(mine, tt)), (t[0] for t in tt))]
            label = code if mine in (None, "rodnet") else f"{code} (vs {mine})"
            rows.append([label] + [f"{fmt(a)} ({fmt(b)})" for a, b in tt]
                        + ([""] * 3 if mine is None else [fmt(x) for x in ratios]))
            for e, (a, b), x in zip(TARGETS, tt, ratios):
                summary_rows.append([problem, label, e, a, b, x])
    common.table(f"{problem}: seconds to a relative error, interpolated (first run meeting it); rodnet / peer",
                 ["code"] + [f"to {e:g}" for e in TARGETS] + [f"ratio {e:g}" for e in TARGETS], rows)
    rows = []
    for code, rs in runs.items():
        for r in rs if not code.startswith("rodnet") else ():
            a, b = common.time_to([q["error"] for q in runs["rodnet"]], [q["seconds"] for q in runs["rodnet"]], r["error"])
            rows.append([code, r["n"], fmt(r["error"], ".2e"), fmt(r["seconds"], ".4g"), f"{fmt(a)} ({fmt(b)})",
                         fmt(None if a is None else a / r["seconds"])])
    common.table(f"{problem}: at each peer run's error, rodnet's time to reach it, interpolated (first run meeting it)",
                 ["code", "level", "rel. error", "peer s", "rodnet s", "rodnet / peer"], rows)


def from_csv(path):
    """The tables of an earlier run, from its runs.csv."""
    problems = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            num = lambda x: None if x in ("", "—") else float(x)
            problems.setdefault(r["problem"], {}).setdefault(r["code"], []).append(dict(
                n=int(r["level"]), seconds=num(r["seconds"]), all_seconds=[float(t) for t in r["seconds_all"].split()],
                value=num(r["value"]), error=num(r["error"]), note=r["note"]))
    for problem, runs in problems.items():
        report(problem, runs, [], [])


def main(problems):
    print(f"# rodnet peers, {time.strftime('%Y-%m-%d %H:%M')}, {platform.node()}, {os.cpu_count()} cores, "
          f"load average {os.getloadavg()[0]:.2f}")
    print(f"openseespy {version('openseespy')}, pyelastica {version('pyelastica')}, numpy {version('numpy')}, "
          f"scipy {version('scipy')}, Python {platform.python_version()}, rodnet {common.RODNET}")
    import opensees_run
    import pyelastica_run
    opensees_run.quiet()
    pyelastica_run.warm_up()
    run_rows, summary_rows = [], []
    jobs = {"cantilever": cantilever, "timoshenko": timoshenko,
            "grid10": lambda: grid(10), "grid20": lambda: grid(20)}
    for name in problems or jobs:
        t0 = time.perf_counter()
        report(name, jobs[name](), run_rows, summary_rows)
        print(f"\n({name}: {time.perf_counter() - t0:.0f} s in all, load average {os.getloadavg()[0]:.2f})")
        common.write_csv("runs.csv", RUN_HEADER, run_rows)
        common.write_csv("summary.csv", SUMMARY_HEADER, summary_rows)


if __name__ == "__main__":
    if sys.argv[1:2] == ["--from"]:
        from_csv(sys.argv[2])
    else:
        main(sys.argv[1:])
