"""A scene file's [geographic] table (refracta.scene_file): the scene's origin on the WGS84 Earth as
SceneFile.frame (a refracta.geo.LocalFrame), so that `refracta render --aovs geographic` works."""

import math
import pickle

import numpy as np
import pytest

import refracta
from refracta import cli, geo

ORIGIN = (60.0, 10.0)  # [deg]
TARGET = (90.0, 5000.0, 20.0)  # azimuth [deg], distance [m], height [m] of a 1 m ball's centre


def _scene_file(tmp_path, geographic="lat = 60.0\nlon = 10.0", atmosphere=""):
    lat, lon, _ = geo.forward(*ORIGIN, TARGET[0], TARGET[1])
    centre = [float(v) for v in geo.LocalFrame(*ORIGIN, earth_radius=math.inf).to_scene(lat, lon, TARGET[2])]
    text = f"""[camera]
position = [0.0, 5.0, 0.0]
look_at = {centre!r}
vfov = 0.04
size = [9, 9]

{atmosphere}
[geographic]
{geographic}

[sky]
horizon = [1.0, 1.0, 1.0]

[[objects]]
type = "sphere"
centre = {centre!r}
radius = 1.0
"""
    path = tmp_path / "place.toml"
    path.write_text(text)
    return path, (lat, lon)


def test_cli_writes_the_geographic_readout_of_a_target_placed_by_latitude_and_longitude(tmp_path):
    path, (lat, lon) = _scene_file(tmp_path)
    loaded = refracta.load_scene(path)
    assert (loaded.frame.lat, loaded.frame.lon, loaded.frame.earth_radius) == (*ORIGIN, math.inf)  # no CurvedEarth
    output = tmp_path / "place.exr"
    assert cli.main(["render", str(path), "-o", str(output), "--method", "straight", "--aovs", "geographic"]) == 0
    names = refracta.io.channel_names(output)
    pixels = refracta.io.read_image(output)
    hit_lat, hit_lon, height = (pixels[..., names.index(f"geographic.{c}")] for c in ("lat", "lon", "height"))
    met = np.isfinite(hit_lat)
    assert met.sum() > 20
    # EXR layers are float32: 1e-5 deg of latitude is ~1 m, so compare on the ball to that.
    distance, _, _ = geo.inverse(hit_lat[met], hit_lon[met], lat, lon)
    assert np.all(np.hypot(distance, height[met] - TARGET[2]) < 1.0 + 1.5)  # the 1 m ball + float32's ~1.1 m


def test_the_frame_takes_the_curved_earth_radius_and_pickles(tmp_path):
    path, _ = _scene_file(tmp_path, atmosphere='[atmosphere]\nmodel = "PhysicalAtmosphere"\ncurved_earth = 6400000.0')
    loaded = refracta.load_scene(path)
    assert isinstance(loaded.field, refracta.CurvedEarth)
    assert loaded.frame.earth_radius == loaded.field.radius == 6400000.0
    again = pickle.loads(pickle.dumps(loaded))
    assert (again.frame.lat, again.frame.lon, again.frame.earth_radius) == (60.0, 10.0, 6400000.0)
    scene, camera, field = loaded  # still unpacks as three
    assert field is loaded.field


@pytest.mark.parametrize(
    "table, message",
    [
        ("lat = 91.0\nlon = 10.0", r"place.toml:[0-9]+: \[geographic\] lat: .*must be in \(-90, 90\)"),
        ("lat = 90.0\nlon = 10.0", r"place.toml:[0-9]+: \[geographic\] lat: .*not a pole"),
        ("lat = 60.0\nlon = 400.0", r"place.toml:[0-9]+: \[geographic\] lon: .*\[-360, 360\]"),
        ('lat = "60 N"\nlon = 10.0', r"place.toml:[0-9]+: \[geographic\] lat: .*must be a number"),
        ("lat = nan\nlon = 10.0", r"place.toml:[0-9]+: \[geographic\] lat: .*finite"),
        ("lat = 60.0", r"place.toml:[0-9]+: \[geographic\] lon: .*missing"),
        ("lat = 60.0\nlon = 10.0\nheight = 3.0", r"unknown key for \[geographic\]"),
    ],
)
def test_bad_geographic_tables_name_file_line_and_key(tmp_path, table, message):
    path, _ = _scene_file(tmp_path, geographic=table)
    with pytest.raises(ValueError, match=message):
        refracta.load_scene(path)


def test_cli_asks_for_the_table_when_geographic_readouts_have_no_place(tmp_path, capsys):
    path, _ = _scene_file(tmp_path, geographic="")
    text = path.read_text().replace("[geographic]\n", "")
    path.write_text(text)
    assert refracta.load_scene(path).frame is None
    assert cli.main(["render", str(path), "-o", str(tmp_path / "x.exr"), "--aovs", "geographic"]) == 1
    assert "add a [geographic] table" in capsys.readouterr().err


def test_longitudes_east_of_greenwich_in_either_convention_are_one_place(tmp_path):
    # refracta.geo takes [-180, 180] and [0, 360] alike; so does a scene file's [geographic] table.
    east, _ = _scene_file(tmp_path, geographic="lat = 60.0\nlon = 359.0")
    a = refracta.load_scene(east).frame
    west, _ = _scene_file(tmp_path, geographic="lat = 60.0\nlon = -1.0")
    b = refracta.load_scene(west).frame
    assert a.lon == 359.0
    np.testing.assert_allclose(a.to_geographic(b.to_scene(60.5, -1.0, 0.0))[:2], (60.5, -1.0), atol=1e-9)  # rounding
