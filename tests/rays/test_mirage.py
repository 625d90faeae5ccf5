"""The inferior mirage: critical depression, tangent point and hidden height (ORACLES.md)."""

import numpy as np
import pytest

import refracta

from .test_closed_forms import direction

EYE = 1.5


def reaches_ground(field, depression_deg, method):
    path = refracta.trace_ray(
        field, [0, EYE, 0], direction(-depression_deg), trace=method, tol=1e-10, max_length=3000.0, stop_height=0.0
    )
    return path.stop == "stop_height"


def critical_depression(field, method, lo=0.0, hi=2.0, iterations=45):
    """Smallest depression [deg] whose ray reaches the ground, by bisection."""
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if reaches_ground(field, mid, method) else (mid, hi)
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("method", ["stratified", "rk45"])
def test_critical_depression_over_a_hot_road(hot_road, method):
    # A ray turns where n(h_t) = n(h_eye) cos(e): it grazes the ground at theta_c = arccos(n(0)/n(h_eye)).
    n_ground, n_eye = hot_road.ior(np.array([[0, 0, 0], [0, EYE, 0]], dtype=float))
    exact = np.degrees(np.arccos(n_ground / n_eye))
    # Bisection to 2^-45 of 2 deg; the rays' own error shifts the boundary by ~ tol / range ~ 1e-10.
    assert critical_depression(hot_road, method) == pytest.approx(exact, abs=1e-8)
    # ORACLES.md's rule of thumb theta_c ~ 4.8' sqrt(dT) at 15 C, with dT ~ 10 K here.
    delta_t = hot_road.temperature(0.0) - hot_road.temperature(EYE)
    assert exact * 60 == pytest.approx(4.8 * np.sqrt(delta_t), rel=0.05)


def test_tangent_point_and_hidden_height_for_n_squared_linear():
    n0, alpha = 1.000277, 2e-5
    field = refracta.LinearSquaredProfile(n0=n0, alpha=alpha)
    g = alpha / (2 * n0**2)  # G = (dn/dh)/n at the ground
    theta_c = np.arccos(n0 / np.sqrt(n0**2 + alpha * EYE))
    assert theta_c == pytest.approx(np.sqrt(2 * g * EYE), rel=1e-4)  # small-angle form
    # The critical ray touches the ground at x* = sqrt(2 h_e / G) and then hides (G/2)(D - x*)^2.
    path = refracta.trace_ray(field, [0, EYE, 0], [np.cos(theta_c), -np.sin(theta_c), 0], tol=1e-11, max_length=2500.0)
    samples = np.array([path.point_at(s)[0] for s in np.linspace(0.0, 1200.0, 24001)])  # 5 cm apart
    lowest = samples[np.argmin(samples[:, 1])]
    x_star = np.sqrt(2 * EYE / g)
    assert lowest[0] == pytest.approx(x_star, rel=2e-3)  # small-angle form vs the exact vertex
    assert abs(lowest[1]) < 1e-8  # touches the ground: G/2 (5 cm)^2 ~ 1e-8 between samples
    for distance in (1200.0, 2000.0):
        ((point, _, _),) = path.crossings([1, 0, 0], distance)
        # Exact parabola with its vertex on the ground: beta = n(h_e) cos(theta_c) = n0, so
        # y = alpha (x - x_v)^2 / (4 n0^2) with x_v = 2 n0^2 tan(theta_c) / alpha.
        x_exact = 2 * n0**2 * np.tan(theta_c) / alpha
        assert point[1] == pytest.approx(alpha * (distance - x_exact) ** 2 / (4 * n0**2), abs=1e-8)
        assert point[1] == pytest.approx(g / 2 * (distance - x_star) ** 2, rel=5e-3)


def test_hot_road_reflects_the_sky_below_the_horizon(hot_road):
    # A ray 0.2 deg down (less than theta_c ~ 0.25 deg) comes back up: the mirage shows the sky.
    path = refracta.trace_ray(hot_road, [0, EYE, 0], direction(-0.2), max_length=2000, stop_height=0.0)
    assert path.stop == "max_length"
    assert path.directions[-1, 1] > 0
    assert path.points[:, 1].min() > 0
