"""The GGX distribution (microfacet.h): normalisation, visible normals, Smith masking."""

import numpy as np
import pytest

from refracta.shading import TrowbridgeReitz
from refracta.testing import chi2

from .conftest import direction, sphere_grid

# Midpoint quadrature over theta (tan substitution-free) at 1500 x 600: lobes with alpha >= 0.1 resolved to 1e-3.
QUADRATURE_TOLERANCE = 2e-3


def hemisphere_quadrature(n_theta=1500, n_phi=600):
    return sphere_grid(n_theta, n_phi, hemisphere=True)


@pytest.mark.parametrize("ax, ay", [(0.1, 0.1), (0.3, 0.3), (0.8, 0.8), (0.1, 0.5), (1.0, 0.25)])
def test_projected_area_of_microfacets_is_one(ax, ay):
    m, w = hemisphere_quadrature()
    d = TrowbridgeReitz(ax, ay)
    assert np.sum(d.D(m) * m[:, 2] * w) == pytest.approx(1.0, abs=QUADRATURE_TOLERANCE)


@pytest.mark.parametrize("ax, ay", [(0.2, 0.2), (0.6, 0.6), (0.15, 0.5)])
@pytest.mark.parametrize("theta", [0.0, 45.0, 80.0])
def test_visible_normal_density_integrates_to_one(ax, ay, theta):
    # int G1(w) max(0, w.m) D(m) / cos theta_w dm = 1 is Smith's G1 definition (Heitz 2014, eq. 17).
    m, w = hemisphere_quadrature()
    d = TrowbridgeReitz(ax, ay)
    wo = direction(theta, 35.0)
    visible = d.D_visible(wo, m) * (m @ wo > 0)
    assert np.sum(visible * w) == pytest.approx(1.0, abs=QUADRATURE_TOLERANCE)


def test_height_correlated_masking_is_bounded_by_g1():
    d = TrowbridgeReitz(0.4, 0.4)
    wo, wi = direction(70.0), direction(50.0, 200.0)
    g, g1o, g1i = d.G(wo, wi)[0], d.G1(wo)[0], d.G1(wi)[0]
    # Heitz 2014: G1(wo) G1(wi) <= G2 <= min(G1(wo), G1(wi)) for uncorrelated heights vs full correlation.
    assert g1o * g1i <= g <= min(g1o, g1i)
    # Exactly 1 at normal incidence in exact arithmetic: rounding.
    assert d.G1(direction(0.0))[0] == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("ax, ay", [(0.3, 0.3), (0.1, 0.4)])
@pytest.mark.parametrize("theta", [5.0, 60.0, 88.0])
def test_visible_normal_sampling_chi2(ax, ay, theta):
    d = TrowbridgeReitz(ax, ay)
    wo = direction(theta, 35.0)
    result = chi2.test_sampler(
        lambda u: (d.sample_wm(wo, u[:, 1:]), np.ones(len(u), bool)),
        lambda m: d.D_visible(wo, m) * (m @ wo > 0) * (m[:, 2] > 0),
        samples=200_000,
        seed=7,
        significance=0.01,
        test_count=6,
    )
    assert result.passed, result
