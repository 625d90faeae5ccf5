"""Argument checks shared by the Python layer's validators (each collects its problems and names
its own arguments)."""

from __future__ import annotations

import math

import numpy as np


class ReadOnly:
    """A class whose public attributes are refused on assignment (its state lives in underscore
    names, built from the constructor's arguments): an assignment the object would not follow left
    its repr describing something else (a trial: Turbulence.cn2, LocalFrame.lat). `_remake` says
    what to do instead."""

    _remake = "make another"

    def __setattr__(self, name: str, value) -> None:
        if not name.startswith("_"):
            raise AttributeError(f"{type(self).__name__}.{name} cannot be set: {self._remake}")
        object.__setattr__(self, name, value)


def is_number(value) -> bool:
    """Whether `value` is a real number given as one: an int, a float or a numpy scalar of them, not a
    bool (float(True) is 1) and not a string (float('1') is 1.0)."""
    return not isinstance(value, (bool, np.bool_)) and isinstance(value, (int, float, np.integer, np.floating))


def number(value, name: str) -> float:
    """`value` as a float when is_number(value); else ValueError naming it (`name`)."""
    if not is_number(value):
        raise ValueError(f"{name} must be a number (got {value!r})")
    return float(value)


def is_seed(value) -> bool:
    """Whether `value` is a whole number >= 0 given as an integer (not a bool, not a float)."""
    return not isinstance(value, bool) and isinstance(value, (int, np.integer)) and bool(value >= 0)


def number_pair(value) -> tuple[float, float] | None:
    """`value` as two floats when it holds exactly two numbers (is_number: not (True, True), not
    ("36", "24")), else None."""
    try:
        items = list(value)
    except TypeError:
        return None
    if len(items) != 2 or not all(is_number(v) for v in items):
        return None
    return float(items[0]), float(items[1])


def finite_pair(value) -> tuple[float, float] | None:
    """`value` as two finite floats, or None when it is not a pair of finite numbers (number_pair)."""
    pair = number_pair(value)
    return pair if pair is not None and math.isfinite(pair[0]) and math.isfinite(pair[1]) else None


def is_flag(value) -> bool:
    """Whether `value` is Python's or numpy's bool (what an on/off argument takes)."""
    return isinstance(value, (bool, np.bool_))


def flag(value, name: str) -> bool:
    """`value` as True or False, else ValueError naming it: bool() would take 'no' as True."""
    if not is_flag(value):
        raise ValueError(f"{name} must be True or False (got {value!r})")
    return bool(value)


def on_image(camera, u: float, v: float) -> bool:
    """Whether pixel coordinates (u, v) lie on `camera`'s image, its edges included (as solve takes
    them): beyond it a pixel's ray is extrapolated, not one the camera shows."""
    return 0.0 <= u <= camera.width and 0.0 <= v <= camera.height


def _holds_bool(value) -> bool:
    """Whether `value` is a bool or a (nested) list or tuple holding one: numpy reads (True, 20.0)
    as the float array [1.0, 20.0]."""
    if is_flag(value):
        return True
    if isinstance(value, (list, tuple)):
        return any(_holds_bool(item) for item in value)
    return False


def real_array(value, what: str, shape: tuple[int, ...] | None = None) -> np.ndarray:
    """`value` as a float64 array (of `shape` when given), else ValueError naming it (`what`):
    strings and booleans too (also among numbers in a list), which numpy would read as numbers,
    numpy's datetime64 and timedelta64, which it reads as counts of their unit (ms, days), complex
    arrays, whose imaginary parts it would drop, and numbers beyond float64's range (10**400)."""
    kind = ""
    try:
        raw = np.asarray(value)
        kind = raw.dtype.kind
        array = None if kind in "bUSmMc" else np.asarray(raw, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):
        array = None
    if array is None or _holds_bool(value) or (shape is not None and array.shape != shape):
        wanted = f" of shape {shape}" if shape is not None else ""
        since = "(t - t[0])" if kind == "M" else "t"  # a datetime64 has no seconds of its own, its span has
        seconds = f"; numpy times count their unit: give seconds, e.g. {since} / np.timedelta64(1, 's')"
        hint = seconds if kind in "mM" else ""
        given = repr(value)
        given = given if len(given) <= 120 else given[:100] + " ..."  # 10**400 has 401 digits
        raise ValueError(f"{what} must be numbers{wanted} (got {given}){hint}")
    return array


def no_unknown_keywords(where: str, unknown: dict, function, hint: str = "") -> None:
    """A TypeError (refracta's ArgumentError) naming keywords ``function`` does not take, with the
    ones it does (Python's own "got an unexpected keyword argument" named an internal function)."""
    if unknown:
        import inspect

        from refracta._arguments import ArgumentError

        parameters = inspect.signature(function).parameters.values()
        names = [p.name for p in parameters if p.kind != p.VAR_KEYWORD and p.name != "self"]
        raise ArgumentError(
            f"{where}: unknown keyword{'s' if len(unknown) > 1 else ''} {', '.join(map(repr, unknown))} "
            f"(it takes {', '.join(names)}){hint}"
        )
