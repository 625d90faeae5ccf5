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
    # EXR sorts channels by name (geographic.height first); read_layers gives them in the readout's order.
    again, read = io.read_layers(tmp_path / "r.exr")
    np.testing.assert_array_equal(again, image)  # float32 both ways
    assert set(read) == set(out)
    for name, values in out.items():
        np.testing.assert_allclose(read[name], values, rtol=1e-7, atol=2e-6)  # as the latitude above


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
    np.testing.assert_allclose(height[~sky], out["geographic"][..., 2][~sky], atol=1e-3)  # as above
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
    # The bound constructors, which LocalFrame.camera calls, do the same (a review: Camera(width=320)
    # kept its default height of 360, Camera.photographic(width=320) its 640).
    eye, ahead = (0.0, 1.5, 0.0), (100.0, 1.5, 0.0)
    assert (refracta.Camera(eye, ahead, width=320).height, refracta.Camera(eye, ahead, height=90).width) == (180, 160)
    assert refracta.Camera.photographic(eye, ahead, 200.0, width=320).height == 213  # 3:2, rounded
    assert refracta.Camera.eye_level((0.0, 0.0, 0.0), (0.0, 0.0, -200.0), width=480).height == 320
    assert refracta.Camera.framing(((-1.0, -1.0, -1.0), (1.0, 1.0, 1.0)), height=180).width == 320
    full = refracta.Camera(eye, ahead)
    assert (full.width, full.height) == (640, 360)  # both left out: the defaults


def test_the_readout_text_gives_each_value_its_unit():
    aovs = {"geographic": np.array([[[47.1234567, 8.7654321, 3660.455695]]]), "distance": np.array([[12.345]])}
    text = readout_text(aovs, 0.5, 0.5).splitlines()
    assert text[1] == "geographic: lat 47.123457 deg, lon 8.765432 deg, height 3660.46 m"
    assert text[2] == "distance: 12.35 m"


def test_a_progress_bar_follows_every_phase_of_the_work():
    """A render first reported (0, 0) (no total yet), then its textures' 379 items, then its 160
    tiles: the bar closed at 0/0 and showed nothing more (a trial)."""
    import io as text_io

    from refracta._progress import ProgressBar

    stream = text_io.StringIO()
    bar = ProgressBar("rendering", stream=stream)
    for call in [(0, 0), (200, 379), (379, 379), (12, 160), (160, 160), (160, 160)]:
        bar(*call)
    shown = stream.getvalue()
    assert "0/0" not in shown and "379/379" in shown and "160/160" in shown
    assert shown.count("160/160") == 1  # the end reported again is not a new phase


def test_the_command_line_edit_writes_the_solved_camera(tmp_path):
    """With camera parameters free, `refracta edit` printed the solved pitch but wrote the old
    [camera]: a render of its file did not line up with the photograph (a trial)."""
    import json
    import shutil
    from pathlib import Path

    from refracta import cli, edit

    data = Path(__file__).resolve().parents[1] / "data"
    for name in ("hot_road.toml", "tent.obj", "tent.mtl"):
        shutil.copy(data / name, tmp_path / name)
    source = [350.0, 0.1, 0.0]
    pairs = tmp_path / "pairs.json"
    pairs.write_text(
        json.dumps(
            {"pairs": [{"destination": [48, 21], "source": source}], "free": ["camera_pitch"], "stop_height": 0.0}
        )
    )
    out = tmp_path / "solved.toml"
    assert cli.main(["edit", str(tmp_path / "hot_road.toml"), "--pairs", str(pairs), "-o", str(out)]) == 0
    _, before, _ = refracta.load_scene(tmp_path / "hot_road.toml")
    _, after, field = refracta.load_scene(out)
    assert not np.array_equal(after.look_at - after.position, before.look_at - before.position)  # turned
    # The written camera meets the pair as the solve did: within solve's pixel tolerance (a tenth of
    # the pixel's footprint at 350 m: ~0.1 * 350 m * pixel angle), and the old camera does not.
    pair = [edit.PointPair((48, 21), source)]
    footprint = 350.0 * after.pixel_angle
    assert edit.distances(field, after, pair, stop_height=0.0)[0] < 0.1 * footprint  # solve's own pixel_tolerance
    assert edit.distances(field, before, pair, stop_height=0.0)[0] > footprint


def test_project_over_a_sphere_is_pick_s_inverse_and_the_editor_draws_a_click_under_the_pointer():
    """Over a curved Earth a click picks its source along the true straight lines, but its marker was
    drawn by the flat projection: 21 px above the pointer on the cold sea's coast (a trial)."""
    from refracta import examples
    from refracta.widgets.model import EditorModel

    sea = examples.cold_sea(320, 120)
    air, radius = refracta.without_refraction(sea.field), sea.field.earth_radius
    for u, v in [(100.0, 60.0), (200.0, 100.0), (50.5, 70.2)]:  # the coast 30 km out, the sea 2 km out
        point = sea.camera.pick(sea.scene, u, v, air)
        projected = sea.camera.project(point, earth_radius=radius)
        # Exact geometry both ways: what is left is the trace's 1 mm tolerance at 2-30 km (< 1e-4 px).
        assert projected[:2] == pytest.approx((u, v), abs=1e-3)
        # depth runs along the view axis: these points lie at most 0.71 deg off it, cos 1 - 8e-5.
        assert projected[2] == pytest.approx(np.linalg.norm(point - sea.camera.position), rel=1e-4)
    model = EditorModel(
        sea.scene, sea.camera, sea.field, free=["inversion_dt"], max_length=sea.max_length, autorender=False
    )
    try:
        model.click(100.0, 60.0)
        marker = model.markers()[-1]
        assert marker["kind"] == "pending" and (marker["u"], marker["v"]) == pytest.approx(
            (100.0, 60.0), abs=1e-3
        )  # as above
    finally:
        model.close()


def test_a_photograph_without_a_lens_in_its_exif_takes_the_field_of_view_given(tmp_path):
    """Without EXIF the errors said "set the camera's vfov yourself", and the size-mismatch errors
    "make the camera with Photo.camera", which had no vfov= (a trial)."""
    from refracta import photo

    path = tmp_path / "photo.png"
    io.write_image(path, np.full((30, 40, 3), 0.2, np.float32))
    picture = photo.load(path)
    with pytest.raises(ValueError, match=r"Photo.camera\(position, look_at, vfov=...\)"):
        picture.camera((0.0, 2.0, 0.0), (100.0, 2.0, 0.0))
    camera = picture.camera((0.0, 2.0, 0.0), (100.0, 2.0, 0.0), vfov=1.5)
    assert (camera.width, camera.height, camera.vfov) == (40, 30, 1.5)
    with pytest.raises(ValueError, match="give vfov or sensor_mm, not both"):
        picture.camera((0.0, 2.0, 0.0), (100.0, 2.0, 0.0), vfov=1.5, sensor_mm=(36.0, 24.0))
