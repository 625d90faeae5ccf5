"""Shared pieces of the property-based suites (test_12, test_13): the errors refracta may raise for
bad input, Hypothesis settings (seeded, bounded) and number strategies reaching the edges."""

import warnings

import numpy as np
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

import refracta

# What a public call may raise for bad input (DESIGN.md, "Errors across the boundary"). TypeError
# is not among them: the strategies give every argument its documented type.
NAMED_ERRORS = (ValueError, refracta.NumericalError, refracta.IoError, FileNotFoundError)

# Derandomized (the same examples every run, so a failure reproduces), no per-example deadline
# (the machine is shared) but few examples: the fast budget keeps each suite to seconds; the
# `fuzz` marker's budget is eight times larger (images: three times, each makes a MIP-mapped
# texture) and still runs in `make test`; the whole suite takes about a minute on 2 cores.
FAST = settings(
    derandomize=True,
    deadline=None,
    max_examples=50,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
FUZZ = settings(FAST, max_examples=400)

# Floats from everywhere: ordinary magnitudes, the edges of double, zero and the non-finite.
edge = st.sampled_from([0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300, 1e308, np.inf, -np.inf, np.nan, 5e-324])
ordinary = st.floats(-1e4, 1e4, allow_nan=False)
anything = st.one_of(ordinary, edge, st.floats(allow_nan=True, allow_infinity=True))
vec3 = st.tuples(anything, anything, anything)
ordinary_vec3 = st.tuples(ordinary, ordinary, ordinary)


def finite(value) -> bool:
    return bool(np.all(np.isfinite(np.asarray(value, dtype=float))))


def calls(function, *args, **kwargs):
    """function(*args, **kwargs), or None when it raised one of refracta's named errors."""
    try:
        return function(*args, **kwargs)
    except NAMED_ERRORS:
        return None


def render_checking_scene_warnings(scene, camera, field, **options):
    """calls(refracta.render, ...) asserting refracta.SceneWarning where it belongs: the no-light
    hint exactly when an image came out of a scene without lights, the ground hint only through a
    field. Any other warning still fails the test (pytest turns warnings into errors)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        image = calls(refracta.render, scene, camera, field, **options)
    messages = [str(w.message) for w in caught if issubclass(w.category, refracta.SceneWarning)]
    assert len(messages) == len(caught), [str(w.message) for w in caught]
    assert any("no light" in m for m in messages) == (image is not None and len(scene.lights) == 0)
    assert field is not None or not any("lowest geometry" in m for m in messages)
    return image
