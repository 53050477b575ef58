"""Progress callbacks, cancelling by the callback, and exceptions raised in it."""
import pytest

import aggpack

# Enough particles that a pack takes several progress intervals.
LONG = {"container": {"length": 0.1, "width": 0.1, "depth": 0.1},
        "grading": {"kind": "fuller", "size_min": 0.003, "size_max": 0.006},
        "particle": {"edge_length": 0.0, "edge_length_ratio": 0.8},
        "packer": {"kind": "random", "target_fraction": 0.3}}


def test_progress_is_reported():
    seen = []
    p = aggpack.pack(aggpack.pack_config(LONG, {"packer.target_fraction": 0.05}),
                     progress=seen.append, progress_interval=0.0)
    assert seen, "no progress reported"
    assert {"stage", "fraction", "placed", "total", "solid_fraction"} <= set(seen[-1])
    assert seen[-1]["placed"] == len(p)
    assert all(0.0 <= s["fraction"] <= 1.0 for s in seen)


def test_callback_returning_false_cancels():
    calls = []

    def stop_after_some(progress):
        calls.append(progress)
        return not (progress["stage"] == "placement" and progress["placed"] >= 20)

    p = aggpack.pack(aggpack.pack_config(LONG), progress=stop_after_some,
                     progress_interval=0.0)
    assert p.report["stop_reason"] == "cancelled"
    assert not p.report["is_target_reached"]
    assert 20 <= len(p) < p.report["requested"]
    assert len(p.positions) == len(p)


def test_exception_in_callback_cancels_and_propagates():
    class Stop(Exception):
        pass

    count = []

    def fail(progress):
        count.append(1)
        raise Stop("enough")

    with pytest.raises(Stop, match="enough"):
        aggpack.pack(aggpack.pack_config(LONG), progress=fail, progress_interval=0.0)
    assert len(count) == 1  # the pack stopped at the first call


def test_ctrl_c_cancels_a_pack_without_callback():
    import os
    import signal
    import threading

    # SIGINT arrives while pack() runs in C++ with the GIL released, as Ctrl-C would; the
    # module's own progress hook checks for it and stops the packer.
    timer = threading.Timer(0.05, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            aggpack.pack(aggpack.pack_config(LONG, {"packer.target_fraction": 0.5}),
                         progress_interval=0.01)
    finally:
        timer.cancel()


def test_gil_is_released_while_packing():
    import threading

    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            stop.wait(0.001)

    thread = threading.Thread(target=tick)
    thread.start()
    try:
        aggpack.pack(aggpack.pack_config(LONG, {"packer.target_fraction": 0.1}))
    finally:
        stop.set()
        thread.join()
    assert len(ticks) > 5  # the other thread ran while pack() worked
