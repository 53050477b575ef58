"""Packing from Python: numpy views, the native file round trip, the same bytes as the CLI."""
import filecmp
import os

import numpy as np
import pytest

import aggpack


def test_default_config_is_the_papers_lattice_case():
    config = aggpack.pack_config()
    assert config.packer == "lattice"
    assert config.container["kind"] == "box"
    assert config.container["length"] == 3.0
    assert "[packer]" in config.resolved_toml


def test_views_share_memory_and_have_the_packings_shapes(small_packing):
    p = small_packing
    n = len(p)
    assert n > 20
    assert p.positions.shape == (n, 3) and p.positions.dtype == np.float64
    assert p.rotations.shape == (n, 4)
    assert p.scales.shape == (n,) and p.size_classes.dtype == np.uint32
    # Views, not copies: no data of their own, and read-only.
    assert not p.positions.flags.owndata and not p.positions.flags.writeable
    assert p.positions.base is not None
    # Unit quaternions; positions inside the container.
    np.testing.assert_allclose(np.linalg.norm(p.rotations, axis=1), 1.0, atol=1e-9)
    c = p.container
    assert np.all(p.positions >= 0) and np.all(p.positions <= [c["length"], c["width"], c["depth"]])
    # Each shape's vertices and triangles.
    s = int(p.shape_indices[0])
    v, t = p.shape_vertices(s), p.shape_triangles(s)
    assert v.shape[1] == 3 and t.shape[1] == 3 and t.max() < len(v)
    # Outward triangles enclose the particle's volume, centroid at the origin (the local frame).
    a, b, c3 = v[t[:, 0]], v[t[:, 1]], v[t[:, 2]]
    tet = np.einsum("ij,ij->i", a, np.cross(b, c3)) / 6.0
    volume = tet.sum()
    particle = int(np.flatnonzero(p.shape_indices == s)[0])
    scale = p.scales[particle]
    assert abs(volume * scale**3 - p.descriptors()["volume"][particle]) < 1e-12 * volume + 1e-18
    centroid = (tet[:, None] * (a + b + c3)).sum(axis=0) / (4.0 * volume)
    assert np.abs(centroid).max() < 1e-9 * np.abs(v).max()


def test_a_view_outlives_its_packing():
    p = aggpack.pack(aggpack.pack_config(None, ["container.length=0.5", "container.depth=0.4"]))
    positions = p.positions
    expected = np.array(positions)
    del p
    np.testing.assert_array_equal(positions, expected)


def test_report_and_statistics_agree(small_packing):
    report = small_packing.report
    assert report["placed"] == len(small_packing)
    assert report["is_target_reached"] and report["stop_reason"] == "target reached"
    stats = small_packing.statistics()
    assert stats["particle_count"] == len(small_packing)
    assert abs(stats["solid_fraction"] - report["solid_fraction"]) < 1e-9
    grading = stats["grading"]
    assert grading is not None and grading["achieved_percent"][-1] == 100.0
    assert len(stats["profiles"]) == 3 and stats["profiles"][2]["solid_fraction"].shape == (10,)


def test_descriptors_are_per_particle(small_packing):
    d = small_packing.descriptors()
    n = len(small_packing)
    assert d["volume"].shape == (n,)
    assert abs(d["volume"].sum() - small_packing.report["solid_volume"]) < 1e-9 * n
    assert np.all((d["sphericity"] > 0) & (d["sphericity"] <= 1))


def test_native_round_trip_gives_equal_arrays(small_packing, tmp_path):
    path = tmp_path / "run.h5"
    small_packing.write(str(path))
    back = aggpack.read(str(path))
    assert back.report is None
    for name in ("positions", "rotations", "scales", "size_classes", "control_radii",
                 "shape_indices"):
        np.testing.assert_array_equal(getattr(back, name), getattr(small_packing, name), name)
    assert back.shape_count == small_packing.shape_count
    for s in range(back.shape_count):
        np.testing.assert_array_equal(back.shape_vertices(s), small_packing.shape_vertices(s))
        np.testing.assert_array_equal(back.shape_triangles(s), small_packing.shape_triangles(s))
    assert back.provenance == small_packing.provenance
    # The stored configuration gives the target grading back.
    np.testing.assert_array_equal(back.statistics()["grading"]["target_percent"],
                                  small_packing.statistics()["grading"]["target_percent"])


def test_same_native_bytes_as_the_cli(small_random, tmp_path, cli):
    config_path = tmp_path / "small.toml"
    config_path.write_text(small_random)
    from_cli = tmp_path / "cli.h5"
    result = cli("pack", str(config_path), "-o", str(from_cli))
    assert result.returncode == 0, result.stderr
    from_python = tmp_path / "python.h5"
    aggpack.pack(aggpack.PackConfig.from_file(str(config_path))).write(str(from_python))
    assert filecmp.cmp(from_cli, from_python, shallow=False)


def test_same_native_bytes_as_the_cli_for_the_lattice_and_a_dict(tmp_path, cli):
    from_cli = tmp_path / "cli.h5"
    result = cli("pack", "--set", "container.length=0.6", "--set", "container.depth=0.5",
                 "--seed", "3", "-o", str(from_cli))
    assert result.returncode == 0, result.stderr
    config = aggpack.pack_config({"container": {"length": 0.6, "depth": 0.5},
                                  "packer.seed": 3})
    from_python = tmp_path / "python.h5"
    aggpack.pack(config).write(str(from_python))
    assert filecmp.cmp(from_cli, from_python, shallow=False)


def test_generate_particles_matches_generate_particle():
    many = aggpack.generate_particles(5, alpha=0.7, radius=0.05, edge_length=0.03, seed=4)
    assert many["volume"].shape == (5,)
    one = aggpack.generate_particle(alpha=0.7, radius=0.05, edge_length=0.03, seed=4, index=3)
    assert one["descriptors"]["volume"] == many["volume"][3]
    assert one["vertices"].shape == (int(many["vertices"][3]), 3)
    assert np.linalg.norm(one["vertices"], axis=1).max() <= 0.05 + 1e-12


def test_dense_kind_matches_the_cli(tmp_path, cli):
    # The dense packer on a small cube: a random fill compressed by the densifier.
    overrides = ["container.length=0.05", "container.width=0.05", "container.depth=0.05",
                 "densify.target_fraction=0.4", "densify.max_sweeps=300"]
    source = os.path.join(os.environ.get("AGGPACK_SOURCE_DIR", "."), "examples", "dense-box.toml")
    from_cli = tmp_path / "cli.h5"
    args = ["pack", source, "-o", str(from_cli), "--progress", "none"]
    for text in overrides:
        args += ["--set", text]
    result = cli(*args)
    assert result.returncode == 0, result.stderr
    stages = set()
    packing = aggpack.pack(aggpack.PackConfig.from_file(source, overrides),
                           progress=lambda p: stages.add(p["stage"]), progress_interval=0.0)
    assert packing.provenance["packer"] == "dense"
    assert "densify" in packing.report and "fill" in packing.report
    assert "densify" in stages
    packing.write(str(tmp_path / "python.h5"))
    assert filecmp.cmp(from_cli, tmp_path / "python.h5", shallow=False)


def test_pack_takes_a_dict_or_a_toml_path_as_the_cli_does(tmp_path, cli):
    keys = {
        "container": {"kind": "box", "length": 0.04, "width": 0.04, "depth": 0.04},
        "grading": {"kind": "fuller", "size_min": 0.004, "size_max": 0.008, "exponent": 0.5},
        "packer": {"kind": "random", "seed": 3, "target_fraction": 0.15},
    }
    toml = tmp_path / "run.toml"
    toml.write_text(aggpack._dict_to_toml(keys))
    from_dict = aggpack.pack(keys)
    from_path = aggpack.pack(toml)
    from_str = aggpack.pack(str(toml))
    for packing, name in ((from_dict, "dict"), (from_path, "path"), (from_str, "str")):
        packing.write(str(tmp_path / f"{name}.h5"))
    cli("pack", str(toml), "-o", str(tmp_path / "cli.h5"))
    expected = (tmp_path / "cli.h5").read_bytes()
    for name in ("dict", "path", "str"):
        assert (tmp_path / f"{name}.h5").read_bytes() == expected, name


def test_pack_refuses_other_config_types_naming_the_argument():
    with pytest.raises(aggpack.InvalidInput, match="config"):
        aggpack.pack(42)
    with pytest.raises(aggpack.IoError, match="no-such.toml"):
        aggpack.pack("no-such.toml")


def test_module_help_lists_every_public_function():
    functions = [
        name
        for name in dir(aggpack)
        if not name.startswith("_") and type(getattr(aggpack, name)).__name__ == "builtin_function_or_method"
    ]
    assert "pack" in functions and "read" in functions
    missing = [name for name in functions if f"{name}(" not in aggpack.__doc__]
    assert not missing, f"help(aggpack) does not list {missing}"
