"""Camera.photographic: a lens of focal length f on a sensor, checked by the pinhole's magnification
(an object of size X at distance D images to f X / D on the sensor)."""

import math

import pytest

import refracta

ROUND_OFF = 1e-9  # [px] projection through the camera's double-precision frame


@pytest.mark.parametrize("focal, sensor, size", [(50.0, (36.0, 24.0), (960, 640)), (300.0, (36.0, 24.0), (1920, 1080)),
                                                 (24.0, (23.5, 15.6), (600, 800))])
def test_an_object_images_at_focal_length_times_its_angle(focal, sensor, size):
    width, height = size
    camera = refracta.Camera.photographic((0, 5, 0), (1000, 5, 0), focal, sensor_mm=sensor, width=width,
                                          height=height)
    # The image spans the sensor's width if relatively wider, else its height: the pixel pitch [mm].
    pitch = sensor[0] / width if width * sensor[1] >= height * sensor[0] else sensor[1] / height
    distance, offset = 1000.0, 7.0  # [m]: a point 7 m to the right of and above the axis at 1 km
    right = camera.project((distance, 5, offset))       # +z is the image's right here
    up = camera.project((distance, 5 + offset, 0))
    expected = focal * offset / distance / pitch          # [px] on the sensor
    assert right[0] - width / 2 == pytest.approx(expected, abs=ROUND_OFF)
    assert height / 2 - up[1] == pytest.approx(expected, abs=ROUND_OFF)


def test_a_300_mm_telephoto_on_full_frame_sees_under_5_degrees():
    camera = refracta.Camera.photographic((0, 5, 0), (28000, 5, 0), 300.0, width=960, height=640)
    assert camera.vfov == pytest.approx(2 * math.degrees(math.atan(12.0 / 300.0)), rel=1e-12)


@pytest.mark.parametrize("arguments, name", [(dict(focal_length_mm=0.0), "focal_length_mm"),
                                             (dict(focal_length_mm=float("nan")), "focal_length_mm"),
                                             (dict(focal_length_mm=-50.0), "focal_length_mm"),
                                             (dict(focal_length_mm=50.0, sensor_mm=(0.0, 24.0)), "sensor_mm"),
                                             (dict(focal_length_mm=50.0, sensor_mm=(36.0, float("inf"))), "sensor_mm")])
def test_impossible_lenses_and_sensors_are_refused(arguments, name):
    with pytest.raises(ValueError, match=name):
        refracta.Camera.photographic((0, 5, 0), (10, 5, 0), **arguments)
