"""Straight continuation above the bending air (issue 21 goal 4; render/caster_straight.cpp).

The rest of a shadow or bounce ray's path goes on as one straight line where the air cannot bend
it off that line by more than its tolerance: K L^2 / 2 <= a quarter of the pixel's footprint, K
the most |dn/dh| / n on the heights it can visit, L its remaining length. Judged against the
exact stratified trace: the camera, 800 m up, looks level into a mirror 30 m away that sends its
rays sideways to a wall 4 km off, bright above a metre over the eye's height and dark below. Each pixel must
show the half its exact reflected path meets, wherever that path meets the wall farther than the
tolerance from the edge."""

from __future__ import annotations

import numpy as np
import pytest

import refracta
from refracta import examples, shading

WIDTH, HEIGHT = 4, 16
EYE = np.array([0.0, 800.0, 0.0])
MIRROR = np.array([30.0, 800.0, 0.0])
MIRROR_NORMAL = np.array([-1.0, 0.0, 1.0]) / np.sqrt(2.0)  # turns the view (+x) to +z
WALL_Z = 4000.0  # the wall's face [m]
EDGE = 801.0  # bright above, dark below [m] (between the inversion's exact and straight row 7)
MAX_LENGTH = 6000.0
SAGITTA_PIXELS = 0.25  # RenderOptions.sagitta_pixels' default: a path may stray this much of a pixel


def mirror_scene():
    scene = refracta.Scene()
    examples.set_physical_sky(scene, examples.sun_direction(35.0, -150.0))
    along = np.array([1.0, 0.0, 1.0]) / np.sqrt(2.0)
    up = np.array([0.0, 1.0, 0.0])
    corners = [MIRROR + 20.0 * (a * along + b * up) for a, b in [(-1, -1), (1, -1), (1, 1), (-1, 1)]]
    scene.add_mesh(np.array(corners), np.array([[0, 1, 2], [0, 2, 3]]), material=shading.Conductor())
    scene.add_box((30.0, 0.5 * (EDGE + 1600.0), WALL_Z + 5.0), (4000.0, 1600.0 - EDGE, 10.0), kd=(0.9, 0.9, 0.9))
    scene.add_box((30.0, 0.5 * EDGE, WALL_Z + 5.0), (4000.0, EDGE, 10.0), kd=(0.02, 0.02, 0.02))
    scene.add_ground(0.0, 8000.0, kd=(0.3, 0.3, 0.3))
    camera = refracta.Camera(EYE, EYE + [1.0, 0.0, 0.0], vfov=2.0, width=WIDTH, height=HEIGHT)
    return scene, camera


AIRS = {
    # A 15 K hot road: 800 m up only the standard atmosphere's ~2.7e-8 / m bends the bounce rays,
    # 0.2 m over the 4 km to the wall: they go on straight.
    "hot_road": refracta.PhysicalAtmosphere(surface_dt=15.0, surface_depth=0.1),
    # A 10 K inversion 20 m thick around the eye's height (~1.3e-6 / m): it ducts the level rays,
    # so the bound must refuse and the rays be traced.
    "inversion_at_the_eye": refracta.PhysicalAtmosphere(
        inversion_dt=10.0, inversion_base=790.0, inversion_thickness=20.0
    ),
}


def wall_height(field, origin, direction):
    """Where the exact path from origin along direction meets the wall's face [m], and its length."""
    path = refracta.trace_ray(
        field, origin, direction, trace="stratified", tol=1e-9, max_length=MAX_LENGTH, stop_height=-1.0
    )
    crossing = path.crossings([0.0, 0.0, 1.0], WALL_Z)
    assert crossing, "the exact reflected path misses the wall"
    point, s, _ = crossing[0]
    return point[1], s


@pytest.mark.parametrize("air", list(AIRS))
def test_bounce_rays_meet_the_wall_where_their_exact_paths_do(air):
    scene, camera = mirror_scene()
    field = AIRS[air]
    image = refracta.render(scene, camera, field, max_length=MAX_LENGTH, progress=False)
    luminance = image @ np.array([0.2126, 0.7152, 0.0722])
    bright_level = np.sqrt(luminance.max() * luminance.min())  # the halves differ 45x in albedo
    judged = flips = 0
    for row in range(HEIGHT):
        for col in range(WIDTH):
            origin, direction = camera.ray(col + 0.5, row + 0.5)
            path = refracta.trace_ray(field, origin, direction, trace="stratified", tol=1e-9, max_length=100.0)
            point, _, incoming = path.crossings(MIRROR_NORMAL, MIRROR_NORMAL @ MIRROR)[0]
            reflected = incoming - 2.0 * (incoming @ MIRROR_NORMAL) * MIRROR_NORMAL
            y, s = wall_height(field, point, reflected)
            # The bounce ray may stray a quarter of the camera's pixel footprint, counted from the
            # mirror (caster.h set_secondary_spread); 1 cm more for the camera ray's 30 m leg.
            tolerance = SAGITTA_PIXELS * camera.pixel_angle * s + 0.01
            if abs(y - EDGE) <= tolerance:
                continue  # within the tolerance of the edge: either half is right
            judged += 1
            assert (luminance[row, col] > bright_level) == (y > EDGE), f"pixel ({col}, {row}): exact path at {y:.2f} m"
            # A straight line from the mirror would meet the wall at:
            straight = point[1] + reflected[1] / reflected[2] * (WALL_Z - point[2])
            flips += abs(straight - EDGE) > tolerance and (straight > EDGE) != (y > EDGE)
    assert judged >= WIDTH * HEIGHT // 2
    if air == "inversion_at_the_eye":
        # The test has teeth: here a straight line would show the wrong half.
        assert flips > 0
