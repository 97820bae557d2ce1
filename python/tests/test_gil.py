"""Long computations release the GIL: another Python thread keeps running meanwhile; an interrupt
(Ctrl-C) stops an optimisation."""

import os
import signal
import threading
import time

import numpy as np
import pytest

import loomkin
from conftest import REPO


def ticks_during(call):
    """Runs `call` in a worker thread while this thread ticks; returns the call's duration and
    the longest gap between ticks while it ran. With the GIL held for the whole call, the gap
    would be the call's whole duration."""
    done = threading.Event()
    box = {}

    def work():
        t0 = time.perf_counter()
        box["result"] = call()
        box["seconds"] = time.perf_counter() - t0
        done.set()

    worker = threading.Thread(target=work)
    last = time.perf_counter()
    gap = 0.0
    worker.start()
    while not done.is_set():
        now = time.perf_counter()
        gap = max(gap, now - last)
        last = now
    worker.join()
    return box["seconds"], gap, box["result"]


def test_sampling_releases_the_gil():
    law = loomkin.Law("modified-sine")
    # Ten calls of 10⁶ points (about 0.1 s in a release build): the GIL is taken back only
    # between the calls, to build the arrays.
    seconds, gap, out = ticks_during(lambda: [law.sample(1_000_000) for _ in range(10)])
    assert out[-1]["x"].shape == (1_000_000,)
    assert seconds > 0.02, "the call is too short to tell"
    assert gap < 0.5 * seconds, f"the other thread stalled {gap:.3f} s of a {seconds:.3f} s call"


def test_optimisation_releases_the_gil():
    seconds, gap, r = ticks_during(lambda: loomkin.servo.optimize([600, 750], starts=6))
    assert r["evaluations"] > 0
    assert seconds > 0.02, "the call is too short to tell"
    assert gap < 0.5 * seconds, f"the other thread stalled {gap:.3f} s of a {seconds:.3f} s call"


class Interrupted(Exception):
    pass


def test_optimisation_stops_on_an_interrupt():
    def handler(signum, frame):
        raise Interrupted()

    old = signal.signal(signal.SIGINT, handler)
    timer = threading.Timer(0.3, lambda: os.kill(os.getpid(), signal.SIGINT))
    t0 = time.perf_counter()
    try:
        timer.start()
        # 1000 starts take tens of seconds; the interrupt ends the call within a few tenths.
        try:
            loomkin.servo.optimize([600, 750], starts=1000)
            raise AssertionError("the optimisation ran to its end despite the interrupt")
        except Interrupted:
            pass
        elapsed = time.perf_counter() - t0
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, old)
    assert elapsed < 5.0, f"stopped only after {elapsed:.2f} s"


def _study(name, **changes):
    tomllib = pytest.importorskip("tomllib")
    d = tomllib.loads((REPO / "examples" / name).read_text())
    d.update(changes)
    return d


HEALD = REPO / "examples" / "heald-frame-cycle.toml"

LONG_CALLS = {
    "dyn-optimize": lambda: loomkin.dynamics.optimize(HEALD, 54, damping_ratio=0.05, speed_rpm=600),
    "dyn-spectrum": lambda: loomkin.dynamics.spectrum(["cycloidal", "modified-sine"], np.linspace(0.5, 10, 40_000)),
    "pick-montecarlo": lambda: loomkin.picking.montecarlo(_study("pick-montecarlo.toml", draws=4000)),
    "dobby-tolerance": lambda: loomkin.dobby.tolerance(_study("dobby-tolerance.toml", draws=200)),
    "cycle-samples": lambda: [loomkin.cycles.sample(HEALD, points=1_000_000) for _ in range(5)],
}


@pytest.mark.parametrize("name", LONG_CALLS)
def test_long_calls_release_the_gil(name):
    seconds, gap, out = ticks_during(LONG_CALLS[name])
    assert out is not None
    assert seconds > 0.02, "the call is too short to tell"
    assert gap < 0.5 * seconds, f"the other thread stalled {gap:.3f} s of a {seconds:.3f} s call"


def interrupted_after(call, delay=0.3):
    """Sends SIGINT `delay` s into `call`; returns how long the call took to raise
    KeyboardInterrupt (fails if it returned normally).

    Ctrl-C raises KeyboardInterrupt only where Python installed its handler, which it does not when
    the process starts with SIGINT ignored (a shell's background job, `nohup … &`); the handler is
    installed here for the test, so that the suite means the same wherever it is started from."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(delay, lambda: os.kill(os.getpid(), signal.SIGINT))
    t0 = time.perf_counter()
    try:
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            call()
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    return time.perf_counter() - t0


def test_montecarlo_stops_on_an_interrupt():
    # 10⁶ draws take minutes; the study stops between two pieces of draws.
    study = _study("pick-montecarlo.toml", draws=1_000_000)
    elapsed = interrupted_after(lambda: loomkin.picking.montecarlo(study))
    assert elapsed < 5.0, f"stopped only after {elapsed:.2f} s"


def test_tolerance_stops_on_an_interrupt():
    study = _study("dobby-tolerance.toml", draws=100_000)
    elapsed = interrupted_after(lambda: loomkin.dobby.tolerance(study))
    assert elapsed < 5.0, f"stopped only after {elapsed:.2f} s"


def test_spectrum_returns_on_an_interrupt():
    # 3·10⁵ ratios of a 20-segment law take seconds; the call returns at once.
    law = loomkin.Law("piecewise", segments=",".join(["0.05:constant:1"] * 10 + ["0.05:constant:-1"] * 10))
    elapsed = interrupted_after(lambda: loomkin.dynamics.spectrum(law, np.linspace(0.5, 10, 300_000)), 0.2)
    assert elapsed < 2.0, f"returned only after {elapsed:.2f} s"
