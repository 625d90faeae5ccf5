"""Shared helpers of the light tests: a chi-squared goodness-of-fit test of a light's direction
sampler against its own pdf_li (as Mitsuba 3's chi2.py and pbrt-v4's sampling tests), with the
expected counts integrated from pdf_li over each bin by a midpoint rule.

refracta.testing.chi2 was not committed when these were written; this is the lights' own.
"""

import numpy as np
from scipy import stats

# Mitsuba's chi2 tests reject at 1%; each call here is one test, so no Sidak correction.
CHI2_SIGNIFICANCE = 0.01
# Bins with fewer expected samples are pooled (the chi-squared approximation needs >= 5).
MIN_EXPECTED = 5.0


def frame(axis):
    """A right-handed orthonormal (s, t, n) about unit `axis`."""
    n = np.asarray(axis, float) / np.linalg.norm(axis)
    helper = np.array([1.0, 0, 0]) if abs(n[0]) < 0.9 else np.array([0, 1.0, 0])
    s = np.cross(helper, n)
    s /= np.linalg.norm(s)
    return s, np.cross(n, s), n


def chi2_test(observed, expected):
    """(statistic, p-value) after pooling low-expectation bins; also returns the dof."""
    observed, expected = np.ravel(observed).astype(float), np.ravel(expected)
    order = np.argsort(expected)
    observed, expected = observed[order], expected[order]
    low = expected < MIN_EXPECTED
    obs = list(observed[~low])
    exp = list(expected[~low])
    if low.any() and expected[low].sum() > 0:
        obs.append(observed[low].sum())
        exp.append(expected[low].sum())
    obs, exp = np.array(obs), np.array(exp)
    statistic = np.sum((obs - exp) ** 2 / exp)
    dof = len(obs) - 1
    return statistic, stats.chi2.sf(statistic, dof), dof


def cone_chi2(light, point, normal, axis, cos_min, count, rng, n_theta=10, n_phi=12, sub=12, hit=None):
    """Chi-squared of light.sample_li's directions from one point, binned in the cone about
    `axis` with cos(theta) in [cos_min, 1] by x = (1 - cos theta) / (1 - cos_min) (equal solid
    angle) and phi; expected counts = count * integral of pdf_li over each bin. `hit(dirs)`, when
    given, returns (p_light, n_light) for pdf_li (area lights).

    Returns (p_value, integral of pdf_li over the cone, fraction of samples outside the cone)."""
    s, t, n = frame(axis)
    points = np.tile(point, (count, 1))
    normals = None if normal is None else np.tile(normal, (count, 1))
    wi, _, pdf, _ = light.sample_li(points, normals, rng.random((count, 2)))
    ok = pdf > 0
    wi = wi[ok]
    one_minus_cos = 0.5 * np.sum((wi - n) ** 2, axis=1)
    x = one_minus_cos / (1.0 - cos_min)
    phi = np.mod(np.arctan2(wi @ t, wi @ s), 2 * np.pi)
    inside = x <= 1.0
    observed, _, _ = np.histogram2d(x[inside], phi[inside], bins=[n_theta, n_phi], range=[[0, 1], [0, 2 * np.pi]])
    # Expected counts: the midpoint rule on a sub x sub grid in each bin.
    xs = (np.arange(n_theta * sub) + 0.5) / (n_theta * sub)
    ps = (np.arange(n_phi * sub) + 0.5) / (n_phi * sub) * 2 * np.pi
    X, P = np.meshgrid(xs, ps, indexing="ij")
    omc = X * (1.0 - cos_min)
    cos = 1.0 - omc
    sin = np.sqrt(np.maximum(0.0, omc * (2.0 - omc)))
    dirs = (np.cos(P) * sin)[..., None] * s + (np.sin(P) * sin)[..., None] * t + cos[..., None] * n
    dirs = dirs.reshape(-1, 3)
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    m = len(dirs)
    p_light = n_light = None
    if hit is not None:
        p_light, n_light = hit(dirs)
    dens = light.pdf_li(
        np.tile(point, (m, 1)), None if normal is None else np.tile(normal, (m, 1)), dirs, p_light, n_light
    )
    d_omega = (1.0 - cos_min) * (1.0 / (n_theta * sub)) * (2 * np.pi / (n_phi * sub))
    cell = (dens * d_omega).reshape(n_theta, sub, n_phi, sub).sum(axis=(1, 3))
    _, p_value, _ = chi2_test(observed, cell * count)
    return p_value, cell.sum(), 1.0 - inside.sum() / count
