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
