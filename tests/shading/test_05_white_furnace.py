"""White furnace: the albedo int f |cos theta_i| d wi, estimated by the mean sample() weight, is
<= 1 for energy-conserving materials, 1 for lossless ones, falls with roughness for a GGX mirror
(single scattering, Kulla & Conty 2017), and agrees with a quadrature of f |cos|."""

import numpy as np
import pytest

from refracta import shading

from .conftest import direction, sphere_grid
from .materials import MATERIALS

SAMPLES = 100_000
NOISE_SIGMAS = 5  # bound on the Monte Carlo mean: 5 standard errors
# Midpoint quadrature at 600 x 1200 of lobes with alpha >= 0.1.
QUADRATURE_TOLERANCE = 3e-3
THETAS = [0.0, 30.0, 60.0, 80.0, 89.0]

# Burley 2012 is not energy conserving (the retro-reflective F_D90 and the additive sheen and
# clearcoat exceed 1 at grazing: 1.09 at 89 degrees for the "principled" test material, and its
# diffuse and specular lobes are not coupled: base 0.9, roughness 0.3 gives 1.11 at 80 degrees), and the
# (ns + 8)/(8 pi) Blinn-Phong normalisation is approximate (kd + ks = 1 reaches 1.04 at normal
# incidence); these two are checked with parameters inside their energy-conserving range.
CONSERVING = [n for n in MATERIALS if n != "principled"]
EXTRA = {
    "principled_no_sheen": lambda: shading.Principled((0.5, 0.5, 0.5), roughness=0.3),
    "plastic_white": lambda: shading.Plastic(1.0),
    "rough_plastic_white": lambda: shading.Plastic(1.0, alpha=0.3),
}


def albedo(material, wo, mode="importance", seed=5):
    u = np.random.default_rng(seed).random((SAMPLES, 3))
    w = material.sample(np.tile(wo, (SAMPLES, 1)), u, mode=mode).weight
    return w.mean(0), w.std(0) / np.sqrt(SAMPLES)


@pytest.mark.parametrize("name", CONSERVING + list(EXTRA))
def test_albedo_is_at_most_one(name):
    make = EXTRA.get(name) or MATERIALS[name][0]
    material = make()
    for theta in THETAS:
        mean, err = albedo(material, direction(theta))
        assert np.all(mean <= 1.0 + NOISE_SIGMAS * err + 1e-12), (theta, mean, err)


@pytest.mark.parametrize(
    "make",
    [
        lambda: shading.Diffuse(1.0),
        lambda: shading.Conductor(),
        lambda: shading.Dielectric(1.5),
        lambda: shading.ThinDielectric(1.5),
        lambda: shading.Plastic(1.0),
    ],
)
def test_lossless_materials_return_everything(make):
    material = make()
    for theta in THETAS:
        for below in (False, True):
            mean, err = albedo(material, direction(theta, below=below))
            # NOISE_SIGMAS standard errors; 1e-12 for zero-variance (delta) lobes.
            assert mean == pytest.approx(np.ones(3), abs=NOISE_SIGMAS * err.max() + 1e-12)


def test_smooth_dielectric_radiance_weights():
    # Radiance mode: reflections weigh 1, refractions (eta_i / eta_t)^2, so the mean is R + T / eta'^2.
    eta = 1.5
    for theta in (0.0, 40.0, 70.0):
        wo = direction(theta)
        mean, err = albedo(shading.Dielectric(eta), wo, mode="radiance")
        r = shading.fresnel_dielectric(wo[2], eta)
        assert mean[0] == pytest.approx(r + (1 - r) / eta**2, abs=NOISE_SIGMAS * err[0] + 1e-12)  # as above


def test_rough_mirror_loses_energy_with_roughness():
    for theta in (0.0, 60.0):
        values = [albedo(shading.RoughConductor(alpha=a), direction(theta))[0][0] for a in (0.05, 0.2, 0.5, 1.0)]
        # A near-mirror (alpha 0.05) conductor of reflectance 1 loses < 1 % to multiple scattering.
        assert values[0] > 0.99
        assert all(a > b for a, b in zip(values, values[1:])), values


@pytest.mark.parametrize(
    "name",
    [
        "diffuse",
        "blinn_phong",
        "rough_conductor",
        "rough_conductor_aniso",
        "rough_dielectric",
        "rough_plastic",
        "principled",
        "thin_film",
    ],
)
def test_albedo_matches_quadrature_of_f_cos(name):
    material = MATERIALS[name][0]()
    d, w = sphere_grid(600, 1200)
    for theta in (10.0, 70.0):
        wo = direction(theta, 25.0)
        quadrature = np.sum(material.f(wo, d, mode="importance") * np.abs(d[:, 2:3]) * w[:, None], axis=0)
        mean, err = albedo(material, wo)
        np.testing.assert_allclose(mean, quadrature, atol=NOISE_SIGMAS * err.max() + QUADRATURE_TOLERANCE)


def test_blinn_phong_normal_incidence_albedo_closed_form():
    # wo = n: h is halfway, cos theta_h = cos(theta_i / 2); 1-D quadrature of the specular lobe.
    ns = 1.0
    t = (np.arange(200_000) + 0.5) * (np.pi / 2) / 200_000
    lobe = (
        np.sum((ns + 8) / (8 * np.pi) * np.cos(t / 2) ** ns * np.cos(t) * np.sin(t)) * 2 * np.pi * (np.pi / 2) / 200_000
    )
    mean, err = albedo(shading.BlinnPhong(0.0, 1.0, ns), direction(0.0))
    assert mean[0] == pytest.approx(lobe, abs=NOISE_SIGMAS * err[0])
    assert lobe > 1.0  # the approximate normalisation: measured 1.022
