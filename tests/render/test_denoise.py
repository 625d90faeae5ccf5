"""refracta.denoise (Intel Open Image Denoise) on a real Monte Carlo render: the error against a
high-sample reference falls, the mean stays, and bad auxiliary images are refused."""

import numpy as np
import pytest

import refracta
from refracta import shading

LOW_SPP, REFERENCE_SPP = 4, 256
# The goal: the denoised relative MSE at least 5x below the noisy image's (measured ~15x;
# the 256-spp reference still carries 4/256 of the noisy image's variance, a floor the ratio meets).
IMPROVEMENT = 5.0
# Open Image Denoise is not exactly energy preserving; 2 % of the mean is three times the mean's
# own Monte Carlo error at 4 spp over 96 x 64 pixels of this scene.
MEAN_DRIFT = 0.02


def relative_mse(image, reference):
    # Relative to the reference's square, with a floor so dark pixels do not dominate (as Mitsuba's
    # and Intel's relMSE).
    return float(np.mean((image - reference) ** 2 / (reference ** 2 + 1e-2)))


@pytest.fixture(scope="module")
def renders():
    scene = refracta.Scene()
    scene.add_ground(0.0, 200.0, material=shading.Diffuse(0.5))
    scene.add_sphere((20, 1, 0), 1.0, material=shading.Diffuse(0.8))
    scene.set_physical_sky((-0.3, 0.4, 0.2))
    camera = refracta.Camera((0, 1.5, 0), (20, 0.5, 0), vfov=30, width=96, height=64)
    noisy = refracta.render(scene, camera, None, transport="path", spp=LOW_SPP, progress=False)
    reference = refracta.render(scene, camera, None, transport="path", spp=REFERENCE_SPP, seed=7, progress=False)
    return noisy, reference


@pytest.mark.slow
def test_denoising_a_path_traced_render_cuts_its_error(renders):
    noisy, reference = renders
    clean = refracta.denoise(noisy)
    assert clean.shape == noisy.shape and clean.dtype == np.float32
    assert relative_mse(clean, reference) * IMPROVEMENT <= relative_mse(noisy, reference)
    assert clean.mean() == pytest.approx(reference.mean(), rel=MEAN_DRIFT)


def test_bad_images_are_refused_naming_them():
    image = np.ones((8, 8, 3), np.float32)
    for bad, name in [(np.ones((8, 8)), "image"), (np.full((8, 8, 3), np.nan), "image"), (-image, "image")]:
        with pytest.raises(ValueError, match=name):
            refracta.denoise(bad)
    with pytest.raises(ValueError, match="albedo"):
        refracta.denoise(image, albedo=np.ones((4, 4, 3)))
    with pytest.raises(ValueError, match="albedo"):
        refracta.denoise(image, albedo=2 * image)
    with pytest.raises(ValueError, match="normal needs albedo"):
        refracta.denoise(image, normal=image * 0.5)
    with pytest.raises(ValueError, match="quality"):
        refracta.denoise(image, quality="best")
