"""The constant environment: chi-squared of its uniform and cosine samplers, pdf consistency,
irradiance pi L, power 4 pi^2 R^2 L."""

import numpy as np
import pytest

from refracta.lights import ConstantEnvironment

from .conftest import CHI2_SIGNIFICANCE, cone_chi2

PDF_CONSISTENCY = 1e-9  # sample_li's pdf and pdf_li of the same direction: the same formula on the same numbers
EXACT = 1e-12  # closed forms in double on both sides: rounding
MC_SIGMAS = 4.0  # 4 standard errors: a 6e-5 false-alarm rate
# Midpoint rule of a smooth (cosine) or constant density over 10 x 12 bins, 8 x 8 sub-cells.
PDF_INTEGRAL = 1e-3


def test_uniform_sphere_sampler_chi2(rng):
    light = ConstantEnvironment(1.0, sampling="uniform")
    normal = np.array([0.0, 1.0, 0.0])
    p, integral, outside = cone_chi2(light, np.zeros(3), normal, [0.2, 0.3, 0.9], -1.0, 100_000, rng, sub=8)
    assert p > CHI2_SIGNIFICANCE and integral == pytest.approx(1.0, abs=PDF_INTEGRAL) and outside == 0


def test_cosine_sampler_chi2(rng):
    light = ConstantEnvironment(1.0)
    normal = np.array([0.0, 0.6, 0.8])
    p, integral, outside = cone_chi2(light, np.zeros(3), normal, normal, 0.0, 100_000, rng, sub=8)
    assert p > CHI2_SIGNIFICANCE and integral == pytest.approx(1.0, abs=PDF_INTEGRAL) and outside == 0
    # Without a normal it falls back to the uniform sphere.
    wi, _, pdf, _ = light.sample_li(np.zeros((1000, 3)), None, rng.random((1000, 2)))
    np.testing.assert_allclose(pdf, 1 / (4 * np.pi), rtol=EXACT)
    assert np.mean(wi[:, 1] < 0) == pytest.approx(0.5, abs=0.06)  # 4 sigma of a binomial(1000, 1/2)


@pytest.mark.parametrize("sampling", ["cosine", "uniform"])
def test_constant_environment_irradiance_is_pi_L(rng, sampling):
    radiance = [0.5, 1.0, 2.0]
    light = ConstantEnvironment(radiance, sampling=sampling)
    n = 100_000
    normal = np.array([0.48, 0.6, 0.64])
    wi, L, pdf, _ = light.sample_li(np.zeros((n, 3)), np.tile(normal, (n, 1)), rng.random((n, 2)))
    np.testing.assert_allclose(light.pdf_li(np.zeros((n, 3)), np.tile(normal, (n, 1)), wi), pdf, rtol=PDF_CONSISTENCY)
    values = L * np.maximum(wi @ normal, 0)[:, None] / pdf[:, None]
    estimate, error = values.mean(axis=0), values.std(axis=0) / np.sqrt(n)
    exact = np.pi * np.array(radiance)
    assert np.all(np.abs(estimate - exact) <= MC_SIGMAS * error + 1e-9 * exact), (estimate, exact, error)
    # Default rtol 1e-7: the constant radiance as given.
    np.testing.assert_allclose(light.Le(wi[:5]), np.tile(radiance, (5, 1)))


def test_constant_environment_power():
    light = ConstantEnvironment(2.0)
    light.preprocess([0, 0, 0], 4.0)
    assert light.power == pytest.approx(4 * np.pi**2 * 16.0 * 2.0, rel=EXACT)
