#!/usr/bin/env python3
"""Read a packing into meshio and VTK from numpy, without an export file in between.

    PYTHONPATH=build/python python3 examples/python/read_packing.py [run.h5] --output out

Reads a native packing file (or packs a small graded sample when none is given), builds every
particle's surface in world coordinates from the Packing's views (shape vertices, rotations,
positions, scales) with numpy, and hands it to meshio (a Mesh with a per-triangle particle id,
written as OUTPUT/packing.vtu) and to VTK (a vtkPolyData, written as OUTPUT/packing.vtp). Checks
that the numpy surfaces equal the library's own world_vertices. Needs python3-meshio and
python3-vtk9. --small: the small sample (a test runs it).
"""
import argparse
import os

import numpy as np

import aggpack

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("packing", nargs="?", help="native packing file (.h5)")
parser.add_argument("--output", default=".", help="folder for packing.vtu and packing.vtp")
parser.add_argument("--small", action="store_true", help="pack a small sample (no file needed)")
args = parser.parse_args()

if args.packing:
    packing = aggpack.read(args.packing)
else:
    side = 0.03 if args.small else 0.1
    packing = aggpack.pack(aggpack.pack_config({
        "container": {"length": side, "width": side, "depth": side},
        "grading": {"kind": "fuller", "size_min": 0.004, "size_max": 0.01},
        "particle": {"edge_length": 0.0, "edge_length_ratio": 0.8},
        "packer": {"kind": "random", "target_fraction": 0.3}}))


def rotation_matrices(q):
    """(N, 4) unit quaternions, scalar last (x, y, z, w) -> (N, 3, 3) rotation matrices."""
    x, y, z, w = q.T
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], -1),
        np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], -1),
        np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], -1),
    ], -2)


rotations = rotation_matrices(packing.rotations)
points, triangles, particle_id = [], [], []
offset = 0
for i, shape in enumerate(packing.shape_indices):
    local = packing.shape_vertices(shape) * packing.scales[i]
    world = local @ rotations[i].T + packing.positions[i]
    points.append(world)
    triangles.append(packing.shape_triangles(shape).astype(np.int64) + offset)
    particle_id.append(np.full(len(triangles[-1]), i + 1, dtype=np.int32))
    offset += len(world)
points = np.concatenate(points)
triangles = np.concatenate(triangles)
particle_id = np.concatenate(particle_id)
# The same surfaces as the library computes them.
np.testing.assert_allclose(points[: len(packing.shape_vertices(packing.shape_indices[0]))],
                           packing.world_vertices(0), atol=1e-12)

os.makedirs(args.output, exist_ok=True)
import meshio  # noqa: E402

mesh = meshio.Mesh(points, [("triangle", triangles)], cell_data={"particle": [particle_id]})
vtu = os.path.join(args.output, "packing.vtu")
mesh.write(vtu)
back = meshio.read(vtu)
assert len(back.points) == len(points) and len(back.cells[0].data) == len(triangles)
print(f"meshio: {len(packing)} particles, {len(points)} points, {len(triangles)} triangles "
      f"-> {vtu}")

import vtk  # noqa: E402
from vtk.util import numpy_support  # noqa: E402

poly = vtk.vtkPolyData()
vtk_points = vtk.vtkPoints()
vtk_points.SetData(numpy_support.numpy_to_vtk(points, deep=True))
poly.SetPoints(vtk_points)
connectivity = np.hstack([np.full((len(triangles), 1), 3), triangles]).ravel()
cells = vtk.vtkCellArray()
cells.SetCells(len(triangles), numpy_support.numpy_to_vtkIdTypeArray(connectivity, deep=True))
poly.SetPolys(cells)
ids = numpy_support.numpy_to_vtk(particle_id, deep=True)
ids.SetName("particle")
poly.GetCellData().AddArray(ids)
writer = vtk.vtkXMLPolyDataWriter()
vtp = os.path.join(args.output, "packing.vtp")
writer.SetFileName(vtp)
writer.SetInputData(poly)
assert writer.Write() == 1
mass = vtk.vtkMassProperties()
mass.SetInputData(poly)
mass.Update()
volume = packing.descriptors()["volume"].sum()
print(f"vtk: {poly.GetNumberOfCells()} triangles -> {vtp}; enclosed volume "
      f"{mass.GetVolume():.6g} m^3 (aggpack: {volume:.6g} m^3)")
assert abs(mass.GetVolume() - volume) < 1e-6 * max(volume, 1e-12) + 1e-12
