"""The public functions whose keywords mirror a bound options class write no numeric default of
their own: a number lives once, in the C++ struct's initialiser (REVIEW.md P3), and the Python
signature says None (or leaves the keyword to **fields) for "C++'s default"."""

import inspect
import numbers

import pytest

import refracta
from refracta import edit, moments, oit

# (function, the bound class its keywords mirror, parameters that are not options: inputs with a
# natural value of their own, kept in the signature on purpose).
MIRRORS = [
    (refracta.render, refracta.RenderOptions, ()),
    (refracta.render_raster, refracta.RasterRenderOptions, ()),
    (oit.composite, refracta.OitSettings, ("background",)),  # the colour behind the fragments: an input
    (moments.shadow_intensity, refracta.MomentShadowSettings, ()),
    (edit.solve, None, ()),
    (refracta.trace_rays, refracta.TraceOptions, ()),
    (refracta.ElevationTable, refracta.ElevationTableOptions, ()),
    (refracta.Turbulence, None, ()),
]


def numeric(value) -> bool:
    """A literal number (True / False are switches, not numbers), or a tuple or list holding one."""
    if isinstance(value, bool):
        return False
    if isinstance(value, numbers.Number):
        return True
    return isinstance(value, (tuple, list)) and any(numeric(v) for v in value)


@pytest.mark.parametrize("function, mirrored, inputs", MIRRORS, ids=lambda v: getattr(v, "__qualname__", ""))
def test_no_numeric_default_in_the_signature(function, mirrored, inputs):
    signature = inspect.signature(function)
    written = {p.name: p.default for p in signature.parameters.values() if p.name not in inputs and numeric(p.default)}
    assert written == {}, f"{function.__qualname__} writes defaults that belong to C++: {written}"


def test_the_check_itself_sees_a_numeric_default():
    def mirrors(spp=1, seed=None, spectral=False, speed=(10.0, 0.0), method="curved"):
        return spp, seed, spectral, speed, method

    flagged = [p.name for p in inspect.signature(mirrors).parameters.values() if numeric(p.default)]
    assert flagged == ["spp", "speed"]


@pytest.mark.parametrize(
    "function, mirrored, inputs", [m for m in MIRRORS if m[1] is not None], ids=lambda v: getattr(v, "__qualname__", "")
)
def test_the_mirrored_class_has_documented_fields(function, mirrored, inputs):
    # The class the keywords go to carries the defaults and their documentation.
    fields = [
        name
        for name in dir(mirrored)
        if isinstance(getattr(mirrored, name, None), property) and not name.startswith("_")
    ]
    assert fields, mirrored
    for name in fields:
        assert getattr(mirrored, name).__doc__, f"{mirrored.__name__}.{name} has no docstring"
