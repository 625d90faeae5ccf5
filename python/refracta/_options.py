"""Options objects from keywords: one rule for every public function that takes a bound C++
options class (its defaults live in the C++ struct initialisers; Python writes none). The rule is
C++'s (bindings/options_binding.h, set_options_fields), the one trace_ray, trace_rays,
ElevationTable and render_raster use:

    settings = build(_core.SolveSettings, max_iterations=40)           # from the defaults
    settings = build(_core.SolveSettings, given, time_limit=10.0)      # a copy of `given`, changed

A keyword that is not a field raises ValueError naming the caller and listing the fields; None
leaves a field that takes no None at its default; a float equal to a whole number sets an integer
field (2.5 raises "must be a whole number"); a value of the wrong type raises ValueError naming
the field; validate() runs last and lists every bad value.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any, TypeVar

from refracta import _core
from refracta._warn import deprecated

T = TypeVar("T")


def fields(cls: type) -> tuple[str, ...]:
    """The public fields of a bound options class: its properties not starting with '_'."""
    return tuple(name for name in dir(cls) if not name.startswith("_") and isinstance(getattr(cls, name), property))


def _document_defaults(cls: type) -> None:
    """Ends each field's docstring with its default, read from a default-constructed object (the C++
    initialiser's value: help(RenderOptions) gave units but no defaults, a trial)."""
    default = cls()
    for name in fields(cls):
        field = cls.__dict__.get(name)
        if isinstance(field, property) and "(default:" not in (field.__doc__ or ""):
            doc = f"{(field.__doc__ or name).rstrip()} (default: {getattr(default, name)!r})"
            setattr(cls, name, property(field.fget, field.fset, field.fdel, doc))


for _cls in vars(_core).values():
    if isinstance(_cls, type) and hasattr(_cls, "validate") and hasattr(_cls, "__getstate__"):
        _document_defaults(_cls)


def build(cls: type[T], options: T | None = None, *, where: str | None = None, **kw: Any) -> T:
    """A `cls` (a bound options class) from `options` (copied; None: the defaults) with the
    keywords set, validated (C++'s rule, above). `where` names the caller in messages (default:
    the class name)."""
    return _core._build_options(cls, options, where or cls.__name__, kw)


def split(kw: dict[str, Any], *classes: type) -> list[dict[str, Any]]:
    """The keywords `kw` shared out among `classes` by field name (each name goes to the first
    class that has it); names no class has are left in `kw` (the caller's to refuse)."""
    out: list[dict[str, Any]] = [{} for _ in classes]
    for i, cls in enumerate(classes):
        for name in fields(cls):
            if name in kw:
                out[i][name] = kw.pop(name)
    return out


def renamed(kw: dict[str, Any], aliases: Mapping[str, str], where: str) -> dict[str, Any]:
    """`kw` with deprecated keyword spellings (aliases: old -> new) replaced by their new names,
    each with a DeprecationWarning; both spellings at once raise TypeError."""
    for old, new in aliases.items():
        if old in kw:
            if new in kw:
                raise TypeError(f"{where}: pass {new}= only ({old}= is its deprecated spelling)")
            deprecated(f"{where}: {old}= is deprecated; call it {new}=")
            kw[new] = kw.pop(old)
    return kw


def unknown(kw: Iterable[str], where: str, valid: Iterable[str]) -> None:
    """ValueError naming keywords no options class took, listing the valid ones (as build's)."""
    names = list(kw)
    if names:
        raise ValueError(
            f"{where}: unknown option{'s' if len(names) > 1 else ''} "
            f"{', '.join(repr(n) for n in names)} (options: {', '.join(sorted(valid))})"
        )
