"""Progress reaches Python; Ctrl-C and exceptions from the callback stop a run cleanly."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import surfgrow


def test_progress_stages(channel):
    seen = []
    surfgrow.grow(channel.cloud, progress=lambda stage, f: seen.append((stage, f)))
    stages = [s for s, _ in seen]
    assert stages[0] == "index" and stages[-1] == "finish"
    assert "grow" in stages and "attach" in stages
    grow = [f for s, f in seen if s == "grow"]
    assert grow == sorted(grow) and all(0 <= f <= 1 for f in grow)


def test_progress_true_and_bad_callback(corner):
    surfgrow.grow(corner.points, progress=True)
    with pytest.raises(TypeError, match="progress"):
        surfgrow.grow(corner.points, progress="yes")


@pytest.mark.parametrize("threads", [1, 2])
def test_callback_exception_stops_the_run(channel, threads):
    # "grow" is reported from inside the slab loop's parallel region, which with one thread is an
    # inactive region: throwing there would end the process.
    def boom(stage, fraction):
        if stage == "grow":
            raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        surfgrow.grow(channel.cloud, progress=boom, threads=threads)
    # The library is left in order: the next run gives the usual result.
    assert np.mean(surfgrow.grow(channel.cloud).labels >= 0) > 0.99


def test_ctrl_c_stops_a_run(channel):
    """SIGINT while the GIL is released: KeyboardInterrupt soon after, then normal service."""
    big = surfgrow.simulate("ibeam-channel", poses=4, seed=1)
    full = time.perf_counter()
    surfgrow.grow(big.cloud, threads=1)
    full = time.perf_counter() - full
    timer = threading.Timer(0.02, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        surfgrow.grow(big.cloud, threads=1)
        time.sleep(5)  # the signal came after the run: wait for it here instead
    stopped = time.perf_counter() - start
    timer.join()
    assert stopped < 0.7 * full
    assert np.mean(surfgrow.grow(channel.cloud).labels >= 0) > 0.99


def test_gil_is_released(channel):
    """Another Python thread runs while grow works."""
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)
    t = threading.Thread(target=tick)
    t.start()
    before = len(ticks)
    surfgrow.grow(channel.cloud, threads=1)
    during = len(ticks) - before
    stop.set()
    t.join()
    assert during >= 5
