"""Child process of test_01_ctrl_c.py's earliest-Ctrl-C test: SIGINT sent at the earliest moments of
a call, before the C++ loop that checks for signals (interruptible.h, every 50 ms) has polled once.

Each trial prints `stopped <label> <latency> <polled>`, latency [s] from the SIGINT to the
KeyboardInterrupt caught here and polled 1 if the waiting loop had already checked for signals when
it was sent (0: the signal was pending before the first check), or `finished <label>` if the call
ran to its end. Every call is unbounded in practice (1e6 samples per pixel; 20 000 rays of a
million rk4 steps through a Python field: hours), so a lost signal shows as the test's hang guard
expiring, never as a finished call.

Trials:
- `render@<ms>`, `sweep_<pool>@<ms>`: a thread sends SIGINT <ms> after it is started, just before
  the call (0 ms lands in the call's Python code, its argument conversion or the C++ work's first
  50 ms, as the scheduler decides).
- `trace_rays_first_evaluation`: the Python field's first evaluation, made by the C++ work
  itself, sends SIGINT: the work has started; `polled` tells whether the loop had checked yet (its
  progress callback runs right after each check, under the GIL this evaluation holds)."""

import concurrent.futures
import multiprocessing
import os
import signal
import sys
import threading
import time

import numpy as np

import refracta
from refracta import examples

# Ctrl-C as a terminal delivers it: a process started from a background job of a non-interactive
# shell (`make test &` in a script) inherits SIGINT ignored, and Python then installs no
# KeyboardInterrupt handler.
signal.signal(signal.SIGINT, signal.default_int_handler)

ROAD = examples.hot_road(160, 60)
UNBOUNDED_SPP = 1_000_000  # hours for 160x60 pixels on any machine
DELAYS = (0.0, 0.005, 0.02, 0.045)  # [s] within the waiting loop's first 50 ms period
FIRST_EVALUATION_TRIALS = 5


def render_road(surface_dt=10.0):
    """A module-level task, so that a process pool's workers can import it."""
    return refracta.render(
        ROAD.scene,
        ROAD.camera,
        ROAD.field.with_params(surface_dt=surface_dt),
        spp=UNBOUNDED_SPP,
        progress=False,
        max_length=ROAD.max_length,
    )


class Sender:
    """Sends SIGINT to this process (like Ctrl-C) and keeps the time it did."""

    def __init__(self):
        self.sent = None

    def send(self):
        self.sent = time.monotonic()
        os.kill(os.getpid(), signal.SIGINT)

    def after(self, delay):
        def run():
            time.sleep(delay)
            self.send()

        return threading.Thread(target=run, daemon=True)


def report(label, call, delay, polled=lambda: 0):
    sender = Sender()
    timer = sender.after(delay)
    try:
        timer.start()
        call()
    except KeyboardInterrupt:
        latency = time.monotonic() - sender.sent
        print(f"stopped {label} {latency:.4f} {polled()}", flush=True)
    else:
        print(f"finished {label}", flush=True)
    timer.join()


def sweep_on(kind, delay):
    if kind == "serial":
        report(
            f"sweep_serial@{delay * 1000:g}",
            lambda: refracta.sweep(render_road, {"surface_dt": [5.0, 15.0]}, progress=False),
            delay,
        )
        return
    # The pool exists before the signal can come: Ctrl-C while a pool is being built is Python's
    # concurrent.futures' business, not refracta's.
    if kind == "threads":
        executor = concurrent.futures.ThreadPoolExecutor(2)
    else:
        executor = concurrent.futures.ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn"))
    with executor:
        report(
            f"sweep_{kind}@{delay * 1000:g}",
            lambda: refracta.sweep(render_road, {"surface_dt": [5.0, 15.0]}, executor=executor, progress=False),
            delay,
        )


def first_evaluation_trial():
    sender = Sender()
    polls = []
    lock = threading.Lock()

    def ior(points):
        with lock:
            if sender.sent is None:
                polled[0] = len(polls) > 0
                sender.send()
        return 1.0 + 1e-4 * points[:, 1]

    polled = [None]
    field = refracta.CustomField(ior, lambda p: np.tile([0.0, 1e-4, 0.0], (len(p), 1)))
    directions = np.tile([1.0, 0.01, 0.0], (20_000, 1))  # 1e6 rk4 steps each: hours
    try:
        refracta.trace_rays(
            field,
            [0, 1, 0],
            directions,
            trace="rk4",
            step=0.01,
            max_length=1e4,
            progress=lambda done, total: polls.append(done),
        )
    except KeyboardInterrupt:
        latency = time.monotonic() - sender.sent
        print(f"stopped trace_rays_first_evaluation {latency:.4f} {int(polled[0])}", flush=True)
    else:
        print("finished trace_rays_first_evaluation", flush=True)


def main():
    for delay in DELAYS:
        report(f"render@{delay * 1000:g}", render_road, delay)
    for _ in range(FIRST_EVALUATION_TRIALS):
        first_evaluation_trial()
    for kind in ("serial", "threads", "processes"):
        for delay in (DELAYS[0], DELAYS[2]):
            sweep_on(kind, delay)


if __name__ == "__main__":
    sys.exit(main())
