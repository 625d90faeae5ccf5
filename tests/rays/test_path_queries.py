"""RayPath queries on the continuous path: closest point, crossings, point_at."""

import numpy as np
import pytest

import refracta

from .test_closed_forms import direction

# Queries solve on the quintic Hermite path to machine precision; paths traced to 1e-11 m.
QUERY_TOLERANCE = 1e-9


def test_closest_point_on_a_straight_path_is_the_perpendicular_foot():
    field = refracta.LinearSquaredProfile(n0=1.0, alpha=0.0)
    origin, t = np.array([1.0, 2.0, -1.0]), direction(5.0, 20.0)
    path = refracta.trace_ray(field, origin, t, max_length=100.0)
    for q in ([30.0, 10.0, 5.0], [-5.0, 0.0, 0.0], [80.0, -3.0, 40.0]):
        q = np.asarray(q)
        s_foot = np.clip((q - origin) @ t, 0.0, 100.0)
        foot = origin + s_foot * t
        point, distance, s = path.closest_point(q)
        np.testing.assert_allclose(point, foot, atol=1e-12)  # a straight path of 100 m: double rounding
        assert distance == pytest.approx(np.linalg.norm(q - foot), abs=1e-12)  # as above
        assert s == pytest.approx(s_foot, abs=1e-12)  # as above


def test_closest_point_on_a_parabola():
    n0, alpha, y0 = 1.000277, 5e-4, 1.0  # strongly curved: 62 m of rise over 1 km
    field = refracta.LinearSquaredProfile(n0=n0, alpha=alpha)
    path = refracta.trace_ray(field, [0, y0, 0], [1, 0, 0], tol=1e-11, max_length=1000.0)
    beta = np.sqrt(n0**2 + alpha * y0)

    def y(x):
        return y0 + alpha * x**2 / (4 * beta**2)

    def dist(x, q):
        return np.hypot(np.hypot(x - q[0], y(x) - q[1]), q[2])

    for q in (np.array([400.0, 30.0, 0.0]), np.array([700.0, 10.0, 3.0]), np.array([123.0, 2.0, 0.0])):
        # Reference: minimise the distance to the closed-form curve (golden section in x).
        lo, hi = 0.0, 999.0
        for _ in range(200):
            a, b = lo + 0.382 * (hi - lo), lo + 0.618 * (hi - lo)
            lo, hi = (lo, b) if dist(a, q) < dist(b, q) else (a, hi)
        x_ref = 0.5 * (lo + hi)
        point, distance, _ = path.closest_point(q)
        assert distance == pytest.approx(dist(x_ref, q), abs=QUERY_TOLERANCE)
        np.testing.assert_allclose(point, [x_ref, y(x_ref), 0.0], atol=1e-6)  # along-track is flat


def test_crossings_of_a_height_on_a_turning_ray():
    n0, alpha, y0, t0 = 1.000277, 6e-6, 1.5, -0.001
    field = refracta.LinearSquaredProfile(n0=n0, alpha=alpha)
    path = refracta.trace_ray(field, [0, y0, 0], [1, t0, 0], tol=1e-11, max_length=1000.0)
    beta = np.sqrt(n0**2 + alpha * y0) / np.sqrt(1 + t0**2)
    level = 1.4
    # y0 + t0 x + a x^2 = level with a = alpha / (4 beta^2): two roots, going down then up.
    a = alpha / (4 * beta**2)
    roots = np.sort(np.roots([a, t0, y0 - level]).real)
    crossings = path.at_height(level)
    assert crossings.shape == (2, 3)
    # The crossing is solved to machine precision (comment at the top).
    np.testing.assert_allclose(crossings[:, 1], level, atol=1e-12)
    np.testing.assert_allclose(crossings[:, 0], roots, atol=1e-6)  # x from y at slope 1e-3: 1e-9/1e-3
    assert path.at_height(5.0).shape == (0, 3)


def test_point_at_interpolates_between_nodes():
    field = refracta.LinearSquaredProfile(n0=1.0003, alpha=4e-6)
    path = refracta.trace_ray(field, [0, 2, 0], [1, 0.002, 0], tol=1e-11, max_length=800.0)
    beta = np.sqrt(1.0003**2 + 4e-6 * 2) / np.sqrt(1 + 0.002**2)
    for s in np.linspace(0, 800, 37):
        point, tangent = path.point_at(s)
        # QUERY_TOLERANCE's 1e-9: the path traced to 1e-11 m, the Hermite query exact.
        assert point[1] == pytest.approx(2 + 0.002 * point[0] + 4e-6 * point[0] ** 2 / (4 * beta**2), abs=1e-9)
        slope = 0.002 + 4e-6 * point[0] / (2 * beta**2)
        # As above, for the unit tangent.
        np.testing.assert_allclose(tangent, np.array([1, slope, 0]) / np.hypot(1, slope), atol=1e-9)
    with pytest.raises(ValueError, match="s must be in"):
        path.point_at(900.0)
