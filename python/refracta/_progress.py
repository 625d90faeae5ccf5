"""The progress bar of long C++ work (``progress=True``): a callback progress(done, total), called
about every 50 ms, that draws through tqdm -- ``tqdm.auto``: a widget in Jupyter, a text bar on
stderr in a terminal."""

from __future__ import annotations

import time
from typing import Callable, Union

import tqdm.auto
import tqdm.std

from refracta._checks import is_flag


# The calls come every 50 ms, so tqdm's monitor thread (which wakes a bar whose updates stall) has
# nothing to do: no thread of its own beside the work's.
class _Widget(tqdm.auto.tqdm):
    monitor_interval = 0


class _Text(tqdm.std.tqdm):
    monitor_interval = 0


_FEW = "{l_bar}{bar}| {n_fmt}/{total_fmt} [{elapsed}<{remaining}]"
_SHARE = "{l_bar}{bar}| [{elapsed}<{remaining}]"


class ProgressBar:
    """A progress(done, total) callback drawing ``label: 52%|#####     | 80k/153k [00:01<00:01, ...]``.

    The bar is made at the first call with a total and closed when done reaches total; a call with
    another total after that is a next phase of the work (a render prepares its textures, then
    renders its tiles), shown by a bar of its own.
    stream: draw a text bar into this file instead (tqdm's ``file``); by default tqdm.auto chooses
    a Jupyter widget or stderr. quiet_seconds: draw nothing until the work has run this long, from
    this object's creation (tqdm's ``delay``): work that ends sooner leaves no trace, e.g. a model
    whose textures are already prepared. share: done / total is a share of the work, not a count
    of items (a solve's budget used): the bar shows the percentage alone."""

    def __init__(self, label: str, stream=None, quiet_seconds: float = 0.0, share: bool = False):
        self.label = label
        self.share = share
        self.stream = stream
        self.quiet_seconds = quiet_seconds
        self.start = time.monotonic()
        self.bar: tqdm.std.tqdm | None = None
        self.finished = False

    def __call__(self, done: int, total: int) -> None:
        if total <= 0:  # the work has not said how much there is yet (a bar of 0/0 read as finished)
            return
        if self.finished:
            if self.bar is not None and total == self.bar.total and done >= total:
                return  # the end, reported again
            self.bar, self.finished = None, False  # a next phase of the work (a render's textures, then its tiles)
        if self.bar is None:
            # The quiet period counts from this object's creation, not from the first call.
            delay = max(0.0, self.quiet_seconds - (time.monotonic() - self.start))
            # Thousands of items: counts and rate in SI units (80k/153k, 7.6Mit/s); a few: the counts
            # alone, as a rate of items ended in microseconds reads 7577944.20it/s.
            shape = (
                {"bar_format": _SHARE}
                if self.share
                else {"unit_scale": True}
                if total >= 1000
                else {"bar_format": _FEW}
            )
            if self.stream is None:
                self.bar = _Widget(total=total, desc=self.label, delay=delay, **shape)
            else:
                self.bar = _Text(total=total, desc=self.label, delay=delay, file=self.stream, **shape)
        if self.bar.total != total:
            self.bar.total = total
            self.bar.refresh()
        if done != self.bar.n:  # the calls come every 50 ms: a bar redrawn unchanged fills a log with copies
            self.bar.update(done - self.bar.n)
        if done >= total:
            self.bar.close()
            self.finished = True


# What a progress= argument may be: True (a bar), False or None (none), or a callable progress(done, total).
ProgressArg = Union[bool, Callable[[int, int], None], None]


def progress_callback(progress: ProgressArg, label: str, share: bool = False) -> Callable[[int, int], None] | None:
    """The callback for a progress= argument: a ProgressBar(label, share=share) for True, None for False or None,
    the callable itself; ValueError for anything else (a string reached C++ and failed there as
    "'str' object is not callable")."""
    if progress is None or is_flag(progress):  # numpy's bools as Python's
        return ProgressBar(label, share=share) if progress else None
    if not callable(progress):
        raise ValueError(f"progress must be True, False or a callable progress(done, total) (got {progress!r})")
    return progress
