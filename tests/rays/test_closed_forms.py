"""Curved rays against the closed forms of ORACLES.md, with every method that applies."""

import numpy as np
import pytest

import refracta

# ORACLES.md asks for the parabola to < 1e-9 m over 1 km with rk4 and rk45.
PARABOLA_TOLERANCE = 1e-9
# The other closed forms use Python CustomFields; 1e-8 m over 500 m is 2e-11 relative.
CLOSED_FORM_TOLERANCE = 1e-8

METHODS = [("rk4", dict(step=0.3)), ("rk45", dict(tol=1e-11)), ("stratified", dict(tol=1e-11))]


def direction(elevation_deg, azimuth_deg=0.0):
    e, a = np.radians(elevation_deg), np.radians(azimuth_deg)
    return np.array([np.cos(e) * np.cos(a), np.sin(e), np.cos(e) * np.sin(a)])


def height_field(n, dn):
    """A CustomField from n(y) and dn/dy (vectorised over y)."""
    return refracta.CustomField(
        lambda p: n(p[:, 1]),
        lambda p: np.stack([np.zeros(len(p)), dn(p[:, 1]), np.zeros(len(p))], axis=1),
        height_only=True,
    )


def sample_path(path, count=200):
    """Points of the continuous path (between nodes too)."""
    return np.array([path.point_at(s)[0] for s in np.linspace(0, path.length, count)])


@pytest.mark.parametrize("method, options", METHODS)
@pytest.mark.parametrize("elevation", [0.0, 0.25, -0.05, -0.3, 3.0])
def test_parabola_in_n_squared_linear_field(method, options, elevation):
    n0, alpha, y0 = 1.000277, 6.0033e-6, 1.5
    field = refracta.LinearSquaredProfile(n0=n0, alpha=alpha)
    path = refracta.trace_ray(field, [0, y0, 0], direction(elevation), trace=method, max_length=1000.0, **options)
    t0 = np.tan(np.radians(elevation))
    beta = np.sqrt(n0**2 + alpha * y0) * np.cos(np.radians(elevation))
    for points in (path.points, sample_path(path)):
        x, y = points[:, 0], points[:, 1]
        np.testing.assert_allclose(y, y0 + t0 * x + alpha * x**2 / (4 * beta**2), rtol=0, atol=PARABOLA_TOLERANCE)
    assert path.length == pytest.approx(1000.0, abs=1e-9)


def test_parabola_editing_oracle():
    # alpha = 4 n(y0)^2 (h - y0 - t0 D) / (D^2 (1 + t0^2)) puts the ray through height h at D.
    n0, y0, distance, h = 1.000277, 1.5, 1000.0, 3.0
    alpha = 4 * n0**2 * (h - y0) / distance**2  # n(y0) ~ n0 to 1e-9 here; solve it exactly below
    for _ in range(5):
        alpha = 4 * (n0**2 + alpha * y0) * (h - y0) / distance**2
    assert alpha == pytest.approx(6.0033e-6, rel=1e-4)
    field = refracta.LinearSquaredProfile(n0=n0, alpha=alpha)
    path = refracta.trace_ray(field, [0, y0, 0], [1, 0, 0], tol=1e-11, max_length=1100)
    ((point, s, _),) = path.crossings([1, 0, 0], distance)
    assert point[1] == pytest.approx(h, abs=PARABOLA_TOLERANCE)


@pytest.mark.parametrize("method", ["rk45", "stratified"])
def test_catenary_in_linear_index_field(method):
    n0, g, y0, elevation = 1.0003, 2e-5, 5.0, -0.4
    field = height_field(lambda y: n0 + g * y, lambda y: np.full_like(y, g))
    path = refracta.trace_ray(field, [0, y0, 0], direction(elevation), trace=method, tol=1e-11, max_length=500)
    beta = (n0 + g * y0) * np.cos(np.radians(elevation))
    x0 = -(beta / g) * np.arcsinh(np.tan(np.radians(elevation)))
    x, y = sample_path(path).T[:2]
    np.testing.assert_allclose(
        y + n0 / g, (beta / g) * np.cosh(g * (x - x0) / beta), rtol=0, atol=CLOSED_FORM_TOLERANCE
    )


@pytest.mark.parametrize("method", ["rk45", "stratified"])
def test_log_cosine_in_exponential_field(method):
    n0, scale, y0, elevation = 1.0003, 3000.0, 2.0, 1.5
    field = height_field(lambda y: n0 * np.exp(-y / scale), lambda y: -n0 / scale * np.exp(-y / scale))
    path = refracta.trace_ray(field, [0, y0, 0], direction(elevation), trace=method, tol=1e-11, max_length=500)
    beta = n0 * np.exp(-y0 / scale) * np.cos(np.radians(elevation))
    y_top = -scale * np.log(beta / n0)
    x0 = scale * np.arctan(np.tan(np.radians(elevation)))
    x, y = sample_path(path).T[:2]
    np.testing.assert_allclose(y, y_top + scale * np.log(np.cos((x - x0) / scale)), rtol=0, atol=CLOSED_FORM_TOLERANCE)


@pytest.mark.parametrize("method", ["rk45", "stratified"])
def test_circle_in_reciprocal_linear_field(method):
    a, c, y0, elevation = 1.0, 1e-4, 3.0, -1.0
    field = height_field(lambda y: 1 / (a - c * y), lambda y: c / (a - c * y) ** 2)
    path = refracta.trace_ray(field, [0, y0, 0], direction(elevation), trace=method, tol=1e-11, max_length=500)
    n_start = 1 / (a - c * y0)
    radius = 1 / (n_start * np.cos(np.radians(elevation)) * c)
    # The centre lies on the normal toward increasing n (up), a radius from the start.
    t = direction(elevation)
    normal = np.array([-t[1], t[0], 0.0])
    centre = np.array([0, y0, 0]) + radius * normal
    distances = np.linalg.norm(sample_path(path) - centre, axis=1)
    np.testing.assert_allclose(distances, radius, rtol=0, atol=CLOSED_FORM_TOLERANCE)


def test_uniform_field_gives_straight_lines():
    field = refracta.LinearSquaredProfile(n0=1.33, alpha=0.0)
    t = direction(12.0, 40.0)
    for method in ("rk4", "rk45", "stratified"):
        path = refracta.trace_ray(field, [1, 2, 3], t, trace=method, max_length=250)
        expected = np.array([1, 2, 3]) + np.outer(path.arc_length, t)
        np.testing.assert_allclose(path.points, expected, rtol=0, atol=1e-11)
        np.testing.assert_allclose(path.directions, np.broadcast_to(t, path.directions.shape), atol=1e-14)


@pytest.mark.parametrize("elevation", [1e-9, 1e-8, 3e-8, -3e-8, 1e-7])
def test_a_nearly_level_ray_in_uniform_air_is_a_straight_line(elevation):
    # Within 4.5e-8 rad of level n - beta is below 1e-15: 'stratified' took such a launch for a
    # turning point, and in uniform air kept the ray level (3e-5 m low after 1 km at 3e-8 rad)
    # or, scanning on, ended it at x = 0. The straight line, from the launch's exact gap.
    field = height_field(lambda y: np.full_like(y, 1.0003), lambda y: np.zeros_like(y))
    start, d = np.array([0.0, 1.5, 0.0]), np.array([np.cos(elevation), np.sin(elevation), 0.0])
    path = refracta.trace_ray(field, start, d, trace="stratified", max_length=1000.0, tol=1e-9)
    # Heights to 1e-12 m (measured <= 1e-16); along the ray the heights' own round-off (2.2e-16 m
    # at 1.5 m) over a slope of 1e-9 leaves 2.2e-7 m (measured 8e-8 m at 1e-9 rad).
    assert path.points[-1][1] - 1.5 == pytest.approx(1000.0 * np.sin(elevation), abs=1e-12)
    assert path.points[-1][0] == pytest.approx(1000.0 * np.cos(elevation), abs=3e-7)  # the round-off above


@pytest.mark.parametrize(
    "field_name, eye, elevation",
    [
        ("curved standard air", 100.0, -1e-9),
        ("curved standard air", 100.0, 1e-9),
        ("curved standard air", 100.0, -3e-8),
        ("flat standard air", 100.0, -1e-9),
        ("n^2 linear", 100.0, 1e-8),
        ("sounding duct", 10.4486, 1e-8),
    ],
)
def test_nearly_level_launches_beside_a_turning_height(field_name, eye, elevation):
    # A ray within ~1e-7 rad of level turns within micrometres of its launch (ahead of it or, where
    # n rises along its motion, behind it). 'stratified' scanned from the launch into the inverse
    # square root beside it: ends 1e130 m away, or 1 mm off over 30 km, whatever tol (a trial).
    # It now starts from the turning height (its u-substitution, n - beta from the launch's exact gap).
    fields = {
        "curved standard air": refracta.CurvedEarth(refracta.PhysicalAtmosphere()),
        "flat standard air": refracta.PhysicalAtmosphere(),
        "n^2 linear": refracta.LinearSquaredProfile(1.000277, -1e-7),
        "sounding duct": refracta.TemperatureProfile([0, 5, 10, 20, 40], [300, 290, 285, 290, 295]),
    }
    field, d = fields[field_name], direction(np.degrees(elevation))
    exact = refracta.trace_ray(field, [0, eye, 0], d, trace="stratified", tol=1e-9, max_length=30000.0)
    reference = refracta.trace_ray(field, [0, eye, 0], d, trace="rk45", tol=1e-9, max_length=30000.0)
    assert exact.length == pytest.approx(30000.0, rel=1e-12)  # its whole length, to arc length's round-off
    # Both to 1e-9 m of their own paths; over 30 km rk45's global error adds up to ~1e-8 (measured
    # differences <= 2.4e-8 m; before: 1.3e-3 m, or x = 7.7e130).
    assert np.linalg.norm(exact.points[-1] - reference.points[-1]) < 1e-7
