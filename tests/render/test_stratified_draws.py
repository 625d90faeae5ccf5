"""The sampler's draws stratified over a pixel's samples (cpp/refracta/core/rng.h Sampler): a
pixel's light samples and wavelengths cover their domains as its positions cover the pixel, so
its noise falls faster than 1 / spp; each draw stays uniform on its own, so the image stays
unbiased. And 'path''s choice of one light a vertex (render/direct_lighting.h): a lamp under a
sky is sampled."""

import numpy as np
import pytest

import refracta
from refracta import shading

from .test_shading_06_area_light import expected_image, scene_and_camera

SEEDS = 4  # independent renders: each pixel's noise variance from their spread (3 dof a pixel)


def noise_variance(scene, camera, spp):
    images = np.stack(
        [
            refracta.render(scene, camera, None, method="straight", spp=spp, seed=seed, max_depth=1, progress=False)
            for seed in range(SEEDS)
        ]
    )
    return images.var(axis=0, ddof=1).mean(), images.mean(axis=0)


@pytest.mark.parametrize("half,height", [(0.8, 0.6), (0.1, 2.0)], ids=["large_near", "small_far"])
def test_a_floor_under_an_area_light_gets_quieter_faster_than_one_over_spp(half, height):
    # Independent draws: the variance of a pixel's mean falls as 1 / spp, 4x from 4 to 16 spp
    # (measured 4.0-4.2x before the draws were stratified: the pixel positions' own stratification
    # adds a little). Stratified, the light sample's smooth 2-D integrand falls faster: measured
    # 14x (large quad) and 19x (small). 8x is twice independence's ratio; the ratio's own sampling
    # spread over 3072 pixels x 3 dof is ~2 %.
    scene, camera, _ = scene_and_camera(half, height)
    camera = camera.resized(64, 48)
    coarse, _ = noise_variance(scene, camera, 4)
    fine, _ = noise_variance(scene, camera, 16)
    assert coarse / fine > 8.0  # twice independence's 4x (comment above)


def test_stratified_draws_leave_the_floor_on_its_closed_form():
    # Lambert's polygon formula, as test_shading_06 checks per pixel: the image's mean over 4 seeds
    # at 4 spp (a pattern of 4, where stratification reshapes the estimate most) within 4 standard
    # errors of the closed form, the standard error from the pixels' spread across seeds.
    scene, camera, quad = scene_and_camera(0.8, 0.6)
    images = np.stack(
        [
            refracta.render(scene, camera, None, method="straight", spp=4, seed=seed, max_depth=1, progress=False)
            for seed in range(16)
        ]
    )
    expected, on_floor = expected_image(camera, quad)
    error = (images[..., 0][:, on_floor] - expected[on_floor]).mean(axis=1)  # per seed, the image's mean error
    standard_error = error.std(ddof=1) / np.sqrt(len(error))
    # 4 standard errors plus the closed form's 6 x 6 pixel quadrature (test_shading_06's 2e-3).
    assert abs(error.mean()) < 4.0 * standard_error + 2e-3 * expected[on_floor].mean()


def test_spectral_samples_stratify_their_wavelengths():
    # A camera looking at a white sky: all noise is the wavelengths'. Four samples of one pixel
    # draw four sets of four wavelengths; with independent draws (or a stratified hero alone: the
    # sets repeat every quarter of the range) the variance falls 4x from 1 to 4 spp; stratified,
    # measured 23x. 8x is twice independence's ratio; 32 seeds x 768 pixels put its own spread
    # near 1 %.
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    camera = refracta.Camera((0, 0, 0), (0, 1, -1), vfov=40, width=32, height=24)

    def variance(spp):
        images = [
            refracta.render(scene, camera, None, method="straight", spectral=True, spp=spp, seed=seed, progress=False)
            for seed in range(32)
        ]
        return np.var(images, axis=0, ddof=1).mean()

    assert variance(1) / variance(4) > 8.0  # twice independence's 4x (comment above)


def test_path_tracing_samples_a_lamp_under_a_sky():
    # A point light and a uniform sky over a 20 km Lambertian ground: 'direct' lights each vertex
    # by every light, 'path' by one it chooses. Chosen by power alone, the sky's power through the
    # scene's 20 km disc left the lamp a probability ~1e-8: 'path' gave 0.31-0.43 of 'direct's
    # image in every seed. Measured now: the 8 seeds' mean within 2e-5 of 'direct'. 1 %: the
    # lamp's share of the image, a third to two thirds, would miss by far more if it were lost.
    scene = refracta.Scene()
    scene.add_ground(0.0, 20000.0, material=shading.Diffuse((0.6, 0.4, 0.8)))
    scene.add_point_light((0.3, 1.2, -1.5), (5.0, 2.0, 7.0))
    scene.set_sky((0.3, 0.2, 0.1))
    camera = refracta.Camera((0, 1, 0), (0, 0, -1), vfov=40, width=32, height=24)
    options = dict(method="straight", spp=16, progress=False)
    direct = refracta.render(scene, camera, None, transport="direct", **options)
    path = np.mean(
        [refracta.render(scene, camera, None, transport="path", max_depth=3, seed=s, **options) for s in range(8)],
        axis=0,
    )
    np.testing.assert_allclose(path.mean(axis=(0, 1)), direct.mean(axis=(0, 1)), rtol=0.01)  # 1 %: comment above
