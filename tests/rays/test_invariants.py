"""Invariants of the ray equations: |v| = n, Bouguer's n cos e, the vertical plane, index scaling,
reversibility, the launch condition, convergence orders and tolerances (ORACLES.md)."""

import numpy as np
import pytest

import refracta

from .test_closed_forms import direction


def test_launch_vector_is_n_times_the_unit_direction(hot_road):
    origin = np.array([0.0, 0.05, 0.0])
    path = refracta.trace_ray(hot_road, origin, [3.0, 0.4, 0.0], max_length=10)
    t0 = np.array([3.0, 0.4, 0.0]) / np.hypot(3.0, 0.4)
    np.testing.assert_allclose(path.ray_vectors[0], hot_road.ior(origin) * t0, rtol=1e-15)  # n t0 in double: rounding


@pytest.mark.parametrize("method", ["rk4", "rk45"])
def test_ray_vector_length_equals_the_index(hot_road, method):
    path = refracta.trace_ray(
        hot_road, [0, 1.5, 0], direction(-0.2), trace=method, tol=1e-9, step=0.05, max_length=1000, stop_height=0.0
    )
    # |v| = n is not built in: the integrator carries v and n separately. Drift stays at the
    # integration error (1e-9 in direction ~ 1e-9 in |v|).
    np.testing.assert_allclose(np.linalg.norm(path.ray_vectors, axis=1), path.ior, rtol=0, atol=2e-9)


@pytest.mark.parametrize("method", ["rk4", "rk45"])
def test_bouguer_invariant_is_conserved(hot_road, method):
    path = refracta.trace_ray(
        hot_road, [0, 1.5, 0], direction(-0.245), trace=method, tol=1e-10, step=0.05, max_length=1000, stop_height=0.0
    )
    cos_e = np.hypot(path.directions[:, 0], path.directions[:, 2])
    beta = path.ior * cos_e
    # 1e-10: the integrators' direction error; the invariant spans the hot layer where n changes 3e-5.
    np.testing.assert_allclose(beta, beta[0], rtol=0, atol=1e-10)
    assert np.ptp(path.ior) > 5e-6  # the ray did pass through the layer


def test_ray_stays_in_its_vertical_plane():
    field = refracta.PhysicalAtmosphere(inversion_dt=10, inversion_base=5, inversion_thickness=20)
    azimuth = np.radians(37.0)
    path = refracta.trace_ray(field, [0, 1, 0], direction(0.3, 37.0), max_length=2000)
    off_plane = path.points[:, 2] * np.cos(azimuth) - path.points[:, 0] * np.sin(azimuth)
    # A vertical plane of a height-only field: only rounding leaves it (1e-12 m over 2 km).
    np.testing.assert_allclose(off_plane, 0.0, atol=1e-12)


def test_scaling_the_index_leaves_paths_unchanged():
    base = refracta.LogisticProfile()
    scaled = refracta.CustomField(lambda p: 1.7 * base.ior(p), lambda p: 1.7 * base.grad_ior(p), height_only=True)
    for method in ("rk45", "stratified"):
        a = refracta.trace_ray(base, [0, 2, 0], direction(-3.0), trace=method, tol=1e-10, max_length=60)
        b = refracta.trace_ray(scaled, [0, 2, 0], direction(-3.0), trace=method, tol=1e-10, max_length=60)
        # 100x the tol 1e-10: step choices differ by the scaled index's rounding.
        np.testing.assert_allclose(b.points[-1], a.points[-1], atol=1e-8)


def test_tracing_back_returns_to_the_start():
    field = refracta.LogisticProfile()
    start = np.array([0.0, 2.0, 0.0])
    forward = refracta.trace_ray(field, start, direction(-4.0, 10.0), tol=1e-10, max_length=80)
    back = refracta.trace_ray(field, forward.points[-1], -forward.directions[-1], tol=1e-10, max_length=80)
    np.testing.assert_allclose(back.points[-1], start, atol=1e-8)  # 100x the tol 1e-10 of each 80 m leg


def test_rk4_converges_with_fourth_order():
    field = refracta.LinearSquaredProfile(n0=1.0, alpha=0.05)  # strong: rays curve with radius ~40 m
    kwargs = dict(origin=[0, 1, 0], direction=direction(10.0), max_length=100.0)
    reference = refracta.trace_ray(field, trace="rk45", tol=1e-13, **kwargs).points[-1]
    errors = [
        np.linalg.norm(refracta.trace_ray(field, trace="rk4", step=h, **kwargs).points[-1] - reference)
        for h in (2.0, 1.0, 0.5)
    ]
    orders = np.log2(np.array(errors[:-1]) / np.array(errors[1:]))
    assert errors[-1] > 1e-11  # above round-off, so the order is measurable
    assert np.all((orders >= 3.7) & (orders <= 4.3)), orders


@pytest.mark.parametrize("tol", [1e-3, 1e-5, 1e-7])
def test_rk45_meets_its_tolerance(hot_road, tol):
    elevations = np.linspace(-0.24, 1.0, 25)  # rays that turn above the road or climb: all reach 2 km
    directions = np.array([direction(e) for e in elevations])
    reference = refracta.trace_rays(
        hot_road, [0, 1.5, 0], directions, trace="stratified", tol=1e-10, max_length=2000, stop_height=0.0
    )
    batch = refracta.trace_rays(
        hot_road, [0, 1.5, 0], directions, trace="rk45", tol=tol, max_length=2000, stop_height=0.0
    )
    assert np.all(reference.stops == "max_length")
    errors = np.linalg.norm(batch.end_points - reference.end_points, axis=1)
    assert errors.max() <= tol, errors.max()


def test_stratified_agrees_with_rk45_on_a_hot_road(hot_road):
    elevations = np.linspace(-1.0, 1.0, 41)
    directions = np.array([direction(e, 25.0) for e in elevations])
    options = dict(max_length=2000.0, stop_height=0.0, tol=1e-8)
    a = refracta.trace_rays(hot_road, [0, 1.5, 0], directions, trace="stratified", **options)
    b = refracta.trace_rays(hot_road, [0, 1.5, 0], directions, trace="rk45", **options)
    assert np.array_equal(a.stops, b.stops)
    # Both at 1e-8 m; ground hits at grazing angles amplify the height error by 1/sin(e) <= 1e3.
    np.testing.assert_allclose(a.end_points, b.end_points, atol=1e-5)
    # Unit directions at 1e-8: no grazing amplification (comment above).
    np.testing.assert_allclose(a.end_directions, b.end_directions, atol=1e-8)
    np.testing.assert_allclose(a.lengths, b.lengths, atol=1e-5)  # lengths amplified like the end points (comment above)
