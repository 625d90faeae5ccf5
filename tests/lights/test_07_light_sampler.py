"""The light sampler: picks in proportion to power (or uniformly), probabilities consistent."""

import numpy as np
import pytest
from scipy import stats

from refracta.lights import AreaLight, ConstantEnvironment, LightSampler, PointLight, SphereLight, SunLight

from .conftest import CHI2_SIGNIFICANCE

EXACT = 1e-12  # closed forms in double on both sides: rounding


def lights():
    sun = SunLight([0, 1, 0], 1.0e4)
    sun.preprocess([0, 0, 0], 10.0)
    sky = ConstantEnvironment(0.1)
    sky.preprocess([0, 0, 0], 10.0)
    return [
        PointLight([0, 3, 0], 10.0),
        SphereLight([1, 2, 0], 0.5, 4.0),
        AreaLight([[0, 1, 0], [1, 1, 0], [0, 1, 1]], [[0, 1, 2]], 7.0),
        sun,
        sky,
    ]


def test_sampler_picks_in_proportion_to_power(rng):
    ls = lights()
    sampler = LightSampler(ls)
    power = np.array([light.power for light in ls])
    expected = power / power.sum()
    # Power / total in double on both sides: rounding.
    np.testing.assert_allclose([sampler.pmf(i) for i in range(len(ls))], expected, rtol=1e-12)
    index, probability = sampler.sample(rng.random(100_000))
    np.testing.assert_allclose(probability, expected[index], rtol=EXACT)
    counts = np.bincount(index, minlength=len(ls))
    assert stats.chisquare(counts, expected * len(index)).pvalue > CHI2_SIGNIFICANCE
    assert len(sampler) == len(ls)
    with pytest.raises(ValueError, match=r"LightSampler.pmf: index must be in \[0, 5\) \(got 5\)"):
        sampler.pmf(len(ls))  # no light there (it was 0: a typo in an index looked like a dark light)


def test_uniform_sampler_and_zero_power_lights(rng):
    ls = lights()
    sampler = LightSampler(ls, strategy="uniform")
    index, probability = sampler.sample(rng.random(50_000))
    np.testing.assert_allclose(probability, 1 / len(ls), rtol=EXACT)
    assert stats.chisquare(np.bincount(index, minlength=len(ls))).pvalue > CHI2_SIGNIFICANCE
    # A black light is never chosen by power; all black falls back to uniform.
    mixed = LightSampler([PointLight([0, 0, 0], 0.0), PointLight([0, 0, 0], 1.0)])
    assert mixed.pmf(0) == 0.0 and mixed.pmf(1) == 1.0
    assert np.all(mixed.sample(rng.random(1000))[0] == 1)
    black = LightSampler([PointLight([0, 0, 0], 0.0), PointLight([0, 0, 0], 0.0)])
    assert black.pmf(0) == pytest.approx(0.5)  # default rel 1e-6: 0.5 exactly (uniform over two dark lights)
