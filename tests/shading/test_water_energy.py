"""Energy of the Water material (white furnace): the albedo int f |cos theta_i| d wi, estimated by the
mean sample() weight in importance transport (no (eta_i / eta_t)^2 radiance scaling), never exceeds
1: reflection + transmission <= 1 for the bare interface, reflection + the water body's return <= 1
over deep water; the body returns exactly its closed-form albedo
T(cos_o) R (1 - Fbar_int) / (1 - R Fbar_int), T the rough interface's tabulated transmittance,
which is the bare interface's own."""

import numpy as np
import pytest

from refracta import shading

from .conftest import direction, sphere_grid

SAMPLES = 100_000
NOISE_SIGMAS = 5.0  # bound on a Monte Carlo mean: 5 standard errors
THETAS = [0.0, 30.0, 60.0, 80.0, 89.0]
WINDS = [0.0, 5.0, 15.0, 30.0]
SPECTRAL = np.array([450.0, 500.0, 550.0, 600.0])  # [nm] integer wavelengths: the 1 nm tables are exact there
# Midpoint quadrature of the body's smooth (transmittance-weighted cosine) lobe over 400 x 800 cells,
# against the table's trapezoidal 2 int T mu dmu (measured 1.1e-4 relative).
QUADRATURE_TOLERANCE = 3e-4
TRANSMITTANCE_TOLERANCE = 2e-3  # the table's quadrature and interpolation (see test_03b)


def albedo(material, wo, wavelengths=None, seed=5):
    u = np.random.default_rng(seed).random((SAMPLES, 3))
    s = material.sample(np.tile(wo, (SAMPLES, 1)), u, mode="importance", wavelengths=wavelengths)
    w = s.weight
    return w.mean(0), w.std(0) / np.sqrt(SAMPLES), s


@pytest.mark.parametrize("wind", WINDS)
@pytest.mark.parametrize("body", [True, False])
def test_01_white_furnace_at_most_one(wind, body):
    water = shading.Water(wind, body=body)
    for theta in THETAS:
        for below in (False, True):
            for wavelengths in (None, SPECTRAL):
                mean, err, _ = albedo(water, direction(theta, below=below), wavelengths)
                assert np.all(mean <= 1.0 + NOISE_SIGMAS * err + 1e-12), (theta, below, mean, err)


@pytest.mark.parametrize("wind", [0.0, 5.0])
def test_02_interface_reflects_and_transmits_nearly_everything_in_light_wind(wind):
    # Single-scattering microfacets lose only what masking hides: at alpha <= 0.17 and incidence up
    # to 60 degrees that is below 1 % (measured 0.99998 at normal incidence, 0.9963 at 60 degrees, 5 m/s).
    water = shading.Water(wind, body=False)
    for theta in (0.0, 30.0, 60.0):
        mean, err, s = albedo(water, direction(theta))
        assert mean[1] > 0.99 - NOISE_SIGMAS * err[1]
        transmitted = (s.flags & 2) > 0
        reflected = s.weight[~transmitted & s.valid, 1].sum() / SAMPLES
        flat = shading.fresnel_dielectric(np.cos(np.radians(theta)), water.ior(550.0))
        assert reflected == pytest.approx(flat, abs=0.2 * flat + NOISE_SIGMAS * err[1])  # the flat surface's F, roughly


def test_03_body_returns_its_closed_form_albedo():
    # Water(body=True) - Water(body=False) on reflection pairs is the body term; its hemispherical
    # integral is T(cos_o) R (1 - Fbar_int) / (1 - R Fbar_int) per wavelength, T the rough interface's
    # transmittance and Fbar_int = 1 - 2 int T mu dmu / eta^2 its internal diffuse reflectance.
    deep, bare = shading.Water(5.0), shading.Water(5.0, body=False)
    d, w = sphere_grid(400, 800, hemisphere=True)
    r = shading.water_body_reflectance(SPECTRAL, deep.salinity)
    fdr = np.array([deep.internal_reflectance(x) for x in SPECTRAL])
    for theta in (0.0, 50.0, 85.0):
        wo = direction(theta)
        body = deep.f(wo, d, wavelengths=SPECTRAL) - bare.f(wo, d, wavelengths=SPECTRAL)
        integral = np.sum(body * (d[:, 2] * w)[:, None], 0)
        t = np.array([deep.transmittance(wo[2], x) for x in SPECTRAL])
        np.testing.assert_allclose(integral, t * r * (1 - fdr) / (1 - r * fdr), rtol=QUADRATURE_TOLERANCE)


@pytest.mark.parametrize("wind", [0.0, 5.0, 15.0])
def test_03b_tabulated_transmittance_is_the_interface_s(wind):
    # The body's T(mu) against the bare interface's own transmission albedo (its sampler, importance
    # transport): the 64 x 64 quadrature per node and the interpolation in sqrt(mu) and eta keep it
    # within TRANSMITTANCE_TOLERANCE of the Monte Carlo mean (measured worst 0.4 %, near mu = 0.02).
    bare = shading.Water(wind, body=False)
    for mu in (1.0, 0.5, 0.1, 0.02):
        wo = np.array([np.sqrt(1 - mu * mu), 0.0, mu])
        mean, err, s = albedo(bare, wo)
        transmitted = np.where((s.flags & 2) > 0, s.weight[:, 1], 0.0)
        estimate, noise = transmitted.mean(), transmitted.std() / np.sqrt(SAMPLES)
        assert bare.transmittance(mu, 532.0) == pytest.approx(
            estimate, abs=NOISE_SIGMAS * noise + TRANSMITTANCE_TOLERANCE
        )
    # A calm sea's (alpha = 0.055) is nearly the flat surface's 1 - F away from grazing (measured
    # 1.4e-4 apart at mu = 0.8), its internal reflectance nearly the flat one's (6.1e-4 apart).
    calm = shading.Water(0.0)
    n = calm.ior(550.0)
    # 1.4e-4 measured (comment above).
    assert calm.transmittance(0.8) == pytest.approx(1 - shading.fresnel_dielectric(0.8, n), abs=1e-3)
    # 6.1e-4 measured (comment above).
    assert calm.internal_reflectance() == pytest.approx(shading.fresnel_diffuse_reflectance(1 / n), abs=2e-3)


def test_04_deep_water_transmits_nothing():
    # body=True: reflection only, from either side (the material bounds no medium).
    water = shading.Water()
    for theta in THETAS:
        for below in (False, True):
            _, _, s = albedo(water, direction(theta, below=below))
            assert not np.any(s.flags[s.valid] & 2)
            wi = s.wi[s.valid]
            assert np.all(np.sign(wi[:, 2]) == (-1 if below else 1))
    assert water.interior_ior() is None
    # The body's index at 550 nm, 20 C, 35 psu from the same formula: rounding.
    assert shading.Water(body=False).interior_ior() == pytest.approx(shading.water_ior(550.0, 20.0, 35.0), abs=1e-8)
