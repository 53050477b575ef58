#!/usr/bin/env python3
"""Shape study: histograms of the measured shape descriptors for several values of alpha.

    PYTHONPATH=build/python python3 examples/python/shape_study.py --output out

Grows N particles per alpha (Eq. 3 shape control) with r = 10 mm and L = 6 mm
(aggpack.generate_particles, the numbers `aggpack shapes` writes) and draws the distributions of
sphericity (Eq. 1), elongation I/L and flatness S/I. Writes OUTPUT/shape_study.png.
--small grows 300 particles per alpha instead of 5,000. Needs python3-matplotlib.
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import aggpack  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", default=".", help="folder for shape_study.png")
parser.add_argument("--small", action="store_true", help="300 particles per alpha")
args = parser.parse_args()

count = 300 if args.small else 5000
alphas = (0.2, 0.5, 0.8, 1.0)
names = (("sphericity", "sphericity SI (Eq. 1)"), ("elongation", "elongation I/L"),
         ("flatness", "flatness S/I"))
fig, axes = plt.subplots(1, 3, figsize=(11, 3.6), dpi=110)
for alpha in alphas:
    d = aggpack.generate_particles(count, alpha=alpha, radius=0.01, edge_length=0.006, seed=1)
    print(f"alpha {alpha:.1f}: sphericity {d['sphericity'].mean():.3f} "
          f"+- {d['sphericity'].std():.3f}, measured alpha {d['measured_alpha'].mean():.3f}")
    for ax, (key, _) in zip(axes, names):
        ax.hist(d[key], bins=np.linspace(0.3, 1.0, 36), histtype="step", lw=1.4,
                density=True, label=f"alpha = {alpha:.1f}")
for ax, (_, label) in zip(axes, names):
    ax.set_xlabel(label)
    ax.grid(alpha=0.3)
axes[0].set_ylabel("probability density")
axes[0].legend(fontsize=8)
fig.suptitle(f"Shape descriptors of {count} particles per alpha (r = 10 mm, L = 6 mm)")
fig.tight_layout()
os.makedirs(args.output, exist_ok=True)
path = os.path.join(args.output, "shape_study.png")
fig.savefig(path)
print(f"wrote {path}")
