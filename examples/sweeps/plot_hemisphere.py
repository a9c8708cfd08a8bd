"""Draws docs/img/sweep_hemisphere.png from the table of examples/sweeps/hemisphere.ron.

    rodnet sweep examples/sweeps/hemisphere.ron
    python examples/sweeps/plot_hemisphere.py examples/sweeps/hemisphere-sweep/sweep.csv out.png
"""

import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

rows = list(csv.DictReader(open(sys.argv[1])))
fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
for q in sorted({float(r["section_ratio [1]"]) for r in rows}):
    sel = [r for r in rows if float(r["section_ratio [1]"]) == q]
    n = [int(r["rods [1]"]) for r in sel]
    for ax, key in zip(axes, ["max_abs_radial_deviation", "rms_radial_deviation"]):
        ax.plot(n, [float(r[f"target.{key} [1]"]) for r in sel], "o-", label=f"r/R = {q}")
axes[0].set_ylabel("max |radial deviation| / R")
axes[1].set_ylabel("rms radial deviation / R")
for a in axes:
    a.set_xlabel("rods per family n")
    a.grid(alpha=0.3)
axes[0].legend(fontsize=8)
fig.suptitle("rodnet sweep examples/sweeps/hemisphere.ron (subdivide 4, ball joints)", fontsize=10)
fig.tight_layout()
fig.savefig(sys.argv[2], dpi=100)
