"""particle.library from Python: a shape library of meshes this test writes (ASCII STL, OBJ, PLY),
given as a folder, as a list of files, in a dict or in TOML. Every placed particle must be one of
the library's shapes: recognised by its vertex count and by volume / diameter^3, which neither
the particle's scale nor its rotation changes, against the exact values of the solids written."""
import itertools
import math

import numpy as np
import pytest

import aggpack

# Convex solids in mm: (vertices, faces as vertex loops). Their exact volume / diameter^3 is
# computed below from the formulas, not from the meshes.
TETRA = ([(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)],
         [(0, 1, 2), (0, 1, 3), (0, 2, 3), (1, 2, 3)])
OCTA = ([(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)],
        [(a, b, c) for a in (0, 1) for b in (2, 3) for c in (4, 5)])
BOX = ([(x, y, z) for x in (0, 1) for y in (0, 2) for z in (0, 3)],
       [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)])
PRISM = ([(math.cos(2 * math.pi * k / 5), math.sin(2 * math.pi * k / 5), z)
          for z in (0.0, 1.5) for k in range(5)],
         [tuple(range(5)), tuple(range(5, 10))] +
         [(k, (k + 1) % 5, 5 + (k + 1) % 5, 5 + k) for k in range(5)])

# Exact volume / (largest vertex distance)^3 of each solid, keyed by its vertex count.
EXACT_RATIO = {
    4: (8.0 / 3.0) / (2.0 * math.sqrt(2.0)) ** 3,  # tetrahedron: V = 8/3, edge 2 sqrt 2
    6: (4.0 / 3.0) / 2.0 ** 3,  # octahedron: V = 4/3, diagonal 2
    8: 6.0 / math.sqrt(1 + 4 + 9) ** 3,  # box 1 x 2 x 3: V = 6, diagonal sqrt 14
}


def triangles(solid):
    """The solid's faces fanned into triangles, each turned to face away from the centroid."""
    vertices = np.array(solid[0], dtype=float)
    centre = vertices.mean(axis=0)
    out = []
    for loop in solid[1]:
        for k in range(1, len(loop) - 1):
            a, b, c = loop[0], loop[k], loop[k + 1]
            normal = np.cross(vertices[b] - vertices[a], vertices[c] - vertices[a])
            out.append((a, b, c) if normal @ (vertices[a] - centre) > 0 else (a, c, b))
    return vertices, out


def stl_ascii(solid):
    vertices, tris = triangles(solid)
    lines = ["solid test"]
    for tri in tris:
        lines += ["facet normal 0 0 0", "outer loop"]
        lines += ["vertex {} {} {}".format(*vertices[i]) for i in tri]
        lines += ["endloop", "endfacet"]
    return "\n".join(lines + ["endsolid test", ""])


def obj_text(solid):
    vertices, tris = triangles(solid)
    return "".join("v {} {} {}\n".format(*v) for v in vertices) + "".join(
        "f {} {} {}\n".format(*(i + 1 for i in tri)) for tri in tris)


def ply_ascii(solid):
    vertices, tris = triangles(solid)
    header = ("ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n"
              "property float z\nelement face {}\nproperty list uchar int vertex_indices\n"
              "end_header\n").format(len(vertices), len(tris))
    return header + "".join("{} {} {}\n".format(*v) for v in vertices) + "".join(
        "3 {} {} {}\n".format(*tri) for tri in tris)


@pytest.fixture
def library(tmp_path):
    """A folder with the tetrahedron (STL), octahedron (OBJ), box (PLY) and a pentagonal prism
    (STL, 10 vertices) that the file-list tests leave out."""
    folder = tmp_path / "rocks"
    folder.mkdir()
    (folder / "a_tetra.stl").write_text(stl_ascii(TETRA))
    (folder / "b_octa.obj").write_text(obj_text(OCTA))
    (folder / "c_box.ply").write_text(ply_ascii(BOX))
    (folder / "d_prism.stl").write_text(stl_ascii(PRISM))
    return folder


def config(library_value):
    return {
        "container": {"kind": "box", "length": 0.04, "width": 0.04, "depth": 0.04},
        "grading": {"kind": "fuller", "size_min": 0.004, "size_max": 0.008, "exponent": 0.5},
        "particle": {"library": library_value},
        "packer": {"kind": "random", "seed": 3, "target_fraction": 0.15},
    }


def hull_volume(points, tris):
    """Volume of a closed triangulated surface (divergence theorem)."""
    p = points[np.asarray(tris)]
    return abs(np.einsum("ij,ij->i", p[:, 0], np.cross(p[:, 1], p[:, 2])).sum()) / 6.0


def diameter(points):
    return max(np.linalg.norm(a - b) for a, b in itertools.combinations(points, 2))


def library_shape_of(packing, i):
    """(vertex count, volume / diameter^3, diameter) of placed particle i."""
    world = packing.world_vertices(i)
    tris = packing.shape_triangles(int(packing.shape_indices[i]))
    d = diameter(world)
    return len(world), hull_volume(world, tris) / d**3, d


def test_every_particle_is_a_listed_library_shape(library):
    files = [str(library / "a_tetra.stl"), str(library / "b_octa.obj"),
             str(library / "c_box.ply")]
    packing = aggpack.pack(config(files))
    assert packing.particle_count >= 20
    # One stored shape per library shape used, not one per particle.
    assert packing.shape_count <= 3
    seen = set()
    for i in range(packing.particle_count):
        vertices, ratio, d = library_shape_of(packing, i)
        assert vertices in EXACT_RATIO, f"particle {i} has {vertices} vertices: not listed"
        assert ratio == pytest.approx(EXACT_RATIO[vertices], rel=1e-9)
        # Scaled to the grading: the diameter is at most the sieve size (enclosing diameter).
        assert d <= 0.008 * (1 + 1e-9)
        seen.add(vertices)
    assert seen == {4, 6, 8}
    provenance = packing.provenance["shape_library"].splitlines()
    assert provenance[0].startswith("library " + ", ".join(files) + " (units mm, 3 shapes, 0 ")
    # One row per stored shape, in the order the packing stores them (first use), so row k
    # names the file of shape index k: every placed particle has its file's vertex count.
    rows = [row.split("\t")[0] for row in provenance[1:]]
    assert sorted(rows) == files
    vertices_of_file = dict(zip(files, (4, 6, 8)))
    for i in range(packing.particle_count):
        shape = int(packing.shape_indices[i])
        assert len(packing.world_vertices(i)) == vertices_of_file[rows[shape]], (i, rows[shape])
    # The resolved configuration writes the list back as an array that reads again.
    assert "library = [" in packing.provenance["config_toml"]


def test_folder_and_toml_array_give_the_same_shapes(library):
    folder = aggpack.pack(config(str(library)))
    counts = {library_shape_of(folder, i)[0] for i in range(folder.particle_count)}
    assert 10 in counts  # the prism is in the folder
    toml = aggpack.pack_config(
        "[container]\nkind = \"box\"\nlength = 0.04\nwidth = 0.04\ndepth = 0.04\n"
        "[grading]\nkind = \"fuller\"\nsize_min = 0.004\nsize_max = 0.008\nexponent = 0.5\n"
        f"[particle]\nlibrary = [\"{library / 'd_prism.stl'}\"]\n"
        "[packer]\nkind = \"random\"\nseed = 3\ntarget_fraction = 0.1\n")
    prisms = aggpack.pack(toml)
    assert {library_shape_of(prisms, i)[0] for i in range(prisms.particle_count)} == {10}
    assert prisms.shape_count == 1


def test_use_once_places_each_shape_at_most_once(library):
    settings = config([str(library)])
    settings["particle"]["library_use_once"] = True
    settings["packer"] = {"kind": "random", "seed": 3, "target_count": 4}
    packing = aggpack.pack(settings)
    assert packing.particle_count == 4
    assert sorted(library_shape_of(packing, i)[0] for i in range(4)) == [4, 6, 8, 10]


def test_bad_lists_name_the_key(library):
    with pytest.raises(aggpack.InvalidInput, match=r"^invalid particle\.library = .*missing\.stl"):
        aggpack.pack(config([str(library / "a_tetra.stl"), str(library / "missing.stl")]))
    with pytest.raises(aggpack.InvalidInput, match="named twice"):
        aggpack.pack(config([str(library), str(library / "a_tetra.stl")]))
    with pytest.raises(aggpack.ConfigError, match=r"particle\.library\[1\] must be a non-empty"):
        aggpack.pack_config(config([str(library), ""]))
    with pytest.raises(aggpack.ConfigError, match=r"particle\.library must be a non-empty path"):
        aggpack.pack_config(config([]))
