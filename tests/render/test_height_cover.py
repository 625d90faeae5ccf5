"""Shadow rays over a spherical Earth skip their chords where nothing stands over the ground they
cross on the way up (render/height_cover.h, Caster::cast_monotone): the sea far from the ships.
Where something does stand there -- towers casting long shadows under a low sun, the shadow rays
from their shadows crossing many of the grid's cells before they clear the towers' tops -- the
shortcut must not light what the towers shade."""

import math

import numpy as np

import refracta
from refracta import shading

SUN_ELEVATION = 5.0  # [deg]: a 40 m tower's shadow is 460 m long, 20 of the grid's 23 m cells
SUN_AZIMUTH = 30.0  # [deg] from +x toward +z: the shadow rays cross the grid's rows and columns


def tower_scene() -> refracta.Scene:
    scene = refracta.Scene()
    scene.add_ground(0.0, 3000.0, material=shading.Diffuse(0.5))
    rng = np.random.default_rng(3)
    for x, z, height in zip(rng.uniform(-500, 500, 10), rng.uniform(-500, 500, 10), rng.uniform(20.0, 60.0, 10)):
        scene.add_box((x, height / 2, z), (30.0, height, 30.0), kd=0.5)
    e, a = math.radians(SUN_ELEVATION), math.radians(SUN_AZIMUTH)
    sun = (math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a))
    scene.set_sun(sun, (2e5, 2e5, 2e5))  # disc radiance [W/(m^2 sr)]: lit ground 20x the shade
    scene.set_environment((0.02, 0.02, 0.02))
    return scene


def test_towers_shade_the_ground_as_the_traced_shadow_rays_say():
    scene = tower_scene()
    camera = refracta.Camera((0.0, 2500.0, 0.0), (0.0, 0.0, 0.001), (1.0, 0.0, 0.0), 40.0, 128, 128)
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere())
    common = dict(spp=2, transport="direct", progress=False)
    fast = refracta.render(scene, camera, field, **common)[..., 1]
    # The reference traces every ray by rk45: no ior floors, so no monotone chords and no cover.
    strict = refracta.render(scene, camera, field, trace="rk45", table=False, **common)[..., 1]
    lit = np.median(strict)
    shade_fast, shade_strict = fast < 0.5 * lit, strict < 0.5 * lit
    # The towers' shadows cover a few hundred pixels (10 towers, each ~2 x 12 pixels of shadow).
    assert shade_strict.sum() >= 150, shade_strict.sum()
    # The same pixels in shadow, but for the shadows' edges: the chords may stray a quarter pixel,
    # the sun's disc is sampled at 2 spp (a penumbra pixel may fall either side), so a few percent of
    # the shadows' pixels may flip. A tower the cover missed would light all of its ~25 pixels.
    assert (shade_fast != shade_strict).sum() <= 0.05 * shade_strict.sum()


def test_a_climb_over_clear_sea_through_a_thin_layer_keeps_the_escape_within_its_tolerance():
    # Without chords a clear climb's run (which turns its exit by run / R over the spherical Earth)
    # comes from a quadrature; a layer thinner than its samples' spacing must not move it. A mirror
    # sea under a sky whose radiance is 1000 sin(e) shows each reflected ray's exit elevation e;
    # the reflections leave at 0.5-1.5 deg through a 20 K inversion 1 m thick at 50 m, below the
    # objects' 60 m top (a mast far off to the side). A single quadrature from the sea to the sky
    # stepped over the layer and tilted exits by 0.13 pixels whatever the tolerance asked; the
    # gradient bound keeps each within the stray asked of it.
    scene = refracta.Scene()
    scene.add_ground(0.0, 60000.0, material=shading.Conductor())
    scene.add_box((3000.0, 30.0, 400.0), (10.0, 60.0, 10.0), kd=0.5)
    scene.set_sky(0.0, 1000.0)
    air = refracta.PhysicalAtmosphere(t_ground=278.15, inversion_dt=20.0, inversion_base=50.0, inversion_thickness=1.0)
    field = refracta.CurvedEarth(air)
    eye, look = np.array([0.0, 5.0, 0.0]), math.radians(-1.0)
    camera = refracta.Camera(eye, eye + [math.cos(look), math.sin(look), 0.0], vfov=1.0, width=16, height=64)
    common = dict(spp=1, transport="direct", progress=False, max_length=41000.0)
    strict = refracta.render(
        scene, camera, field, trace="rk45", table=False, tol=1e-6, sagitta=1e-4, sagitta_pixels=0.0, **common
    )[..., 1]
    pixel = math.radians(1.0) / camera.height
    for sagitta_pixels in (0.25, 0.02):
        fast = refracta.render(scene, camera, field, sagitta_pixels=sagitta_pixels, **common)[..., 1]
        # The exit's error in pixels: the radiance's, over dL/de = 1000 cos(e).
        exit_error = np.abs(fast - strict) / (1000.0 * np.cos(np.arcsin(strict / 1000.0))) / pixel
        # Each reflection may stray sagitta_pixels twice: its camera ray's and its own escape's.
        assert exit_error.max() <= 2.0 * sagitta_pixels, (sagitta_pixels, exit_error.max())
