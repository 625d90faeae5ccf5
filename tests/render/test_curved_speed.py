"""Curved rays' shortcuts (issue 21 goals 2, 4, 5): shadow and bounce rays held to the camera's
pixel, per-height ior floors, escapes integrated to a quarter pixel's angle. Their images do not
depend on the thread count, the tiles or the pixel bounds (the images themselves: tests/render's
renders against their references, unchanged)."""

from __future__ import annotations

import numpy as np
import pytest

import refracta
from refracta import examples, shading

WIDTH, HEIGHT = 48, 24


def hills_scene():
    """A small stand-in for the Portland case: a hill mesh 300 m high behind a hot road and boxes,
    sun and physical sky (shadow rays rise through the air to above every object)."""
    scene = refracta.Scene()
    examples.set_physical_sky(scene, examples.sun_direction(35.0, 30.0))
    n = 21
    x, z = np.meshgrid(np.linspace(200.0, 2200.0, n), np.linspace(-1000.0, 1000.0, n), indexing="ij")
    y = 300.0 * np.clip((x - 400.0) / 1500.0, 0.0, 1.0) ** 2 * (1.0 + 0.2 * np.sin(z / 300.0)) - 0.05
    i, j = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="ij")
    a = (i * n + j).ravel()
    triangles = np.concatenate([np.stack([a, a + 1, a + n], 1), np.stack([a + 1, a + n + 1, a + n], 1)])
    scene.add_mesh(np.stack([x, y, z], -1).reshape(-1, 3), triangles, material=shading.Diffuse((0.3, 0.3, 0.2)))
    scene.add_ground(0.0, 5000.0, material=shading.Diffuse((0.4, 0.35, 0.25)))
    for k in range(6):
        height = 10.0 + 4.0 * k
        scene.add_box((60.0 + 40.0 * k, height / 2, (-1) ** k * 20.0), (10.0, height, 10.0), kd=(0.6, 0.6, 0.6))
    eye = np.array([0.0, 1.5, 0.0])
    camera = refracta.Camera(eye, eye + [1.0, 0.002, 0.0], vfov=2.0, width=WIDTH, height=HEIGHT)
    return scene, camera, refracta.PhysicalAtmosphere(surface_dt=15.0, surface_depth=0.1)


def compact_spot_air():
    """hills_scene's road 2 K warm but for a compact hot spot 20 K warmer under the view: its
    camera, shadow and bounce rays through the spot are cast in rk45 legs."""
    spot = refracta.HotSpot(300.0, 0.0, 250.0, 20.0, footprint="compact")
    return refracta.PhysicalAtmosphere(surface_dt=2.0, surface_depth=0.1, hot_spots=[spot])


@pytest.mark.parametrize("air", ["hot_road", "hot_spot"])
def test_curved_renders_do_not_depend_on_threads_tiles_or_bounds(air):
    scene, camera, field = hills_scene()
    if air == "hot_spot":
        field = compact_spot_air()
    options = dict(progress=False, max_length=5000.0)
    whole = refracta.render(scene, camera, field, **options)
    threads = refracta.get_threads()
    try:
        refracta.set_threads(1)
        single = refracta.render(scene, camera, field, **options)
    finally:
        refracta.set_threads(threads)
    tiled = refracta.render(scene, camera, field, tile=5, **options)
    part = refracta.render(scene, camera, field, pixel_bounds=(10, 4, 40, 20), **options)
    np.testing.assert_array_equal(whole, single)
    np.testing.assert_array_equal(whole, tiled)
    np.testing.assert_array_equal(whole[4:20, 10:40], part)
    if air == "hot_spot":  # the spot's legs were cast: its air shows
        plain = refracta.PhysicalAtmosphere(surface_dt=2.0, surface_depth=0.1)
        assert not np.array_equal(whole, refracta.render(scene, camera, plain, **options))
