"""A CustomField's values are checked where they enter refracta (issue 13): NaN, 0, negative or
infinite n from ior() is a NumericalError naming the point (it was returned as is), a (3, N)
gradient is a ValueError (it was reinterpreted as (N, 3)), and n outside [1e-50, 1e50] -- where
the ray equations' n^3 and n^2 - beta^2 leave double's range -- is refused by every integrator
(n = 1e-300 gave NaN points, 1e300 a stratified trace that never ended)."""

import numpy as np
import pytest

import refracta


def constant(n, height_only=True):
    return refracta.CustomField(lambda p: np.full(len(p), n), lambda p: np.zeros((len(p), 3)), height_only=height_only)


@pytest.mark.parametrize("n", [np.nan, 0.0, -1.0, np.inf, 1e-300, 1e300])
def test_unusable_indices_from_a_custom_field_raise_numerical_error(n):
    field = constant(n)
    with pytest.raises(refracta.NumericalError, match=r"ior returned n = .* at \(0, 1, 0\) m"):
        field.ior([[0.0, 1.0, 0.0]])
    for method in ("stratified", "rk45", "rk4"):
        with pytest.raises(refracta.NumericalError):
            refracta.trace_ray(field, [0, 1, 0], [1, 0.1, 0], trace=method, max_length=10.0)


def test_a_transposed_gradient_is_refused():
    field = refracta.CustomField(lambda p: np.ones(len(p)), lambda p: np.zeros((3, len(p))))
    with pytest.raises(ValueError, match=r"expected shape \(5, 3\)"):
        field.grad_ior(np.zeros((5, 3)))
    one = refracta.CustomField(lambda p: np.ones(len(p)), lambda p: np.zeros((3, 1)))
    with pytest.raises(ValueError, match=r"expected shape \(1, 3\)"):
        refracta.trace_ray(one, [0, 1, 0], [1, 0, 0])


def test_a_non_finite_gradient_is_a_numerical_error():
    field = refracta.CustomField(lambda p: np.ones(len(p)), lambda p: np.full((len(p), 3), np.nan))
    with pytest.raises(refracta.NumericalError, match="grad_ior returned"):
        field.grad_ior([[0.0, 0.0, 0.0]])


@pytest.mark.parametrize("n0", [1e-45, 1e45])
def test_extreme_but_usable_indices_trace_like_n_of_one(n0):
    # The ray equations depend on n only through grad n / n: n0 (1 + 1e-4 y) bends exactly as
    # 1 + 1e-4 y does, whatever n0 (a scale invariance), so the paths agree to the trace tolerance.
    def field(scale):
        return refracta.CustomField(
            lambda p: scale * (1 + 1e-4 * p[:, 1]),
            lambda p: np.tile([0.0, 1e-4 * scale, 0.0], (len(p), 1)),
            height_only=True,
        )

    for method in ("stratified", "rk45"):
        a = refracta.trace_ray(field(n0), [0, 1, 0], [1, 0.1, 0], trace=method, max_length=100.0)
        b = refracta.trace_ray(field(1.0), [0, 1, 0], [1, 0.1, 0], trace=method, max_length=100.0)
        assert np.isfinite(a.points).all()
        np.testing.assert_allclose(a.points[-1], b.points[-1], atol=1e-6)


def test_a_custom_field_that_is_not_height_only_is_refused_where_it_is_traced():
    # height_only=True let 'stratified' trace the column at x = z = 0 of a field that changes with
    # x: silently the wrong rays. Its first evaluation now compares n and grad_ior 1 m aside.
    field = refracta.CustomField(
        lambda p: 1.0003 - 1e-5 * p[:, 1] + 1e-6 * p[:, 0],
        lambda p: np.tile([1e-6, -1e-5, 0.0], (len(p), 1)),
        height_only=True,
    )
    with pytest.raises(ValueError, match=r"height_only=True, but the field depends on x or z.*height_only=False"):
        refracta.trace_ray(field, [0, 1.5, 0], [1, 0, 0], trace="stratified", max_length=100.0)


def test_a_gradient_that_is_not_the_fields_is_warned_about():
    # grad_ior twice ior's slope bends rays twice as much as n changes: a RuntimeWarning naming
    # both at the first point evaluated (central differences 1 mm apart, 1e-3 relative allowance).
    field = refracta.CustomField(lambda p: 1.0003 - 1e-5 * p[:, 1], lambda p: np.tile([0, -2e-5, 0.0], (len(p), 1)))
    with pytest.warns(RuntimeWarning, match=r"grad_ior\(0, 1.5, 0\) = \(0, -2e-05, 0\) but ior's central differences"):
        refracta.trace_ray(field, [0, 1.5, 0], [1, 0, 0], max_length=100.0)
    right = refracta.CustomField(lambda p: 1.0003 - 1e-5 * p[:, 1], lambda p: np.tile([0, -1e-5, 0.0], (len(p), 1)))
    refracta.trace_ray(right, [0, 1.5, 0], [1, 0, 0], max_length=100.0)  # no warning: pytest's filter is "error"
