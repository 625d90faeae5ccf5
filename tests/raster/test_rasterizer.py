"""The CPU rasterizer against Embree ray casting (an independent reference at pixel centres),
and the rasterization rules: near clipping, guard band, top-left fill, perspective correction."""

import numpy as np
import pytest

import refracta
from refracta.raster import rasterize

DEPTH_REL = 1e-6  # depth is stored as float32 (relative precision 6e-8); interpolation adds round-off


def boxes_scene():
    scene = refracta.Scene()
    scene.add_ground(0.0, 5000.0)
    for x, z, h in [(30.0, -3.0, 4.0), (55.0, 4.0, 7.0), (120.0, -10.0, 15.0), (12.0, 1.5, 1.0)]:
        scene.add_box((x, h / 2, z), (4.0, h, 3.0))
    return scene


CAMERA = refracta.Camera((0.0, 1.6, 0.0), (50.0, 1.0, 0.5), (0, 1, 0), 40.0, 96, 64)


def test_depth_and_points_match_ray_casting_at_pixel_centres():
    scene = boxes_scene()
    buffers = rasterize(scene, CAMERA)
    forward = CAMERA.ray(48.0, 32.0)[1]
    mismatched = 0
    for y in range(CAMERA.height):
        for x in range(CAMERA.width):
            origin, direction = CAMERA.ray(x + 0.5, y + 0.5)
            hit = scene.intersect(origin, direction)
            if hit is None:
                mismatched += np.isfinite(buffers.depth[y, x])
                continue
            point, _, geometry = hit
            depth = np.dot(point - origin, forward)
            assert buffers.geometry[y, x] == geometry
            assert abs(buffers.depth[y, x] - depth) <= DEPTH_REL * depth
    assert mismatched == 0


def test_barycentrics_are_perspective_correct():
    """A ground plane seen at a grazing angle: screen-linear interpolation would miss by metres;
    the barycentrics rebuild the ray-cast point on the two ground triangles."""
    scene = refracta.Scene()
    scene.add_ground(0.0, 1000.0)
    camera = refracta.Camera((0.0, 1.5, 0.0), (100.0, 0.0, 0.0), (0, 1, 0), 30.0, 64, 48)
    buffers = rasterize(scene, camera)
    corners = 500.0 * np.array([[-1.0, 0, -1], [1, 0, -1], [1, 0, 1], [-1, 0, 1]])  # side 1000 m
    triangles = [(0, 2, 1), (0, 3, 2)]
    for y in range(30, 48, 3):
        for x in range(0, 64, 7):
            origin, direction = camera.ray(x + 0.5, y + 0.5)
            point = scene.intersect(origin, direction)[0]
            rebuilt = buffers.barycentric[y, x] @ corners[list(triangles[buffers.primitive[y, x]])]
            assert np.linalg.norm(rebuilt - point) < 1e-4 * np.linalg.norm(point - origin)


def test_a_plane_through_the_eye_level_is_clipped_cleanly():
    """The ground reaches behind the camera: near clipping keeps every row below the horizon
    covered and every row above it empty (the horizon of a level camera is the centre line)."""
    scene = refracta.Scene()
    scene.add_ground(0.0, 1e6)
    camera = refracta.Camera((0.0, 2.0, 0.0), (1.0, 2.0, 0.0), (0, 1, 0), 60.0, 80, 40)
    covered = rasterize(scene, camera).geometry >= 0
    assert not covered[:20].any()
    assert covered[21:].all()


def test_shared_edges_are_drawn_exactly_once():
    """Top-left rule: a pixel-aligned square of two triangles facing the camera gets one fragment
    per covered pixel, none twice."""
    scene = refracta.Scene()
    # An orthographic-like square 10 m ahead filling the middle of a 60 deg, 40 x 40 camera.
    half = 10.0 * np.tan(np.radians(30.0)) * 0.5
    scene.add_mesh(
        [[10.0, -half, -half], [10.0, -half, half], [10.0, half, half], [10.0, half, -half]], [[0, 1, 2], [0, 2, 3]]
    )
    camera = refracta.Camera((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0, 1, 0), 60.0, 40, 40)
    buffers = rasterize(scene, camera)
    covered = buffers.geometry >= 0
    assert covered.sum() == buffers.fragments == 400  # the middle 20 x 20 pixels
    assert covered[10:30, 10:30].all()


def test_the_guard_band_widens_the_view_around_the_same_pixels():
    scene = boxes_scene()
    plain = rasterize(scene, CAMERA)
    wide = rasterize(scene, CAMERA, guard_band=0.25)
    ox, oy = wide.offset
    assert (ox, oy) == (24, 16)
    assert wide.depth.shape == (64 + 2 * oy, 96 + 2 * ox)
    # Float32 depth buffers, the wider frustum's different rounding: 1e-6.
    np.testing.assert_allclose(wide.depth[oy : oy + 64, ox : ox + 96], plain.depth, rtol=1e-6)


def test_an_empty_scene_draws_nothing():
    buffers = rasterize(refracta.Scene(), CAMERA)
    assert np.isinf(buffers.depth).all() and (buffers.geometry == -1).all()


def test_bad_arguments_raise_value_error():
    with pytest.raises(ValueError, match="guard_band"):
        rasterize(boxes_scene(), CAMERA, guard_band=-0.1)
    with pytest.raises(ValueError, match="tile"):
        rasterize(boxes_scene(), CAMERA, tile=0)


# The sphere's mean radiance, raster against the ray tracer's at 1024 spp: they differ by 2.2 %
# (the tessellated silhouette's edge pixels and the raster's own sky sampling); a sphere shadowed
# by itself was black (100 % off).
SPHERE_AGAINST_RAY_TRACER = 0.05


def test_a_sphere_is_lit_and_shadowed_as_the_ray_tracer_sees_it():
    # Its tessellation lies inside the exact sphere Embree intersects: shadow rays from the
    # tessellation met the sphere from inside, and every sphere was black under the sky.
    scene = refracta.Scene()
    scene.add_ground(0.0, 100.0)
    sphere = scene.add_sphere((5.0, 1.0, 0.0), 1.0)
    scene.set_sky((0.5, 0.6, 0.8), (0.2, 0.3, 0.7))
    camera = refracta.Camera((6.0, 8.0, -6.0), (5.0, 1.0, 0.0), (0.0, 1.0, 0.0), 30.0, 40, 30)
    reference, aovs = refracta.render(
        scene, camera, None, method="straight", spp=1024, aovs=["object_id"], progress=False
    )
    on = aovs["object_id"] == sphere
    raster = refracta.render_raster(scene, camera)
    assert raster[on].mean() == pytest.approx(reference[on].mean(), rel=SPHERE_AGAINST_RAY_TRACER)

    # Under a sun straight above, its upper half is lit: Embree's shadow rays agree with the maps'.
    scene.add_light(refracta.lights.SunLight((0.0, 1.0, 0.0), 10.0))
    shadowed = {
        method: refracta.render_raster(scene, camera, shadows=method, output="shadow")[on]
        for method in ("embree", "hard")
    }
    np.testing.assert_array_equal(shadowed["embree"], shadowed["hard"])
