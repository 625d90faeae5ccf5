"""Spectral evaluation (wavelengths=): grey reflectances stay grey, a dispersive dielectric refracts
the hero wavelength by its own Snell's law and keeps only it, reflection keeps all four."""

import numpy as np
import pytest

from refracta import shading
from refracta.testing import chi2

from .conftest import direction

LAMBDA = np.array([400.0, 517.5, 635.0, 752.5])  # a hero wavelength and its three rotations [nm]
UPSAMPLING_TOLERANCE = 1e-3  # Jakob-Hanika round trip of in-gamut colours (SHADING.md section 7)


def test_grey_diffuse_is_flat():
    f = shading.Diffuse(0.5).f([0.0, 0.0, 1.0], direction(30.0), wavelengths=LAMBDA)
    assert f.shape == (1, 4)
    np.testing.assert_allclose(f[0], 0.5 / np.pi, atol=UPSAMPLING_TOLERANCE / np.pi)


def test_dispersive_refraction_keeps_the_hero():
    glass = shading.Dielectric("bk7")
    wo = direction(50.0, 0.0)
    s = glass.sample(wo, [0.999, 0.5, 0.5], wavelengths=LAMBDA)
    n = shading.Ior("bk7").at(LAMBDA[0])
    assert s.terminated[0] and s.eta[0] == pytest.approx(n)
    sin_t = np.hypot(s.wi[0, 0], s.wi[0, 1])
    assert sin_t == pytest.approx(np.sin(np.radians(50.0)) / n, rel=1e-12)  # Snell at the hero wavelength
    np.testing.assert_allclose(s.weight[0], [1 / n**2, 0, 0, 0], rtol=1e-12)
    r = glass.sample(wo, [0.0, 0.5, 0.5], wavelengths=LAMBDA)
    assert not r.terminated[0]
    fr = shading.fresnel_dielectric(wo[2], shading.Ior("bk7").at(LAMBDA))
    np.testing.assert_allclose(r.weight[0], fr / fr[0], rtol=1e-12)  # each wavelength's F over the hero's


def test_spectral_rough_conductor_sampling_chi2():
    m = shading.RoughConductor(alpha=0.3, eta=(0.2, 0.9, 1.1), k=(3.9, 2.4, 2.1))
    result = chi2.test_bsdf(m, direction(45.0), samples=100_000, seed=4, wavelengths=LAMBDA)
    assert result.passed, result
