"""Chi-square goodness-of-fit test of a direction sampler against its density over the sphere.

The idea of Mitsuba 3's ``chi2.py`` (and pbrt-v4's ``bsdfs_test.cpp``): draw many directions,
histogram them in (theta, phi) cells (uniform in the polar angle theta, so that lobes peaked at
the poles, e.g. refraction near the normal, still span several cells), integrate the claimed
density over every cell numerically (Gauss-Legendre in theta and phi, d omega = sin theta d theta
d phi),
compare counts with Pearson's statistic after pooling cells whose expected count is below
``min_expected``, and turn it into a p-value with the chi-square distribution. Directions the
sampler does not produce (failed or delta samples) form one more cell, so a density that
integrates to less than 1 is tested too. A small p-value means the sampler and the density
disagree. Several tests at once: pass ``test_count`` to apply the Sidak correction
1 - (1 - significance)^(1 / test_count) to the significance level.

The chi-square survival function is the regularised upper incomplete gamma function
Q(dof / 2, x / 2), by its series or continued fraction (Numerical Recipes, 3rd ed., 6.2), with
numpy only.

Example::

    from refracta.shading import RoughConductor
    from refracta.testing import chi2
    result = chi2.test_bsdf(RoughConductor(alpha=0.3), wo=[0.6, 0.0, 0.8], samples=200_000, seed=1)
    assert result.passed, result
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

__all__ = ["Result", "chi2_survival", "test_sampler", "test_bsdf"]

_GAMMA_EPS = 1e-14  # relative accuracy of the incomplete gamma series and continued fraction
_GAMMA_ITERATIONS = 10_000
# A cell whose integrated density is 0 may still be partly inside the support (its quadrature
# nodes all missed it); more than this fraction of the samples there is a failure, fewer are pooled.
_ZERO_CELL_FRACTION = 1e-4


def _gamma_q(a: float, x: float) -> float:
    """Regularised upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a), a > 0, x >= 0."""
    if x <= 0.0:
        return 1.0
    log_prefactor = -x + a * math.log(x) - math.lgamma(a)
    if x < a + 1.0:  # series for P(a, x)
        term = total = 1.0 / a
        ap = a
        for _ in range(_GAMMA_ITERATIONS):
            ap += 1.0
            term *= x / ap
            total += term
            if abs(term) < abs(total) * _GAMMA_EPS:
                break
        return max(0.0, 1.0 - total * math.exp(log_prefactor))
    # Lentz's continued fraction for Q(a, x)
    tiny = 1e-300
    b = x + 1.0 - a
    c = 1.0 / tiny
    d = 1.0 / b
    h = d
    for i in range(1, _GAMMA_ITERATIONS):
        an = -i * (i - a)
        b += 2.0
        d = an * d + b
        d = tiny if abs(d) < tiny else d
        c = b + an / c
        c = tiny if abs(c) < tiny else c
        d = 1.0 / d
        delta = d * c
        h *= delta
        if abs(delta - 1.0) < _GAMMA_EPS:
            break
    return min(1.0, math.exp(log_prefactor) * h)


def chi2_survival(statistic: float, dof: int) -> float:
    """P(X >= statistic) for X chi-square distributed with ``dof`` degrees of freedom (> 0)."""
    if dof <= 0:
        raise ValueError(f"dof must be > 0 (got {dof})")
    if not np.isfinite(statistic) or statistic < 0:
        raise ValueError(f"statistic must be finite and >= 0 (got {statistic})")
    return _gamma_q(0.5 * dof, 0.5 * statistic)


@dataclass(eq=False)  # arrays: == would be ambiguous (equal by identity)
class Result:
    """Outcome of a chi-square test.

    p_value: probability of a statistic at least this large if the sampler matches the density;
    statistic, dof: Pearson's statistic and its degrees of freedom after pooling; passed:
    p_value > significance (Sidak-corrected); significance: the corrected level used;
    samples: directions drawn; produced: fraction that landed on the sphere (non-delta, valid);
    pdf_integral: the density's integral over the sphere (compare with ``produced``);
    observed, expected: (res_theta, res_phi) histograms (rows: theta from 0 to pi,
    columns: phi from -pi to pi); message: why it failed, if it did."""

    p_value: float
    statistic: float
    dof: int
    passed: bool
    significance: float
    samples: int
    produced: float
    pdf_integral: float
    observed: np.ndarray = field(repr=False)
    expected: np.ndarray = field(repr=False)
    message: str = ""


def _directions(theta: np.ndarray, phi: np.ndarray) -> np.ndarray:
    sin_theta = np.sin(theta)
    return np.stack([sin_theta * np.cos(phi), sin_theta * np.sin(phi), np.cos(theta)], axis=-1)


def _gauss_cells(pdf, bounds: np.ndarray, order: int) -> np.ndarray:
    """Integral of pdf over each (theta0, theta1, phi0, phi1) row of `bounds` (M, 4) by order x
    order Gauss-Legendre (sin theta dtheta dphi)."""
    x, w = np.polynomial.legendre.leggauss(order)
    half_t = 0.5 * (bounds[:, 1] - bounds[:, 0])
    half_p = 0.5 * (bounds[:, 3] - bounds[:, 2])
    t = bounds[:, 0, None] + half_t[:, None] * (1.0 + x)[None, :]  # (M, order)
    p = bounds[:, 2, None] + half_p[:, None] * (1.0 + x)[None, :]
    tt = np.broadcast_to(t[:, :, None], (len(bounds), order, order)).reshape(-1)
    pp = np.broadcast_to(p[:, None, :], (len(bounds), order, order)).reshape(-1)
    dirs = _directions(tt, pp)
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    values = np.asarray(pdf(dirs), dtype=np.float64)
    if not np.all(np.isfinite(values)) or np.any(values < 0):
        raise ValueError("the density returned negative or non-finite values")
    values = (values * np.sin(tt)).reshape(len(bounds), order, order)
    return np.einsum("mij,i,j->m", values, w, w) * half_t * half_p


# Halvings of a cell's sides at most (2^-10 of a 3.75 deg cell: 0.2 arcsec), and the parts split
# at once at most (each costs four order^2 evaluations of the density: 0.7 M at order 6; the worst
# go on, the rest are kept as they are): a density sharper than that is accepted at its last level.
_MAX_DEPTH = 10
_MAX_SPLIT = 5_000


def _quarters(bounds: np.ndarray) -> np.ndarray:
    """The four quarters of each (theta0, theta1, phi0, phi1) row: (4, M, 4), quarter-major."""
    mt, mp = 0.5 * (bounds[:, 0] + bounds[:, 1]), 0.5 * (bounds[:, 2] + bounds[:, 3])
    t0, t1, p0, p1 = bounds.T
    return np.stack(
        [
            np.stack([t0, mt, p0, mp], 1),
            np.stack([t0, mt, mp, p1], 1),
            np.stack([mt, t1, p0, mp], 1),
            np.stack([mt, t1, mp, p1], 1),
        ]
    )


def _integrate_cells(
    pdf: Callable[[np.ndarray], np.ndarray], res_theta: int, res_phi: int, order: int, samples: int = 0
) -> np.ndarray:
    """Integral of pdf over every (theta, phi) cell by order x order Gauss-Legendre, adaptive: a
    cell (or part) whose rule disagrees with the sum of the same rule over its quarters by more
    than its allowance is replaced by its quarters, down to _MAX_DEPTH halvings. The allowance:
    a tenth of the cell's expected count's standard deviation for `samples` draws (sqrt(N I) / N;
    at least 1e-9 of the whole), halved with each halving of a part's side -- the error a
    discontinuity leaves in a part shrinks with its side, not its area, so a cone's rim converges
    (a share of the area never did). A lobe narrower than the cells (a clearcoat's GGX alpha of
    0.001 in 3.75 deg cells) is integrated, not missed between the nodes."""
    dt, dphi = np.pi / res_theta, 2.0 * np.pi / res_phi
    ti, pi = np.meshgrid(np.arange(res_theta), np.arange(res_phi), indexing="ij")
    t0, p0 = (dt * ti).reshape(-1), (-np.pi + dphi * pi).reshape(-1)
    bounds = np.stack([t0, t0 + dt, p0, p0 + dphi], axis=1)
    whole = _gauss_cells(pdf, bounds, order)
    owner = np.arange(len(bounds))
    share = np.ones(len(bounds))  # each part's share of its cell's allowance
    total = np.zeros(len(bounds))
    per_draw = 1.0 / max(samples, 1)
    for depth in range(_MAX_DEPTH + 1):
        quarters = _quarters(bounds)
        parts = _gauss_cells(pdf, quarters.reshape(-1, 4), order).reshape(4, -1)
        summed = parts.sum(axis=0)
        allowed = np.maximum(0.1 * np.sqrt(np.maximum(summed, per_draw) * per_draw), 1e-9) * share
        excess = np.abs(summed - whole) / allowed
        split = excess > 1.0
        if depth == _MAX_DEPTH:
            split[:] = False
        elif np.count_nonzero(split) > _MAX_SPLIT:  # the worst parts go on, the rest are kept
            split[np.argsort(excess)[: len(excess) - _MAX_SPLIT]] = False
        np.add.at(total, owner[~split], summed[~split])
        if not split.any():
            break
        bounds = quarters[:, split].reshape(-1, 4)
        whole = parts[:, split].reshape(-1)
        owner = np.tile(owner[split], 4)
        share = np.tile(share[split] / 2.0, 4)
    return total.reshape(res_theta, res_phi)


def test_sampler(
    sample: Callable[[np.ndarray], tuple],
    pdf: Callable[[np.ndarray], np.ndarray],
    samples: int = 200_000,
    seed: int = 0,
    significance: float = 0.01,
    test_count: int = 1,
    res_theta: int = 48,
    res_phi: int = 64,
    integration_order: int = 6,
    min_expected: float = 5.0,
) -> Result:
    """Chi-square test of ``sample`` against ``pdf`` over the unit sphere.

    sample(u) takes u (N, 3) uniform in [0, 1) and returns (directions (N, 3), produced (N,) bool):
    the rows with produced False (failed or delta samples) are outside the density's support.
    pdf(directions (M, 3)) returns the density per unit solid angle (M,) of the produced
    directions. seed makes the draw reproducible; significance is the family-wise level and
    test_count the number of tests it covers (Sidak)."""
    if samples < 1000:
        raise ValueError(f"samples must be >= 1000 (got {samples})")
    if not 0.0 < significance < 1.0:
        raise ValueError(f"significance must be in (0, 1) (got {significance})")
    if test_count < 1:
        raise ValueError(f"test_count must be >= 1 (got {test_count})")
    level = 1.0 - (1.0 - significance) ** (1.0 / test_count)
    rng = np.random.default_rng(seed)
    u = rng.random((samples, 3))
    directions, produced = sample(u)
    directions = np.asarray(directions, dtype=np.float64)[np.asarray(produced, dtype=bool)]
    if not np.all(np.isfinite(directions)):
        raise ValueError("the sampler returned non-finite directions")
    theta = np.arccos(np.clip(directions[:, 2], -1.0, 1.0))
    phi = np.arctan2(directions[:, 1], directions[:, 0])
    it = np.clip((theta / np.pi * res_theta).astype(int), 0, res_theta - 1)
    ip = np.clip(((phi + np.pi) / (2.0 * np.pi) * res_phi).astype(int), 0, res_phi - 1)
    observed = np.zeros((res_theta, res_phi))
    np.add.at(observed, (it, ip), 1.0)
    integral = _integrate_cells(pdf, res_theta, res_phi, integration_order, samples)
    expected = integral * samples
    # One more cell: the samples the density does not cover (failed or delta).
    obs = np.append(observed.reshape(-1), samples - len(directions))
    exp = np.append(expected.reshape(-1), max(0.0, samples - expected.sum()))
    fail = dict(
        observed=observed,
        expected=expected,
        samples=samples,
        produced=len(directions) / samples,
        pdf_integral=float(integral.sum()),
        significance=level,
    )
    # Pearson's statistic with low-expectation cells pooled (Mitsuba's chi2 pooling).
    order = np.argsort(exp)
    statistic, dof = 0.0, 0
    pooled_obs = pooled_exp = 0.0
    for i in order:
        if exp[i] == 0.0:
            if obs[i] > samples * _ZERO_CELL_FRACTION:
                return Result(
                    0.0,
                    math.inf,
                    0,
                    False,
                    message=f"{int(obs[i])} samples in a cell of zero density (cell {i})",
                    **fail,
                )
            pooled_obs += obs[i]
        elif exp[i] < min_expected or (0.0 < pooled_exp < min_expected):
            pooled_obs += obs[i]
            pooled_exp += exp[i]
        else:
            statistic += (obs[i] - exp[i]) ** 2 / exp[i]
            dof += 1
    if pooled_exp > 0.0:
        statistic += (pooled_obs - pooled_exp) ** 2 / pooled_exp
        dof += 1
    dof -= 1
    if dof < 1:
        return Result(1.0, statistic, dof, True, message="too few populated cells to test", **fail)
    p = chi2_survival(statistic, dof)
    passed = p > level
    message = "" if passed else f"p-value {p:.3g} <= {level:.3g}: the sampler and the density disagree"
    return Result(p, statistic, dof, passed, message=message, **fail)


def test_bsdf(
    material,
    wo,
    samples: int = 200_000,
    seed: int = 0,
    significance: float = 0.01,
    test_count: int = 1,
    res_theta: int = 48,
    res_phi: int = 64,
    integration_order: int = 6,
    **eval_kwargs,
) -> Result:
    """Chi-square test of ``material.sample(wo, u)`` against ``material.pdf(wo, wi)`` for one unit
    direction wo (3,) in the local shading frame. Delta samples and failed samples form the cell
    outside the density. eval_kwargs (eta_outside=, mode=, wavelengths=) go to both. Works for any
    object with refracta's ``sample`` / ``pdf`` conventions (refracta.shading)."""
    wo = np.asarray(wo, dtype=np.float64)
    if wo.shape != (3,) or not np.all(np.isfinite(wo)) or abs(np.linalg.norm(wo) - 1.0) > 1e-6:
        raise ValueError(f"wo must be one finite unit vector of shape (3,) (got {wo!r})")

    def sample(u):
        s = material.sample(np.broadcast_to(wo, u.shape).copy(), u, **eval_kwargs)
        return s.wi, s.valid & ~s.is_delta

    def pdf(wi):
        return material.pdf(wo, wi, **eval_kwargs)

    return test_sampler(
        sample,
        pdf,
        samples=samples,
        seed=seed,
        significance=significance,
        test_count=test_count,
        res_theta=res_theta,
        res_phi=res_phi,
        integration_order=integration_order,
    )
