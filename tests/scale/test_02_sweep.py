"""refracta.sweep without a cluster: grid order, failures reported with their parameters while
every other result is kept, progress, and the same results from thread and process pools."""

import concurrent.futures
import multiprocessing
import os
import pickle
import queue
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import refracta
from refracta import SweepError, sweep
from refracta._sweep import grid_points
from tests.scale import scenes


def mirage_end_height(surface_dt, eye):
    """Height [m] where a ray launched 0.2 deg down from the eye is after 600 m over a hot road."""
    road = refracta.PhysicalAtmosphere(surface_dt=surface_dt, surface_depth=0.2)
    e = np.radians(-0.2)
    return refracta.trace_ray(road, [0, eye, 0], [np.cos(e), np.sin(e), 0], max_length=600.0).points[-1, 1]


def fails_when_hot(surface_dt, eye):
    if surface_dt > 9:
        raise ValueError(f"too hot: {surface_dt}")
    return surface_dt * eye


def test_a_dict_grid_is_the_cartesian_product_with_the_last_key_fastest():
    points = grid_points({"a": [1, 2], "b": ["x", "y", "z"]})
    assert points == [
        {"a": 1, "b": "x"},
        {"a": 1, "b": "y"},
        {"a": 1, "b": "z"},
        {"a": 2, "b": "x"},
        {"a": 2, "b": "y"},
        {"a": 2, "b": "z"},
    ]
    assert grid_points([{"a": 3}, {"a": 1, "b": 2}]) == [{"a": 3}, {"a": 1, "b": 2}]


def test_serial_sweep_returns_results_in_grid_order():
    grid = {"surface_dt": [2.0, 8.0, 15.0], "eye": [1.2, 1.6]}
    result = sweep(mirage_end_height, grid, progress=False)
    expected = [mirage_end_height(**p) for p in grid_points(grid)]
    assert list(result) == expected and result.points == grid_points(grid) and result.ok
    # The physics orders them: a hotter road bends the same ray further up (higher end point).
    assert result[0] < result[2] < result[4] and result[1] < result[3] < result[5]


@pytest.mark.parametrize("pool", ["threads", "processes"])
def test_pools_give_the_serial_results(pool):
    grid = {"surface_dt": [2.0, 8.0, 15.0], "eye": [1.2, 1.6]}
    serial = sweep(mirage_end_height, grid, progress=False)
    if pool == "threads":
        executor = concurrent.futures.ThreadPoolExecutor(2)
    else:
        executor = concurrent.futures.ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn"))
    with executor:
        parallel = sweep(mirage_end_height, grid, executor=executor, progress=False)
    assert list(parallel) == list(serial)


def shared_reads(_big, index):
    """(this worker's pid, the shared file its arguments came from, index): for the test below."""
    import os

    from refracta import _sweep

    return os.getpid(), _sweep._shared_in_worker[0], index


def test_a_process_pool_gets_the_shared_arguments_as_one_file_removed_after(tmp_path, monkeypatch):
    # They went with every task (a default Turbulence's 67 MB with every animation frame, a
    # trial): now one pickle file, read once by each worker process, removed at the end.
    import tempfile

    from refracta._sweep import map_ordered

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    big = np.zeros(1_000_000)
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=context) as executor:
        outcomes = map_ordered(shared_reads, [(i,) for i in range(8)], executor, shared=(big,))
    assert all(ok for ok, _ in outcomes) and [value[2] for _, value in outcomes] == list(range(8))
    files = {value[1] for _, value in outcomes}
    assert len(files) == 1 and not list(tmp_path.iterdir())  # one file for every task, removed after


def test_failed_points_are_reported_with_their_parameters_and_the_rest_kept():
    grid = {"surface_dt": [5.0, 10.0, 3.0, 12.0], "eye": [2.0]}
    with pytest.raises(
        SweepError, match=r"2 of 4 sweep points failed: point 1 \{'surface_dt': 10.0, 'eye': 2.0\}"
    ) as caught:
        sweep(fails_when_hot, grid, progress=False)
    error = caught.value
    assert [f.index for f in error.failures] == [1, 3]
    assert error.failures[1].point == {"surface_dt": 12.0, "eye": 2.0}
    assert isinstance(error.failures[0].error, ValueError) and "too hot: 10.0" in error.failures[0].traceback
    assert list(error.results) == [10.0, None, 6.0, None]
    kept = sweep(fails_when_hot, grid, progress=False, errors="keep")
    assert list(kept) == [10.0, None, 6.0, None] and not kept.ok and len(kept.failures) == 2
    copy = pickle.loads(pickle.dumps(error))  # travels back from workers / to other processes
    assert [f.point for f in copy.failures] == [f.point for f in error.failures]


def test_progress_reports_every_finished_point():
    calls = []
    sweep(fails_when_hot, {"surface_dt": [1.0, 2.0, 3.0], "eye": [1.0]}, progress=lambda d, t: calls.append((d, t)))
    assert calls == [(0, 3), (1, 3), (2, 3), (3, 3)]


def test_a_sweep_of_renders_equals_the_renders():
    grid = [{"surface_dt": 4.0}, {"surface_dt": 14.0}]
    images = sweep(render_road, grid, progress=False)
    for point, image in zip(grid, images):
        assert np.array_equal(image, render_road(**point))
    assert not np.array_equal(images[0], images[1])  # the mirage differs


def render_road(surface_dt):
    scene = refracta.Scene()
    scene.add_ground(0.0, 400.0, kd=(0.2, 0.2, 0.2))
    scene.add_box((120.0, 1.0, 0.0), (2.0, 2.0, 4.0), kd=(0.8, 0.1, 0.1))
    scene.set_sky(horizon=(0.8, 0.85, 0.9), zenith=(0.3, 0.4, 0.8))
    camera = refracta.Camera((0.0, 1.2, 0.0), (120.0, 0.9, 0.0), vfov=3.0, width=scenes.WIDTH, height=scenes.HEIGHT)
    field = refracta.PhysicalAtmosphere(surface_dt=surface_dt, surface_depth=0.2)
    return refracta.render(scene, camera, field, progress=False, max_length=400.0)


@pytest.mark.parametrize(
    "bad, message",
    [
        (dict(function=5, grid={"a": [1]}), "callable"),
        (dict(function=fails_when_hot, grid={"a": 3}), "list of values"),
        (dict(function=fails_when_hot, grid=[1, 2]), "dict of parameter names"),
        (dict(function=fails_when_hot, grid={"a": [1]}, errors="ignore"), "errors must be"),
        (dict(function=fails_when_hot, grid={"a": [1]}, executor="cluster"), "executor must be"),
        (dict(function=fails_when_hot, grid={"a": [1]}, progress=3), "progress must be"),
    ],
)
def test_bad_arguments_raise_value_errors(bad, message):
    with pytest.raises(ValueError, match=message):
        sweep(**bad)


# Ctrl-C, measured with real SIGINTs to a child running a sweep: the child prints "ready" once a
# render is under way (its progress callback's first call: in a pool's thread or worker process,
# whose stdout is the child's) and "stopped" when the KeyboardInterrupt has left the `with
# executor` block, i.e. after the pool's work has stopped. Every render would run for many
# minutes (spp below), so no machine finishes one first.
# [s] the property asserted (DESIGN.md: stops promptly on Ctrl-C), as test_01_ctrl_c's: within a
# second when the machine is not overloaded (serial and thread-pool sweeps: 0.0001-0.15 s measured
# with two CPU burners beside them).
LATENCY_BOUND = 2.0
HANG_GUARD = 60.0  # [s] a bound against a hung child, not a timing assertion
# [s] a bound against orphaned workers rendering on; they check for their parent every 0.2 s
# (_sweep._PARENT_POLL), so this is a hang guard rather than a timing assertion.
ORPHAN_GUARD = 10.0

_INTERRUPTED_SWEEP = """
import concurrent.futures, multiprocessing, os, signal, sys
import refracta
from refracta import examples

# Ctrl-C as a terminal delivers it: a process started from a background job of a non-interactive
# shell (CI's or a script's `make test &`) inherits SIGINT ignored, and Python then installs no
# KeyboardInterrupt handler (seen: SigIgn 0x81001007 in such a child, which rendered on).
signal.signal(signal.SIGINT, signal.default_int_handler)

announced = False

def started(done, total):
    global announced
    if not announced:
        announced = True
        # One write(2) below PIPE_BUF is atomic: the pool's two workers share this pipe and may
        # announce at the same moment (print's buffered writes interleaved as "ready 7440ready").
        os.write(1, f"ready {os.getpid()}\\n".encode())

# Built once, before the sweep: a task is then a refracta call from its first instruction (Python
# code a task runs before or between refracta calls is not interrupted on a thread pool).
road = examples.hot_road(160, 60)

def long_render(surface_dt):
    return refracta.render(road.scene, road.camera, road.field.with_params(surface_dt=surface_dt),
                           spp=1_000_000, progress=started, max_length=road.max_length)

if __name__ == "__main__":
    kind = sys.argv[1]
    executor = {"serial": None,
                "threads": concurrent.futures.ThreadPoolExecutor(2),
                "processes": concurrent.futures.ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")),
                }[kind]
    try:
        if executor is None:
            refracta.sweep(long_render, {"surface_dt": [5.0, 10.0, 15.0]}, progress=False)
        else:
            with executor:
                refracta.sweep(long_render, {"surface_dt": [5.0, 10.0, 15.0]}, executor=executor, progress=False)
    except KeyboardInterrupt:
        print("stopped", flush=True)
"""


def _start_sweep(tmp_path, kind):
    script = tmp_path / "interrupted_sweep.py"  # a file, so that spawned workers can import it
    script.write_text(_INTERRUPTED_SWEEP)
    process = subprocess.Popen(
        [sys.executable, str(script), kind], cwd=tmp_path, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    ready = process.stdout.readline().split()
    if len(ready) != 2 or ready[0] != "ready" or not ready[1].isdigit():
        process.kill()
        _, stderr = process.communicate(timeout=HANG_GUARD)  # closes the pipes
        pytest.fail(f"the sweep's child did not announce a render: {ready} {stderr}")
    return process, int(ready[1])


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["serial", "threads", "processes"])
def test_ctrl_c_stops_a_sweep_promptly(tmp_path, kind):
    process, _ = _start_sweep(tmp_path, kind)
    try:
        sent = time.monotonic()
        process.send_signal(signal.SIGINT)
        reply = _read_line(process, HANG_GUARD)
        while reply.startswith("ready"):  # a process pool's other worker announcing its own render
            reply = _read_line(process, HANG_GUARD)
        latency = time.monotonic() - sent
        process.communicate(timeout=HANG_GUARD)
    finally:
        process.kill()
        process.communicate()  # reaped and its pipes closed, even when the test failed
    assert reply == "stopped" and process.returncode == 0
    assert latency < LATENCY_BOUND, f"{kind}: Ctrl-C took {latency:.2f} s"


def _read_line(process, timeout):
    """The child's next line of output, stripped; "" if none comes within `timeout` [s] (a child
    that ignored Ctrl-C must fail the test, not hang the suite)."""
    lines: queue.Queue[str] = queue.Queue()
    threading.Thread(target=lambda: lines.put(process.stdout.readline()), daemon=True).start()
    try:
        return lines.get(timeout=timeout).strip()
    except queue.Empty:  # the reader ends when the caller kills the child
        return ""


def _gone(pid):
    """True once pid has exited (a zombie left for a parent that does not reap counts as gone)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")
def test_process_pool_workers_exit_when_their_parent_is_killed(tmp_path):
    process, worker = _start_sweep(tmp_path, "processes")
    assert worker != process.pid  # the announcing render runs in a pool worker
    process.kill()  # SIGKILL: no handler, no cleanup in the parent
    process.communicate(timeout=HANG_GUARD)
    deadline = time.monotonic() + ORPHAN_GUARD
    while not _gone(worker) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert _gone(worker), f"worker {worker} still rendering {ORPHAN_GUARD} s after its parent was killed"


def test_unpicklable_shared_arguments_leave_no_file(tmp_path, monkeypatch):
    import tempfile

    from refracta._sweep import map_ordered

    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    context = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=context) as executor:
        with pytest.raises((pickle.PicklingError, AttributeError, TypeError)):
            map_ordered(shared_reads, [(0,)], executor, shared=(lambda: 0,))
    assert not list(tmp_path.iterdir())


def test_a_sigint_while_waiting_is_raised_between_waits_not_inside_them():
    # Raised at any bytecode, a Ctrl-C could land inside concurrent.futures.wait between its
    # acquisitions of the futures' locks, leaving one held, and the sweep hung (a make test).
    from refracta import _sweep

    # Python's own Ctrl-C handler, as in a terminal (a background job may inherit SIGINT ignored).
    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        _sigint_noted_then_raised(_sweep)
    finally:
        signal.signal(signal.SIGINT, inherited)


def _sigint_noted_then_raised(_sweep):
    with _sweep._sigint_between_waits() as raise_if_interrupted:
        os.kill(os.getpid(), signal.SIGINT)  # delivered to this (the main) thread: only noted
        time.sleep(0.01)  # the handler runs between bytecodes: it must not raise here
        with pytest.raises(KeyboardInterrupt):
            raise_if_interrupted()
        raise_if_interrupted()  # noted once
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    with pytest.raises(KeyboardInterrupt):  # one noted after the last wait is raised on leaving
        with _sweep._sigint_between_waits():
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.01)
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


# [s] a bound against a hung wait (the fault below waited forever), not a timing assertion.
RESCUE_AFTER = 30.0
# [s] how long the busy thread keeps the GIL after the signal: well past the 50 ms wait.
GIL_HELD = 0.3


def test_a_wait_interrupted_past_its_deadline_still_wakes():
    # A make test: the thread-pool sweep hung after Ctrl-C, its main thread waiting for ever. CPython
    # 3.11's SimpleQueue.get(timeout) waits again with the time left after a signal, and when that
    # is negative (the main thread got the GIL back after the deadline) the wait has no timeout.
    # Here a thread holds the GIL well past the 50 ms wait when the SIGINT reaches the main thread.
    from refracta import _sweep

    never_done: concurrent.futures.Future = concurrent.futures.Future()
    main = threading.get_ident()

    def interrupt_while_holding_the_gil():
        time.sleep(0.02)  # the main thread is inside a wait by now (all but microseconds of a loop)
        signal.pthread_kill(main, signal.SIGINT)
        end = time.monotonic() + GIL_HELD
        while time.monotonic() < end:  # pure Python: keeps the GIL within the switch interval
            pass

    rescue = threading.Timer(RESCUE_AFTER, never_done.set_result, args=(None,))
    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    switch_interval = sys.getswitchinterval()
    sys.setswitchinterval(1.0)  # the busy thread is not asked to give the GIL up sooner
    try:
        rescue.start()
        threading.Thread(target=interrupt_while_holding_the_gil, daemon=True).start()
        with pytest.raises(KeyboardInterrupt):
            next(_sweep._as_completed_waking({never_done: 0}))
        assert not never_done.done(), "the interrupted wait woke only when its future finished"
    finally:
        sys.setswitchinterval(switch_interval)
        signal.signal(signal.SIGINT, inherited)
        rescue.cancel()


class TwoArgumentError(Exception):
    def __init__(self, code, text):
        super().__init__(f"{code}: {text}")


def raises_an_exception_that_does_not_unpickle(x):
    if x == 2:
        raise TwoArgumentError(7, "bad point")
    return x * x


def test_a_process_pool_point_whose_exception_cannot_come_back_loses_no_other_point():
    # A trial: the exception could not be rebuilt in the parent, the pool broke, points 2-5 were lost.
    with concurrent.futures.ProcessPoolExecutor(2) as pool:
        result = sweep(raises_an_exception_that_does_not_unpickle, {"x": range(6)}, pool, progress=False, errors="keep")
    assert list(result) == [0, 1, None, 9, 16, 25]
    assert "7: bad point" in str(result.failures[0].error)


def test_one_huge_axis_is_refused_by_name_before_it_is_listed():
    with pytest.raises(ValueError, match=r"grid\['x'\] has more than 10,000,000 values"):
        grid_points({"x": range(10**12)})


def test_many_points_are_waited_for_in_one_pass():
    # A trial: each wake waited on every pending future again, n points costing n^2 (20 000
    # trivial points 84 s). Counted, not timed: each future's done-callback is registered once.
    registered = []

    class CountingFuture(concurrent.futures.Future):
        def add_done_callback(self, fn):
            registered.append(self)
            super().add_done_callback(fn)

    class Immediate(concurrent.futures.Executor):
        def submit(self, fn, /, *args, **kwargs):
            future = CountingFuture()
            future.set_result(fn(*args, **kwargs))
            return future

    result = sweep(lambda x: x + 1, {"x": range(500)}, Immediate(), progress=False)
    assert list(result) == list(range(1, 501))
    assert len(registered) == 500  # once each (concurrent.futures.wait registers a waiter per call instead)
