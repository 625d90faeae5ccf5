"""Emissive spheres: chi-squared of the cone sampler, pdf consistency, the points on the sphere,
on-axis irradiance pi L (r/d)^2, power 4 pi^2 r^2 L, and points inside or on the sphere."""

import numpy as np
import pytest

from refracta.lights import SphereLight

from .conftest import CHI2_SIGNIFICANCE, cone_chi2

# sample_li's pdf and pdf_li: the same constant inside the cone.
PDF_CONSISTENCY = 1e-9
# Points on the sphere: |p - c| = r up to the cone geometry's rounding.
ON_SPHERE = 1e-9
EXACT = 1e-12  # closed forms in double on both sides: rounding
MC_SIGMAS = 4.0  # 4 standard errors: a 6e-5 false-alarm rate
# The pdf is constant in the cone, so the midpoint integral is exact to rounding.
PDF_INTEGRAL = 1e-9

CENTRE, RADIUS = np.array([0.5, 3.0, -1.0]), 0.7


@pytest.mark.parametrize("point", [(0.0, 0.0, 0.0), (0.5, 3.75, -1.0), (0.5, 3.0, 500.0)])
def test_sphere_cone_sampler_chi2(rng, point):
    light = SphereLight(CENTRE, RADIUS, 2.0)
    point = np.array(point)
    to_centre = CENTRE - point
    d = np.linalg.norm(to_centre)
    cos_max = np.sqrt(1 - (RADIUS / d) ** 2)
    p, integral, outside = cone_chi2(light, point, None, to_centre / d, cos_max, 100_000, rng, sub=4)
    assert p > CHI2_SIGNIFICANCE
    assert integral == pytest.approx(1.0, abs=PDF_INTEGRAL)
    assert outside == 0.0


def test_sphere_samples_lie_on_the_visible_cap_and_pdfs_agree(rng):
    light = SphereLight(CENTRE, RADIUS, [1.0, 2.0, 3.0])
    n = 5000
    directions = rng.normal(size=(n, 3))
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    points = CENTRE + directions * rng.uniform(RADIUS * 1.0001, 30 * RADIUS, size=(n, 1))
    wi, L, pdf, distance = light.sample_li(points, None, rng.random((n, 2)))
    assert np.all(pdf > 0)
    hit = points + wi * distance[:, None]
    np.testing.assert_allclose(np.linalg.norm(hit - CENTRE, axis=1), RADIUS, rtol=ON_SPHERE)
    outward = (hit - CENTRE) / RADIUS
    assert np.all(np.sum(outward * -wi, axis=1) > -1e-9)  # on the side facing the point
    np.testing.assert_allclose(light.pdf_li(points, None, wi, hit, outward), pdf, rtol=PDF_CONSISTENCY)
    np.testing.assert_allclose(L, np.tile([1.0, 2.0, 3.0], (n, 1)))  # default rtol 1e-7: the constant radiance as given
    np.testing.assert_allclose(light.L(hit, outward, -wi), L)  # default rtol 1e-7: the same radiance by two calls
    assert np.all(light.L(hit, outward, wi)[np.sum(outward * wi, axis=1) < 0] == 0)


@pytest.mark.parametrize("distance", [1.2, 4.0, 1000.0])
def test_sphere_irradiance_on_axis_is_pi_L_r2_over_d2(rng, distance):
    radiance = 3.0
    light = SphereLight([0.0, distance, 0.0], RADIUS, radiance)
    n = 100_000
    normals = np.tile([0.0, 1.0, 0.0], (n, 1))
    wi, L, pdf, _ = light.sample_li(np.zeros((n, 3)), normals, rng.random((n, 2)))
    values = L[:, 0] * wi[:, 1] / pdf
    estimate, error = values.mean(), values.std() / np.sqrt(n)
    exact = np.pi * radiance * (RADIUS / distance) ** 2
    assert abs(estimate - exact) <= MC_SIGMAS * error + EXACT * exact, (estimate, exact, error)


def test_sphere_power_and_points_inside(rng):
    light = SphereLight(CENTRE, RADIUS, [1.0, 1.0, 1.0])
    assert light.power == pytest.approx(4 * np.pi**2 * RADIUS**2, rel=EXACT)
    assert light.type == "area"
    # Inside, or exactly on the surface: the outward emission never reaches the point; no NaN.
    inside = np.vstack([CENTRE + [0.1, 0.2, 0.0], CENTRE + [RADIUS, 0, 0], CENTRE])
    wi, L, pdf, distance = light.sample_li(inside, None, rng.random((3, 2)))
    assert np.all(pdf == 0) and np.all(np.isfinite(wi)) and np.all(L == 0)


def test_a_point_on_the_surface_a_rounding_outside_samples_from_inside(rng):
    # The inner wall of a sphere light: a hit point there may lie a rounding (~1e-16 relative)
    # outside, where the cone toward the sphere is the whole hemisphere and every sample lands right
    # under the point, lit (a trial: the inside of an emissive sphere was lit by the sphere).
    light = SphereLight(CENTRE, RADIUS, [1.0, 1.0, 1.0])
    on_surface = np.tile(CENTRE + [RADIUS * (1 + 1e-15), 0.0, 0.0], (64, 1))
    _, L, _, _ = light.sample_li(on_surface, np.tile([-1.0, 0.0, 0.0], (64, 1)), rng.random((64, 2)))
    assert np.all(L == 0)
    # A point clearly outside (1e-6 of the radius, above the 1e-9 tolerance) is lit as before.
    near = np.tile(CENTRE + [RADIUS * (1 + 1e-6), 0.0, 0.0], (64, 1))
    _, L, pdf, _ = light.sample_li(near, np.tile([-1.0, 0.0, 0.0], (64, 1)), rng.random((64, 2)))
    assert np.all(L[:, 0] == 1.0) and np.all(pdf > 0)


def test_the_inside_of_an_emissive_sphere_is_dark():
    # Its emission goes outward only (as a box light's): nothing reaches its inner wall, directly
    # or after bounces (it was 0.013 at max_depth 1, 0.024 in 'path' at depth 5).
    import refracta
    from refracta import shading

    scene = refracta.Scene()
    scene.add_sphere((0.0, 0.0, 0.0), 2.0, material=shading.Diffuse(0.5), emission=1.0)
    camera = refracta.Camera((0.0, 0.0, 0.0), (1.0, 0.2, 0.3), vfov=60, width=16, height=16)
    for transport, depth in (("direct", 1), ("path", 5)):
        image = refracta.render(scene, camera, None, spp=4, max_depth=depth, transport=transport, progress=False)
        assert np.all(image == 0.0), transport
