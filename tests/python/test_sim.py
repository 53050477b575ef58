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


SMALL_TROUGH = {"trough": {"length": 1.2, "width": 0.2, "height": 0.6, "baffle_position": 0.6},
                "particle": {"radius": 0.05, "edge_length": 0.05, "fill_height": 0.4},
                "rest": {"max_time": 2.0, "confirm_window": 0.0}}


def test_repose_on_a_small_trough():
    result = aggpack.repose(SMALL_TROUGH)
    count = result["particle_count"]
    assert count > 10
    assert len(result["final"]) == count == len(result["initial"])
    profile = result["profile"]
    assert profile["x"].shape == profile["height"].shape and profile["height"].max() > 0
    # The baffle moved and the particles spread beyond it.
    assert result["baffle_travel"] > 0
    assert result["final"].positions[:, 0].max() > 0.6
    if result["fit"]["is_valid"]:
        assert 0 < result["angle_degrees"] < 90


def test_repose_bad_key_names_it():
    with pytest.raises(aggpack.ConfigError) as caught:
        aggpack.repose(SMALL_TROUGH, ["trough.baffle_speed=-1"])
    assert caught.value.key == "trough.baffle_speed"
