"""The light sampler: picks in proportion to power (or uniformly), probabilities consistent."""

import pickle

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


def test_kind_sampler_gives_each_infinite_light_the_share_of_all_bounded_ones(rng):
    # 'kind' (the path tracer's choice): the sun and the sky (2 infinite lights of some power) and
    # the three bounded lights as one kind: each infinite light is as likely as the three together,
    # 1/3 of the choices for the bounded kind and 2/3 for the infinite, by power within each kind.
    ls = lights()
    sampler = LightSampler(ls, strategy="kind")
    power = np.array([light.power for light in ls])
    bounded, infinite = power[:3], power[3:]
    expected = np.concatenate([bounded / bounded.sum() / 3.0, infinite / infinite.sum() * 2.0 / 3.0])
    # Shares and powers in double on both sides: rounding.
    np.testing.assert_allclose([sampler.pmf(i) for i in range(len(ls))], expected, rtol=1e-12)
    index, probability = sampler.sample(rng.random(100_000))
    np.testing.assert_allclose(probability, expected[index], rtol=EXACT)
    assert stats.chisquare(np.bincount(index, minlength=len(ls)), expected * len(index)).pvalue > CHI2_SIGNIFICANCE
    # One kind alone: by power, as 'power' chooses.
    only_bounded = LightSampler(ls[:3], strategy="kind")
    # Power / total in double on both sides: rounding.
    np.testing.assert_allclose([only_bounded.pmf(i) for i in range(3)], bounded / bounded.sum(), rtol=1e-12)
    copy = pickle.loads(pickle.dumps(sampler))  # keeps its strategy
    assert [copy.pmf(i) for i in range(len(ls))] == [sampler.pmf(i) for i in range(len(ls))]
    with pytest.raises(ValueError, match="strategy must be 'power', 'uniform' or 'kind'"):
        LightSampler(ls, strategy="bvh")
