"""Every long operation stops promptly on Ctrl-C (DESIGN.md; issues 13, 22, 23): within a second on
a machine that is not overloaded, and within LATENCY_BOUND (2 s) on a busy one.

One child process (interrupt_child.py) runs each operation in turn; it prints `start <name>` once
the work is under way (its progress callback's first call), the test sends it SIGINT
WORK_BEFORE_SIGNAL later and measures the time until the child reports the KeyboardInterrupt.
Every operation would run for minutes, so a slow or busy machine cannot finish it first: the
only property asserted is the latency. C++ work polls its cancel flags at every pixel, sample,
ray step (every 64 field evaluations in the stratified tracer) and optimiser evaluation, and the
waiting thread checks for signals every 50 ms. Measured latencies: 0.01-0.1 s on 2 idle cores;
with two CPU burners beside the test and other engineers' builds (load average 13 on 2 cores)
0.03-0.57 s (trace_rays' 2e6 rays the slowest)."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import refracta

# [s] the property asserted: 3.5x the worst latency measured at load average 13 on 2 cores (0.57 s),
# so a CI machine that busy passes, while work that stopped polling (minutes here) still fails.
LATENCY_BOUND = 2.0
WORK_BEFORE_SIGNAL = 0.5  # [s] after the work has started; every operation would run for minutes more
HANG_GUARD = 60.0  # [s] a bound against a hang of the whole child, not a timing assertion

OPERATIONS = [
    "trace_rays",
    "trace_ray",
    "render_straight",
    "render_curved",
    "render_raster_march",
    "render_table",
    "render_raster",
    "render_turbulent_path",
    "solve",
    "sweep",
]
ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_every_long_operation_stops_promptly_on_ctrl_c():
    latencies = {}
    with subprocess.Popen(
        [sys.executable, "-m", "tests.hardening.interrupt_child", *OPERATIONS],
        cwd=ROOT,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    ) as child:
        try:
            for name in OPERATIONS:
                assert child.stdout.readline().strip() == f"start {name}"
                time.sleep(WORK_BEFORE_SIGNAL)
                sent = time.monotonic()
                child.send_signal(signal.SIGINT)
                reply = child.stdout.readline().strip()
                latencies[name] = time.monotonic() - sent
                assert reply == f"stopped {name}", f"{name}: {reply!r}"
            _, stderr = child.communicate(timeout=HANG_GUARD)
        finally:
            child.kill()
    assert child.returncode == 0, stderr
    slow = {name: round(t, 3) for name, t in latencies.items() if t >= LATENCY_BOUND}
    assert not slow, f"Ctrl-C took >= {LATENCY_BOUND} s: {slow} (all: {latencies})"


# SIGINT before the waiting loop's first check (interruptible.h polls every 50 ms): CPython's C
# handler only marks the signal as tripped, and the mark stays until the main thread's next
# PyErr_CheckSignals, which the loop's first check is, so an early signal is late by at most
# that first period (measured 0.003-0.09 s idle, up to 0.15 s at load average 13), never lost.
EARLY_TRIALS = 15  # printed by earliest_interrupt_child: 4 renders, 5 first evaluations, 6 sweeps


@pytest.mark.slow
def test_ctrl_c_at_the_earliest_moment_of_a_call_still_stops_it_promptly():
    child = subprocess.run(
        [sys.executable, "-m", "tests.hardening.earliest_interrupt_child"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=HANG_GUARD,
    )
    assert child.returncode == 0, child.stderr
    trials = [line.split() for line in child.stdout.splitlines()]
    assert len(trials) == EARLY_TRIALS, child.stdout
    finished = [label for outcome, label, *_ in trials if outcome != "stopped"]
    assert not finished, f"calls ran to their end despite a SIGINT: {finished}"
    slow = {label: float(latency) for _, label, latency, _ in trials if float(latency) >= LATENCY_BOUND}
    assert not slow, f"Ctrl-C took >= {LATENCY_BOUND} s: {slow}"
    # The field's first evaluation comes within microseconds of the work's start, so some (all,
    # measured) of its signals were pending before the loop's first check, the case at issue.
    assert any(polled == "0" for _, label, _, polled in trials if label == "trace_rays_first_evaluation"), child.stdout


# [s] a bound against building the whole sounding (7 s at 1e6 levels before the limit); the
# refusal itself is the arrays' conversion, ~0.04 s.
REFUSAL_GUARD = 3.0


def test_a_sounding_of_millions_of_levels_is_refused_up_front():
    # 1e6 levels took 7 s and 2e7 3 minutes, Ctrl-C ignored (issue 23): at most 1e5 (~0.5 s).
    heights = np.linspace(0.0, 1e4, 1_000_000)
    start = time.monotonic()
    with pytest.raises(ValueError, match=r"TemperatureProfile: at most 100000 levels \(got 1000000\)"):
        refracta.TemperatureProfile(heights, 288.0 - 0.0065 * heights)
    assert time.monotonic() - start < REFUSAL_GUARD


@pytest.mark.parametrize("special", ["fifo", "folder"])
def test_a_pairs_file_that_is_not_a_regular_file_is_refused_before_opening(tmp_path, special):
    # A FIFO as the pairs file blocked refracta edit --pairs and the editor's import for 20 s
    # (reading waits for a writer): load_pairs, which both use, refuses it without opening it.
    from refracta.edit import load_pairs

    path = tmp_path / "pairs.json"
    if special == "fifo":
        os.mkfifo(path)
    else:
        path.mkdir()
    with pytest.raises(refracta.IoError, match=f"cannot read pairs file {path}: not a regular file"):
        load_pairs(path)
