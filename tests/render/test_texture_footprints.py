"""Texture footprints through curved air (issue 10): a camera ray's footprint on a textured
surface comes from the paths of its neighbours (ray differentials through the air), so a
mirage's stretched or squeezed image of a texture is filtered by its true footprint, where the
ray cone (pixel angle x path length) over- or under-blurs it.

The scene: a checkerboard wall 400 m down a road 15 K warmer than the air (e-folding 15 cm), seen
from 0.8 m: the wall appears directly and, inverted and stretched near the fold of the mirage,
below it. The reference averages 144 point samples per pixel (the pixel's box filter)."""

import numpy as np
import pytest

import refracta

CHECKS = 8  # texels per check


@pytest.fixture(scope="module")
def mirage_wall(tmp_path_factory):
    texture = tmp_path_factory.mktemp("textures") / "checker.png"
    i, j = np.meshgrid(np.arange(1024), np.arange(128))
    checker = (((i // CHECKS) + (j // CHECKS)) % 2).astype(np.float32) * 0.9 + 0.05
    refracta.io.write_image(texture, np.repeat(checker[..., None], 3, axis=2))
    scene = refracta.Scene()
    scene.set_sun([-1.0, 0.4, 0.0], (1e5, 1e5, 1e5))  # behind the camera: the wall's lighting has no noise
    scene.add_ground(0.0, 5000.0, material=refracta.shading.Diffuse(0.0))
    scene.add_billboard([400.0, 1.25, 0.0], 20.0, 2.5, str(texture))
    field = refracta.PhysicalAtmosphere(surface_dt=15.0, surface_depth=0.15)
    depression = np.radians(0.12)
    camera = refracta.Camera([0, 0.8, 0], [400.0, 0.8 - 400.0 * np.tan(depression), 0], vfov=0.4, width=48, height=54)
    return scene, camera, field


@pytest.mark.slow
def test_differentials_filter_a_mirage_closer_to_the_reference_than_the_cone(mirage_wall):
    scene, camera, field = mirage_wall
    common = dict(max_length=1000.0, progress=False)
    reference = refracta.render(scene, camera, field, spp=144, texture_filter=False, **common)
    errors = {}
    for name, options in [
        ("differentials", {}),
        ("cone", dict(differentials=False)),
        ("point", dict(texture_filter=False)),
    ]:
        image = refracta.render(scene, camera, field, **options, **common)
        errors[name] = float(np.abs(image - reference).mean())
    # Measured: differentials 0.035, cone 0.056, point sampling 0.043 (the reference's own noise,
    # 144 samples of a 0/1 checker, is ~0.02 per pixel and the same for all three).
    assert errors["differentials"] < 0.8 * errors["cone"], errors
    assert errors["differentials"] < errors["point"], errors


def test_in_straight_air_differentials_are_the_cone(mirage_wall):
    # Without a field both describe the same pixel footprint (a pinhole's neighbouring rays are the
    # cone's edges): the images agree to the difference between a square footprint and a disc's.
    scene, camera, _ = mirage_wall
    common = dict(max_length=1000.0, progress=False)
    differentials = refracta.render(scene, camera, None, **common)
    cone = refracta.render(scene, camera, None, differentials=False, **common)
    assert np.abs(differentials - cone).mean() < 0.05 * differentials.mean()
