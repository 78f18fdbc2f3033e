"""How a call behaves around the computation: the progress bar, Ctrl-C, and no copy of the input."""

import os
import signal
import threading
import time
import tracemalloc

import numpy as np
import pytest

import wavejets


def torus(n, seed=0):
    rng = np.random.default_rng(seed)
    u, v = rng.uniform(0, 2 * np.pi, n), rng.uniform(0, 2 * np.pi, n)
    return np.column_stack([(1 + 0.3 * np.cos(v)) * np.cos(u), (1 + 0.3 * np.cos(v)) * np.sin(u), 0.3 * np.sin(v)])


def test_progress_bar_on_stderr(capfd):
    wavejets.estimate_normals(torus(20000), k=18, progress=True)
    err = capfd.readouterr().err
    assert "wavejets.estimate_normals" in err and "100%" in err


def test_progress_callable_sees_the_fractions_and_its_exception_stops_the_call():
    seen = []
    wavejets.estimate_curvatures(torus(20000), k=18, progress=seen.append)
    assert seen and seen[-1] == 1.0 and all(0.0 <= x <= 1.0 for x in seen)

    def stop(fraction):
        raise RuntimeError("stopped by the progress callable")

    with pytest.raises(RuntimeError, match="stopped by the progress callable"):
        wavejets.enhance_positions(torus(400000), k=40, progress=stop)


def test_ctrl_c_stops_a_running_call_promptly():
    points = torus(2000000)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        wavejets.enhance_positions(points, k=60, order=4)
    elapsed = time.monotonic() - start
    timer.join()
    # The whole call takes far longer (tens of seconds on 2 cores); the stop comes within a few
    # hundred milliseconds of the signal.
    assert elapsed < 5.0
    # The module still works after an interrupt.
    assert wavejets.estimate_normals(points[:1000], k=10).shape == (1000, 3)


def test_other_python_threads_run_during_a_call():
    """The GIL is released while computing: a Python thread keeps ticking through a long call."""
    points = torus(300000)
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.monotonic())
            time.sleep(0.005)

    ticker = threading.Thread(target=tick)
    ticker.start()
    start = time.monotonic()
    wavejets.enhance_positions(points, k=40, order=4)
    end = time.monotonic()
    stop.set()
    ticker.join()
    during = [t for t in ticks if start < t < end]
    gaps = np.diff([start] + during + [end])
    assert end - start > 0.5                  # a long call (seconds on 2 cores)
    assert len(during) >= 20                  # with the GIL held there would be none
    assert gaps.max() < 0.5 * (end - start)   # and they are spread over the whole call


def test_ctrl_c_after_writing_a_file_raises_keyboard_interrupt(tmp_path):
    """Writing a file leaves Python's SIGINT handler in place (the tool's own, which removes the
    temporary file and exits, is not installed by the module)."""
    points = torus(1000)
    wavejets.write(tmp_path / "cloud.ply", points)
    wavejets.render(tmp_path / "cloud.png", points, width=100, height=100)
    with pytest.raises(KeyboardInterrupt):
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(1.0)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cloud.ply", "cloud.png"]


def test_float64_input_is_not_copied():
    points = torus(200000)
    tracemalloc.start()
    wavejets.estimate_normals(points, k=10, threads=1)
    _, peak_float64 = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    points32 = points.astype(np.float32)
    tracemalloc.start()
    wavejets.estimate_normals(points32, k=10, threads=1)
    _, peak_float32 = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    # NumPy's allocations are traced: the result (N x 3 doubles) and the fitted flags, and with
    # float32 input also the float64 copy of the points (another N x 3 doubles).
    result = points.nbytes
    assert peak_float64 < result * 1.2
    assert peak_float32 > peak_float64 + 0.9 * result
