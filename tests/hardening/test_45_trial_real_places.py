"""A photographer's trial of the real-places workflow: render's readouts written to an EXR under
the names the command line gives them (geographic.X held the latitude), sky pixels of the
'position' readout converted to latitude and longitude whole (NaN there, not an error), a camera
given one side of its image (320 wide became 320 x 360), and the readout text's units per value
("height 3660.455695 deg, deg, m")."""

import math

import numpy as np
import pytest

import refracta
from refracta import geo, io
from refracta._readout_text import readout_text


def sphere_view():
    frame = geo.LocalFrame(60.0, 10.0, earth_radius=np.inf)  # a flat-Earth scene: y is the height
    lat, lon, _ = geo.forward(60.0, 10.0, 90.0, 5000.0)
    centre = frame.to_scene(lat, lon, 20.0)
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    scene.add_sphere(centre, 1.0)
    camera = refracta.Camera((0.0, 5.0, 0.0), centre, (0, 1, 0), 0.04, 9, 9)
    return frame, scene, camera


def test_readouts_are_written_under_their_own_channel_names(tmp_path):
    frame, scene, camera = sphere_view()
    image, out = refracta.render(
        scene, camera, None, method="straight", aovs=["geographic", "hidden_height", "distance"], frame=frame
    )
    io.write_layers(tmp_path / "r.exr", image, out)
    names = io.channel_names(tmp_path / "r.exr")
    assert sorted(names[3:]) == [
        "distance.Y",
        "geographic.height",
        "geographic.lat",
        "geographic.lon",
        "hidden_height.geometric",
        "hidden_height.refracted",
    ]
    layers = io.read_image(tmp_path / "r.exr")
    latitude = layers[..., names.index("geographic.lat")]
    # The latitude, as named, stored as float32: 60 deg to half a float32 step, 2^-19 deg ~ 1.9e-6.
    np.testing.assert_allclose(latitude, out["geographic"][..., 0], atol=2e-6)


def test_sky_pixels_of_the_position_readout_give_nan_places():
    frame, scene, camera = sphere_view()
    _, out = refracta.render(scene, camera, None, method="straight", aovs=["position", "geographic"], frame=frame)
    lat, lon, height = frame.to_geographic(out["position"])
    sky = np.isnan(out["position"][..., 0])
    assert sky.any() and (~sky).any()
    assert np.isnan(lat[sky]).all() and np.isnan(lon[sky]).all() and np.isnan(height[sky]).all()
    # Elsewhere the render's own 'geographic' readout: the same conversion, of float32 positions
    # (~4e-4 m at 5 km: 4e-9 deg of latitude; 1e-6 deg and 1e-3 m allow for it many times over).
    np.testing.assert_allclose(lat[~sky], out["geographic"][..., 0][~sky], atol=1e-6)
    np.testing.assert_allclose(height[~sky], out["geographic"][..., 2][~sky], atol=1e-3)
    with pytest.raises(ValueError, match=r"points must be finite \(got inf\)"):
        frame.to_geographic([math.inf, 0.0, 0.0])


def test_a_camera_given_one_side_keeps_the_default_shape():
    frame = geo.LocalFrame(47.0, 8.0)
    full = frame.camera(10.0, 90.0, 0.0, vfov=2.0)
    one = frame.camera(10.0, 90.0, 0.0, vfov=2.0, image_width=320)
    assert (one.width, one.height) == (320, round(320 * full.height / full.width))
    tall = frame.camera(10.0, 90.0, 0.0, vfov=2.0, image_height=90)
    assert (tall.width, tall.height) == (round(90 * full.width / full.height), 90)
    photo = frame.camera(10.0, 90.0, 0.0, focal_length_mm=200.0, sensor_mm=(24.0, 36.0), image_width=300)
    assert (photo.width, photo.height) == (300, 450)  # the sensor's own shape: square pixels


def test_the_readout_text_gives_each_value_its_unit():
    aovs = {"geographic": np.array([[[47.1234567, 8.7654321, 3660.455695]]]), "distance": np.array([[12.345]])}
    text = readout_text(aovs, 0.5, 0.5).splitlines()
    assert text[1] == "geographic: lat 47.123457 deg, lon 8.765432 deg, height 3660.46 m"
    assert text[2] == "distance: 12.35 m"
