"""Environment maps: the documented direction <-> (u, v) mapping, a single bright texel seen and
sampled where the mapping says, Le against Mitsuba 3's envmap emitter, chi-squared of the
importance sampler, pdf consistency, irradiance and power of a constant map."""

import numpy as np
import pytest

from refracta.lights import EnvironmentLight

from .conftest import CHI2_SIGNIFICANCE, chi2_test

# Le against Mitsuba 3 (scalar_rgb computes in float32): its float32 to_world and uv move the
# bilinear weights by ~1e-7, by 1/sin(theta) more near the poles (measured max 2.1e-5).
MITSUBA_RELATIVE = 1e-4
# sample_li's pdf and pdf_li of the same direction (uv re-derived from the direction).
PDF_CONSISTENCY = 1e-9
EXACT = 1e-12
# The mapping formulas in numpy against the C++ ones: double rounding of trigonometry.
MAPPING = 1e-12
MC_SIGMAS = 4.0  # 4 standard errors: a 6e-5 false-alarm rate
# pdf_li over a bin is constant in (s, v) up to sin(theta) rounding; midpoint rule is exact.
PDF_INTEGRAL = 1e-9


def mitsuba_direction(u, v):
    """Mitsuba 3 envmap.cpp uv_to_direction: theta = pi v, phi = 2 pi u."""
    theta, phi = np.pi * v, 2 * np.pi * u
    return np.stack([np.sin(phi) * np.sin(theta), np.cos(theta), -np.cos(phi) * np.sin(theta)], axis=-1)


def mitsuba_uv(d):
    """Mitsuba 3 envmap.cpp direction_to_uv (wrapped into [0, 1) as its eval does)."""
    u = np.arctan2(d[:, 0], -d[:, 2]) / (2 * np.pi)
    return np.stack([u - np.floor(u), np.arccos(np.clip(d[:, 1], -1, 1)) / np.pi], axis=1)


def random_dirs(rng, n):
    d = rng.normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1)[:, None]


def random_map(rng, h=6, w=8):
    image = rng.random((h, w, 3)) ** 3 * 4.0  # strongly non-uniform
    image[1, 2] = 0.0
    image[:, 5, 1] = 0.0
    return image


def test_mapping_is_mitsubas(rng):
    light = EnvironmentLight(np.ones((4, 8, 3)))
    d = random_dirs(rng, 1000)
    np.testing.assert_allclose(light.direction_to_uv(d), mitsuba_uv(d), rtol=0, atol=MAPPING)
    uv = rng.random((1000, 2))
    np.testing.assert_allclose(light.uv_to_direction(uv), mitsuba_direction(uv[:, 0], uv[:, 1]), atol=MAPPING)
    # The landmarks of the docstring: u = 0 looks along -z, 1/4 along +x, 1/2 along +z; v = 0 up.
    landmarks = light.direction_to_uv(np.array([[0, 0, -1.0], [1.0, 0, 0], [0, 0, 1.0], [-1.0, 0, 0]]))
    np.testing.assert_allclose(landmarks, [[0, 0.5], [0.25, 0.5], [0.5, 0.5], [0.75, 0.5]], atol=MAPPING)
    np.testing.assert_allclose(light.direction_to_uv(np.array([[0, 1.0, 0], [0, -1.0, 0]]))[:, 1], [0, 1], atol=MAPPING)


@pytest.mark.parametrize("row, column", [(3, 5), (1, 0), (6, 15)])
def test_single_bright_texel_is_seen_and_sampled_where_the_mapping_says(rng, row, column):
    h, w = 8, 16
    image = np.zeros((h, w, 3), np.float32)
    image[row, column] = [10.0, 20.0, 30.0]
    light = EnvironmentLight(image, scale=2.0)
    predicted = mitsuba_direction((column + 0.5) / w, row / (h - 1))
    # The texel's own value at its centre direction: mapping round trip in double.
    np.testing.assert_allclose(light.Le(predicted[None])[0], [20.0, 40.0, 60.0], rtol=1e-9)
    # Every sample lies in the four bilinear patches around the texel.
    n = 2000
    wi, L, pdf, _ = light.sample_li(np.zeros((n, 3)), None, rng.random((n, 2)))
    assert np.all(pdf > 0)
    patch = np.hypot(2 * np.pi / w, np.pi / (h - 1))  # one patch's diagonal [rad], an upper bound
    angle = np.arccos(np.clip(wi @ predicted, -1, 1))
    assert angle.max() <= patch * 1.0001 * (1 if 0 < row < h - 1 else 2)
    # The brightest direction sampled is the texel's: L peaks at the predicted direction.
    assert np.all(L[:, 2] <= 60.0 + 1e-9)


@pytest.mark.parametrize("rotation", [None, 30.0, "random"])
def test_Le_matches_mitsuba3_envmap(rng, rotation):
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    image = random_map(rng, 7, 12).astype(np.float32)
    if rotation == "random":
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        rotation = q * np.sign(np.linalg.det(q))
    light = EnvironmentLight(image, scale=1.7, rotation=rotation)
    to_world = np.eye(4)
    to_world[:3, :3] = light.rotation
    emitter = mi.load_dict(
        {
            "type": "envmap",
            "bitmap": mi.Bitmap(image),
            "scale": 1.7,
            "to_world": mi.ScalarTransform4f(to_world.tolist()),
        }
    )
    dirs = random_dirs(rng, 300)
    ours = light.Le(dirs)
    theirs = np.empty_like(ours)
    for k, d in enumerate(dirs):
        si = mi.SurfaceInteraction3f()
        si.wi = mi.Vector3f(*(-d))  # Mitsuba's eval looks along -si.wi
        theirs[k] = np.array(emitter.eval(si))
    # Per direction: the largest channel difference relative to the largest channel (float32 uv in
    # Mitsuba moves the bilinear weights by ~1e-7, which a dim channel next to a bright texel feels).
    relative = np.max(np.abs(ours - theirs), axis=1) / np.max(np.abs(theirs), axis=1)
    assert relative.max() < MITSUBA_RELATIVE, relative.max()


@pytest.mark.parametrize("rotation", [None, 75.0])
def test_environment_importance_sampler_chi2(rng, rotation):
    h, w = 6, 8
    light = EnvironmentLight(random_map(rng, h, w), rotation=rotation)
    count, sub = 200_000, 8
    wi, _, pdf, _ = light.sample_li(np.zeros((count, 3)), None, rng.random((count, 2)))
    assert np.all(pdf > 0)
    local = wi @ light.rotation  # rotation^T wi, row-wise
    uv = mitsuba_uv(local)
    s = np.mod(uv[:, 0] - 0.5 / w, 1.0)  # the patches of the documented bilinear grid
    observed, _, _ = np.histogram2d(s, uv[:, 1], bins=[w, h - 1], range=[[0, 1], [0, 1]])
    # Expected: integral over each patch of pdf_li dOmega, dOmega = 2 pi^2 sin(theta) du dv.
    gs = (np.arange(w * sub) + 0.5) / (w * sub)
    gv = (np.arange((h - 1) * sub) + 0.5) / ((h - 1) * sub)
    S, V = np.meshgrid(gs, gv, indexing="ij")
    U = np.mod(S + 0.5 / w, 1.0)
    dirs = mitsuba_direction(U.ravel(), V.ravel()) @ light.rotation.T
    dens = light.pdf_li(np.zeros((len(dirs), 3)), None, dirs)
    weight = 2 * np.pi**2 * np.sin(np.pi * V.ravel()) / (w * sub * (h - 1) * sub)
    cell = (dens * weight).reshape(w, sub, h - 1, sub).sum(axis=(1, 3))
    assert cell.sum() == pytest.approx(1.0, abs=PDF_INTEGRAL)
    _, p_value, _ = chi2_test(observed, cell * count)
    assert p_value > CHI2_SIGNIFICANCE
    # Importance: patches with black corners are never sampled; the density follows luminance.
    assert np.all(observed[cell == 0] == 0)


def test_environment_pdf_matches_pdf_li_and_Le(rng):
    light = EnvironmentLight(random_map(rng, 9, 13), scale=0.5, rotation=20.0)
    n = 5000
    points = rng.normal(size=(n, 3))
    wi, L, pdf, distance = light.sample_li(points, None, rng.random((n, 2)))
    assert np.all(pdf > 0) and np.all(np.isinf(distance))
    np.testing.assert_allclose(light.pdf_li(points, None, wi), pdf, rtol=PDF_CONSISTENCY)
    # The same bilinear lookup for the sampled direction: rounding; 1e-12 where the map is 0.
    np.testing.assert_allclose(light.Le(wi), L, rtol=1e-9, atol=1e-12)


def test_constant_map_irradiance_and_power(rng):
    radiance = 0.8
    light = EnvironmentLight(np.full((16, 32, 3), radiance, np.float32), rotation=10.0)
    n = 100_000
    normal = np.array([0.0, 0.6, 0.8])
    wi, L, pdf, _ = light.sample_li(np.zeros((n, 3)), np.tile(normal, (n, 1)), rng.random((n, 2)))
    values = L[:, 0] * np.maximum(wi @ normal, 0) / pdf
    estimate, error = values.mean(), values.std() / np.sqrt(n)
    assert abs(estimate - np.pi * radiance) < MC_SIGMAS * error, (estimate, error)
    light.preprocess([0, 0, 0], 3.0)
    assert light.power == pytest.approx(4 * np.pi**2 * 9.0 * radiance, rel=1e-6)  # float32 texels


def test_grey_and_rgba_maps():
    grey = EnvironmentLight(np.full((4, 6), 2.0))
    rgba = EnvironmentLight(np.dstack([np.full((4, 6, 3), 2.0), np.zeros((4, 6))]))
    d = np.array([[0.0, 1.0, 0.0], [0.6, 0.0, 0.8]])
    np.testing.assert_allclose(grey.Le(d), 2.0)  # default rtol 1e-7: a constant map's value anywhere, rounding only
    np.testing.assert_allclose(rgba.Le(d), 2.0)  # as above (alpha ignored)
    black = EnvironmentLight(np.zeros((4, 6, 3)))
    assert np.all(black.sample_li(np.zeros((3, 3)), None, np.full((3, 2), 0.5))[2] == 0)
    assert black.power == 0.0
