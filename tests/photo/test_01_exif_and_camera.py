"""refracta.photo.load: pixels through OpenImageIO, EXIF through Pillow (written here by Pillow),
orientation applied as Pillow's exif_transpose does, and the field of view it gives a Camera."""

import dataclasses
import math

import numpy as np
import pytest
from PIL import Image, ImageOps, TiffImagePlugin

import refracta
from refracta import photo

STORED_H, STORED_W = 20, 30  # pixels of the JPEG as stored (3:2)
ANGLE_TOL = 1e-9  # [deg] the field of view is a closed form of the EXIF numbers: round-off only


def _write_jpeg(path, *, orientation=1, focal=None, focal_35mm=None, sensor=None):
    """A JPEG with a white 5x5 block in its stored top-left corner and the EXIF asked for."""
    pixels = np.zeros((STORED_H, STORED_W, 3), dtype=np.uint8)
    pixels[:5, :5] = 255
    exif = Image.Exif()
    exif[0x0112] = orientation
    sub = exif.get_ifd(0x8769)
    if focal is not None:
        sub[0x920A] = TiffImagePlugin.IFDRational(int(focal * 10), 10)
    if focal_35mm is not None:
        sub[0xA405] = focal_35mm
    if sensor is not None:  # focal-plane resolution in pixels per mm (unit 4) and the pixel size
        sub[0xA20E] = TiffImagePlugin.IFDRational(STORED_W * 1000, int(sensor[0] * 1000))
        sub[0xA20F] = TiffImagePlugin.IFDRational(STORED_H * 1000, int(sensor[1] * 1000))
        sub[0xA210] = 4
        sub[0xA002], sub[0xA003] = STORED_W, STORED_H
    Image.fromarray(pixels).save(path, exif=exif, quality=100)
    return path


def test_exif_focal_length_and_sensor_give_the_vfov(tmp_path):
    path = _write_jpeg(tmp_path / "a.jpg", focal=50.0, sensor=(36.0, 24.0))
    picture = photo.load(path)
    assert picture.exif.focal_length_mm == 50.0  # the rational 500/10 read exactly
    # [mm] the sensor from rationals of 1/1000 mm: a quotient of doubles, round-off only
    assert picture.exif.sensor_mm == pytest.approx((36.0, 24.0), abs=1e-12)
    assert (picture.width, picture.height) == (STORED_W, STORED_H)
    assert not picture.linear
    assert picture.vfov() == pytest.approx(math.degrees(2 * math.atan(24.0 / 100.0)), abs=ANGLE_TOL)


def test_orientation_is_applied_as_pillow_does_and_turns_the_sensor(tmp_path):
    path = _write_jpeg(tmp_path / "r.jpg", orientation=6, focal=50.0, sensor=(36.0, 24.0))
    picture = photo.load(path)
    shown = np.asarray(ImageOps.exif_transpose(Image.open(path)), dtype=np.float32) / 255.0
    assert picture.image.shape == (STORED_W, STORED_H, 3)
    np.testing.assert_array_equal(picture.image, shown)  # same decoder (libjpeg), same turn: exact
    # Orientation 6: the stored top-left block is shown top-right.
    assert picture.image[0, -1, 0] == 1.0 and picture.image[0, 0, 0] == 0.0
    # The displayed image is portrait: its height is the sensor's 36 mm side.
    assert picture.sensor_mm() == pytest.approx((24.0, 36.0), abs=1e-12)  # [mm] as above, round-off only
    assert picture.vfov() == pytest.approx(math.degrees(2 * math.atan(36.0 / 100.0)), abs=ANGLE_TOL)


def test_35mm_equivalent_is_read_on_the_full_frame_diagonal(tmp_path):
    picture = photo.load(_write_jpeg(tmp_path / "e.jpg", focal=8.0, focal_35mm=50))
    # No sensor size: the 35 mm equivalent. A 3:2 image spans a full frame's 24 mm height exactly.
    assert picture.vfov() == pytest.approx(math.degrees(2 * math.atan(24.0 / 100.0)), abs=ANGLE_TOL)
    camera = picture.camera((0.0, 2.0, 0.0), (0.0, 2.0, -10.0), width=15)
    assert (camera.width, camera.height) == (15, 10)
    assert camera.vfov == pytest.approx(picture.vfov(), abs=ANGLE_TOL)
    # A given sensor size overrides: 8 mm on a 6.4 x 4.8 mm (4:3) sensor. The 3:2 picture is
    # relatively wider than the sensor, so it spans the sensor's width, a crop of its height:
    # 6.4 x 20 / 30 mm (it took the whole 4.8 mm, as Camera.photographic does not).
    cropped = 6.4 * STORED_H / STORED_W
    assert picture.vfov(sensor_mm=(6.4, 4.8)) == pytest.approx(
        math.degrees(2 * math.atan(cropped / 16.0)), abs=ANGLE_TOL
    )
    lens = refracta.Camera.photographic((0, 0, 0), (0, 0, -1), 8.0, (6.4, 4.8), width=STORED_W, height=STORED_H)
    assert picture.vfov(sensor_mm=(6.4, 4.8)) == pytest.approx(lens.vfov, abs=ANGLE_TOL)


def test_a_picture_wider_than_its_sensor_spans_the_sensors_width(tmp_path):
    # A trial's 3:1 picture at 300 mm on full frame: 4.58 deg from the sensor's height, where
    # Camera.photographic (and the camera, which crops a wide frame from the sensor's width) gives 2.29.
    picture = photo.load(_write_jpeg(tmp_path / "w.jpg", focal=300.0))
    picture = dataclasses.replace(picture, image=picture.image[:10])  # 30 x 10: 3:1
    wide = math.degrees(2 * math.atan(36.0 * 10 / 30 / 600.0))
    assert picture.vfov(sensor_mm=(36.0, 24.0)) == pytest.approx(wide, abs=ANGLE_TOL)
    assert refracta.Camera.photographic_vfov(300.0, (36.0, 24.0), 30, 10) == pytest.approx(wide, abs=ANGLE_TOL)
    # A picture narrower than the sensor (1:1) spans its height: 24 mm.
    square = dataclasses.replace(picture, image=picture.image[:, :10])
    assert square.vfov(sensor_mm=(36.0, 24.0)) == pytest.approx(
        math.degrees(2 * math.atan(24.0 / 600.0)), abs=ANGLE_TOL
    )


def test_a_float_photograph_is_linear_and_shown_through_the_tone_curve(tmp_path):
    radiance = np.full((4, 6, 3), 2.0, dtype=np.float32)
    refracta.io.write_image(tmp_path / "p.exr", radiance)
    picture = photo.load(tmp_path / "p.exr")
    assert picture.linear and picture.exif == photo.Exif()  # an EXR carries no EXIF here
    np.testing.assert_array_equal(picture.image, radiance)
    np.testing.assert_array_equal(picture.display(), refracta.io.to_display(radiance))


def test_bad_input_raises_clear_errors(tmp_path):
    with pytest.raises(refracta.IoError, match="no such file"):
        photo.load(tmp_path / "missing.jpg")
    (tmp_path / "text.jpg").write_text("not an image")
    with pytest.raises(refracta.IoError, match="text.jpg"):
        photo.load(tmp_path / "text.jpg")
    no_focal = photo.load(_write_jpeg(tmp_path / "n.jpg"))
    with pytest.raises(ValueError, match="gives no focal length"):
        no_focal.vfov()
    focal_only = photo.load(_write_jpeg(tmp_path / "f.jpg", focal=35.0))
    with pytest.raises(ValueError, match="pass sensor_mm"):
        focal_only.vfov()
    with pytest.raises(ValueError, match="sensor_mm must be two finite sizes"):
        focal_only.vfov(sensor_mm=(0.0, 24.0))
    with pytest.raises(ValueError, match="width must be a whole number"):
        focal_only.camera((0, 0, 0), (0, 0, -1), width=0, sensor_mm=(36.0, 24.0))
