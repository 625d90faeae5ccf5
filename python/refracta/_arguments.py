"""Argument errors that name the argument.

pybind11 answers a call whose arguments do not convert with a generic TypeError ("__init__():
incompatible constructor arguments. The following argument types are supported: ...") that names
neither the argument nor what is wrong with it: `Camera(p, q, vfov="wide")` or `HotSpot(0, 300,
"big", 8)`. install(), run as this module loads (refracta's __init__ imports it first), wraps
every public function and method of refracta._core so that such a failure is diagnosed from the
call's own signature (the one pybind11 prints: every bound function has exactly one) and raised
as an ArgumentError naming the argument: "Camera: vfov must be a number (got 'wide')". The C++
conversions stay the only rule: the wrapper only reads a failure that has happened, and
re-raises pybind11's error unchanged where it cannot say more.

The stubs describe refracta._core itself: with REFRACTA_UNWRAPPED_CORE set (make stubs and the
stubs' test) nothing is wrapped.
"""

from __future__ import annotations

import functools
import operator
import os
import re
from collections.abc import Callable
from typing import Any

from refracta._checks import is_flag


class ArgumentError(TypeError, ValueError):
    """An argument of the wrong kind, named (a TypeError, as Python's own, and a ValueError, as
    refracta's other messages about bad input)."""


_INCOMPATIBLE = re.compile(r"^(\w+)\(\): incompatible (?:function|constructor) arguments")
_SIGNATURE = re.compile(r"^\s*1\. (?P<owner>[\w.]*)\((?P<params>.*)\)(?: -> .*)?$", re.MULTILINE)


def _split_top_level(text: str, separator: str = ",") -> list[str]:
    """`text` split at the separators outside brackets and quotes."""
    parts, depth, quote, start = [], 0, "", 0
    for i, ch in enumerate(text):
        if quote:
            quote = "" if ch == quote and text[i - 1] != "\\" else quote
        elif ch in "'\"":
            quote = ch
        elif ch in "([{":
            depth += 1
        elif ch in ")]}":
            depth -= 1
        elif ch == separator and depth == 0:
            parts.append(text[start:i].strip())
            start = i + 1
    if text[start:].strip():
        parts.append(text[start:].strip())
    return parts


def _parameters(signature: str) -> tuple[list[tuple[str, str, bool]], int]:
    """(name, annotation, has a default) of each parameter of a pybind11 signature's parameter
    list, and how many may be given by position (those before a bare `*`)."""
    out: list[tuple[str, str, bool]] = []
    positional = -1
    for part in _split_top_level(signature):
        if part == "*":
            positional = len(out)
            continue
        if part.startswith("*"):  # *args, **kwargs: anything goes
            return out, -2
        name, _, rest = part.partition(":")
        annotation, *default = _split_top_level(rest, "=") or [""]  # "annotation = default"
        out.append((name.strip(), annotation, bool(default)))
    return out, len(out) if positional < 0 else positional


def _what_is_wrong(annotation: str, value: Any, ranges: bool = False) -> str | None:
    """Why `value` cannot be the annotated parameter, or None if it may be (or we cannot tell).
    ranges: also a whole number beyond a C++ int (which an int64 parameter would take: asked only
    once no argument is surely wrong)."""
    alternatives = _split_top_level(annotation, "|")
    reasons = []
    for alternative in alternatives:
        reason = _against_one(alternative, value, ranges)
        if reason is None:
            return None
        reasons.append(reason)
    reasons = list(dict.fromkeys(reasons))
    for wider, narrower in _SUBSUMES:  # "a number or a whole number": a number
        if wider in reasons and narrower in reasons:
            reasons.remove(narrower)
    return " or ".join(reasons)


_SUBSUMES = (
    ("a number", "a whole number"),
    ("a number (not an array)", "a whole number (not an array)"),
    ("a path (str or os.PathLike)", "a string"),
)


def _is_array(value: Any) -> bool:
    """Whether `value` is an array of one dimension or more (numpy's, or anything with an ndim)."""
    ndim = getattr(value, "ndim", None)
    return isinstance(ndim, int) and ndim > 0


def _against_one(annotation: str, value: Any, ranges: bool = False) -> str | None:
    """Why pybind11 surely refuses `value` for one alternative of an annotation (bindings/
    strict_numbers.h's rule for numbers), or None where it may take it: only a sure refusal is
    named, so that another argument, the one at fault, is not blamed."""
    if annotation == "None":
        return None if value is None else "None"
    if annotation in ("typing.SupportsFloat", "float"):  # any __float__ or __index__, never a bool
        ok = not is_flag(value) and (hasattr(type(value), "__float__") or hasattr(type(value), "__index__"))
        if ok and _is_array(value):  # numpy 2 converts only 0-d arrays to a number
            return "a number (not an array)"
        return None if ok else "a number"
    if annotation in ("typing.SupportsInt", "int", "typing.SupportsIndex"):  # __index__, never a float
        ok = not is_flag(value) and hasattr(type(value), "__index__")
        if ok and _is_array(value):  # an array's __index__ takes 0-d integer arrays only
            return "a whole number (not an array)"
        if ranges and ok and abs(operator.index(value)) >= 2**31:  # beyond a C++ int, which pybind11 refuses
            # The annotation does not say which integer: seeds are 64-bit (a trial was told 2**31 of one).
            return "a whole number of magnitude below 2**31 (2**63 where it is 64-bit, as seeds are)"
        return None if ok else "a whole number"
    if annotation == "bool":  # bound with noconvert: Python's and numpy's bools only
        return None if is_flag(value) else "True or False"
    if annotation == "str":
        return None if isinstance(value, (str, bytes)) else "a string"
    if annotation in ("os.PathLike", "bytes"):
        return None if isinstance(value, (str, bytes, os.PathLike)) else "a path (str or os.PathLike)"
    if annotation.startswith(("refracta._core.", "refracta::")):  # the second: a C++ name pybind11 left raw
        from refracta import _core

        cls = getattr(_core, re.split(r"\.|::", annotation)[-1], None)
        if cls is None or value is None:  # a holder argument may take None
            return None
        return None if isinstance(value, cls) else f"a refracta.{cls.__name__}"
    if annotation.startswith("tuple[") and annotation.endswith("]"):
        items = _split_top_level(annotation[len("tuple[") : -1])
        described = _described_tuple(items)
        if described is None:
            return None
        return None if _is_sequence_of(value, items) else described
    return None  # other containers, arrays, objects, callables: the C++ conversion names those itself


def _is_sequence_of(value: Any, items: list[str]) -> bool:
    """Whether pybind11's tuple caster may take `value`: a sequence (not a string) of len(items)
    elements, each one its item may be."""
    if isinstance(value, (str, bytes)):
        return False
    try:
        elements = list(value)
    except TypeError:  # not iterable (a number, a 0-d array)
        return False
    return len(elements) == len(items) and all(_what_is_wrong(i, e) is None for i, e in zip(items, elements))


def _described_tuple(items: list[str]) -> str | None:
    """ "a pair of numbers" for tuple[float, float]; None unless every item is a number."""
    if not all("typing.SupportsFloat" in item or item == "float" for item in items):
        return None
    return "a pair of numbers" if len(items) == 2 else f"{len(items)} numbers"


def _shown(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def diagnose(owner: str, message: str, args: tuple, kwargs: dict) -> str | None:
    """What is wrong with a call that pybind11 refused with `message`, naming the argument; None
    where the signature in the message does not say."""
    match = _SIGNATURE.search(message)
    if not match:
        return None
    params, positional = _parameters(match.group("params"))
    if positional == -2:
        return None
    if params and params[0][0] == "self":  # a method's (a constructor's signature has none)
        params, positional = params[1:], positional - 1
    names = [name for name, _, _ in params]
    if len(args) > positional:
        rest = "; pass the rest by name" if positional < len(params) else ""
        return f"{owner} takes at most {positional} arguments by position (got {len(args)}){rest}"
    given = dict(zip(names, args))
    for key, value in kwargs.items():
        if key not in names:
            return f"{owner}: unknown argument '{key}' (arguments: {', '.join(names)})"
        if key in given:
            return f"{owner}: {key} given by position and by name"
        given[key] = value
    for name, _, has_default in params:
        if name not in given and not has_default:
            return f"{owner}: missing argument '{name}'"
    for ranges in (False, True):
        for name, annotation, _ in params:
            reason = _what_is_wrong(annotation, given[name], ranges) if name in given else None
            if reason:
                return f"{owner}: {name} must be {reason} (got {_shown(given[name])})"
    return None


def _wrap(function: Callable, owner: str, name: str, is_method: bool) -> Callable:
    @functools.wraps(function)
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except TypeError as error:
            try:
                diagnosis = _diagnosis(error, function, owner, name, args[1:] if is_method else args, kwargs)
            except Exception:  # (a value whose repr or len raises): pybind11's own message
                diagnosis = None
            # No reference to the arguments may stay in this frame once it raises: a traceback that
            # shows its arguments (pytest's, IPython's verbose mode) would take repr() of a `self`
            # whose __init__ failed, and pybind11's methods crash on an unconstructed instance.
            del args, kwargs
            if diagnosis is None:
                raise
            raise ArgumentError(diagnosis) from None
        except BaseException:
            del args, kwargs
            raise

    call.__qualname__ = name if not is_method else (owner if "." in owner else f"{owner}.{name}")  # pickling
    call.__module__ = "refracta._core"
    return call


def _diagnosis(error: TypeError, function: Callable, owner: str, name: str, args: tuple, kwargs: dict) -> str | None:
    """diagnose() of a TypeError that is pybind11's refusal of this call's arguments. Any other
    TypeError is diagnosed from the function's own signature: a conversion that failed inside
    pybind11 ("len() of unsized object" for a 0-d array given as a pair) is named where an
    argument is surely refused (then the call cannot have run); else None, and the error stands
    (raised inside the call, or by another function it called)."""
    message = str(error)
    failed = _INCOMPATIBLE.match(message)
    if failed:
        return diagnose(owner, message, args, kwargs) if failed.group(1) == name else None
    signature = (function.__doc__ or "").split("\n", 1)[0]
    if not signature.startswith(f"{name}("):
        return None
    return diagnose(owner, f"    1. {signature}", args, kwargs)


def install(core) -> None:
    """Wraps refracta._core's public functions and its classes' public methods and constructors
    (not other dunders: pickling and operators keep pybind11's own)."""
    if os.environ.get("REFRACTA_UNWRAPPED_CORE"):
        return
    for name, value in list(vars(core).items()):
        if name.startswith("__"):
            continue
        if type(value).__name__ == "builtin_function_or_method":
            setattr(core, name, _wrap(value, name.lstrip("_"), name, is_method=False))
        elif isinstance(value, type):
            _install_class(value)


def _install_class(cls: type) -> None:
    for name, member in list(vars(cls).items()):
        if name.startswith("_") and name != "__init__":
            continue
        owner = cls.__name__ if name == "__init__" else f"{cls.__name__}.{name}"
        kind = type(member).__name__
        if kind == "instancemethod":
            setattr(cls, name, _wrap(member.__func__, owner, name, is_method=True))
        elif kind == "staticmethod":
            setattr(cls, name, staticmethod(_wrap(member.__func__, owner, name, is_method=False)))


from refracta import _core  # noqa: E402 (the functions above first; then every later import of _core is wrapped)

install(_core)
