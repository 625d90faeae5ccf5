"""refracta.sweep: map a function over a parameter grid on any concurrent.futures.Executor (the module refracta._sweep).

The same code runs in-process (``executor=None``), on the cores of one machine
(``ProcessPoolExecutor``) or on a cluster through dask.distributed: pass a ``distributed.Client``
(its ``get_executor()`` is used) or any ``concurrent.futures.Executor``. refracta has no cluster
manager of its own; a real cluster is just another Client::

    from dask_jobqueue import SLURMCluster          # or dask_kubernetes.operator.KubeCluster
    from distributed import Client
    cluster = SLURMCluster(cores=8, memory="16GB", walltime="01:00:00")
    cluster.scale(jobs=10)
    client = Client(cluster)
    results = refracta.sweep(render_road, {"surface_dt": [2, 5, 10, 15]}, executor=client)

Every refracta object pickles (fields, scenes with their meshes and texture paths, cameras,
materials, lights, pairs, results), so arguments and results travel between processes; texture
and OBJ files are referenced by path and must be readable by the workers (a shared file system).
dask re-runs the tasks of a worker that dies (up to its ``allowed-failures``), so a lost worker
costs time, not results. The tiled ``refracta.render(..., executor=, tiles=)`` and animations go
through the same executor path (:func:`map_ordered`).
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import itertools
import math
import multiprocessing
import os
import pickle
import queue
import signal
import tempfile
import threading
import time
import traceback
import uuid
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

from refracta import _core
from refracta._progress import ProgressArg, progress_callback

__all__ = ["SweepError", "SweepFailure", "SweepResult", "grid_points", "map_ordered", "sweep"]


@dataclass(frozen=True)
class SweepFailure:
    """A point whose call raised: its position in grid order, its parameters and the error."""

    index: int
    point: dict[str, Any]
    error: BaseException
    traceback: str

    def __str__(self) -> str:
        return f"point {self.index} {self.point!r}: {type(self.error).__name__}: {self.error}"


class SweepResult(list):
    """The results of a sweep in grid order (a list; None where a point failed).

    Attributes:
        points: the parameter dicts, in the same order.
        failures: one SweepFailure per failed point (empty when all succeeded).
    """

    def __init__(self, results: Iterable[Any], points: Sequence[dict[str, Any]], failures: Sequence[SweepFailure]):
        super().__init__(results)
        self.points = list(points)
        self.failures = list(failures)

    @property
    def ok(self) -> bool:
        """True when every point succeeded."""
        return not self.failures

    def __reduce__(self):
        return (SweepResult, (list(self), self.points, self.failures))


class SweepError(RuntimeError):
    """Raised by sweep(errors='raise') when points failed, after every other point finished.

    Attributes:
        failures: the SweepFailure of each failed point (parameters and exception).
        results: the SweepResult: every successful point's result is kept (None at failures).
    """

    def __init__(self, failures: Sequence[SweepFailure], results: SweepResult):
        self.failures = list(failures)
        self.results = results
        shown = "; ".join(str(f) for f in self.failures[:3])
        more = f" (and {len(self.failures) - 3} more)" if len(self.failures) > 3 else ""
        super().__init__(f"{len(self.failures)} of {len(results)} sweep points failed: {shown}{more}")

    def __reduce__(self):
        return (SweepError, (self.failures, self.results))


# The most points a dict-of-lists grid may hold: they are made (a dict each, ~0.5 kB) before the
# first run, so 10^10 of them (ten axes of ten values, a typo away) filled the memory instead.
_MOST_GRID_POINTS = 10_000_000


def grid_points(grid: Mapping[str, Sequence[Any]] | Sequence[Mapping[str, Any]]) -> list[dict[str, Any]]:
    """The points of a grid, in sweep order.

    A dict of lists is the cartesian product in the dict's key order, the last key varying fastest
    (as nested for loops, itertools.product, numpy.meshgrid(indexing='ij')): ``{"a": [1, 2], "b":
    [3, 4]}`` gives a=1,b=3; a=1,b=4; a=2,b=3; a=2,b=4. A list of dicts is taken as it is.
    """
    if isinstance(grid, Mapping):
        names = list(grid)
        if not names:  # the product of no axes is one empty point: f() once, which no one means
            raise ValueError("sweep: grid names no parameter (a dict of lists: {'name': [values], ...})")
        values = []
        for name in names:
            if not isinstance(name, str):
                raise ValueError(f"sweep: grid keys must be parameter names (got {name!r})")
            axis = grid[name]
            zero_d = isinstance(axis, np.ndarray) and axis.ndim == 0  # iterable by type, not by shape
            if isinstance(axis, (str, bytes)) or not isinstance(axis, Iterable) or zero_d:
                raise ValueError(f"sweep: grid[{name!r}] must be a list of values (got {axis!r})")
            if isinstance(axis, (set, frozenset)):  # its order is arbitrary, and so would the sweep's be
                raise ValueError(f"sweep: grid[{name!r}] must be ordered values (a list; got a set)")
            # At most the grid's limit of values (a range(10**12) axis was listed whole: MemoryError).
            values.append(list(itertools.islice(axis, _MOST_GRID_POINTS + 1)))
            if len(values[-1]) > _MOST_GRID_POINTS:
                raise ValueError(
                    f"sweep: grid[{name!r}] has more than {_MOST_GRID_POINTS:,} values; sweep fewer, "
                    "or pass a list of the points to run"
                )
            if not values[-1]:  # the product is then empty: nothing would run
                raise ValueError(f"sweep: grid[{name!r}] has no values (the sweep would run nothing)")
        count = math.prod(len(axis) for axis in values)
        if count > _MOST_GRID_POINTS:  # each point a dict, built before the first run: refuse, not swap
            lengths = " x ".join(f"{name}={len(axis)}" for name, axis in zip(names, values))
            raise ValueError(
                f"sweep: the grid has {count:,} points ({lengths}), more than {_MOST_GRID_POINTS:,}; "
                "sweep fewer values per parameter, or pass a list of the points to run"
            )
        return [dict(zip(names, combination)) for combination in itertools.product(*values)]
    if isinstance(grid, (str, bytes)) or not isinstance(grid, Iterable):
        raise ValueError(f"sweep: grid must be a dict of lists or a list of dicts (got {type(grid).__name__})")
    points = []
    for i, point in enumerate(grid):
        if not isinstance(point, Mapping) or not all(isinstance(k, str) for k in point):
            raise ValueError(f"sweep: grid[{i}] must be a dict of parameter names to values (got {point!r})")
        points.append(dict(point))
    if not points:
        raise ValueError("sweep: grid is an empty list of points (the sweep would run nothing)")
    return points


def as_executor(executor) -> concurrent.futures.Executor | None:
    """A concurrent.futures.Executor for `executor`: None stays None (in-process), a
    dask.distributed Client a _DaskExecutor on it (every task runs; futures are
    concurrent.futures futures), an Executor is returned as is."""
    if executor is None or isinstance(executor, concurrent.futures.Executor):
        return executor
    if callable(getattr(executor, "get_executor", None)):
        return _DaskExecutor(executor)
    raise ValueError(
        "executor must be None, a concurrent.futures.Executor or a dask.distributed Client "
        f"(got {type(executor).__name__})"
    )


class _DaskExecutor(concurrent.futures.Executor):
    """A dask.distributed Client as a concurrent.futures.Executor: Client.submit(pure=False), each
    remote future's end carried to a concurrent.futures.Future, whatever it was. The Client's own
    get_executor left a future unset when a result could not be serialised (its cascade raised
    inside the callback), and a sweep waited on it forever (a trial)."""

    def __init__(self, client):
        self.client = client
        self._remote: list = []

    def submit(self, fn, /, *args, **kwargs):
        local: concurrent.futures.Future = concurrent.futures.Future()
        remote = self.client.submit(fn, *args, pure=False, **kwargs)
        self._remote.append(remote)

        def carry(remote) -> None:
            if local.done():
                return
            try:
                if remote.status == "cancelled":
                    local.set_exception(concurrent.futures.CancelledError())
                elif remote.status == "error":
                    local.set_exception(remote.exception())
                else:
                    local.set_result(remote.result())
            except BaseException as error:  # the result's own transfer failed
                if not local.done():
                    local.set_exception(error)

        remote.add_done_callback(carry)
        return local

    def shutdown(self, wait: bool = True, *, cancel_futures: bool = False) -> None:
        if cancel_futures:
            self.client.cancel(self._remote)


def map_ordered(
    function: Callable,
    arguments: Sequence[tuple],
    executor=None,
    progress: ProgressArg = False,
    label: str = "sweep",
    shared: tuple = (),
) -> list[tuple]:
    """Calls function(*shared, *args) for each tuple of `arguments` on `executor` (as_executor's
    kinds); returns one (ok, value) per call in the order of `arguments`: (True, result) or
    (False, (exception, traceback text)). `shared`: arguments common to every call (a tiled render's
    scene), sent to each dask worker once (Client.scatter, broadcast) instead of with every task;
    they are lost if every worker holding them dies, so use it for short jobs over large data. To
    a ProcessPoolExecutor they go as one pickle file, which each worker process reads once (a
    default Turbulence's 67 MB went with every animation frame), removed when the calls end.
    progress(done, total) after each finished call. The shared path of sweep, tiled renders and
    animation frames.

    Ctrl-C (or any exception while waiting) stops the work before it is raised: calls not yet
    started are cancelled; on a ThreadPoolExecutor the refracta calls running on its threads are
    cancelled, and any refracta call those tasks start afterwards fails at once (RuntimeError into
    futures nobody reads; Python code a task runs between refracta calls is not interrupted);
    a ProcessPoolExecutor is shut down and its worker processes terminated (the executor cannot
    be used again). Workers of a ProcessPoolExecutor also exit when the process that submitted
    their work dies (they would otherwise render on as orphans)."""
    pool = as_executor(executor)
    if shared and callable(getattr(executor, "scatter", None)):  # a dask Client
        shared = tuple(executor.scatter(list(shared), broadcast=True, hash=False))
    shared = tuple(shared)
    callback = progress_callback(progress, label)
    total = len(arguments)
    outcomes: dict[int, tuple] = {}  # by call index, filled as the calls finish
    if callback:
        callback(0, total)
    if pool is None:
        for i, args in enumerate(arguments):
            try:
                outcomes[i] = (True, function(*shared, *args))
            except Exception as error:  # recorded with its point; KeyboardInterrupt propagates
                outcomes[i] = (False, (error, traceback.format_exc()))
            if callback:
                callback(i + 1, total)
        return [outcomes[i] for i in range(total)]
    futures = {}
    threads = _RunningThreads()
    shared_file: str | None = None
    task: Callable[..., Any]
    head: tuple[Any, ...]
    if isinstance(pool, concurrent.futures.ThreadPoolExecutor):
        task, head = threads.call, (function,)
    elif isinstance(pool, concurrent.futures.ProcessPoolExecutor):
        shared_file = _pickled(shared)
        task, head, shared = _call_in_worker, (os.getpid(), function, shared_file), ()
    else:
        task, head = function, ()
    try:
        for i, args in enumerate(arguments):
            try:
                futures[pool.submit(task, *head, *shared, *args)] = i
            except Exception as error:  # this point's arguments do not travel (dask: not serialisable)
                outcomes[i] = (False, (error, traceback.format_exc()))
        done = len(outcomes)
        if callback and done:
            callback(done, total)
        for future in _as_completed_waking(futures):
            i = futures[future]
            failure = future.exception()
            if failure is None:
                outcomes[i] = (True, future.result())
            else:
                text = "".join(traceback.format_exception(type(failure), failure, failure.__traceback__))
                outcomes[i] = (False, (failure, text))
            done += 1
            if callback:
                callback(done, total)
    except BaseException:
        _stop(pool, futures, threads)
        raise
    finally:
        if shared_file is not None:
            os.remove(shared_file)
    return [outcomes[i] for i in range(total)]


# How often the waiting main thread wakes (a Ctrl-C is handled within it, below).
_WAKE_SECONDS = 0.05


def _as_completed_waking(futures):
    """concurrent.futures.as_completed, waking every _WAKE_SECONDS. Python runs a signal's handler
    only in the main thread, and the kernel may deliver SIGINT to any thread: one delivered to a
    pool or TBB thread only flags it, and a main thread blocked in as_completed's untimed wait
    never runs the handler, so Ctrl-C was lost while the renders ran on (seen in a fresh-clone
    `make test`: tests/scale/test_02_sweep.py's thread-pool sweep still rendering minutes after
    SIGINT). Each timed wait returns to the interpreter, and the Ctrl-C is raised between waits
    (_sigint_between_waits). The futures report to a queue as they finish: a
    concurrent.futures.wait over every pending future at each wake made n points cost n^2 (a
    trial: 20 000 trivial points took 84 s against executor.map's 6 s). A queue.Queue, not a
    SimpleQueue: CPython 3.11's SimpleQueue.get(timeout=...), interrupted by a signal and given the
    GIL back after its deadline, waits again with the negative time left, i.e. for ever (the check
    _thread's lock.acquire makes is missing there). On a loaded machine the sweep hung so after
    Ctrl-C, about 1 run in 25 beside two CPU burners."""
    finished: queue.Queue = queue.Queue()
    for future in futures:
        future.add_done_callback(finished.put)
    remaining = len(futures)
    with _sigint_between_waits() as raise_if_interrupted:
        while remaining:
            try:
                future = finished.get(timeout=_WAKE_SECONDS)
            except queue.Empty:
                raise_if_interrupted()
                continue
            raise_if_interrupted()
            remaining -= 1
            yield future


@contextlib.contextmanager
def _sigint_between_waits():
    """In the main thread with Python's own Ctrl-C handler: SIGINT only noted while inside, and
    KeyboardInterrupt raised by the callable it yields (or on leaving), between waits. Raised at
    any bytecode, it could land inside concurrent.futures.wait between its acquisitions of the
    futures' locks, leaving one held: cancelling the futures then deadlocked, and the sweep hung
    (a `make test`: tests/scale/test_02_sweep.py's thread-pool sweep, no reply 60 s after SIGINT).
    Elsewhere (another thread, a handler of the user's): no change."""
    main = threading.current_thread() is threading.main_thread()
    if not main or signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield lambda: None
        return
    caught: list[int] = []

    def raise_if_interrupted() -> None:
        if caught:
            caught.clear()
            raise KeyboardInterrupt

    previous = signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
    try:
        yield raise_if_interrupted
    finally:
        signal.signal(signal.SIGINT, previous)
    raise_if_interrupted()  # one that came after the last wait


class _RunningThreads:
    """The threads of a thread pool running one map_ordered's calls, so that Ctrl-C in the main
    thread can cancel their refracta work: the calls running and any a task starts afterwards
    (a task interrupted while still in Python would otherwise start its render after the cancel)."""

    def __init__(self):
        self._lock = threading.Lock()
        self._ids: dict[int, int] = {}  # threading.get_ident() -> tasks running there
        self._stopped = False

    def call(self, function: Callable, *args) -> Any:
        ident = threading.get_ident()
        with self._lock:
            if self._stopped:
                raise concurrent.futures.CancelledError()
            self._ids[ident] = self._ids.get(ident, 0) + 1
        try:
            return function(*args)
        finally:
            with self._lock:
                self._ids[ident] -= 1
                if not self._ids[ident]:
                    del self._ids[ident]
                    if self._stopped:
                        _core._end_thread_cancel(ident)

    def stop(self) -> None:
        """Cancels the running tasks' refracta work and refuses tasks not yet started."""
        with self._lock:
            self._stopped = True
            _core._cancel_thread_work(list(self._ids))


def _stop(pool: concurrent.futures.Executor, futures, threads: _RunningThreads) -> None:
    """Stops the work of an interrupted map_ordered: pending calls cancelled, running refracta
    calls on pool threads cancelled, a process pool's workers terminated."""
    for future in futures:
        future.cancel()
    if isinstance(pool, _DaskExecutor):
        pool.shutdown(wait=False, cancel_futures=True)
    elif isinstance(pool, concurrent.futures.ThreadPoolExecutor):
        threads.stop()
    elif isinstance(pool, concurrent.futures.ProcessPoolExecutor):
        processes = list((getattr(pool, "_processes", None) or {}).values())
        pool.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            process.terminate()
        for process in processes:
            process.join(_TERMINATE_WAIT)


# [s] how long an interrupted map_ordered waits for each terminated worker process to be reaped:
# SIGTERM ends it at once (the default action, even inside C++ work); this only bounds a stuck one.
_TERMINATE_WAIT = 5.0
# [s] how often a process-pool worker checks that the process that submitted its work is alive:
# an orphan stops within this (its work is lost anyway: nobody is left to read it).
_PARENT_POLL = 0.2
_watching_parent = False


def _pickled(shared: tuple) -> str:
    """The path of a new temporary file holding `shared` pickled (map_ordered removes it)."""
    # A name of its own (a cached worker copy is known by it, and mkstemp may reuse a removed one's).
    handle, path = tempfile.mkstemp(prefix=f"refracta-shared-{uuid.uuid4().hex}-", suffix=".pickle")
    try:
        with os.fdopen(handle, "wb") as file:
            pickle.dump(shared, file, protocol=pickle.HIGHEST_PROTOCOL)
    except BaseException:  # unpicklable (a lambda), a full disk: no file left behind
        os.remove(path)
        raise
    return path


# A worker process's shared arguments: (the file they came from, the arguments), read once.
_shared_in_worker: tuple[str, tuple] | None = None


def _call_in_worker(parent_pid: int, function: Callable, shared_file: str, *args) -> Any:
    """function(*shared, *args) in a ProcessPoolExecutor worker, `shared` read from shared_file
    once per worker process (map_ordered's); the worker exits once `parent_pid` (the submitting
    process) has died: a killed parent's workers would otherwise render on."""
    global _watching_parent, _shared_in_worker
    if not _watching_parent:
        _watching_parent = True
        threading.Thread(
            target=_exit_with_parent, args=(parent_pid, os.getppid()), daemon=True, name="refracta-parent-watch"
        ).start()
    if _shared_in_worker is None or _shared_in_worker[0] != shared_file:
        with open(shared_file, "rb") as file:
            _shared_in_worker = (shared_file, pickle.load(file))
    try:
        return function(*_shared_in_worker[1], *args)
    except Exception as error:
        try:  # it must come back whole: one that cannot be rebuilt broke the pool, every later point lost
            pickle.loads(pickle.dumps(error))
        except Exception:
            raise RuntimeError(f"{type(error).__name__}: {error}\n{traceback.format_exc()}") from None
        raise


def _exit_with_parent(parent_pid: int, first_ppid: int) -> None:
    while True:
        # Reparented (the parent, or a forkserver between us, died), or the submitter is gone.
        if os.getppid() != first_ppid or not _alive(parent_pid):
            os._exit(1)
        time.sleep(_PARENT_POLL)


# Linux's process table as files. Elsewhere (macOS) there is no /proc: opening one raised
# FileNotFoundError, read as "the parent has died", and every worker exited on its first task.
_HAS_PROC = os.path.isdir("/proc/self")


def _alive(pid: int) -> bool:
    """False once pid has exited, including as a zombie not yet reaped (a killed parent whose own
    parent waits for our pipes to close: a worker that started its task only after the kill)."""
    if _HAS_PROC:
        try:
            with open(f"/proc/{pid}/stat") as stat:
                return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
        except FileNotFoundError:
            return False
        except OSError:  # unreadable: alive
            return True
    if os.name == "nt":  # os.kill(pid, 0) would send CTRL_C_EVENT there: ask multiprocessing instead
        parent = multiprocessing.parent_process()
        return parent is None or parent.pid != pid or parent.is_alive()
    try:  # signal 0 tells whether the pid exists (a zombie counts as alive; getppid's change tells)
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # alive, owned by someone else
        return True
    return True


def sweep(
    function: Callable[..., Any], grid, executor=None, progress: ProgressArg = True, errors: str = "raise"
) -> SweepResult:
    """Run ``function(**point)`` for every point of `grid`; results in grid order.

    grid: a dict of lists (the cartesian product, last key fastest: see grid_points) or a list of
    dicts. executor: None runs the points one after another in this process; any
    concurrent.futures.Executor (ThreadPoolExecutor, ProcessPoolExecutor: `function` must then
    pickle, i.e. be defined at module level) or a dask.distributed Client (functions travel by
    cloudpickle; lambdas work) runs them in parallel. progress: a bar on stderr (True), a callable
    progress(done, total) called as points finish, or False. errors: 'raise' -- after every point
    finished, raise SweepError naming each failed point's parameters, its ``results`` keeping
    every other result; 'keep' -- return the SweepResult with None at failed points and their
    SweepFailure records in ``.failures``. The function (with what it closes over) travels with
    every task; a large object every point needs can be sent once instead with dask,
    ``scene = client.scatter(scene, broadcast=True)``, and passed in the grid (``{"scene": [scene]}``).

    Returns a SweepResult: a list of the results, with ``.points`` and ``.failures``.

    Example::

        def mirage_height(surface_dt, eye):
            road = refracta.PhysicalAtmosphere(surface_dt=surface_dt)
            return refracta.trace_ray(road, [0, eye, 0], [1, -0.003, 0], max_length=800).points[-1, 1]

        heights = refracta.sweep(mirage_height, {"surface_dt": [5, 10, 15], "eye": [1.2, 1.6]},
                                 executor=client)      # or None, or ProcessPoolExecutor()
    """
    if not callable(function):
        raise ValueError(f"sweep: function must be callable (got {function!r})")
    if errors not in ("raise", "keep"):
        raise ValueError(f"sweep: errors must be 'raise' or 'keep' (got {errors!r})")
    points = grid_points(grid)
    # The function travels with every task (not scattered once): a task then re-runs on any worker,
    # even after every worker that held a scattered copy has died.
    outcomes = map_ordered(_call_with, [(function, point) for point in points], executor, progress, "sweep")
    results, failures = [], []
    for i, (ok, value) in enumerate(outcomes):
        if ok:
            results.append(value)
        else:
            results.append(None)
            failures.append(SweepFailure(i, points[i], value[0], value[1]))
    result = SweepResult(results, points, failures)
    if failures and errors == "raise":
        raise SweepError(failures, result)
    return result


def _call_with(function: Callable[..., Any], point: dict[str, Any]) -> Any:
    """function(**point): a module-level function, so that it pickles for process pools."""
    return function(**point)
