"""The scene's ready-made parts, now library functions behind thin bindings: the gradient and the
physical sky (shading/sky_presets.h), the billboard (scene/embree_scene.h), spot-light numbering
(RenderScene::spots)."""

import numpy as np
import pytest

import refracta
from refracta import lights

UP, HORIZONTAL, DOWN = [[0.0, 1.0, 0.0]], [[1.0, 0.0, 0.0]], [[0.0, -1.0, 0.0]]
# The gradient map's rows sit on the lookup's nodes, the horizon one of them: exact at the nodes
# but for float32 texels, linear between them within (pi / 256)^2 / 8 = 2e-5 of (zenith - horizon).
ROW_OFFSET_TOLERANCE = 3e-5
# RGB round trip of an illuminant colour through float32 texels: float rounding.
FLOAT_TOLERANCE = 1e-6


def test_a_gradient_sky_runs_from_the_horizon_below_to_the_zenith_above():
    horizon, zenith = np.array([0.8, 0.85, 0.9]), np.array([0.2, 0.3, 0.8])
    scene = refracta.Scene()
    scene.set_sky(horizon=horizon, zenith=zenith)
    (sky,) = scene.lights
    span = np.abs(zenith - horizon).max()
    np.testing.assert_allclose(sky.Le(UP)[0], zenith, atol=ROW_OFFSET_TOLERANCE * span)
    np.testing.assert_allclose(sky.Le(HORIZONTAL)[0], horizon, atol=ROW_OFFSET_TOLERANCE * span)
    np.testing.assert_allclose(sky.Le(DOWN)[0], horizon, rtol=FLOAT_TOLERANCE)
    # Linear in the sine of the elevation (set_sky's docstring) between the nodes too.
    elevation = np.radians(np.linspace(0.05, 89.95, 181))
    directions = np.stack([np.cos(elevation), np.sin(elevation), np.zeros_like(elevation)], axis=1)
    expected = horizon + np.sin(elevation)[:, None] * (zenith - horizon)
    np.testing.assert_allclose(sky.Le(directions), expected, atol=ROW_OFFSET_TOLERANCE * span)


def test_a_sky_without_zenith_is_constant_and_without_colours_the_default_blue():
    scene = refracta.Scene()
    scene.set_sky(horizon=0.5, scale=2.0)
    (sky,) = scene.lights
    assert isinstance(sky, lights.ConstantEnvironment)
    np.testing.assert_allclose(sky.Le(UP + DOWN), 1.0, rtol=FLOAT_TOLERANCE)
    scene.set_sky()
    np.testing.assert_allclose(scene.lights[0].Le(UP)[0], [0.7, 0.8, 0.95], rtol=FLOAT_TOLERANCE)
    scene.set_sky(horizon=0.0)
    assert scene.lights == []


def test_the_sky_keeps_the_sun_and_the_sun_replaces_the_sun():
    scene = refracta.Scene()
    scene.set_sun([0, 1, 0], 10.0)
    scene.set_sky(horizon=0.5)
    scene.set_sun([1, 1, 0], 20.0)
    kinds = sorted(type(light).__name__ for light in scene.lights)
    assert kinds == ["ConstantEnvironment", "SunLight"]


def test_the_physical_sky_brings_its_sun_and_scale_multiplies_both():
    one, two = refracta.Scene(), refracta.Scene()
    one.set_physical_sky([0.0, 0.5, -1.0], aerial_perspective=False)
    two.set_physical_sky([0.0, 0.5, -1.0], scale=2.0, aerial_perspective=False)
    for scene in (one, two):  # the sky (scaled or not) and its sun
        assert len(scene.lights) == 2
        assert sum(isinstance(light, lights.SunLight) for light in scene.lights) == 1
    sun_one = next(light for light in one.lights if isinstance(light, lights.SunLight))
    sun_two = next(light for light in two.lights if isinstance(light, lights.SunLight))
    # The direction is normalised once in double precision: a few ulps.
    np.testing.assert_allclose(sun_one.direction, np.array([0.0, 0.5, -1.0]) / np.sqrt(1.25), rtol=1e-15)
    # The sun's spectrum is scaled before it is turned into RGB: the same linear map, rounding only.
    np.testing.assert_allclose(sun_two.irradiance, 2.0 * sun_one.irradiance, rtol=1e-12)
    assert (sun_one.irradiance > 0).all()
    with pytest.raises(ValueError, match="limb_darkening"):
        one.set_physical_sky([0.0, 0.5, -1.0], limb_darkening=2.0)


def test_a_billboard_stands_upright_facing_its_direction(tmp_path):
    texture = str(tmp_path / "photo.png")
    refracta.io.write_image(texture, np.full((4, 4, 3), 0.5, np.float32), exposure=1.0)
    scene = refracta.Scene()
    scene.add_billboard((10.0, 1.5, 0.0), 2.0, 1.0, texture, facing=(-1.0, 0.0, 0.0))
    lower, upper = scene.bounds
    np.testing.assert_array_equal(lower, [10.0, 1.0, -1.0])
    np.testing.assert_array_equal(upper, [10.0, 2.0, 1.0])
    point, distance, _ = scene.intersect([0.0, 1.5, 0.0], [1.0, 0.0, 0.0])
    assert distance == pytest.approx(10.0, rel=1e-6)  # Embree's float32 hit
    with pytest.raises(ValueError, match="facing must have a horizontal component"):
        scene.add_billboard((0.0, 0.0, 0.0), 1.0, 1.0, texture, facing=(0.0, 1.0, 0.0))


def test_spot_lights_are_numbered_among_spot_lights_however_added():
    scene = refracta.Scene()
    scene.add_point_light([0, 5, 0], 1.0)
    assert scene.add_spot_light([0, 5, 0], [0, -1, 0]) == 0
    scene.add_light(lights.SpotLight([1, 5, 0], [0, -1, 0], 40.0, 1.0))
    scene.add_point_light([0, 6, 0], 1.0)
    assert scene.add_spot_light([2, 5, 0], [0, -1, 0]) == 2
