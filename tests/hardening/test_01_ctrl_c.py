"""Every long operation stops within 1 s of Ctrl-C (DESIGN.md: "stops promptly on Ctrl-C"; issue 13).

One child process (interrupt_child.py) runs each operation in turn; the test sends it SIGINT once
the operation has run for WORK_BEFORE_SIGNAL and measures the time until the child reports the
KeyboardInterrupt. The bound is the API's stated property, not a benchmark: C++ work polls its
cancel flag at least every 64 samples / one ray step / one optimiser evaluation, and the waiting
thread checks for signals every 50 ms; measured latencies are 0.01-0.15 s on 2 loaded cores,
so 1 s leaves a margin of more than 5x for a slower or busier machine."""

import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

LATENCY_BOUND = 1.0        # [s] the property asserted
WORK_BEFORE_SIGNAL = 0.8   # [s] every operation below would run for many seconds more
HANG_GUARD = 60.0          # [s] a bound against a hang of the whole child, not a timing assertion

OPERATIONS = ["trace_rays", "trace_ray", "render_straight", "render_curved", "render_raster_march",
              "render_table", "render_raster", "solve", "sweep"]
ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.slow
def test_every_long_operation_stops_within_a_second_of_ctrl_c():
    latencies = {}
    with subprocess.Popen([sys.executable, "-m", "tests.hardening.interrupt_child", *OPERATIONS], cwd=ROOT,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as child:
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
