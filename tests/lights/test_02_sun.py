"""The sun disc: chi-squared of its cone sampler (uniform and limb-darkened), pdf consistency,
Le inside and outside the disc, the irradiance, and its power through the scene's disc."""

import numpy as np
import pytest

from refracta.lights import SunLight

from .conftest import CHI2_SIGNIFICANCE, cone_chi2

# sample_li's pdf and pdf_li of the same direction: re-measured 1 - cos to ~1e-11 relative.
PDF_CONSISTENCY = 1e-9
# Closed forms in double precision.
EXACT = 1e-12
# cos(theta) varies by 1e-5 over the 0.53 deg disc: a 4000-sample mean of it is within ~1e-7.
SUN_IRRADIANCE_MC = 1e-6
# Limb darkening makes the disc's cosine-weighted mean differ from its mean by ~(1 - cos a)/2.
LIMB_COSINE = 1e-5
# The chi2 quadrature integrates pdf_li over the cone to 1 (sqrt profile at the rim: 16 sub-cells).
PDF_INTEGRAL = 1e-3

DIRECTION = np.array([0.3, 0.8, 0.2]) / np.linalg.norm([0.3, 0.8, 0.2])


@pytest.mark.parametrize("limb", [0.0, 0.6, 1.0])
@pytest.mark.parametrize("diameter", [0.53, 20.0])
def test_sun_cone_sampler_chi2(rng, limb, diameter):
    light = SunLight(DIRECTION, 1000.0, angular_diameter=diameter, limb_darkening=limb)
    cos_max = np.cos(np.radians(diameter / 2))
    p, integral, outside = cone_chi2(light, np.zeros(3), None, DIRECTION, cos_max, 100_000, rng, sub=16)
    assert p > CHI2_SIGNIFICANCE
    assert integral == pytest.approx(1.0, abs=PDF_INTEGRAL)
    assert outside == 0.0


@pytest.mark.parametrize("limb", [0.0, 0.6])
def test_sun_pdf_matches_pdf_li_and_Le_over_pdf_is_radiance_times_solid_angle(rng, limb):
    light = SunLight(DIRECTION, [800.0, 900.0, 1000.0], limb_darkening=limb)
    n = 2000
    points = rng.normal(size=(n, 3))
    wi, L, pdf, distance = light.sample_li(points, None, rng.random((n, 2)))
    assert np.all(pdf > 0) and np.all(np.isinf(distance))
    np.testing.assert_allclose(light.pdf_li(points, None, wi), pdf, rtol=PDF_CONSISTENCY)
    np.testing.assert_allclose(light.Le(wi), L, rtol=PDF_CONSISTENCY)
    omega = 2 * np.pi * (1 - np.cos(np.radians(0.53 / 2)))
    assert light.solid_angle == pytest.approx(omega, rel=EXACT)
    np.testing.assert_allclose(L / pdf[:, None], np.tile([800.0, 900.0, 1000.0], (n, 1)) * omega, rtol=PDF_CONSISTENCY)


def test_sun_Le_is_zero_outside_the_disc_and_limb_darkened_inside():
    axis = np.array([0.0, 1.0, 0.0])
    light = SunLight(axis, 1.0, angular_diameter=2.0, limb_darkening=0.5)
    alpha = np.radians(1.0)
    theta = np.array([0.0, 0.5, 0.9, 1.01, 5.0]) * alpha
    dirs = np.stack([np.sin(theta), np.cos(theta), np.zeros_like(theta)], axis=1)
    t = (1 - np.cos(theta)) / (1 - np.cos(alpha))
    mu = np.sqrt(np.clip(1 - t, 0, None))
    expected = np.where(t <= 1, (1 - 0.5 * (1 - mu)) / (1 - 0.5 / 3), 0.0)
    # The limb-darkening closed form in double on both sides: rounding; EXACT where it is 0.
    np.testing.assert_allclose(light.Le(dirs)[:, 0], expected, rtol=1e-9, atol=EXACT)
    assert np.all(light.pdf_li(np.zeros((5, 3)), None, dirs)[3:] == 0)


@pytest.mark.parametrize("limb", [0.0, 0.6])
def test_sun_irradiance_on_a_facing_surface(rng, limb):
    light = SunLight(DIRECTION, 1.0e3, angular_diameter=0.53, limb_darkening=limb)
    n = 4000
    normals = np.tile(DIRECTION, (n, 1))
    wi, L, pdf, _ = light.sample_li(np.zeros((n, 3)), normals, rng.random((n, 2)))
    estimate = np.mean(L[:, 0] * np.sum(wi * normals, axis=1) / pdf)
    exact = 1.0e3 * np.pi * np.sin(np.radians(0.53 / 2)) ** 2  # integral of cos over the cone
    assert estimate == pytest.approx(exact, rel=SUN_IRRADIANCE_MC if limb == 0 else LIMB_COSINE)
    assert light.irradiance[0] == pytest.approx(exact, rel=EXACT)


def test_sun_power_through_the_scene_disc():
    light = SunLight(DIRECTION, 2.0e3)
    e = 2.0e3 * np.pi * np.sin(np.radians(0.53 / 2)) ** 2
    assert light.power == pytest.approx(np.pi * e, rel=EXACT)  # 1 m before preprocess
    light.preprocess([1, 2, 3], 50.0)
    assert light.power == pytest.approx(np.pi * 50.0**2 * e, rel=EXACT)
    assert light.type == "infinite" and light.is_infinite and not light.is_delta
