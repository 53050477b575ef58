"""Settling from Python (when the module is built with the physics module)."""
import numpy as np
import pytest

import aggpack

pytestmark = pytest.mark.skipif(not aggpack.has_sim, reason="built without Bullet")


def test_settle_returns_a_packing_and_a_report(small_packing):
    settled, report = small_packing.settle(max_time=0.3)
    assert len(settled) == len(small_packing)
    assert report["simulated_time"] > 0 and report["steps"] > 0
    assert report["height_after"] <= report["height_before"] + 1e-9
    # Gravity moved the particles down on average.
    assert settled.positions[:, 2].mean() < small_packing.positions[:, 2].mean()
    assert report["escaped_particles"] == 0
    assert np.isfinite(settled.positions).all()


def test_settle_bad_option_names_it(small_packing):
    with pytest.raises(aggpack.InvalidInput, match="friction"):
        small_packing.settle(friction=-1.0)
