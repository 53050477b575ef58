"""A periodic box from Python: the key in pack_config, the container dict, the native file, the
dense kind in it and the STL cut to the box."""
import numpy as np

import aggpack

from conftest import SMALL_RANDOM


def test_periodic_box_round_trip(tmp_path):
    config = aggpack.pack_config(SMALL_RANDOM, {"container.periodic": "xy"})
    assert config.container["periodic"] == "xy"
    p = aggpack.pack(config)
    assert p.container["periodic"] == "xy"
    # Centres stay in the box (a particle may reach beyond a periodic face).
    c = p.container
    size = np.array([c["length"], c["width"], c["depth"]])
    assert np.all(p.positions >= 0) and np.all(p.positions <= size)
    path = str(tmp_path / "rve.h5")
    p.write(path)
    back = aggpack.read(path)
    assert back.container["periodic"] == "xy"
    np.testing.assert_array_equal(back.positions, p.positions)


def test_walled_box_says_none():
    p = aggpack.pack(aggpack.pack_config(SMALL_RANDOM))
    assert p.container["periodic"] == "none"


def _stl_volume_and_bounds(path):
    """The enclosed volume (divergence theorem) and vertex bounds of a binary STL."""
    data = np.fromfile(path, dtype=np.uint8)
    count = int(np.frombuffer(data[80:84].tobytes(), dtype=np.uint32)[0])
    facets = np.frombuffer(data[84:84 + 50 * count].tobytes(),
                           dtype=np.dtype([("n", "<f4", 3), ("v", "<f4", (3, 3)), ("a", "<u2")]))
    v = facets["v"].astype(np.float64)
    volume = np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0
    return volume, v.reshape(-1, 3).min(axis=0), v.reshape(-1, 3).max(axis=0)


def test_dense_periodic_and_the_stl_cut_to_the_box(tmp_path, cli):
    config = aggpack.pack_config(SMALL_RANDOM, {"container.periodic": "xyz",
                                                "packer.kind": "dense",
                                                "densify.target_fraction": 0.3})
    p = aggpack.pack(config)
    assert p.container["periodic"] == "xyz"
    c = p.container
    size = np.array([c["length"], c["width"], c["depth"]])
    assert np.all(p.positions >= 0) and np.all(p.positions < size)
    path = tmp_path / "cut.stl"
    summary = p.export(str(path), cut_to_box=True)
    assert summary["particles"] > len(p.positions)  # the images' pieces too
    volume, lowest, highest = _stl_volume_and_bounds(path)
    solid = p.statistics()["solid_volume"]
    assert np.all(lowest >= -1e-7) and np.all(highest <= size + 1e-7)
    # The pieces tile the box: their volume is the particles' (float32 coordinates).
    whole = tmp_path / "whole.stl"
    p.export(str(whole))
    whole_volume, _, _ = _stl_volume_and_bounds(whole)
    assert abs(volume - whole_volume) < 1e-5 * whole_volume
    assert abs(volume - solid) < 1e-5 * solid
    # The same bytes as the CLI's flag.
    native = tmp_path / "run.h5"
    p.write(str(native))
    result = cli("export", str(native), "-o", str(tmp_path / "cli.stl"), "--cut-to-box")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "cli.stl").read_bytes() == path.read_bytes()
