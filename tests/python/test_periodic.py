"""A periodic box from Python: the key in pack_config, the container dict, the native file."""
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
