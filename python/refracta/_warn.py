"""Deprecation warnings attributed to the user's code."""

from __future__ import annotations

import os
import sys
import warnings

_PACKAGE = os.path.dirname(os.path.abspath(__file__)) + os.sep


def deprecated(message: str) -> None:
    """A DeprecationWarning attributed to the first caller outside refracta. Python's default
    filters show one only where it is attributed to __main__ (a script, a notebook cell), and a
    fixed stacklevel that landed in refracta's own wrappers hid it (a trial: trace_ray(method=...)
    and edit.solve(ground=...) printed nothing). Also called from C++ (a bound function's old
    keyword), where the first frame is the Python code that called it."""
    level, frame = 2, sys._getframe(1)
    while frame.f_code.co_filename.startswith(_PACKAGE) and frame.f_back is not None:
        frame, level = frame.f_back, level + 1
    warnings.warn(message, DeprecationWarning, stacklevel=level)
