"""A minimal text progress bar for long C++ work (called with (done, total) about every 50 ms)."""

from __future__ import annotations

import sys
import time


class ProgressBar:
    """Writes ``label [#####-----] 52% 1.3 s`` to stderr, redrawn in place; a newline when done.

    quiet_seconds: draw nothing until the work has run this long (work that ends sooner leaves no
    trace), e.g. a model whose textures are already prepared."""

    def __init__(self, label: str, width: int = 30, stream=None, quiet_seconds: float = 0.0):
        self.label = label
        self.width = width
        self.stream = stream or sys.stderr
        self.quiet_seconds = quiet_seconds
        self.start = time.perf_counter()
        self.finished = False

    def __call__(self, done: int, total: int) -> None:
        if self.finished:
            return
        if time.perf_counter() - self.start < self.quiet_seconds:
            self.finished = done >= total  # ended within the quiet period: no bar at all
            return
        fraction = 1.0 if total <= 0 else min(done / total, 1.0)
        filled = int(round(fraction * self.width))
        elapsed = time.perf_counter() - self.start
        bar = "#" * filled + "-" * (self.width - filled)
        self.stream.write(f"\r{self.label} [{bar}] {fraction:4.0%} {elapsed:.1f} s")
        if done >= total:
            self.stream.write("\n")
            self.finished = True
        self.stream.flush()
