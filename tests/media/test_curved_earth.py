"""Rays over a spherical Earth through the Earth-flattening transform (ORACLES.md, 'The air')."""

import numpy as np
import pytest

import refracta

R = 6371e3


def smallest_depression_reaching_the_sea(field, eye, length=60000.0):
    """Depression [rad] of the ray that just grazes the sea, by bisection on traced rays."""
    lo, hi = 0.0, 0.02
    for _ in range(48):
        mid = 0.5 * (lo + hi)
        path = refracta.trace_ray(
            field,
            [0, field.flat_height(eye), 0],
            [np.cos(mid), -np.sin(mid), 0],
            trace="stratified",
            tol=1e-9,
            max_length=length,
            stop_height=0.0,
        )
        lo, hi = (lo, mid) if path.stop == "stop_height" else (mid, hi)
    return 0.5 * (lo + hi)


def test_horizon_dip_without_refraction_is_geometric():
    field = refracta.CurvedEarth(refracta.LinearSquaredProfile(n0=1.0003, alpha=0.0))
    for eye in (2.0, 30.0):
        # Straight rays on a sphere: the horizon lies arccos(R / (R + h)) below the horizontal.
        assert smallest_depression_reaching_the_sea(field, eye) == pytest.approx(np.arccos(R / (R + eye)), rel=1e-8)


def test_standard_refraction_shrinks_the_dip_by_the_ray_curvature():
    # Ray curvature k = -R (dn/dh) / n ~ 0.17 of Earth's (ORACLES.md): dip ~ sqrt(2 h (1 - k) / R).
    air = refracta.PhysicalAtmosphere()
    field = refracta.CurvedEarth(air)
    eye = 10.0
    k = -R * air.grad_ior([0, 5.0, 0])[1] / air.ior([0, 5.0, 0])
    assert k == pytest.approx(0.170, abs=0.005)  # ORACLES.md's ~0.17 (standard air at 15 C), to 3 %
    dip = smallest_depression_reaching_the_sea(field, eye)
    # The formula takes k at 5 m and small angles; k varies along the ray: 2e-3.
    assert dip == pytest.approx(np.sqrt(2 * eye * (1 - k) / R), rel=2e-3)


def test_a_ducting_gradient_keeps_a_level_ray_at_its_height():
    # dn/dh = -n/R_E (an inversion of ~0.13 K/m at 15 C) bends rays with the Earth.
    ducting = refracta.PhysicalAtmosphere(lapse_rate=-0.1325)
    field = refracta.CurvedEarth(ducting)
    path = refracta.trace_ray(field, [0, 20.0, 0], [1, 0, 0], trace="stratified", tol=1e-9, max_length=20000.0)
    # Without refraction the ray would rise x^2/(2R) = 31 m above the sea at 20 km.
    assert abs(path.points[-1, 1] - 20.0) < 0.03 * 31.4
    flat = refracta.CurvedEarth(refracta.LinearSquaredProfile(n0=1.0, alpha=0.0))
    straight = refracta.trace_ray(flat, [0, 20.0, 0], [1, 0, 0], max_length=20000.0)
    # The parabola x^2/2R (relative error ~(x/R)^2) and the tracer's default tol on 31 m.
    assert straight.points[-1, 1] - 20.0 == pytest.approx(20000.0**2 / (2 * R), rel=1e-3)


def test_conversions_and_parameters():
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(surface_dt=3.0), radius=6.4e6)
    # A round trip through the exact conversion in double.
    assert field.true_height(field.flat_height(100.0)) == pytest.approx(100.0, rel=1e-14)
    # H^2/2R is the conversion's leading term: relative error of order h/R = 2e-5.
    assert 100.0 - field.flat_height(100.0) == pytest.approx(100.0**2 / (2 * 6.4e6), rel=1e-3)
    assert field.param_names[-1] == "earth_radius" and field.params["surface_dt"] == 3.0
    assert field.with_params(surface_dt=5.0).base.params["surface_dt"] == 5.0
    with pytest.raises(ValueError, match="height only"):
        refracta.CurvedEarth(refracta.CustomField(lambda p: p[:, 0] * 0 + 1, lambda p: 0 * p))
    with pytest.raises(ValueError, match="radius"):
        refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius=-1.0)


def test_rk45_traces_a_hot_road_over_the_curved_earth_at_its_default_tolerance():
    # The flat frame's true height was R (e^(y/R) - 1) in two steps, rounded to R eps ~ 1e-9 m: rk45
    # saw the jitter as structure near the hot road and its steps collapsed (33 of 84 rays at the
    # default tol, a new user's trial). With expm1 every ray traces, and agrees with 'stratified'.
    road = refracta.CurvedEarth(refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1))
    e = np.radians(np.linspace(-0.5, 0.5, 11))
    directions = np.c_[np.cos(e), np.sin(e), 0 * e]
    rk45 = refracta.trace_rays(road, [0, 1.5, 0], directions, max_length=20000.0, stop_height=0.0)
    exact = refracta.trace_rays(
        road, [0, 1.5, 0], directions, max_length=20000.0, stop_height=0.0, trace="stratified", tol=1e-9
    )
    assert list(rk45.stops) == list(exact.stops)
    # rk45's tolerance is 1e-6 m on the path (measured 4.9e-9 m).
    np.testing.assert_allclose(rk45.end_points, exact.end_points, rtol=0, atol=1e-6)
