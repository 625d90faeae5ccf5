"""trace_rays, the elevation table, progress and interruption, and argument errors."""

import numpy as np
import pytest

import refracta

from .test_closed_forms import direction


def test_batch_matches_single_rays(hot_road):
    directions = np.array([direction(e, a) for e, a in [(-0.5, 0), (-0.2, 30), (0.0, 60), (0.4, -45)]])
    batch = refracta.trace_rays(hot_road, [0, 1.5, 0], directions, max_length=500, stop_height=0.0)
    end_points, end_directions, lengths = batch  # unpacks as three arrays
    for i, d in enumerate(directions):
        path = refracta.trace_ray(hot_road, [0, 1.5, 0], d, max_length=500, stop_height=0.0)
        np.testing.assert_array_equal(end_points[i], path.points[-1])
        np.testing.assert_array_equal(end_directions[i], path.directions[-1])
        assert lengths[i] == path.length and batch.stops[i] == path.stop
        assert batch.evaluations[i] == path.evaluations
    assert list(batch.stops) == ["stop_height", "max_length", "max_length", "max_length"]


def test_batch_broadcasts_one_origin_or_one_direction():
    field = refracta.LinearSquaredProfile(alpha=1e-5)
    origins = np.array([[0, 1, 0], [0, 2, 0], [5, 3, 1]], dtype=float)
    batch = refracta.trace_rays(field, origins, [1, 0, 0], max_length=10)
    assert batch.end_points.shape == (3, 3)
    with pytest.raises(ValueError, match="matching shapes"):
        refracta.trace_rays(field, origins, np.ones((2, 3)))


def test_batch_with_a_python_field_runs_in_parallel_threads():
    field = refracta.CustomField(
        lambda p: 1 + 1e-4 * p[:, 1], lambda p: np.tile([0.0, 1e-4, 0.0], (len(p), 1)), height_only=True
    )
    reference = refracta.LinearSquaredProfile(n0=1.0, alpha=2e-4)  # n^2 = 1 + 2e-4 y ~ (1 + 1e-4 y)^2
    batch = refracta.trace_rays(field, [0, 1, 0], [direction(e) for e in (-1, 0, 1, 2)], max_length=20)
    assert np.all(np.isfinite(batch.end_points))
    exact = refracta.trace_rays(reference, [0, 1, 0], [direction(e) for e in (-1, 0, 1, 2)], max_length=20)
    np.testing.assert_allclose(batch.end_points, exact.end_points, atol=1e-5)  # n differs by ~1e-8 y^2


def test_progress_callback_reports_completion():
    calls = []
    refracta.trace_rays(
        refracta.LogisticProfile(),
        [0, 1, 0],
        [direction(e) for e in np.linspace(-5, 5, 50)],
        max_length=20,
        progress=lambda done, total: calls.append((done, total)),
    )
    assert calls[-1] == (50, 50)


@pytest.mark.parametrize("progress", ["yes", 5])
def test_a_progress_that_is_neither_a_flag_nor_a_callable_is_named(progress):
    # Was "TypeError: 'str' object is not callable" from inside the batch (a trial); render's rule now.
    field = refracta.LogisticProfile()
    with pytest.raises(ValueError, match="progress must be True, False or a callable"):
        refracta.trace_rays(field, [0, 1, 0], [1, 0, 0], progress=progress)
    with pytest.raises(ValueError, match="progress must be True, False or a callable"):
        refracta.ElevationTable(field, 1.5, -1.0, 1.0, progress=progress)


def test_numpy_bools_are_flags_for_progress():
    # A review: the shared rule took progress=np.True_ for neither a flag nor a callable.
    field = refracta.LogisticProfile()
    refracta.trace_rays(field, [0, 1, 0], [1, 0, 0], progress=np.False_)
    refracta.trace_rays(field, [0, 1, 0], [1, 0, 0], progress=np.True_)


def test_interrupt_stops_a_long_batch_promptly():
    slow = refracta.CustomField(lambda p: 1 + 1e-4 * p[:, 1], lambda p: np.tile([0.0, 1e-4, 0.0], (len(p), 1)))

    calls = []

    def interrupt(done, total):
        calls.append((done, total))
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):  # 2e8 rk4 steps calling Python: hours if not stopped
        refracta.trace_rays(
            slow,
            [0, 1, 0],
            np.tile([1.0, 0.01, 0.0], (20000, 1)),
            trace="rk4",
            step=0.01,
            max_length=100,
            progress=interrupt,
        )
    # Raised from the first periodic call, while the rays were being traced (the call after the
    # last ray, (20000, 20000), would raise it too, but only once the work had run to its end).
    assert len(calls) == 1 and calls[0][0] < calls[0][1]


def test_elevation_table_matches_exact_traces(hot_road):
    table = refracta.ElevationTable(hot_road, 1.5, -1.0, 1.0, tol=1e-4, max_length=1500, stop_height=0.0)
    elevations = np.linspace(-1.0, 1.0, 301)
    ends = table.ends(elevations, azimuths=30.0)
    exact = refracta.trace_rays(
        hot_road,
        [0, 1.5, 0],
        [direction(e, 30.0) for e in elevations],
        trace="stratified",
        tol=1e-8,
        max_length=1500,
        stop_height=0.0,
    )
    errors = np.linalg.norm(ends.end_points - exact.end_points, axis=1)
    assert errors.max() <= 1e-4
    assert np.array_equal(ends.stops, exact.stops)
    np.testing.assert_allclose(ends.end_directions, exact.end_directions, atol=1e-6)
    assert 10 < table.size < 3000
    with pytest.raises(ValueError, match="outside the table"):
        table.ends([1.5])


@pytest.mark.parametrize(
    "kwargs, error, message",
    [
        (dict(origin=[0, float("nan"), 0]), ValueError, "origin must be finite"),
        (dict(direction=[0, 0, 0]), ValueError, "direction must be finite and non-zero"),
        (dict(direction=[1, 2]), ValueError, r"shape \(3,\), one point"),
        (dict(tol=0.0), ValueError, "tol must be > 0"),
        (dict(tol=float("nan")), ValueError, "tol must be > 0"),
        (dict(step=-1.0), ValueError, "step must be > 0"),
        (dict(max_length=-5.0), ValueError, "max_length must be > 0"),
        (dict(trace="euler"), ValueError, "trace must be 'rk4', 'rk45' or 'stratified'"),
        (dict(stop_height=3.0), ValueError, "below stop_height"),
    ],
)
def test_bad_arguments_raise_value_errors(kwargs, error, message):
    args = dict(field=refracta.PhysicalAtmosphere(), origin=[0, 1.5, 0], direction=[1, 0, 0])
    args.update(kwargs)
    with pytest.raises(error, match=message):
        refracta.trace_ray(**args)


def test_reaching_an_undefined_index_raises_numerical_error():
    field = refracta.LinearSquaredProfile(n0=1.0, alpha=-0.01)  # n^2 = 1 - 0.01 y: n -> 0 at y = 100
    for method in ("rk4", "rk45", "stratified"):
        with pytest.raises(refracta.NumericalError, match="must be finite and > 0|singular"):
            refracta.trace_ray(field, [0, 0, 0], [0, 1, 0], trace=method, max_length=500)
    with pytest.raises(refracta.NumericalError):
        refracta.trace_rays(field, [0, 0, 0], [[0, 1, 0], [1, 0, 0]], max_length=500)


def test_python_exceptions_in_a_custom_field_propagate():
    def broken(points):
        raise ZeroDivisionError("inside the user's field")

    field = refracta.CustomField(broken, lambda p: np.zeros_like(p))
    with pytest.raises(ZeroDivisionError, match="user's field"):
        refracta.trace_ray(field, [0, 0, 0], [1, 0, 0])
    with pytest.raises(ZeroDivisionError):
        refracta.trace_rays(field, [0, 0, 0], [[1, 0, 0]] * 4)


def test_every_problem_with_the_options_is_listed_at_once():
    with pytest.raises(ValueError, match=r"tol must be > 0 .*; step must be > 0.*; max_length must be > 0"):
        refracta.trace_ray(refracta.PhysicalAtmosphere(), [0, 1.5, 0], [1, 0, 0], tol=0.0, step=-1.0, max_length=-5.0)
    with pytest.raises(ValueError, match="unknown option 'tolerance'"):
        refracta.trace_rays(refracta.PhysicalAtmosphere(), [0, 1.5, 0], [[1, 0, 0]], tolerance=1e-3)


def test_options_objects_and_keywords_are_the_same_call(hot_road):
    options = refracta.TraceOptions()
    options.trace, options.max_length, options.stop_height = "stratified", 500.0, 0.0
    by_object = refracta.trace_ray(hot_road, [0, 1.5, 0], direction(-0.3), options)
    by_keywords = refracta.trace_ray(
        hot_road, [0, 1.5, 0], direction(-0.3), trace="stratified", max_length=500.0, stop_height=0.0
    )
    np.testing.assert_array_equal(by_object.points, by_keywords.points)
    # Keywords override the object's fields; the object itself is not changed.
    shorter = refracta.trace_rays(hot_road, [0, 1.5, 0], [direction(0.1)], options, max_length=100.0)
    assert shorter.lengths[0] == 100.0 and options.max_length == 500.0
    # None leaves a field that takes no None at its default, as before (step=None: the default).
    unset = refracta.trace_ray(hot_road, [0, 1.5, 0], direction(-0.3), options, step=None)
    np.testing.assert_array_equal(unset.points, by_object.points)


def test_method_is_a_deprecated_name_of_trace(hot_road):
    with pytest.warns(DeprecationWarning, match="method= is deprecated"):
        old = refracta.trace_ray(hot_road, [0, 1.5, 0], direction(-0.3), method="rk4", max_length=50.0)
    new = refracta.trace_ray(hot_road, [0, 1.5, 0], direction(-0.3), trace="rk4", max_length=50.0)
    np.testing.assert_array_equal(old.points, new.points)
    with pytest.raises(ValueError, match="not both"):
        refracta.trace_rays(hot_road, [0, 1.5, 0], [direction(0.0)], method="rk4", trace="rk45")


def test_python_signatures_write_no_numeric_default():
    """The defaults live in the C++ options (TraceOptions, ElevationTableOptions, TurbulenceSettings)."""
    import inspect
    import numbers

    for function in (refracta.trace_rays, refracta.ElevationTable.__init__, refracta.Turbulence.__init__):
        defaults = {
            name: p.default
            for name, p in inspect.signature(function).parameters.items()
            if isinstance(p.default, numbers.Number) and not isinstance(p.default, bool)
        }
        assert not defaults, (function, defaults)


def test_a_fine_tolerance_over_the_curved_earth_traces():
    # A trial: tol 1e-8 over 40 km had rk45's step collapse ("finer than double precision"), where
    # the cause was the flat frame's height, R (e^(y/R) - 1), rounded to R eps ~ 1e-9 m: now expm1.
    # The ray meets the ground ~4.9 km out (the trial's 4909 m), where 'stratified' puts it.
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(surface_dt=-2.0, surface_depth=2.0))
    e = np.radians(-0.05)
    direction = [np.cos(e), np.sin(e), 0.01]
    exact = refracta.trace_ray(
        field, [0.0, 5.0, 0.0], direction, max_length=40000.0, stop_height=0.0, trace="stratified", tol=1e-9
    )
    for tol in (1e-8, 1e-10):
        path = refracta.trace_ray(field, [0.0, 5.0, 0.0], direction, max_length=40000.0, stop_height=0.0, tol=tol)
        assert 4000.0 < path.points[-1][0] < 6000.0  # the ground ~4.9 km out, as in the trial
        # Heights to tol; along the ground a height error grows by 1 / tan(0.05 deg) = 1146 (measured 1.7e-7 m).
        assert np.linalg.norm(path.points[-1] - exact.points[-1]) < 1146 * 1e-8 + 1e-9
