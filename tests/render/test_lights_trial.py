"""A lighting artist's trial: render_raster under a map bright at its zenith, under a wide or
grazing sun, and without cracks along a ground's diagonal; each against an analytic value or the
ray renderer, which matched the trial's independent quadratures within 0.05 %."""

import numpy as np
import pytest

import refracta
from refracta import shading

LOOKING_DOWN = dict(up=(0.0, 0.0, -1.0), vfov=20.0, width=16, height=16)


def floor(albedo, size=1000.0):
    scene = refracta.Scene()
    scene.add_ground(0.0, size, material=shading.Diffuse(albedo))
    return scene


def test_a_map_bright_at_its_zenith_lights_a_floor_as_the_ray_renderer_does():
    # Two rows of 100 at the top of the map: the raster's first sample of a level floor is its
    # normal, the map's pole, where the light density was taken as 0 (3.70x too bright).
    cap = np.zeros((64, 128, 3), np.float32)
    cap[:2] = 100.0
    scene = floor(0.5)
    scene.set_environment(cap)
    camera = refracta.Camera((0.0, 5.0, 0.001), (0.0, 0.0, 0.0), **LOOKING_DOWN)
    reference = refracta.render(scene, camera, None, spp=64).mean()
    raster = refracta.render_raster(scene, camera).mean()
    # The raster's 64 light and 64 BSDF samples of the cap: +0.6 % (as with the map turned 0.2 deg).
    assert raster == pytest.approx(reference, rel=0.02)


def sun_on_floor(elevation_deg, diameter_deg):
    scene = floor(1.0)
    e = np.radians(elevation_deg)
    scene.set_sun((np.cos(e), np.sin(e), 0.0), (1.0, 1.0, 1.0), angular_diameter=diameter_deg)
    return scene


def disc_irradiance(elevation_deg, diameter_deg, steps=1500):
    """A uniform disc of radiance 1 on a level floor: the integral of sin(elevation) over the
    disc's part above the horizon, on a grid of its tangent plane (small discs)."""
    e, radius = np.radians(elevation_deg), np.radians(diameter_deg / 2)
    x = (np.arange(steps) + 0.5) / steps * 2 - 1
    u, v = np.meshgrid(x * radius, x * radius)
    inside = u**2 + v**2 < radius**2
    return np.sum(np.maximum(np.sin(e + v), 0.0) * inside) * (2 * radius / steps) ** 2


def test_a_wide_sun_lights_the_floor_by_its_disc_not_its_solid_angle():
    camera = refracta.Camera((0.0, 5.0, 0.001), (0.0, 0.0, 0.0), **LOOKING_DOWN)
    for diameter in (170.0, 90.0):
        # A uniform disc at the zenith: E = pi L sin^2(alpha), so a white floor's radiance sin^2(alpha)
        # (the centre alone gave L x solid angle: +84 % at 170 deg).
        exact = np.sin(np.radians(diameter / 2)) ** 2
        raster = refracta.render_raster(sun_on_floor(90.0, diameter), camera).mean()
        # 64 quasi-random samples of the disc: +1.4 % at 170 deg, +0.3 % at 90 deg.
        assert raster == pytest.approx(exact, rel=0.03)


def test_a_sun_the_horizon_cuts_lights_the_floor_by_its_part_above():
    camera = refracta.Camera((0.0, 5.0, 0.001), (0.0, 0.0, 0.0), **LOOKING_DOWN)
    # The physical 0.53 deg sun 0.1 deg up: a quarter of its disc below the floor's horizon.
    exact = disc_irradiance(0.1, 0.53) / np.pi
    raster = refracta.render_raster(sun_on_floor(0.1, 0.53), camera).mean()
    # 64 samples of a disc with a straight cut through it: -2.6 % (the centre alone: -15 %).
    assert raster == pytest.approx(exact, rel=0.05)
    # A small disc well above the horizon keeps its single centre sample: within alpha^2 / 4.
    high = refracta.render_raster(sun_on_floor(30.0, 0.53), camera).mean()
    # alpha^2 / 4 = 5.3e-6 for the 0.265 deg radius, with float32 pixels' 1e-7 beside it.
    assert high == pytest.approx(disc_irradiance(30.0, 0.53) / np.pi, rel=1e-4)


@pytest.mark.parametrize("size", [(48, 36), (64, 48), (160, 120)])
def test_no_crack_along_the_diagonal_of_the_ground(size):
    # A camera on the z axis looking at the origin sees the ground's two triangles meet along a
    # line through pixel centres: rounding put 4, 7 and 1 of them outside both (the sky showed).
    width, height = size
    camera = refracta.Camera((0.0, 3.0, 4.0), (0.0, 0.0, 0.0), vfov=40.0, width=width, height=height)
    scene = floor(0.5, size=100.0)
    scene.add_point_light((1.0, 2.0, 0.5), (10.0, 10.0, 10.0))
    scene.set_environment((0.0, 0.0, 1.0))
    sky = np.array([0.0, 0.0, 1.0])
    ground = ~np.all(refracta.render(scene, camera, None, spp=1) == sky, axis=-1)
    for image in (
        refracta.render_raster(scene, camera, shadows="none"),
        refracta.render(scene, camera, None, spp=1, method="raster_march"),
    ):
        assert not np.any(np.all(image == sky, axis=-1) & ground)


def test_render_raster_told_to_light_by_a_sun_the_scene_lacks_says_so():
    scene = floor(0.5, size=20.0)
    scene.add_point_light((0.0, 3.0, 0.0), (10.0, 10.0, 10.0))
    camera = refracta.Camera((0.0, 5.0, 0.001), (0.0, 0.0, 0.0), **LOOKING_DOWN)
    with pytest.raises(ValueError, match="lights names the sun, but the scene has none"):
        refracta.render_raster(scene, camera, lights="sun")
    scene.set_sun((0.0, 1.0, 0.0), (1.0, 1.0, 1.0))
    assert refracta.render_raster(scene, camera, lights=["sun"]).mean() > 0.0
