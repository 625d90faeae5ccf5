"""The physics shows in the image: mirage boundaries, traced rays landing on their pixels."""

import numpy as np
import pytest

import refracta

EYE = 1.5
SKY = (0.8, 0.8, 0.8)
GROUND = (0.2, 0.2, 0.2)


# Basic radiance L / n^2 is conserved along rays (Ament et al. 2014): between the hot road
# (n - 1 about 2.6e-4) and the air the eye and the sky are in, radiance changes by (n_a / n_b)^2,
# within 1e-3 of 1; ground (0.16) and sky (0.8) stay far apart.
AIR_RADIANCE_RATIO = 1e-3


def flat_scene():
    """A ground plane under a constant sky, no sun: ground pixels have radiance kd * sky (the
    constant sky is sampled by cosine, so unoccluded Lambertian ground is exact at 1 spp)."""
    scene = refracta.Scene()
    scene.add_ground(0.0, 40000.0, kd=GROUND)
    scene.set_sky(SKY, SKY)
    return scene


def pixel_depressions(camera, column):
    return np.array([-np.degrees(np.arcsin(camera.ray(column + 0.5, v + 0.5)[1][1])) for v in range(camera.height)])


def test_sky_ground_boundary_lies_at_the_critical_depression(hot_road):
    camera = refracta.Camera(
        [0, EYE, 0], [1000, EYE - 1000 * np.tan(np.radians(0.3)), 0], vfov=1.2, width=24, height=96
    )
    image = refracta.render(flat_scene(), camera, hot_road, progress=False)
    n_ground, n_eye = hot_road.ior(np.array([[0, 0, 0], [0, EYE, 0]], dtype=float))
    theta_c = np.degrees(np.arccos(n_ground / n_eye))
    pixel = camera.vfov / camera.height  # one pixel [deg] (uniform enough over a 1.2 deg field)
    ground_value = GROUND[0] * SKY[0]
    for column in range(camera.width):
        is_ground = np.isclose(image[:, column, 0], ground_value, rtol=AIR_RADIANCE_RATIO)
        first = int(np.argmax(is_ground))
        assert is_ground[first] and np.all(is_ground[first:]), "ground below the boundary"
        depression = pixel_depressions(camera, column)
        # The boundary is at theta_c: the first ground pixel's centre lies within one pixel of it.
        assert abs(depression[first] - theta_c) <= pixel, (column, depression[first], theta_c)
    # Without the atmosphere the ground starts right below the horizon (depression 0).
    straight = refracta.render(flat_scene(), camera, None, progress=False)
    first_straight = int(np.argmax(np.isclose(straight[:, 0, 0], ground_value, rtol=AIR_RADIANCE_RATIO)))
    assert abs(pixel_depressions(camera, 0)[first_straight]) <= pixel
    assert first - first_straight >= int(0.8 * theta_c / pixel)  # the mirage band is there


def test_a_traced_ray_lands_on_the_pixel_that_shows_its_colour(hot_road):
    # A wall 300 m away, glowing red below 1 m and blue above: through the hot road its inverted
    # image appears below; the colour at each pixel must be the stripe trace_ray's path meets.
    # Emitters seen directly (max_depth 0): the colour is the geometry's alone, no lighting noise.
    scene = refracta.Scene()
    scene.add_ground(0.0, 40000.0, kd=(0.1, 0.1, 0.1))
    scene.add_box([301, 0.5, 0], [2, 1, 60], emission=(0.9, 0.0, 0.0))
    scene.add_box([301, 2.0, 0], [2, 2, 60], emission=(0.0, 0.0, 0.9))
    scene.set_sky((1, 1, 1), (1, 1, 1))
    camera = refracta.Camera([0, EYE, 0], [300, 0.8, 0], vfov=0.8, width=8, height=64)
    image = refracta.render(scene, camera, hot_road, progress=False, max_depth=0)
    checked = 0
    for v in range(camera.height):
        origin, direction = camera.ray(4.5, v + 0.5)
        path = refracta.trace_ray(
            hot_road, origin, direction, trace="stratified", tol=1e-6, max_length=400, stop_height=0.0
        )
        crossing = path.crossings([1, 0, 0], 300.0)
        if path.stop == "stop_height" and not crossing:
            continue  # reaches the road before the wall
        if not crossing:
            continue
        height = crossing[0][0][1]
        if abs(height - 1.0) < 0.02 or height > 2.95:
            continue  # at a stripe edge or above the wall
        colour = image[v, 4]
        expected_red = height < 1.0
        assert (colour[0] > colour[2]) == expected_red, (v, height, colour)
        checked += 1
    assert checked > 20


def test_uniform_field_renders_like_straight_rays():
    scene = refracta.Scene()
    scene.add_ground(0.0, 2000.0, kd=(0.3, 0.3, 0.3))
    scene.add_box([40, 1, 0], [2, 2, 2], kd=(0.8, 0.2, 0.1), ks=(0.2, 0.2, 0.2), ns=30)
    scene.add_sphere([25, 1, -4], 1.0, kd=(0.1, 0.7, 0.2))
    scene.set_sun([0.4, 0.6, 0.3], [1e4, 1e4, 1e4])
    camera = refracta.Camera([0, 2, 0], [40, 1, 0], vfov=30, width=64, height=40)
    straight = refracta.render(scene, camera, None, method="straight", progress=False)
    uniform = refracta.LinearSquaredProfile(n0=1.0003, alpha=0.0)
    curved = refracta.render(scene, camera, uniform, method="curved", progress=False)
    differs = np.any(np.abs(curved - straight) > 1e-4 * (1 + straight), axis=2)
    assert differs.mean() <= 0.01  # float chord joints may flip a silhouette pixel, nothing more
    assert np.array_equal(refracta.render(scene, camera, None, method="curved", progress=False), straight)


def test_empty_scene_renders_the_sky():
    scene = refracta.Scene()
    scene.set_sky((0.5, 0.6, 0.7), (0.1, 0.2, 0.9))
    camera = refracta.Camera([0, 1, 0], [10, 1, 0], vfov=90, width=16, height=16)
    image = refracta.render(scene, camera, refracta.PhysicalAtmosphere(), progress=False)
    # Upper rows: between horizon and zenith colours; lower rows (below the horizon): horizon colour.
    np.testing.assert_allclose(image[-1, 8], (0.5, 0.6, 0.7), atol=1e-6)
    assert image[0, 8, 2] > 0.7


def test_spp_and_seed_are_reproducible():
    scene = flat_scene()
    scene.add_sphere([10, 1, 0], 1.0)
    scene.set_sun([0, 1, 0.2], [1e4, 1e4, 1e4])
    camera = refracta.Camera([0, 1, 0], [10, 1, 0], vfov=20, width=16, height=12)
    a = refracta.render(scene, camera, spp=4, seed=3, progress=False)
    b = refracta.render(scene, camera, spp=4, seed=3, progress=False)
    c = refracta.render(scene, camera, spp=4, seed=4, progress=False)
    assert np.array_equal(a, b) and not np.array_equal(a, c)


@pytest.mark.parametrize("name", ["hot_road", "cold_sea"])
def test_table_rendering_matches_tracing_every_pixel(name):
    from refracta import examples

    example = getattr(examples, name)(64, 24)
    options = dict(progress=False, max_length=example.max_length)
    table = refracta.render(example.scene, example.camera, example.field, **options)
    traced = refracta.render(example.scene, example.camera, example.field, table=False, **options)
    # A pixel differs when it changes by more than 1 % of its radiance: the examples' radiance is in
    # W/(m^2 sr) (up to ~2000 in the cold sea's glitter), where the paths' interpolation moves a hit
    # by a fraction of a millimetre and changes the radiance by ~1e-5 of itself -- not a flip.
    scale = np.maximum(table, traced).max(axis=2, keepdims=True)
    differs = np.any(np.abs(table - traced) > 1e-2 * scale, axis=2)
    # The table interpolates paths to a quarter pixel: at most an edge pixel may flip (measured
    # 0.8 % of the hot road's 64 x 24 pixels, in its mirage band's rows; none over the cold sea).
    assert differs.mean() <= 0.01, differs.mean()
