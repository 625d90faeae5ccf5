"""A trial of the readouts, as someone comparing a render with a photograph reads them: one ray per
pixel behind its apparent and true elevation and its distance, at any spp; pick refusing points
off the image; the readout text refusing a NaN point."""

import numpy as np
import pytest

import refracta
from refracta import widgets

EYE_HEIGHT = 2.0  # [m]


def ground_view(width=40, height=30):
    scene = refracta.Scene()
    scene.add_ground(0.0, 5000.0)
    scene.set_sky((0.4, 0.5, 0.8))
    camera = refracta.Camera([0.0, EYE_HEIGHT, 0.0], [1.0, EYE_HEIGHT, 0.0], [0.0, 1.0, 0.0], 10.0, width, height)
    return scene, camera


def test_apparent_and_true_elevation_are_one_ray_at_many_samples():
    scene, camera = ground_view()
    _, aovs = refracta.render(
        scene, camera, None, aovs=["distance", "apparent_elevation", "true_elevation"], spp=16, max_length=5000.0
    )
    ground = np.isfinite(aovs["distance"])
    assert ground.sum() > 100
    # No air: apparent minus true elevation is 0. The mean ray's direction beside the nearest
    # sample's hit made it 0.146-0.168 deg (half a pixel).
    difference = (aovs["apparent_elevation"] - aovs["true_elevation"])[ground]
    # float32 angles of a few degrees: ~1e-5 deg, with 100x margin
    assert np.abs(difference).max() < 1e-3
    # A flat ground from h: the path to the hit is h / sin(depression) of that same ray (the
    # readouts disagreed by 24 % at row 16).
    depression = np.radians(-aovs["apparent_elevation"][ground])
    # float32 distances and angles: 1e-4 relative
    np.testing.assert_allclose(aovs["distance"][ground], EYE_HEIGHT / np.sin(depression), rtol=1e-4)


def test_pick_refuses_a_pixel_off_the_image():
    scene, camera = ground_view(80, 60)
    assert camera.pick(scene, 40.0, 59.5) is not None
    # v = 1e9 returned the camera's foot from an 80 x 60 image.
    for u, v in [(40.0, 1e9), (-100.0, 30.0), (80.5, 30.0)]:
        with pytest.raises(ValueError, match=r"pick: pixel .* lies outside the camera's 80 x 60 image"):
            camera.pick(scene, u, v)


def test_the_readout_text_refuses_a_nan_point():
    scene, camera = ground_view(8, 6)
    _, aovs = refracta.render(scene, camera, None, aovs=["distance"], max_length=5000.0)
    with pytest.raises(ValueError, match="readout_text: the image point must be finite"):
        widgets.readout_text(aovs, float("nan"), 3.0)
