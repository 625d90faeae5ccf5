"""The interpreter exits cleanly while a daemon thread is inside render or trace_rays (a
CustomField, calling back into Python, included): the atexit hook cancels the work and waits for
it; before issue 13 the process aborted ("terminate called without an active exception",
"FATAL: exception not rethrown", exit status -6)."""

import subprocess
import sys

import pytest

HANG_GUARD = 60.0  # [s] a bound against a hang at exit, not a timing assertion

_CHILD = """
import threading, time
import numpy as np
import refracta
from refracta import examples

kind = {kind!r}
if kind == "render":
    road = examples.hot_road(160, 60)
    work = lambda: refracta.render(road.scene, road.camera, road.field, spp=4096, max_length=road.max_length,
                                   progress=False)
elif kind == "trace_rays":
    field = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    work = lambda: refracta.trace_rays(field, [0, 1.5, 0], np.tile([1, -0.001, 0.0], (200_000, 1)), tol=1e-9,
                                       max_length=1e5)
else:
    field = refracta.CustomField(lambda p: 1.0 + 1e-6 * p[:, 1], lambda p: np.tile([0, 1e-6, 0], (len(p), 1)))
    work = lambda: refracta.trace_rays(field, [0, 1.5, 0], np.tile([1, -0.001, 0.0], (20_000, 1)), max_length=1e5)
started = threading.Event()
def run():
    started.set()
    work()
threading.Thread(target=run, daemon=True).start()
started.wait()
time.sleep(0.5)  # well inside the C++ work
print("exiting", flush=True)
"""


@pytest.mark.parametrize("kind", ["render", "trace_rays", "custom_field"])
def test_exit_while_a_daemon_thread_works_is_clean(kind):
    result = subprocess.run(
        [sys.executable, "-c", _CHILD.format(kind=kind)], capture_output=True, text=True, timeout=HANG_GUARD
    )
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "exiting"
    assert "terminate" not in result.stderr and "FATAL" not in result.stderr, result.stderr


def test_calls_after_the_exit_hook_raise_instead_of_running():
    code = (
        "import refracta, refracta._core as c\nc._shutdown_running_work(1.0)\n"
        "try:\n    refracta.trace_ray(refracta.PhysicalAtmosphere(), [0, 1, 0], [1, 0, 0])\n"
        "except RuntimeError as e:\n    print(e)\n"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=HANG_GUARD)
    assert result.returncode == 0, result.stderr
    assert "shutting down" in result.stdout
