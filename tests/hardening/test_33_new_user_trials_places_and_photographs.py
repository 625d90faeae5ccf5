"""Two new-user trials (real places; a photographer's realism features): each test failed before its fix.

(Aiming a camera at a latitude and longitude: tests/geo/test_geographic_camera.py; a frame of another
Earth than the field's: tests/render/test_readouts.py; either longitude convention in a scene file:
tests/render/test_scene_file_geographic.py; an overlay's fractional object ids: tests/photo.)
"""

import io

import numpy as np
import pytest

import refracta
from refracta import geo, photo, terrain
from refracta._progress import ProgressBar


def _truncated(tmp_path, suffix):
    image = np.random.default_rng(3).random((48, 64, 3)).astype(np.float32)
    whole = tmp_path / f"whole{suffix}"
    refracta.io.write_image(whole, image)
    data = whole.read_bytes()
    cut = tmp_path / f"cut{suffix}"
    cut.write_bytes(data[: len(data) // 2])
    return cut


@pytest.mark.parametrize("suffix", [".jpg", ".tif", ".png", ".exr"])
def test_a_truncated_image_is_refused_not_filled_with_grey(tmp_path, suffix):
    # A half-written JPEG or TIFF read "successfully", its lower rows grey or black, the damage
    # only in OpenImageIO's error message; a photograph so read went into an overlay or a fit.
    with pytest.raises(refracta.IoError, match="cannot read"):
        photo.load(_truncated(tmp_path, suffix))


def test_a_photographs_camera_is_refused_beyond_the_pixels_a_camera_holds():
    image = np.full((8, 12, 3), 0.5, dtype=np.float32)
    picture = photo.Photo(image=image, linear=False, exif=photo.Exif(focal_length_35mm=50.0), path=None)
    with pytest.raises(ValueError, match=r"width must be a whole number of pixels in \[1, 2147483647\]"):
        picture.camera((0, 20, 0), (0, 20, -1), width=2**31)
    assert picture.camera((0, 20, 0), (0, 20, -1), width=24).height == 16


def test_a_scene_point_beyond_the_reach_in_height_is_refused():
    with pytest.raises(ValueError, match="a scene height of 3.23e\\+07 m, beyond the scene's reach"):
        geo.LocalFrame(50.0, 1.0).to_scene(50.1, 1.0, 1e9)


def test_geodesy_names_none_and_shapes_that_do_not_broadcast():
    with pytest.raises(ValueError, match=r"lat1 must be a number or an array of numbers \(got None\)"):
        geo.inverse(None, 1.0, 50.0, 1.0)
    with pytest.raises(ValueError, match=r"do not broadcast together: lat1 \(2,\), lon1 \(3,\)"):
        geo.inverse([50.0, 51.0], [1.0, 2.0, 3.0], 50.0, 1.0)


def test_elevation_file_errors_name_the_call_and_keep_tifffile_quiet(tmp_path, capsys):
    bad = tmp_path / "bad.tif"
    bad.write_bytes(b"II*\x00" + b"\xff" * 40)  # a TIFF header pointing nowhere
    with pytest.raises(ValueError, match="^read_elevation: .*not a readable TIFF file: damaged or truncated"):
        terrain.read_elevation(bad)
    with pytest.raises(refracta.IoError, match="^read_elevation: no such elevation file"):
        terrain.read_elevation(tmp_path / "N46E007.hgt")
    with pytest.raises(ValueError, match="^add_terrain: .*not a readable TIFF file"):
        refracta.Scene().add_terrain(bad, frame=geo.LocalFrame(46.0, 7.0))
    assert "invalid offset" not in capsys.readouterr().err  # tifffile's own log line


def test_a_progress_bar_of_a_few_items_shows_no_rate_of_millions():
    stream = io.StringIO()
    bar = ProgressBar("eye table", stream=stream)
    bar(0, 10)
    bar(10, 10)
    text = stream.getvalue()
    assert "10/10" in text and "it/s" not in text  # was "7577944.20it/s" for items ended in microseconds


def test_fog_the_multiple_scattering_table_does_not_resolve_is_warned_of():
    # A trial's horizon against visibility (sun 30 deg up): 0.0085 at 0.5 km, 0.0105 at 0.55, 0.0047
    # at 0.65, 0.0053 at 1 km -- below 0.8 km the table's steps do not resolve the fog.
    with pytest.warns(UserWarning, match="visibility 0.5 km is fog the sky's multiple-scattering table does not"):
        refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0), visibility=0.5)
    with pytest.warns(UserWarning, match="Scene.set_physical_sky: visibility 0.3 km is fog"):
        refracta.Scene().set_physical_sky((0.0, 1.0, 0.0), visibility=0.3)
