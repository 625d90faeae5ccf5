"""Fourth new-user trial (real places and the command line): each test failed before its fix.

(The orthophoto mirrored north-south is tests/scene/test_terrain.py's draping test.)
"""

import os

import numpy as np
import pytest

import refracta
from refracta import cli, geo

SCENE = "[camera]\nposition = [0, 1.5, 0]\nlook_at = [100, 1, 0]\nvfov = 10\nsize = [16, 8]\n"


@pytest.fixture
def scene_file(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(SCENE)
    return path


def run(capsys, *argv):
    status = cli.main([str(a) for a in argv])
    return status, capsys.readouterr().err


def test_a_fifo_output_is_refused_before_the_render(tmp_path, scene_file, capsys):
    # Writing a FIFO waits for a reader that may never come: render finished, then hung.
    fifo = tmp_path / "fifo.jpg"
    os.mkfifo(fifo)
    status, err = run(capsys, "render", scene_file, "-o", fifo)
    assert status == 1 and "is not a regular file" in err


def test_render_refuses_a_scene_file_or_video_output_before_rendering(tmp_path, scene_file, capsys):
    # .toml and .mp4 were exempt from the format check for every command: the render ran, then
    # the write failed.
    for name in ("out.toml", "out.mp4"):
        status, err = run(capsys, "render", scene_file, "-o", tmp_path / name)
        assert status == 1 and "could not find a format writer" in err
        assert not (tmp_path / name).exists()


def test_edit_writes_only_a_scene_file(tmp_path, scene_file, capsys):
    # It wrote the solved scene's TOML text into solved.exr.
    pairs = tmp_path / "pairs.toml"
    pairs.write_text("pairs = []\n")
    status, err = run(capsys, "edit", scene_file, "--pairs", pairs, "-o", tmp_path / "solved.exr")
    assert status == 1 and "must be a scene file (.toml)" in err
    assert not (tmp_path / "solved.exr").exists()


def test_an_empty_readout_list_is_refused(tmp_path, scene_file, capsys):
    # --aovs ',,' rendered no readouts and exited 0.
    with pytest.raises(SystemExit):
        cli.main(["render", str(scene_file), "-o", str(tmp_path / "o.exr"), "--aovs", ",,"])
    assert "names no readout" in capsys.readouterr().err


def test_a_size_beyond_an_int_is_named_not_a_traceback(tmp_path, capsys):
    # 1e20 pixels reached Camera's int and escaped main as pybind11's TypeError.
    path = tmp_path / "big.toml"
    path.write_text(SCENE.replace("size = [16, 8]", "size = [99999999999999999999, 8]"))
    status, err = run(capsys, "render", path, "-o", tmp_path / "big.png")
    assert status == 1 and "[camera] size: must be two whole numbers of pixels in [1, 16777216]" in err


def test_a_float_tiff_photograph_is_linear(tmp_path):
    # Only the suffix decided: a float TIFF was taken as display values and refused by overlay.
    import tifffile

    from refracta import photo

    rng = np.random.default_rng(1)
    tifffile.imwrite(tmp_path / "f.tif", (4.0 * rng.random((9, 16, 3))).astype(np.float32), photometric="rgb")
    tifffile.imwrite(tmp_path / "b.tif", (255 * rng.random((9, 16, 3))).astype(np.uint8), photometric="rgb")
    assert photo.load(tmp_path / "f.tif").linear
    assert not photo.load(tmp_path / "b.tif").linear
    photo.overlay(photo.load(tmp_path / "f.tif"), np.zeros((9, 16, 3), np.float32))


def test_a_malformed_exif_unit_reads_as_none(tmp_path):
    # A FocalPlaneResolutionUnit that is a string broke photo.load (int('x')).
    from PIL import Image

    from refracta import photo

    exif = Image.Exif()
    exif.get_ifd(0x8769).update({0x920A: 50.0, 0xA20E: 1000.0, 0xA20F: 1000.0, 0xA210: "x"})
    Image.new("RGB", (16, 9)).save(tmp_path / "p.jpg", exif=exif)
    assert photo.read_exif(tmp_path / "p.jpg").sensor_mm is None
    assert photo.load(tmp_path / "p.jpg").exif.focal_length_mm == 50.0


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: geo.LocalFrame(46.0, 7.0, earth_radius=True), "earth_radius must be a number"),
        (lambda: geo.LocalFrame(46.0, 7.0, earth_radius="6e6"), "earth_radius must be a number"),
        (lambda: refracta.refraction_coefficient(refracta.PhysicalAtmosphere(), True, 1000.0), "eye_height must be"),
        (lambda: refracta.refraction_coefficient(refracta.PhysicalAtmosphere(), "30", 1000.0), "eye_height must be"),
        # k came out 0.185 at 1 mm and 1.0 at 1 um (0.1695 from 1 m on): the drop is rounding there.
        (lambda: refracta.refraction_coefficient(refracta.PhysicalAtmosphere(), 2.0, 1e-3), r"distance must be in \[1"),
        (lambda: _terrain(spacing=(True, True)), "spacing must be two numbers"),
        (lambda: _terrain(spacing=("1", "1")), "spacing must be two numbers"),
        (lambda: _terrain(heights=np.full((3, 3), "1")), "heights must be a"),
        (lambda: _terrain(earth_radius=True), "earth_radius must be a number"),
        (lambda: _terrain(earth_radius="abc"), "earth_radius must be a number"),
        (lambda: _terrain(water_level="200"), "water_level must be a number"),
        (lambda: _terrain(water_level=True), "water_level must be a number"),
    ],
)
def test_bools_and_strings_are_not_numbers_in_the_places_api(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def _terrain(heights=None, **kwargs):
    arguments = dict(origin=(0.0, 0.0), spacing=(10.0, 10.0)) | kwargs
    return refracta.Scene().add_terrain(np.zeros((3, 3)) if heights is None else heights, **arguments)


def test_the_array_form_takes_a_curved_earth_as_local_frame_does():
    earth = refracta.CurvedEarth(refracta.PhysicalAtmosphere())
    ids = refracta.Scene().add_terrain(np.zeros((3, 3)), origin=(0, 0), spacing=(10, 10), earth_radius=earth)
    assert ids.terrain


def test_photo_sensor_and_overlay_flags_refuse_what_is_not_theirs(tmp_path):
    from PIL import Image

    from refracta import photo

    exif = Image.Exif()
    exif.get_ifd(0x8769)[0x920A] = 50.0
    Image.new("RGB", (16, 9)).save(tmp_path / "p.jpg", exif=exif)
    loaded = photo.load(tmp_path / "p.jpg")
    # 16:9 is relatively wider than the 3:2 sensor: it spans the sensor's width, 36 x 9 / 16 mm high.
    assert loaded.vfov(sensor_mm=(36, 24)) == pytest.approx(2 * np.degrees(np.arctan(20.25 / 100)), rel=1e-12)  # exact
    with pytest.raises(ValueError, match="sensor_mm must be"):
        loaded.vfov(sensor_mm=(True, True))  # was 0.573 deg: a 1 mm sensor
    with pytest.raises(ValueError, match="linear must be True, False or None"):
        photo.overlay(loaded, np.zeros((9, 16, 3), np.float32), linear="no")  # bool("no") is True


@pytest.mark.parametrize(
    "make, match",
    [
        # An array of azimuths made an array of Earth radii, and the message blamed earth_radius.
        (lambda: refracta.Camera.geographic(47, 8, 450, [120.0, 1.0], 0, vfov=5), "azimuth must be one number"),
        (lambda: geo.LocalFrame(46, 7).camera(10, 90, 0, vfov=10, position=46), r"position must be \(lat, lon\)"),
        (lambda: geo.LocalFrame(46, 7).camera(10, 90, 0, vfov=10, image_width=10**12), "image_width must be"),
        (lambda: geo.LocalFrame(46, 1e9), r"lon must be finite in \[-360, 360\]"),  # as geo's functions take it
        (lambda: refracta.examples.real_place(16, 8, field="x"), "real_place: field must be a refracta field"),
    ],
)
def test_the_places_api_names_the_argument_at_fault(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_a_fifo_photograph_is_named_as_one(tmp_path):
    from refracta import photo

    fifo = tmp_path / "p.jpg"
    os.mkfifo(fifo)
    with pytest.raises(refracta.IoError, match="not a regular file"):  # it said "no such file"
        photo.load(fifo)
