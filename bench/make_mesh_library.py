#!/usr/bin/env python3
"""Writes N bumpy, non-convex particle meshes of exactly 20,000 triangles each as binary STL
(a latitude-longitude sphere of 100 segments x 100 rings + 2 poles with a random radial relief), for
bench/shape_library.sh. Usage: make_mesh_library.py FOLDER N [SEED]."""
import os
import sys

import numpy as np


def bumpy_sphere(rng, segments=100, rings=102):
    theta = np.linspace(0.0, np.pi, rings)[1:-1]          # interior rings
    phi = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    coeff = rng.normal(0.0, 0.06, size=(4, 4))
    radius = 1.0 + sum(coeff[i, j] * np.sin((i + 1) * t) * np.cos((j + 1) * p + i)
                       for i in range(4) for j in range(4))
    radius *= 1.0 + 0.01 * rng.standard_normal(radius.shape)  # scan noise: non-convex
    points = np.stack([radius * np.sin(t) * np.cos(p), radius * np.sin(t) * np.sin(p),
                       radius * np.cos(t) * 0.7], axis=-1).reshape(-1, 3)
    points = np.vstack([points, [[0, 0, 0.7 * (1 + coeff[0, 0])], [0, 0, -0.7 * (1 - coeff[1, 1])]]])
    north, south = len(points) - 2, len(points) - 1
    index = np.arange((rings - 2) * segments).reshape(rings - 2, segments)
    triangles = []
    for j in range(segments):
        k = (j + 1) % segments
        triangles.append((north, index[0, j], index[0, k]))
        triangles.append((south, index[-1, k], index[-1, j]))
    a = index[:-1, :]
    b = index[:-1, np.r_[1:segments, 0]]
    c = index[1:, :]
    d = index[1:, np.r_[1:segments, 0]]
    quads = np.stack([np.stack([a, c, b], -1), np.stack([b, c, d], -1)], 2).reshape(-1, 3)
    triangles = np.vstack([np.array(triangles), quads])
    return points * 5.0, triangles  # ~10 mm particles, coordinates in mm


def write_stl(path, points, triangles):
    record = np.zeros(len(triangles), dtype=[("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")])
    record["v"] = points[triangles].astype(np.float32)
    with open(path, "wb") as out:
        out.write(b"bumpy rock".ljust(80, b" "))
        out.write(np.uint32(len(triangles)).tobytes())
        out.write(record.tobytes())


def main():
    folder, count = sys.argv[1], int(sys.argv[2])
    rng = np.random.default_rng(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
    os.makedirs(folder, exist_ok=True)
    for i in range(count):
        points, triangles = bumpy_sphere(rng)
        assert len(triangles) == 20000
        write_stl(os.path.join(folder, f"rock{i:04d}.stl"), points, triangles)


if __name__ == "__main__":
    main()
