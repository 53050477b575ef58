#!/usr/bin/env python3
"""Plot a cut through a mesomodel phase image (aggpack mesomodel --voxels N -o BASE.raw).

    aggpack pack examples/concrete-fuller.toml -o c.h5
    aggpack mesomodel c.h5 --voxels 256 --itz 0.0005 -o c.raw
    python3 examples/python/plot_voxel_cut.py c.json cut.png [--z 0.5]

Reads BASE.json (dims, spacing, file names, phase codes) and BASE.phase.raw (uint8, x fastest),
draws the horizontal cut at the given fraction of the height: aggregate blue, ITZ red, mortar
grey, outside white. Needs numpy and matplotlib (python3-numpy, python3-matplotlib).
"""
import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("header", help="BASE.json written by aggpack mesomodel")
parser.add_argument("png", help="picture to write")
parser.add_argument("--z", type=float, default=0.5, help="cut height as a fraction, [0, 1]")
args = parser.parse_args()

header = json.load(open(args.header))
nx, ny, nz = header["dims"]
folder = os.path.dirname(os.path.abspath(args.header))
phase = np.fromfile(os.path.join(folder, header["files"]["phase"]["path"]), dtype=np.uint8)
phase = phase.reshape(nz, ny, nx)
k = min(nz - 1, max(0, int(args.z * nz)))
h = header["spacing_m"] * 1000.0
extent = [0, nx * h, 0, ny * h]
colours = ListedColormap(["#c8c8c8", "#e05050", "#5070b0", "#ffffff"])
fractions = header["voxel_volume_fractions"]
plt.figure(figsize=(6, 6))
plt.imshow(phase[k], origin="lower", cmap=colours, vmin=0, vmax=3, interpolation="nearest",
           extent=extent)
plt.xlabel("x / mm")
plt.ylabel("y / mm")
plt.title("cut at z = %.1f mm: aggregate %.1f %%, ITZ %.1f %%, mortar %.1f %%"
          % ((k + 0.5) * h, 100 * fractions["aggregate"], 100 * fractions["itz"],
             100 * fractions["mortar"]), fontsize=9)
plt.savefig(args.png, dpi=110, bbox_inches="tight")
print("wrote", args.png)
