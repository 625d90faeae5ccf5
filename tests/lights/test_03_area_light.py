"""Emissive triangle meshes: chi-squared of the directions seen from a point (binned through the
light's plane), pdf consistency, one/two-sidedness, irradiance against the polygon formula,
power, and zero-area triangles."""

import numpy as np
import pytest

from refracta.lights import AreaLight

from .conftest import CHI2_SIGNIFICANCE, chi2_test

# sample_li's pdf and pdf_li for the same direction: the same formula on the same numbers.
PDF_CONSISTENCY = 1e-9
# Closed forms in double precision.
EXACT = 1e-12
# Monte Carlo estimates are judged at 4 standard errors (a 6e-5 false-alarm rate).
MC_SIGMAS = 4.0
# Midpoint integration of pdf_li over the light (smooth r^2 / cos factors, 32 x 32 sub-cells).
PDF_INTEGRAL = 1e-4

HEIGHT, HALF = 2.0, 1.0


def square_light(emission=3.0, two_sided=False, centre=(0.3, 0.6)):
    """The square |x|, |z| <= HALF at y = HEIGHT facing down (-y), as a fan of four triangles of
    unequal area around an off-centre point (so the triangle choice by area matters)."""
    corners = [(-HALF, -HALF), (HALF, -HALF), (HALF, HALF), (-HALF, HALF)]
    vertices = [[centre[0], HEIGHT, centre[1]]] + [[x, HEIGHT, z] for x, z in corners]
    triangles = []
    for i in range(4):
        tri = [0, 1 + i, 1 + (i + 1) % 4]
        v = np.array(vertices)[tri]
        if np.cross(v[1] - v[0], v[2] - v[0])[1] > 0:  # make the front face -y
            tri = [tri[0], tri[2], tri[1]]
        triangles.append(tri)
    return AreaLight(vertices, triangles, emission, two_sided=two_sided), np.array(vertices), np.array(triangles)


def plane_hit(point, dirs):
    """(p_light, n_light) where rays from point along dirs meet the square (n = 0 when they miss)."""
    t = (HEIGHT - point[1]) / dirs[:, 1]
    p = point + t[:, None] * dirs
    inside = (t > 0) & (np.abs(p[:, 0]) <= HALF) & (np.abs(p[:, 2]) <= HALF)
    n = np.where(inside[:, None], [0.0, -1.0, 0.0], 0.0)
    return p, n


def polygon_irradiance(point, normal, polygon, radiance):
    """Lambert's polygon formula: E = L/2 |sum_i Theta_i (n . gamma_i)|, Theta_i the angle the edge
    (v_i, v_i+1) subtends at the point, gamma_i the unit normal of the plane through it and the edge."""
    a = polygon - point
    a /= np.linalg.norm(a, axis=1)[:, None]
    total = 0.0
    for i in range(len(a)):
        b, c = a[i], a[(i + 1) % len(a)]
        g = np.cross(b, c)
        total += np.arccos(np.clip(b @ c, -1, 1)) * (normal @ g) / np.linalg.norm(g)
    return 0.5 * radiance * abs(total)


@pytest.mark.parametrize("point", [(0.0, 0.0, 0.0), (0.9, 1.2, -0.4), (3.0, 0.5, 2.0)])
def test_area_light_directions_chi2(rng, point):
    light, _, _ = square_light()
    point = np.array(point)
    count, bins, sub = 100_000, 10, 32
    wi, _, pdf, distance = light.sample_li(np.tile(point, (count, 1)), None, rng.random((count, 2)))
    assert np.all(pdf > 0)
    hit = point + wi * distance[:, None]
    observed, _, _ = np.histogram2d(hit[:, 0], hit[:, 2], bins=bins, range=[[-HALF, HALF], [-HALF, HALF]])
    # Expected: count * integral of pdf_li over each bin's solid angle, dOmega = cos_l dA / r^2.
    g = (np.arange(bins * sub) + 0.5) / (bins * sub) * 2 * HALF - HALF
    X, Z = np.meshgrid(g, g, indexing="ij")
    q = np.stack([X.ravel(), np.full(X.size, HEIGHT), Z.ravel()], axis=1)
    d = q - point
    r = np.linalg.norm(d, axis=1)
    dirs = d / r[:, None]
    p_light, n_light = plane_hit(point, dirs)
    dens = light.pdf_li(np.tile(point, (len(q), 1)), None, dirs, p_light, n_light)
    d_omega = np.abs(dirs[:, 1]) / r**2 * (2 * HALF / (bins * sub)) ** 2
    cell = (dens * d_omega).reshape(bins, sub, bins, sub).sum(axis=(1, 3))
    assert cell.sum() == pytest.approx(1.0, abs=PDF_INTEGRAL)
    _, p_value, _ = chi2_test(observed, cell * count)
    assert p_value > CHI2_SIGNIFICANCE


def test_area_light_pdf_matches_pdf_li(rng):
    light, _, _ = square_light()
    n = 3000
    points = rng.uniform(-3, 3, size=(n, 3)) * [1, 0.5, 1]  # below the light
    wi, L, pdf, distance = light.sample_li(points, None, rng.random((n, 2)))
    ok = pdf > 0
    p_light, n_light = points + wi * distance[:, None], np.tile([0.0, -1.0, 0.0], (n, 1))
    np.testing.assert_allclose(
        light.pdf_li(points[ok], None, wi[ok], p_light[ok], n_light[ok]), pdf[ok], rtol=PDF_CONSISTENCY
    )
    # The normal's orientation does not change the density.
    np.testing.assert_allclose(
        light.pdf_li(points[ok], None, wi[ok], p_light[ok], -n_light[ok]), pdf[ok], rtol=PDF_CONSISTENCY
    )
    np.testing.assert_allclose(L[ok], 3.0)  # default rtol 1e-7: the constant radiance as given, rounding only


def test_one_sided_light_is_dark_from_behind_and_two_sided_is_not(rng):
    one, _, _ = square_light(two_sided=False)
    two, _, _ = square_light(two_sided=True)
    above = np.tile([0.2, 4.0, 0.1], (500, 1))
    u = rng.random((500, 2))
    assert np.all(one.sample_li(above, None, u)[2] == 0)
    _, L, pdf, _ = two.sample_li(above, None, u)
    assert np.all(pdf > 0) and np.allclose(L, 3.0)  # numpy's default 1e-5/1e-8: the constant radiance as given
    down, up = np.array([[0.0, -1.0, 0.0]]), np.array([[0.0, 1.0, 0.0]])
    p = np.array([[0.0, HEIGHT, 0.0]])
    assert one.L(p, down, down)[0, 0] == 3.0 and one.L(p, down, up)[0, 0] == 0.0
    assert two.L(p, down, up)[0, 0] == 3.0
    np.testing.assert_allclose(one.normal(0), [0, -1, 0], atol=EXACT)


@pytest.mark.parametrize(
    "point, normal",
    [
        ((0.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
        ((1.5, 0.3, -0.8), (0.0, 1.0, 0.0)),
        ((0.5, 1.0, 0.5), (0.3 / 1.044030650891055, 1 / 1.044030650891055, 0.0)),
    ],
)
def test_area_light_irradiance_matches_the_polygon_formula(rng, point, normal):
    radiance = 5.0
    light, _, _ = square_light(radiance)
    point, normal = np.array(point), np.array(normal)
    n = 200_000
    wi, L, pdf, _ = light.sample_li(np.tile(point, (n, 1)), np.tile(normal, (n, 1)), rng.random((n, 2)))
    ok = pdf > 0
    values = np.zeros(n)
    values[ok] = L[ok, 0] * np.maximum(wi[ok] @ normal, 0) / pdf[ok]
    estimate, error = values.mean(), values.std() / np.sqrt(n)
    square = np.array([[-HALF, HEIGHT, -HALF], [HALF, HEIGHT, -HALF], [HALF, HEIGHT, HALF], [-HALF, HEIGHT, HALF]])
    exact = polygon_irradiance(point, normal, square, radiance)  # every case sees the whole square
    assert abs(estimate - exact) < MC_SIGMAS * error, (estimate, exact, error)


def test_area_light_power_and_zero_area_triangles(rng):
    light, _, _ = square_light(emission=[1.0, 2.0, 0.5])
    y = 0.2126 * 1.0 + 0.7152 * 2.0 + 0.0722 * 0.5
    assert light.area == pytest.approx(4 * HALF * HALF, rel=EXACT)
    assert light.power == pytest.approx(np.pi * y * 4 * HALF * HALF, rel=EXACT)
    assert square_light(emission=1.0, two_sided=True)[0].power == pytest.approx(2 * np.pi * 4 * HALF**2, rel=EXACT)
    # A degenerate (collinear) triangle has zero weight: never sampled, no NaN.
    vertices = [[0, 1, 0], [1, 1, 0], [0, 1, 1], [2, 1, 0]]
    light = AreaLight(vertices, [[0, 1, 3], [0, 1, 2]], 1.0)
    assert light.area == pytest.approx(0.5, rel=EXACT)
    wi, L, pdf, distance = light.sample_li(np.zeros((2000, 3)), None, rng.random((2000, 2)))
    assert np.all(np.isfinite(wi)) and np.all(np.isfinite(pdf)) and np.all(pdf > 0)
    hit = wi * distance[:, None]
    assert np.all(hit[:, 2] > 0)  # on the triangle with area, off the degenerate one (z = 0)
