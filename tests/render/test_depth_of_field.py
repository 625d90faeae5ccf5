"""Thin-lens depth of field (Camera.photographic(f_number=, focus_distance=)): the blur of an edge
out of focus against the thin-lens circle of confusion, sharpness in focus, Mitsuba 3's thinlens
sensor on the same scene, determinism across tiles, and refused lenses.

The scene: a constant environment of radiance 1 and a black (kd = 0) plate covering x < 0 at
depth d, seen straight (field=None) along -z by a 100 mm lens on full frame. A uniform disc of
radius R [px] blurs the edge into the fraction of the disc on the bright side; with the pixel's
box filter that is the model fitted to each render's column profile (mean over its rows).

The thin-lens circle of confusion on the sensor is c = A f |d - d_f| / (d (d_f - f)) [mm]
(A = f / N). refracta keeps the field of view of focus at infinity (no focus breathing: the image
is the sensor scaled by f / v = (d_f - f) / d_f, v the image distance), so in pixels
c_px = c (d_f - f) / d_f / pitch = A f |d - d_f| / (d d_f) / pitch, pitch = sensor width / W.
"""

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import refracta

WIDTH, HEIGHT = 320, 48
FOCAL = 100.0  # [mm]
SENSOR = 36.0  # [mm], the width the image spans (320 x 48 is relatively wider than 3:2)
EYE, LOOK = (0.0, 1.0, 0.0), (0.0, 1.0, -10.0)
SPP = 256
# The fitted blur radius against the thin-lens one: the 256 independent lens samples per pixel,
# averaged over 48 rows, leave a ~0.5 % scatter in the fitted radius (measured over 3 seeds x 3
# cases: at most 0.58 %); 3 % also covers the pixel-box model's sub-sampling (64 positions per pixel).
RADIUS_REL = 0.03
# In focus the lens's rays of a pixel sample meet the plate where the pinhole's ray does, up to
# the rounding of the two paths' arithmetic: the images agree to float32 rounding, save pixels
# whose sample lands within rounding of the edge (none here).
IN_FOCUS = 1e-6


def plate_scene(depth):
    scene = refracta.Scene()
    scene.set_environment((1.0, 1.0, 1.0))
    # A 1 mm thick black plate whose front face is at depth `depth`, its right edge at x = 0.
    scene.add_box((-5.0, 1.0, -depth - 0.0005), (10.0, 10.0, 0.001), kd=(0.0, 0.0, 0.0))
    return scene


def lens_camera(f_number=None, focus=None, width=WIDTH, height=HEIGHT):
    return refracta.Camera.photographic(
        EYE, LOOK, FOCAL, width=width, height=height, f_number=f_number, focus_distance=focus
    )


def thin_lens_coc_pixels(f_number, focus, depth):
    """The circle of confusion c = A f |d - d_f| / (d (d_f - f)) [mm] in pixels of the unbreathing image."""
    f = FOCAL * 1e-3  # [m]
    aperture = f / f_number
    coc_mm = aperture * FOCAL * abs(depth - focus) / (depth * (focus - f))
    pitch = SENSOR / WIDTH
    return coc_mm * (focus - f) / focus / pitch


def disc_edge(x, radius):
    """Fraction of a disc of `radius` centred at x lying at positions > 0."""
    if radius <= 0:
        return (x > 0).astype(float)
    t = np.clip(x / radius, -1.0, 1.0)
    return 1.0 - (np.arccos(t) - t * np.sqrt(1.0 - t * t)) / np.pi


def model_profile(radius, columns):
    # Pixel i covers u in [i, i + 1); the edge is at u = WIDTH / 2. Box filter: 64 positions.
    offsets = (np.arange(64) + 0.5) / 64
    u = columns[:, None] + offsets[None, :]
    return disc_edge(u - WIDTH / 2, radius).mean(axis=1)


def fitted_radius(image):
    profile = image[:, :, 1].mean(axis=0)
    columns = np.arange(WIDTH, dtype=float)
    result = minimize_scalar(
        lambda r: np.sum((model_profile(r, columns) - profile) ** 2),
        bounds=(0.01, 60.0),
        method="bounded",
        options={"xatol": 1e-4},
    )
    return result.x


@pytest.mark.parametrize(
    "f_number, focus, depth",
    [
        (2.0, 10.0, 3.0),  # in front of focus
        (2.0, 10.0, 40.0),  # behind it
        (5.6, 4.0, 1.5),
    ],
)  # stopped down, close up
def test_blur_of_an_edge_is_the_thin_lens_circle_of_confusion(f_number, focus, depth):
    image = refracta.render(
        plate_scene(depth), lens_camera(f_number, focus), None, method="straight", spp=SPP, progress=False
    )
    expected = 0.5 * thin_lens_coc_pixels(f_number, focus, depth)
    assert fitted_radius(image) == pytest.approx(expected, rel=RADIUS_REL)


def test_the_plane_in_focus_is_as_sharp_as_through_a_pinhole():
    scene = plate_scene(10.0)
    pinhole = refracta.render(scene, lens_camera(), None, method="straight", spp=16, progress=False)
    lens = refracta.render(scene, lens_camera(1.4, 10.0), None, method="straight", spp=16, progress=False)
    np.testing.assert_allclose(lens, pinhole, atol=IN_FOCUS)


def test_focus_defaults_to_the_look_at_distance_and_aperture_is_f_over_n():
    camera = refracta.Camera.photographic(EYE, (0.0, 1.0, -7.5), 50.0, f_number=2.8)
    assert camera.focus_distance == pytest.approx(7.5, rel=1e-15)  # the look-at distance in double: rounding
    assert camera.aperture_diameter == pytest.approx(0.05 / 2.8, rel=1e-15)  # 0.05 / 2.8 in double: rounding
    pinhole = refracta.Camera.photographic(EYE, (0.0, 1.0, -7.5), 50.0)
    assert pinhole.aperture_diameter == 0.0 and pinhole.focus_distance == 0.0


def test_lens_renders_do_not_depend_on_tiles_or_pixel_bounds():
    scene = plate_scene(3.0)
    camera = lens_camera(2.0, 10.0, 64, 16)
    whole = refracta.render(scene, camera, None, method="straight", spp=4, progress=False)
    tiled = refracta.render(scene, camera, None, method="straight", spp=4, progress=False, tile=3)
    part = refracta.render(scene, camera, None, method="straight", spp=4, progress=False, pixel_bounds=(20, 4, 50, 12))
    np.testing.assert_array_equal(whole, tiled)
    np.testing.assert_array_equal(whole[4:12, 20:50], part)  # the part comes back cropped


def test_lens_renders_do_not_depend_on_the_thread_count():
    scene = plate_scene(3.0)
    camera = lens_camera(2.0, 10.0, 64, 16)
    threads = refracta.get_threads()
    try:
        refracta.set_threads(1)
        single = refracta.render(scene, camera, None, method="straight", spp=9, progress=False)
    finally:
        refracta.set_threads(threads)
    np.testing.assert_array_equal(
        single, refracta.render(scene, camera, None, method="straight", spp=9, progress=False)
    )


def test_stratified_lens_samples_cover_the_lens():
    # 16 samples a pixel: the lens cells are a shuffled 4 x 4 grid, so a blurred edge's pixels
    # scatter less than with independent lens points. Against the exact disc model the column
    # profile's RMS error over the edge, mean of 4 seeds: 0.0048 stratified, 0.0092 independent
    # (the pixels' spread 0.037 against 0.069). Bound: half the binomial error of independent
    # points, sqrt(p (1 - p) / (48 x 16)) / 2 at p = 1/2, 0.009 (the render is seeded: no flakiness).
    image = refracta.render(plate_scene(3.0), lens_camera(2.0, 10.0), None, method="straight", spp=16, progress=False)
    columns = np.arange(WIDTH, dtype=float)
    model = model_profile(0.5 * thin_lens_coc_pixels(2.0, 10.0, 3.0), columns)
    error = image[:, :, 1].mean(axis=0) - model
    assert np.sqrt(np.mean(error[150:170] ** 2)) < 0.5 * math.sqrt(0.25 / (HEIGHT * 16))


def test_lens_renders_through_a_field_do_not_depend_on_tiles():
    # Through a height-only field a lens's rays leave the lens, off the eye: traced, not tabulated.
    scene = refracta.Scene()
    scene.set_environment((1.0, 1.0, 1.0))
    scene.add_ground(0.0, kd=(0.4, 0.4, 0.4))
    scene.add_box((-5.0, 2.5, -30.0), (10.0, 5.0, 0.001), kd=(0.0, 0.0, 0.0))
    field = refracta.LogisticProfile()
    camera = lens_camera(2.0, 10.0, 48, 16)
    whole = refracta.render(scene, camera, field, spp=2, progress=False)
    tiled = refracta.render(scene, camera, field, spp=2, progress=False, tile=5)
    np.testing.assert_array_equal(whole, tiled)


def test_pickled_lens_camera_renders_the_same():
    import pickle

    camera = lens_camera(2.0, 10.0, 32, 8)
    copy = pickle.loads(pickle.dumps(camera))
    assert copy.aperture_diameter == camera.aperture_diameter and copy.focus_distance == camera.focus_distance
    scene = plate_scene(3.0)
    np.testing.assert_array_equal(
        refracta.render(scene, camera, None, method="straight", spp=4, progress=False),
        refracta.render(scene, copy, None, method="straight", spp=4, progress=False),
    )


@pytest.mark.parametrize(
    "arguments, name",
    [
        (dict(f_number=0.0), "f_number"),
        (dict(f_number=-2.0), "f_number"),
        (dict(f_number=float("nan")), "f_number"),
        (dict(f_number=2.0, focus_distance=0.0), "focus_distance"),
        (dict(f_number=2.0, focus_distance=float("nan")), "focus_distance"),
        (dict(f_number=2.0, focus_distance=-3.0), "focus_distance"),
    ],
)
def test_impossible_lens_settings_are_refused(arguments, name):
    with pytest.raises(ValueError, match=name):
        refracta.Camera.photographic(EYE, LOOK, 50.0, **arguments)


def test_rasterizers_refuse_a_lens():
    # They draw through a pinhole: a lens would be silently ignored.
    with pytest.raises(ValueError, match="raster_march"):
        refracta.render(
            plate_scene(3.0),
            lens_camera(2.0, 10.0, 16, 8),
            refracta.LogisticProfile(),
            method="raster_march",
            progress=False,
        )
    with pytest.raises(ValueError, match="render_raster draws through a pinhole"):
        refracta.render_raster(plate_scene(3.0), lens_camera(2.0, 10.0, 16, 8))


# --- Mitsuba 3's thinlens sensor on the same scene -------------------------------------------------

# Both fits' scatter (~1 % each, above) and Mitsuba's float32: the two radii agree within 3 %.
MITSUBA_RADIUS_REL = 0.03
# Column profiles: each column mean averages 48 x 256 lens samples per renderer; the binomial
# standard error of a fraction p is sqrt(p (1 - p) / 12288) <= 0.0045 per renderer, so their
# difference has sigma <= 0.0064; 5 sigma over 320 columns leaves a ~2e-4 false alarm.
PROFILE_ABS = 5 * math.sqrt(2 * 0.25 / (HEIGHT * SPP))


def test_blur_matches_mitsuba_thinlens():
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    f_number, focus, depth = 2.0, 10.0, 3.0
    camera = lens_camera(f_number, focus)
    aperture = FOCAL * 1e-3 / f_number
    scene = mi.load_dict(
        {
            "type": "scene",
            "integrator": {"type": "path", "max_depth": 2},
            "sensor": {
                "type": "thinlens",
                "fov": camera.vfov,
                "fov_axis": "y",
                "aperture_radius": aperture / 2,
                "focus_distance": focus,
                "to_world": mi.ScalarTransform4f().look_at(origin=EYE, target=LOOK, up=(0, 1, 0)),
                "film": {
                    "type": "hdrfilm",
                    "width": WIDTH,
                    "height": HEIGHT,
                    "rfilter": {"type": "box"},
                    "pixel_format": "rgb",
                },
                "sampler": {"type": "independent", "sample_count": SPP},
            },
            "light": {"type": "constant", "radiance": {"type": "rgb", "value": [1.0, 1.0, 1.0]}},
            # The plate: a rectangle [-1, 1]^2 scaled to 10 x 10 m, centred at (-5, 1, -depth), facing +z.
            "plate": {
                "type": "rectangle",
                "to_world": mi.ScalarTransform4f().translate((-5.0, 1.0, -depth)).scale((5.0, 5.0, 1.0)),
                "bsdf": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.0, 0.0, 0.0]}},
            },
        }
    )
    theirs = np.array(mi.render(scene, seed=1))
    ours = refracta.render(plate_scene(depth), camera, None, method="straight", spp=SPP, progress=False)
    assert fitted_radius(ours) == pytest.approx(fitted_radius(theirs), rel=MITSUBA_RADIUS_REL)
    np.testing.assert_allclose(ours[:, :, 1].mean(axis=0), theirs[:, :, 1].mean(axis=0), atol=PROFILE_ABS)
