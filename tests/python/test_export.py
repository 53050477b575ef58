"""Every export format from Python, read back by real readers where one exists."""
import filecmp
import os

import numpy as np
import pytest

import aggpack


def require_reader(name):
    """Imports a reader module; missing, it fails the test (skips with AGGPACK_REQUIRE_READERS=0)."""
    try:
        return __import__(name)
    except ImportError:
        if os.environ.get("AGGPACK_REQUIRE_READERS", "1") == "0":
            pytest.skip(f"{name} not installed")
        pytest.fail(f"reader {name} missing: apt-get install python3-{name}")


def test_vtu_and_stl_read_by_meshio(small_packing, tmp_path):
    meshio = require_reader("meshio")
    summary = small_packing.export(str(tmp_path / "run.vtu"))
    assert summary["format"] == "vtu" and summary["particles"] == len(small_packing)
    mesh = meshio.read(str(tmp_path / "run.vtu"))
    assert len(mesh.points) == summary["nodes"]
    assert sum(len(block.data) for block in mesh.cells) == summary["elements"]
    # The points are the particles' world vertices, particle by particle.
    first = small_packing.world_vertices(0)
    np.testing.assert_allclose(mesh.points[: len(first)], first, rtol=0, atol=1e-12)

    small_packing.export(str(tmp_path / "run.stl"))
    stl = meshio.read(str(tmp_path / "run.stl"))
    assert sum(len(block.data) for block in stl.cells) == summary["elements"]

    tets = small_packing.export(str(tmp_path / "tets.vtu"), cells="tetrahedra", scale=1000.0)
    mesh = meshio.read(str(tmp_path / "tets.vtu"))
    assert mesh.cells[0].type == "tetra" and len(mesh.cells[0].data) == tets["elements"]
    assert np.abs(mesh.points).max() > 1.0  # millimetres


def test_every_format_writes(small_packing, tmp_path):
    for extension in ("stl", "dat", "inp", "vtu", "msh", "k", "mac", "obj", "py", "h5"):
        path = tmp_path / f"run.{extension}"
        summary = small_packing.export(str(path))
        assert summary["particles"] == len(small_packing), extension
        assert path.stat().st_size > 100, extension


def test_export_matches_the_cli(small_packing, tmp_path, cli):
    native = tmp_path / "run.h5"
    small_packing.write(str(native))
    result = cli("export", str(native), "-o", str(tmp_path / "cli.inp"), "--quadratic",
                 "--scale", "1000")
    assert result.returncode == 0, result.stderr
    small_packing.export(str(tmp_path / "py.inp"), quadratic=True, scale=1000.0)
    assert filecmp.cmp(tmp_path / "cli.inp", tmp_path / "py.inp", shallow=False)
