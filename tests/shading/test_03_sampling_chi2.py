"""Chi-square goodness of fit of every material's sample() against its pdf() (refracta.testing.chi2),
several wo including grazing and from inside for dielectrics; and the chi-square tester itself."""

import math

import numpy as np
import pytest

from refracta.testing import chi2

from .conftest import direction
from .materials import MATERIALS, SAMPLED

ANGLES = [10.0, 60.0, 85.0]
CASES = [
    (name, theta, below)
    for name in SAMPLED
    for theta in ANGLES
    for below in ((False, True) if MATERIALS[name][1] else (False,))
]
SIGNIFICANCE = 0.01  # family-wise, Sidak-corrected over every case below
SAMPLES = 200_000


@pytest.mark.parametrize("name, theta, below", CASES)
def test_sampling_matches_pdf(name, theta, below):
    material = MATERIALS[name][0]()
    result = chi2.test_bsdf(
        material,
        direction(theta, 30.0, below),
        samples=SAMPLES,
        seed=11,
        significance=SIGNIFICANCE,
        test_count=len(CASES),
    )
    assert result.passed, (result, result.message)
    # The density's integral matches the fraction of directions produced (binomial noise, 5 sigma + quadrature).
    noise = 5 * math.sqrt(result.produced * (1 - result.produced) / SAMPLES) + 2e-3
    assert result.pdf_integral == pytest.approx(result.produced, abs=noise)


def test_chi2_survival_closed_forms():
    # dof = 2: Q = exp(-x/2); dof = 1: erfc(sqrt(x/2)); dof = 4: (1 + x/2) exp(-x/2).
    for x in (0.1, 1.0, 7.0, 40.0, 300.0):
        # The series and continued fraction stop at 1e-14 (_GAMMA_EPS): 1e-12 leaves 100x.
        assert chi2.chi2_survival(x, 2) == pytest.approx(math.exp(-x / 2), rel=1e-12)
        # As above, with math.erfc's own accuracy and lgamma(1/2) in the prefactor.
        assert chi2.chi2_survival(x, 1) == pytest.approx(math.erfc(math.sqrt(x / 2)), rel=1e-10)
        assert chi2.chi2_survival(x, 4) == pytest.approx((1 + x / 2) * math.exp(-x / 2), rel=1e-12)  # as above
    # Large dof: the mean dof has Q near 1/2 (Wilson-Hilferty: median = dof (1 - 2/(9 dof))^3).
    dof = 1000
    # Wilson-Hilferty's median is approximate: O(1/dof) = 1e-3.
    assert chi2.chi2_survival(dof * (1 - 2 / (9 * dof)) ** 3, dof) == pytest.approx(0.5, abs=1e-3)


def test_chi2_detects_a_wrong_pdf():
    from refracta.shading import Diffuse

    material = Diffuse(0.5)

    class WrongPdf:  # uniform-hemisphere density claimed for a cosine sampler
        def sample(self, wo, u, **kw):
            return material.sample(wo, u, **kw)

        def pdf(self, wo, wi, **kw):
            return (np.asarray(wi)[:, 2] > 0) / (2 * np.pi)

    result = chi2.test_bsdf(WrongPdf(), [0.0, 0.0, 1.0], samples=50_000, seed=1)
    # A wrong pdf fails decisively at 50 000 samples (a right one: p ~ U(0, 1)).
    assert not result.passed and result.p_value < 1e-10


def test_chi2_integrates_a_lobe_narrower_than_its_cells():
    from refracta.shading import Principled

    # The default clearcoat's GTR1 lobe (alpha 0.001) is ~1/60 of a 3.75 deg cell: 6 x 6 fixed
    # nodes missed it (pdf integral 0.980 against 0.966 produced, p = 3e-263, a new user's trial);
    # the adaptive cells integrate it.
    result = chi2.test_bsdf(Principled((0.5, 0.5, 0.5), clearcoat=1.0), [0.6, 0.0, 0.8], samples=SAMPLES, seed=2)
    assert result.passed, (result, result.message)
    # As test_sampling_matches_pdf: binomial noise of the produced fraction, 5 sigma, + quadrature.
    noise = 5 * math.sqrt(result.produced * (1 - result.produced) / SAMPLES) + 2e-3
    assert result.pdf_integral == pytest.approx(result.produced, abs=noise)


@pytest.mark.parametrize("half_angle", [20.3, 47.0, 80.1])
def test_chi2_integrates_a_density_with_a_rim(half_angle):
    # A uniform cone, sampled exactly: its rim crosses cells, where 6 x 6 nodes (and a first
    # adaptive version, which compared two orders that agree by chance at a step) left the
    # integral 0.5 % off and failed it at p = 2e-99 (a review).
    cos_a = math.cos(math.radians(half_angle))

    def sample(u):
        z = 1 - u[:, 0] * (1 - cos_a)
        s, phi = np.sqrt(1 - z * z), 2 * np.pi * u[:, 1]
        return np.stack([s * np.cos(phi), s * np.sin(phi), z], 1), np.ones(len(u), bool)

    def pdf(d):
        return np.where(d[:, 2] > cos_a, 1 / (2 * np.pi * (1 - cos_a)), 0.0)

    result = chi2.test_sampler(sample, pdf, samples=SAMPLES, seed=3, significance=SIGNIFICANCE, test_count=3)
    assert result.passed, (result, result.message)
    # The density integrates to 1: the cells' allowances left it within 2e-4 at eight half-angles
    # from 10 to 80 deg (measured); 1e-3 is 5x that.
    assert result.pdf_integral == pytest.approx(1.0, abs=1e-3)


def test_sidak_correction_and_arguments():
    from refracta.shading import Diffuse

    r = chi2.test_bsdf(Diffuse(0.5), [0.0, 0.0, 1.0], samples=20_000, seed=2, significance=0.05, test_count=10)
    assert r.significance == pytest.approx(1 - 0.95**0.1)  # default rel 1e-6: Sidak's closed form in double
    with pytest.raises(ValueError, match="wo"):
        chi2.test_bsdf(Diffuse(0.5), [0.0, 0.0, 2.0])
    with pytest.raises(ValueError, match="significance"):
        chi2.test_bsdf(Diffuse(0.5), [0.0, 0.0, 1.0], significance=1.5)
