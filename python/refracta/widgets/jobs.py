"""Background work for the mirage editor: one worker thread per slot ('render', 'solve'), where a
newer request supersedes the one running.

refracta.render and refracta.edit.solve run C++ with the GIL released and call their `progress`
callable about every 50 ms from the calling thread; an exception raised by that callable cancels
the C++ work and comes back out of render/solve. A Job's progress callable does exactly that: it
raises Cancelled once the job was cancelled (Job.cancel, JobRunner.cancel) or superseded (a newer
submit to the same slot), so the worker thread is free for the newer request within ~50 ms::

    runner = JobRunner(on_progress=print)
    def work(job):
        image = refracta.render(scene, camera, field, progress=job.progress("rendering"))
        job.check()                      # between steps too: fast work may never call progress
        return image
    runner.submit("render", work, on_done=show)   # show(image) runs on the worker thread

Callbacks (on_done, on_error, on_progress) run on the worker thread; exceptions they raise are
reported to on_error as well, never to the thread's excepthook (a notebook would show them as a
traceback).
"""

from __future__ import annotations

import threading
import time
from typing import Callable

__all__ = ["Cancelled", "Job", "JobRunner"]

PROGRESS_INTERVAL = 0.1  # [s] at most ten progress reports per second reach the view: each one is a
# message to the browser


class Cancelled(Exception):
    """Raised inside a job (by Job.check or its progress callable) once it is cancelled or superseded."""


class Job:
    """One request: `work(job)` run on a slot's worker thread.

    Attributes:
        slot: the slot's name; label: what the job does (shown with its progress).
        state: 'pending', 'running', 'done', 'cancelled' or 'failed'.
        result: what work returned (state 'done'); error: the exception it raised ('failed').
    """

    def __init__(
        self,
        runner: JobRunner,
        slot: str,
        work: Callable,
        label: str,
        on_done: Callable | None = None,
        on_error: Callable | None = None,
    ):
        self.slot, self.label = slot, label
        self.state = "pending"
        self.result = None
        self.error: BaseException | None = None
        self._runner = runner
        self._work, self._on_done, self._on_error = work, on_done, on_error
        self._cancelled = threading.Event()
        self._finished = threading.Event()
        self._last_report = 0.0

    @property
    def cancelled(self) -> bool:
        return self._cancelled.is_set()

    def cancel(self) -> None:
        """Ask the job to stop: its next check or progress call raises Cancelled."""
        self._cancelled.set()

    def check(self) -> None:
        """Raise Cancelled if the job was cancelled or superseded."""
        if self._cancelled.is_set():
            raise Cancelled(f"{self.label}: cancelled")

    def progress(self, label: str | None = None, start: float = 0.0, end: float = 1.0) -> Callable[[int, int], None]:
        """A progress(done, total) callable for render/solve: raises Cancelled once the job is
        cancelled, otherwise reports `label` and the overall fraction start + (end - start) *
        done / total to the runner's on_progress (at most every PROGRESS_INTERVAL seconds, and
        always when done == total)."""
        label = label or self.label

        def report(done: int, total: int) -> None:
            self.check()
            self.report(
                label, start + (end - start) * (min(done / total, 1.0) if total > 0 else 1.0), force=done >= total
            )

        return report

    def report(self, label: str, fraction: float, force: bool = False) -> None:
        """Report progress (fraction in [0, 1]) to the runner's on_progress, throttled."""
        now = time.perf_counter()
        if force or now - self._last_report >= PROGRESS_INTERVAL:
            self._last_report = now
            self._runner._progress(self, label, fraction)

    def wait(self, timeout: float | None = None) -> bool:
        """Block until the job has finished (done, cancelled or failed); False on timeout."""
        return self._finished.wait(timeout)

    def _run(self) -> None:
        self.state = "running"
        try:
            self.check()
            self.result = self._work(self)
            self.check()  # superseded while finishing: its result is stale
            self.state = "done"
            if self._on_done is not None:
                self._on_done(self.result)
        except Cancelled:
            self.state = "cancelled"
        except Exception as error:  # reported to the view, never a traceback in a thread
            self.state, self.error = "failed", error
            handler = self._on_error or self._runner.on_error
            if handler is not None:
                try:
                    handler(error)
                except Exception:  # a broken handler must not kill the worker
                    pass
        finally:
            self._finished.set()

    def __repr__(self) -> str:
        return f"Job({self.slot!r}, {self.label!r}, state={self.state!r})"


class _Slot:
    def __init__(self):
        self.pending: Job | None = None
        self.running: Job | None = None
        self.thread: threading.Thread | None = None


class JobRunner:
    """Runs jobs on one daemon worker thread per slot, newest request first.

    submit(slot, work) cancels the slot's running job and replaces its pending one: at most one
    job per slot runs, and the last request always runs. Slots run concurrently (a solve does not
    wait for a render).

    Args:
        on_progress: on_progress(job, label, fraction) while jobs run (fraction in [0, 1]).
        on_error: on_error(exception) for jobs without their own on_error.
        on_finished: on_finished(job) after each job that ran ends, whatever its state.
    """

    def __init__(
        self, on_progress: Callable | None = None, on_error: Callable | None = None, on_finished: Callable | None = None
    ):
        self.on_progress = on_progress
        self.on_error = on_error
        self.on_finished = on_finished
        self._slots: dict[str, _Slot] = {}
        self._lock = threading.Condition()
        self._closed = False
        self._finishing = 0

    def submit(
        self,
        slot: str,
        work: Callable,
        label: str = "",
        on_done: Callable | None = None,
        on_error: Callable | None = None,
    ) -> Job:
        """Queue work(job) on `slot`, superseding the slot's running and pending jobs; returns the Job."""
        job = Job(self, slot, work, label or slot, on_done, on_error)
        with self._lock:
            if self._closed:
                raise RuntimeError("JobRunner is closed")
            state = self._slots.setdefault(slot, _Slot())
            for old in (state.pending, state.running):
                if old is not None:
                    old.cancel()
            if state.pending is not None:
                state.pending.state = "cancelled"
                state.pending._finished.set()
            state.pending = job
            if state.thread is None:
                state.thread = threading.Thread(target=self._worker, args=(slot,), name=f"refracta-{slot}", daemon=True)
                state.thread.start()
            self._lock.notify_all()
        return job

    def cancel(self, slot: str | None = None) -> None:
        """Cancel the running and pending jobs of `slot` (None: of every slot)."""
        with self._lock:
            for name, state in self._slots.items():
                if slot is not None and name != slot:
                    continue
                if state.running is not None:
                    state.running.cancel()
                if state.pending is not None:
                    state.pending.cancel()
                    state.pending.state = "cancelled"
                    state.pending._finished.set()
                    state.pending = None
            self._lock.notify_all()

    def busy(self, slot: str | None = None) -> bool:
        """Whether `slot` (None: any slot) has a job running or pending."""
        with self._lock:
            return any(
                (state.running is not None or state.pending is not None)
                for name, state in self._slots.items()
                if slot is None or name == slot
            )

    def running(self, slot: str) -> Job | None:
        """The job `slot` is running, or None."""
        with self._lock:
            state = self._slots.get(slot)
            return None if state is None else state.running

    def wait(self, timeout: float | None = None) -> bool:
        """Block until no slot has work (a job's on_done may queue more; that is waited for too).
        Returns False if `timeout` [s] passed first."""
        deadline = None if timeout is None else time.monotonic() + timeout
        with self._lock:
            while self._finishing or any(
                state.running is not None or state.pending is not None for state in self._slots.values()
            ):
                remaining = None if deadline is None else deadline - time.monotonic()
                if remaining is not None and remaining <= 0.0:
                    return False
                self._lock.wait(remaining)
        return True

    def close(self) -> None:
        """Cancel everything and stop the worker threads (waits for them)."""
        with self._lock:
            self._closed = True
        self.cancel()
        with self._lock:
            self._lock.notify_all()
            threads = [state.thread for state in self._slots.values() if state.thread is not None]
        for thread in threads:
            if thread is not threading.current_thread():
                thread.join()

    def _progress(self, job: Job, label: str, fraction: float) -> None:
        if self.on_progress is not None:
            self.on_progress(job, label, fraction)

    def _worker(self, slot: str) -> None:
        state = self._slots[slot]
        while True:
            with self._lock:
                while state.pending is None and not self._closed:
                    self._lock.wait()
                if state.pending is None:  # closed with nothing left to run
                    state.thread = None
                    return
                job, state.pending = state.pending, None
                state.running = job
            job._run()
            with self._lock:
                state.running = None
                self._finishing += 1  # wait() also waits for on_finished
            try:
                if self.on_finished is not None:
                    self.on_finished(job)
            except Exception:  # a broken handler must not kill the worker
                pass
            finally:
                with self._lock:
                    self._finishing -= 1
                    self._lock.notify_all()
