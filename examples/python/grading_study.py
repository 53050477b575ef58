#!/usr/bin/env python3
"""Grading study: pack three gradings and plot the achieved sieve curves against the targets.

    PYTHONPATH=build/python python3 examples/python/grading_study.py --output docs/images

Packs a 100 mm cube by random sequential addition (largest first) to 30 % solid with three
gradings of the same 5-20 mm range: Fuller-Thompson (q = 0.5), a coarser power law (q = 1) and a
gap-graded sieve table. The achieved curve is the volume percent passing of the packing's exact
particle volumes by control diameter (Packing.statistics(), as `aggpack info` computes it).
Writes OUTPUT/grading_study.png. --small packs a 50 mm cube (a test runs it so it does not rot).
Needs python3-matplotlib.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import aggpack  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", default=".", help="folder for grading_study.png")
parser.add_argument("--small", action="store_true", help="a 50 mm cube instead of 100 mm")
args = parser.parse_args()

side = 0.05 if args.small else 0.1  # m
base = {
    "container": {"kind": "box", "length": side, "width": side, "depth": side,
                  "wall_gap": 0.001},
    "particle": {"alpha": 0.6, "edge_length": 0.0, "edge_length_ratio": 0.8},
    "packer": {"kind": "random", "seed": 1, "target_fraction": 0.30, "gap": 0.0005},
}
gradings = {
    "Fuller-Thompson, q = 0.5": {"kind": "fuller", "size_min": 0.005, "size_max": 0.02,
                                 "exponent": 0.5},
    "power law, q = 1 (coarser)": {"kind": "fuller", "size_min": 0.005, "size_max": 0.02,
                                   "exponent": 1.0},
    "gap-graded sieve table": {"kind": "sieve",
                               "sieve": [[0.005, 0.0], [0.008, 40.0], [0.014, 45.0],
                                         [0.02, 100.0]]},
}
sieves = np.geomspace(0.005, 0.02, 25)  # m

fig, ax = plt.subplots(figsize=(7.5, 4.8), dpi=120)
for (name, grading), colour in zip(gradings.items(), ("C0", "C1", "C2")):
    config = aggpack.pack_config({**base, "grading": grading})
    packing = aggpack.pack(config)
    stats = packing.statistics(descriptors=False, sieve_sizes=list(sieves))
    curve = stats["grading"]
    size_mm = 1000 * curve["size"]
    ax.plot(size_mm, curve["target_percent"], "--", color=colour, lw=1.2)
    ax.plot(size_mm, curve["achieved_percent"], "o-", color=colour, ms=3,
            label=f"{name}: {len(packing)} particles, {100 * stats['solid_fraction']:.1f} %")
    worst = np.abs(curve["achieved_percent"] - curve["target_percent"]).max()
    print(f"{name}: {len(packing)} particles, solid {stats['solid_fraction']:.3f}, "
          f"largest deviation from the target {worst:.1f} % passing")
ax.set_xscale("log")
ax.set_xticks([5, 8, 10, 14, 20])
ax.get_xaxis().set_major_formatter(matplotlib.ticker.ScalarFormatter())
ax.get_xaxis().set_minor_formatter(matplotlib.ticker.NullFormatter())
ax.set_xlabel("sieve size = control diameter (mm)")
ax.set_ylabel("volume % passing")
ax.set_title(f"Achieved (solid) vs target (dashed) grading, {1000 * side:.0f} mm cube")
ax.grid(True, which="both", alpha=0.3)
ax.legend(fontsize=8, loc="upper left")
fig.tight_layout()
os.makedirs(args.output, exist_ok=True)
path = os.path.join(args.output, "grading_study.png")
fig.savefig(path)
print(f"wrote {path}")
