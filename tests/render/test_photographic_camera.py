"""Camera.photographic: a lens of focal length f on a sensor, checked by the pinhole's magnification
(an object of size X at distance D images to f X / D on the sensor)."""

import math

import pytest

import refracta

ROUND_OFF = 1e-9  # [px] projection through the camera's double-precision frame


@pytest.mark.parametrize(
    "focal, sensor, size",
    [(50.0, (36.0, 24.0), (960, 640)), (300.0, (36.0, 24.0), (1920, 1080)), (24.0, (23.5, 15.6), (600, 800))],
)
def test_an_object_images_at_focal_length_times_its_angle(focal, sensor, size):
    width, height = size
    camera = refracta.Camera.photographic((0, 5, 0), (1000, 5, 0), focal, sensor_mm=sensor, width=width, height=height)
    # The image spans the sensor's width if relatively wider, else its height: the pixel pitch [mm].
    pitch = sensor[0] / width if width * sensor[1] >= height * sensor[0] else sensor[1] / height
    distance, offset = 1000.0, 7.0  # [m]: a point 7 m to the right of and above the axis at 1 km
    right = camera.project((distance, 5, offset))  # +z is the image's right here
    up = camera.project((distance, 5 + offset, 0))
    expected = focal * offset / distance / pitch  # [px] on the sensor
    assert right[0] - width / 2 == pytest.approx(expected, abs=ROUND_OFF)
    assert height / 2 - up[1] == pytest.approx(expected, abs=ROUND_OFF)


def test_a_300_mm_telephoto_on_full_frame_sees_under_5_degrees():
    camera = refracta.Camera.photographic((0, 5, 0), (28000, 5, 0), 300.0, width=960, height=640)
    # The same atan in double: rounding.
    assert camera.vfov == pytest.approx(2 * math.degrees(math.atan(12.0 / 300.0)), rel=1e-12)


@pytest.mark.parametrize(
    "arguments, name",
    [
        (dict(focal_length_mm=0.0), "focal_length_mm"),
        (dict(focal_length_mm=float("nan")), "focal_length_mm"),
        (dict(focal_length_mm=-50.0), "focal_length_mm"),
        (dict(focal_length_mm=50.0, sensor_mm=(0.0, 24.0)), "sensor_mm"),
        (dict(focal_length_mm=50.0, sensor_mm=(36.0, float("inf"))), "sensor_mm"),
    ],
)
def test_impossible_lenses_and_sensors_are_refused(arguments, name):
    with pytest.raises(ValueError, match=name):
        refracta.Camera.photographic((0, 5, 0), (10, 5, 0), **arguments)


# --- Camera.eye_level: a photographer's level view toward a target ---------------------------------


def test_eye_level_stands_at_eye_height_and_puts_the_horizon_on_the_centre_row():
    ground, target, height = (3.0, 0.5, -2.0), (103.0, 0.2, -2.0 - 100.0), 1.6
    camera = refracta.Camera.eye_level(ground, target, eye_height=height, focal_length_mm=200.0, width=640, height=240)
    assert camera.position.tolist() == [3.0, 0.5 + height, -2.0]
    # Points at eye height far away (a flat Earth's horizon), across the whole view: the centre row.
    for azimuth_offset in (-2.0, 0.0, 2.5):  # [deg] about the target's direction, inside the 10.3 deg view
        a = math.radians(45.0 + azimuth_offset)  # the target lies 45 deg from -z toward +x
        far = (3.0 + 1e6 * math.sin(a), 0.5 + height, -2.0 - 1e6 * math.cos(a))
        u, v, depth = camera.project(far)
        assert depth > 0 and 0 <= u <= 640
        assert v == pytest.approx(120.0, abs=ROUND_OFF)
    # The target's direction is the centre column; a target below the eye images below the centre
    # by f (eye - target height) / distance on the sensor.
    u, v, depth = camera.project(target)
    pitch = 36.0 / 640  # [mm]: 640 x 240 is relatively wider than the sensor
    distance = math.hypot(100.0, 100.0)
    assert u == pytest.approx(320.0, abs=ROUND_OFF)
    assert depth == pytest.approx(distance, rel=1e-12)  # hypot in double: rounding
    assert v - 120.0 == pytest.approx(200.0 * (0.5 + height - 0.2) / distance / pitch, abs=ROUND_OFF)
    # The same computation twice: rounding.
    assert camera.vfov == pytest.approx(
        refracta.Camera.photographic((0, 0, 0), (1, 0, 0), 200.0, width=640, height=240).vfov, rel=1e-15
    )


def test_eye_level_focuses_at_the_target_distance():
    camera = refracta.Camera.eye_level((0, 0, 0), (30.0, 5.0, 40.0), focal_length_mm=85.0, f_number=1.8)
    # the level distance hypot(30, 40) = 50: double rounding.
    assert camera.focus_distance == pytest.approx(50.0, rel=1e-15)
    assert camera.aperture_diameter == pytest.approx(0.085 / 1.8, rel=1e-15)  # 0.085 / 1.8 in double: rounding
    assert (
        refracta.Camera.eye_level((0, 0, 0), (30.0, 5.0, 40.0), f_number=1.8, focus_distance=7.0).focus_distance == 7.0
    )


@pytest.mark.parametrize(
    "arguments, name",
    [
        (dict(eye_height=0.0), "eye_height"),
        (dict(eye_height=float("nan")), "eye_height"),
        (dict(target=(0.0, 50.0, 0.0)), "target"),
        (dict(focal_length_mm=-1.0), "focal_length_mm"),
        (dict(f_number=0.0), "f_number"),
    ],
)
def test_eye_level_refuses_impossible_views(arguments, name):
    kwargs = dict(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -100.0))
    kwargs.update(arguments)
    with pytest.raises(ValueError, match=name):
        refracta.Camera.eye_level(**kwargs)
