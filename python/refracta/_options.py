"""Options objects from keywords: one rule for every public function that takes a bound C++
options class (its defaults live in the C++ struct initialisers; Python writes none).

    settings = build(_core.SolveSettings, max_iterations=40)           # from the defaults
    settings = build(_core.SolveSettings, given, time_limit=10.0)      # a copy of `given`, changed

A keyword that is not a field raises TypeError naming it and listing the fields; a value of the
wrong type raises ValueError naming the field; validate() runs last and lists every bad value.
"""

from __future__ import annotations

import numbers
import warnings
from collections.abc import Iterable, Mapping
from typing import Any, TypeVar

T = TypeVar("T")


def fields(cls: type) -> tuple[str, ...]:
    """The public fields of a bound options class: its properties not starting with '_'."""
    return tuple(name for name in dir(cls) if not name.startswith("_") and isinstance(getattr(cls, name), property))


def _owner(cls: type, where: str | None) -> str:
    return where or cls.__name__


def _set(options: Any, name: str, value: Any, owner: str) -> None:
    try:
        setattr(options, name, value)
        return
    except TypeError:
        pass
    current = getattr(options, name)
    # A whole number given as a float (max_iterations=200.0) sets an integer field; 2.5 does not.
    if (
        isinstance(current, int)
        and not isinstance(current, bool)
        and isinstance(value, numbers.Real)
        and not isinstance(value, bool)
        and float(value).is_integer()
    ):
        setattr(options, name, int(float(value)))
        return
    kind = (
        "a whole number"
        if isinstance(current, int) and not isinstance(current, bool)
        else ("True or False" if isinstance(current, bool) else f"a {type(current).__name__}")
    )
    raise ValueError(f"{owner}: {name} must be {kind} (got {value!r})") from None


def build(cls: type[T], options: T | None = None, *, where: str | None = None, **kw: Any) -> T:
    """A `cls` (a bound options class) from `options` (copied; None: the defaults) with the
    keywords set, validated. `where` names the caller in messages (default: the class name).

    None for a field that does not take None leaves it at its value (the default): the keyword
    was left unset, as public signatures write `x=None`."""
    owner = _owner(cls, where)
    if options is None:
        result = cls()
    elif isinstance(options, cls):
        result = cls()
        for name in fields(cls):
            setattr(result, name, getattr(options, name))
    else:
        raise TypeError(f"{owner}: expected a refracta.{cls.__name__} (got {type(options).__name__})")
    valid = fields(cls)
    unknown = [name for name in kw if name not in valid]
    if unknown:
        raise TypeError(
            f"{owner}: unknown keyword{'s' if len(unknown) > 1 else ''} "
            f"{', '.join(repr(n) for n in unknown)} (valid: {', '.join(valid)})"
        )
    for name, value in kw.items():
        if value is None and getattr(result, name) is not None:
            try:
                setattr(result, name, None)
            except TypeError:
                continue  # left at its default
            continue
        _set(result, name, value, owner)
    result.validate()  # type: ignore[attr-defined]
    return result


def split(kw: dict[str, Any], *classes: type) -> list[dict[str, Any]]:
    """The keywords `kw` shared out among `classes` by field name (each name goes to the first
    class that has it); names no class has are left in `kw` (the caller's to refuse)."""
    out: list[dict[str, Any]] = [{} for _ in classes]
    for i, cls in enumerate(classes):
        for name in fields(cls):
            if name in kw:
                out[i][name] = kw.pop(name)
    return out


def renamed(kw: dict[str, Any], aliases: Mapping[str, str], where: str, stacklevel: int = 3) -> dict[str, Any]:
    """`kw` with deprecated keyword spellings (aliases: old -> new) replaced by their new names,
    each with a DeprecationWarning; both spellings at once raise TypeError."""
    for old, new in aliases.items():
        if old in kw:
            if new in kw:
                raise TypeError(f"{where}: pass {new}= only ({old}= is its deprecated spelling)")
            warnings.warn(f"{where}: {old}= is deprecated; call it {new}=", DeprecationWarning, stacklevel=stacklevel)
            kw[new] = kw.pop(old)
    return kw


def unknown(kw: Iterable[str], where: str, valid: Iterable[str]) -> None:
    """TypeError naming keywords no options class took, listing the valid ones."""
    names = list(kw)
    if names:
        raise TypeError(
            f"{where}: unknown keyword{'s' if len(names) > 1 else ''} "
            f"{', '.join(repr(n) for n in names)} (valid: {', '.join(sorted(valid))})"
        )
