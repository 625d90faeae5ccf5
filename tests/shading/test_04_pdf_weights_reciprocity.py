"""sample() against f() and pdf(); the pdf's integral; reciprocity of reflection; the eta^2
relation of transmission (SHADING.md sections 0, 2, 9)."""

import numpy as np
import pytest

from refracta import shading

from .conftest import direction, sphere_grid
from .materials import MATERIALS, SAMPLED

# Values recomputed from the same double-precision formulas in another order.
EVAL_TOLERANCE = 1e-9
# Midpoint quadrature over the sphere at 600 x 1200 for lobes with alpha >= 0.1.
QUADRATURE_TOLERANCE = 3e-3

rng = np.random.default_rng(2024)


@pytest.mark.parametrize("name", SAMPLED)
@pytest.mark.parametrize("theta", [20.0, 75.0])
def test_sample_weight_is_f_cos_over_pdf(name, theta):
    material = MATERIALS[name][0]()
    below = MATERIALS[name][1] and theta > 50
    wo = direction(theta, 40.0, below)
    s = material.sample(np.tile(wo, (4000, 1)), rng.random((4000, 3)))
    ok = s.valid & ~s.is_delta
    assert ok.mean() > 0.3  # smooth plastic at grazing picks its delta lobe about half the time
    wi = s.wi[ok]
    f, pdf = material.f(wo, wi), material.pdf(wo, wi)
    np.testing.assert_allclose(s.pdf[ok], pdf, rtol=EVAL_TOLERANCE)
    # EVAL_TOLERANCE; 1e-300 only so that exact zeros compare.
    np.testing.assert_allclose(s.f[ok], f, rtol=EVAL_TOLERANCE, atol=1e-300)
    np.testing.assert_allclose(s.weight[ok], f * np.abs(wi[:, 2:3]) / pdf[:, None], rtol=EVAL_TOLERANCE)


@pytest.mark.parametrize("name", SAMPLED)
def test_pdf_integrates_to_at_most_one(name):
    material = MATERIALS[name][0]()
    d, w = sphere_grid(600, 1200)
    for theta in (0.0, 45.0, 80.0):
        integral = np.sum(material.pdf(direction(theta, 10.0), d) * w)
        assert integral <= 1.0 + QUADRATURE_TOLERANCE
        assert integral > 0.1  # the smooth plastic spends most samples on its delta lobe at grazing


@pytest.mark.parametrize("name", ["diffuse"])
def test_cosine_pdf_integrates_to_one(name):
    d, w = sphere_grid(600, 1200)
    assert np.sum(MATERIALS[name][0]().pdf(direction(30.0), d) * w) == pytest.approx(1.0, abs=QUADRATURE_TOLERANCE)


REFLECTIVE = [n for n in SAMPLED if not MATERIALS[n][1]] + ["rough_dielectric", "rough_dielectric_aniso"]


@pytest.mark.parametrize("name", REFLECTIVE)
def test_reflection_is_reciprocal(name):
    material = MATERIALS[name][0]()
    a = rng.normal(size=(500, 3))
    b = rng.normal(size=(500, 3))
    a[:, 2], b[:, 2] = np.abs(a[:, 2]) + 0.05, np.abs(b[:, 2]) + 0.05
    a /= np.linalg.norm(a, axis=1, keepdims=True)
    b /= np.linalg.norm(b, axis=1, keepdims=True)
    # Reciprocity is exact algebra: double rounding; 1e-300 lets zeros compare.
    np.testing.assert_allclose(material.f(a, b), material.f(b, a), rtol=1e-10, atol=1e-300)


@pytest.mark.parametrize("ior", [1.5, 1.33])
def test_transmission_eta_squared_relation(ior):
    # Radiance mode, eta_o and eta_i the indices on the sides of wo and wi:
    #   f(wo, wi) / eta_o^2 = f(wi, wo) / eta_i^2          (Veach 1997, eq. 5.14 for radiance)
    # and the adjoint: f_importance(wo, wi) = f_radiance(wi, wo).
    material = shading.RoughDielectric(alpha=0.4, ior=ior)
    up = rng.normal(size=(500, 3))
    up[:, 2] = np.abs(up[:, 2]) + 0.05
    up /= np.linalg.norm(up, axis=1, keepdims=True)
    down = rng.normal(size=(500, 3))
    down[:, 2] = -np.abs(down[:, 2]) - 0.05
    down /= np.linalg.norm(down, axis=1, keepdims=True)
    f_ud, f_du = material.f(up, down)[:, 0], material.f(down, up)[:, 0]
    assert np.count_nonzero(f_ud) > 50
    # As above (the 1/eta^2 radiance scaling is exact algebra).
    np.testing.assert_allclose(f_ud / 1.0**2, f_du / ior**2, rtol=1e-10, atol=1e-300)
    # As above.
    np.testing.assert_allclose(material.f(up, down, mode="importance"), material.f(down, up), rtol=1e-10, atol=1e-300)
