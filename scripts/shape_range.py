#!/usr/bin/env python3
"""The shapes the generator reaches: mean descriptors over a grid of inputs, for each growth rule.

Draws two panels into a PNG: elongation vs flatness, and sphericity vs V / V_circ (volume over the
smallest enclosing sphere's), one point per input set (mean of COUNT particles), the paper's two
acrylic particles marked by their measured V / V_circ. Also writes the points as CSV beside it.

    PYTHONPATH=build/python python3 scripts/shape_range.py docs/images/shape-range.png [COUNT]

Grid: hull growth over alpha {0, 0.25, 0.5, 0.75, 1} x L/r {0.35, 0.5, 0.7, 1, 1.4} x control
axis ratios (elongation, flatness) {(1, 1), (0.7, 1), (1, 0.7), (0.5, 0.5), (0.35, 1), (1, 0.35),
(0.35, 0.35)}; midpoint growth (aggpack 0.1's rule) over the same alpha x L/r on a sphere.
"""

import csv
import itertools
import sys

import aggpack
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ALPHAS = [0.0, 0.25, 0.5, 0.75, 1.0]
EDGE_RATIOS = [0.35, 0.5, 0.7, 1.0, 1.4]
AXES = [(1, 1), (0.7, 1), (1, 0.7), (0.5, 0.5), (0.35, 1), (1, 0.35), (0.35, 0.35)]
# Table 1 of the paper: V / (pi/6 D^3) of the two acrylic particles.
ACRYLIC = {"acrylic 1 (390.3 mm^3, 10 mm)": 0.7454, "acrylic 2 (467.2 mm^3, 12.5 mm)": 0.4569}


def mean(values):
    return float(sum(values)) / len(values)


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "shape-range.png"
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 100
    rows = []
    cases = [("hull", a, l, e, f) for a, l, (e, f) in itertools.product(ALPHAS, EDGE_RATIOS, AXES)]
    cases += [("midpoint", a, l, 1.0, 1.0) for a, l in itertools.product(ALPHAS, EDGE_RATIOS)]
    for growth, alpha, edge_ratio, elongation, flatness in cases:
        d = aggpack.generate_particles(count, alpha=alpha, radius=1.0, edge_length=edge_ratio,
                                       growth=growth, elongation=elongation, flatness=flatness,
                                       seed=1)
        rows.append({"growth": growth, "alpha": alpha, "edge_ratio": edge_ratio,
                     "elongation_input": elongation, "flatness_input": flatness,
                     "volume_ratio": mean(d["volume_ratio"]), "sphericity": mean(d["sphericity"]),
                     "elongation": mean(d["elongation"]), "flatness": mean(d["flatness"])})
    with open(path.rsplit(".", 1)[0] + ".csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)

    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5.2))
    style = {"hull": dict(color="tab:blue", marker="o", s=14, alpha=0.7),
             "midpoint": dict(color="tab:red", marker="x", s=22, alpha=0.9)}
    for growth in ("hull", "midpoint"):
        points = [r for r in rows if r["growth"] == growth]
        label = {"hull": "hull (default: the paper's words)", "midpoint": "midpoint (aggpack 0.1)"}
        left.scatter([p["flatness"] for p in points], [p["elongation"] for p in points],
                     label=label[growth], **style[growth])
        right.scatter([p["volume_ratio"] for p in points], [p["sphericity"] for p in points],
                      label=label[growth], **style[growth])
    for name, ratio in ACRYLIC.items():
        right.axvline(ratio, color="tab:green", linestyle="--", linewidth=1)
        right.text(ratio, 0.42, " " + name, rotation=90, fontsize=8, color="tab:green",
                   va="bottom")
    left.set_xlabel("flatness S / I (mean)")
    left.set_ylabel("elongation I / L (mean)")
    left.set_title("Form: elongation vs flatness")
    right.set_xlabel("V / V_circ (smallest enclosing sphere, mean)")
    right.set_ylabel("sphericity SI, Eq. 1 (mean)")
    right.set_title("Fullness: sphericity vs V / V_circ")
    for axis in (left, right):
        axis.set_xlim(0, 1.02)
        axis.set_ylim(0.3 if axis is right else 0, 1.02)
        axis.grid(True, alpha=0.3)
        axis.legend(loc="lower right", fontsize=8)
    fig.suptitle(f"Reachable shapes: means of {count} particles per input set "
                 f"(alpha x L/r x control axis ratios)")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    print(f"wrote {path} and {path.rsplit('.', 1)[0]}.csv ({len(rows)} input sets)")


if __name__ == "__main__":
    main()
