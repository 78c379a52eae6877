"""A long encode releases the GIL and reports progress to a Python callable."""

import threading
import time

import pytest

import dcurve
from conftest import grid_wave


def test_progress_is_called_in_order_up_to_one(corpus_arrays):
    frames, faces = corpus_arrays
    seen = []
    dcurve.encode(frames, faces, progress=seen.append)
    assert seen, "no progress reported"
    assert all(0.0 <= x <= 1.0 for x in seen)
    assert seen == sorted(seen) and seen[-1] == pytest.approx(1.0)


def test_an_exception_in_the_callback_is_raised_after_the_encode():
    frames, faces = grid_wave()

    def fail(fraction):
        raise RuntimeError("stop at %g" % fraction)

    with pytest.raises(RuntimeError, match="stop at"):
        dcurve.encode(frames, faces, progress=fail)


def test_other_threads_run_during_an_encode(corpus_arrays):
    frames, faces = corpus_arrays
    done = threading.Event()
    ticks = []

    def encode():
        dcurve.encode(frames, faces)
        done.set()

    worker = threading.Thread(target=encode)
    start = time.monotonic()
    worker.start()
    while not done.is_set():
        ticks.append(time.monotonic())
        time.sleep(0.005)
    worker.join()
    elapsed = time.monotonic() - start
    assert elapsed > 0.2, "the encode was too short to tell"
    # With the GIL held for the encode, this loop would not run until it ended (a tick or two);
    # released, it ticks every 5 ms, or every few tens of ms on a loaded machine.
    assert len(ticks) >= 10
