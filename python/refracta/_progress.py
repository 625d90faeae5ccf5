"""A minimal text progress bar for long C++ work (called with (done, total) about every 50 ms)."""

from __future__ import annotations

import sys
import time


class ProgressBar:
    """Writes ``label [#####-----] 52% 1.3 s`` to stderr, redrawn in place; a newline when done."""

    def __init__(self, label: str, width: int = 30, stream=None):
        self.label = label
        self.width = width
        self.stream = stream or sys.stderr
        self.start = time.perf_counter()
        self.finished = False

    def __call__(self, done: int, total: int) -> None:
        if self.finished:
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
