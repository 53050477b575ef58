#!/usr/bin/env python3
"""Draw a periodic RVE and its homogenised stiffness in one picture.

    aggpack pack examples/periodic-rve.toml -o rve.h5
    aggpack mesomodel rve.h5 -o rve.inp --homogenize --solver iterative
    aggpack render rve.h5 -o rve.png
    aggpack render rve.h5 --mesomodel-cut z=0.02 -o rve-cut.png
    python3 examples/python/plot_rve.py rve.png rve-cut.png rve-stiffness.json rve-figure.png

Three panels: the packing, the cut through its mesomodel, and the 6x6 stiffness tensor (GPa,
Voigt order 11 22 33 23 13 12) from RVE-stiffness.json with the isotropic projection's E and nu
beside the Reuss, Hashin-Shtrikman and Voigt bounds. Needs matplotlib (python3-matplotlib).
"""
import argparse
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("packing", help="PNG of aggpack render RUN.h5")
parser.add_argument("cut", help="PNG of aggpack render RUN.h5 --mesomodel-cut AXIS=VALUE")
parser.add_argument("stiffness", help="OUT-stiffness.json of aggpack mesomodel --homogenize")
parser.add_argument("png", help="picture to write")
args = parser.parse_args()

result = json.load(open(args.stiffness))
c = [[value * 1e-9 for value in row] for row in result["stiffness_pa"]]
iso = result["isotropic_projection"]
bounds = result["bounds"]
size = [1000 * s for s in result["rve"]["size_m"]]

figure = plt.figure(figsize=(15, 5.4))
grid = figure.add_gridspec(2, 3, height_ratios=[3, 1.1], width_ratios=[1.25, 1, 1])
for column, (path, title) in enumerate([
        (args.packing, f"periodic RVE {size[0]:g} x {size[1]:g} x {size[2]:g} mm"),
        (args.cut, "mesomodel cut (aggregate / mortar tetrahedra)")]):
    axes = figure.add_subplot(grid[:, column])
    image = mpimg.imread(path)
    if column == 0:  # the render has a wide margin around the box
        h, w = image.shape[:2]
        image = image[int(0.12 * h):int(0.92 * h), int(0.25 * w):int(0.75 * w)]
    axes.imshow(image)
    axes.set_title(title, fontsize=11)
    axes.axis("off")

axes = figure.add_subplot(grid[0, 2])
largest = max(abs(v) for row in c for v in row)
axes.imshow([[abs(v) for v in row] for row in c], cmap="Blues", vmin=0, vmax=1.6 * largest)
labels = result["voigt_order"]
axes.set_xticks(range(6), labels)
axes.set_yticks(range(6), labels)
for i in range(6):
    for j in range(6):
        axes.text(j, i, f"{c[i][j]:.1f}", ha="center", va="center", fontsize=8)
axes.set_title(f"stiffness (GPa), CalculiX {result['solver']['wall_seconds']:.0f} s", fontsize=11)

axes = figure.add_subplot(grid[1, 2])
marks = [("Reuss", bounds["reuss_youngs_modulus_pa"]),
         ("HS lower", bounds["hashin_shtrikman_lower"]["youngs_modulus_pa"]),
         ("HS upper", bounds["hashin_shtrikman_upper"]["youngs_modulus_pa"]),
         ("Voigt", bounds["voigt_youngs_modulus_pa"])]
for k, (name, value) in enumerate(marks):
    axes.axvline(value * 1e-9, color="0.5", lw=1, ls=":" if name in ("Reuss", "Voigt") else "-")
    axes.text(value * 1e-9, 1.05 + 0.32 * (k % 2), name, ha="center", fontsize=8,
              transform=axes.get_xaxis_transform())
axes.plot([iso["youngs_modulus_pa"] * 1e-9], [0.5], "o", color="tab:red")
axes.set_yticks([])
axes.set_ylim(0, 1)
axes.set_xlabel(f"E (GPa): RVE {iso['youngs_modulus_pa'] * 1e-9:.2f}, "
                f"nu {iso['poisson_ratio']:.3f}")
figure.tight_layout()
figure.savefig(args.png, dpi=100)
print(f"wrote {args.png}")
