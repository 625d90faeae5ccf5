"""Cameras, scenes, image files and their errors."""

import numpy as np
import pytest

import refracta


def test_camera_ray_and_project_are_inverse():
    camera = refracta.Camera([1, 2, 3], [10, 1, -2], vfov=40, width=200, height=100)
    for u, v in [(0.5, 0.5), (100, 50), (199.5, 10.25)]:
        origin, direction = camera.ray(u, v)
        # Project(ray) round trip in double: 1e-9 of a pixel.
        np.testing.assert_allclose(camera.project(origin + 7.0 * direction)[:2], [u, v], atol=1e-9)
    # The image centre looks at look_at; vfov spans the height.
    np.testing.assert_allclose(camera.project([10, 1, -2])[:2], [100, 50], atol=1e-9)
    top = camera.ray(100, 0)[1]
    bottom = camera.ray(100, 100)[1]
    # The vfov's two edge rays in double: arccos rounding.
    assert np.degrees(np.arccos(top @ bottom)) == pytest.approx(40.0, abs=1e-9)


def test_camera_ray_takes_arrays_of_pixel_coordinates():
    camera = refracta.Camera([1, 2, 3], [10, 1, -2], vfov=40, width=200, height=100)
    u, v = np.array([0.5, 100.0, 199.5]), np.array([0.5, 50.0, 10.25])
    origins, directions = camera.ray(u, v)
    assert origins.shape == directions.shape == (3, 3)
    # Each row as the scalar call gives it (the same double arithmetic: exact).
    for i in range(3):
        np.testing.assert_array_equal(directions[i], camera.ray(u[i], v[i])[1])
        np.testing.assert_array_equal(origins[i], camera.position)
    # One coordinate may be a number: a row of pixels.
    row = camera.ray(np.arange(200) + 0.5, 50.0)[1]
    np.testing.assert_array_equal(row[100], camera.ray(100.5, 50.0)[1])
    # Round trip through project, as for one ray (1e-9 of a pixel in double).
    np.testing.assert_allclose(camera.project(origins + 7.0 * directions)[:, :2], np.stack([u, v], 1), atol=1e-9)
    with pytest.raises(ValueError, match="u and v must have the same length"):
        camera.ray(u, v[:2])
    with pytest.raises(ValueError, match="Camera.ray: v"):
        camera.ray(u, np.array([1.0, np.nan, 2.0]))


def test_pick_returns_the_visible_point():
    scene = refracta.Scene()
    scene.add_box([10, 0, 0], [2, 2, 2])
    camera = refracta.Camera([0, 0, 0], [10, 0, 0], width=11, height=11)
    # Embree's float32 hit distance at 9 m: ~1e-6 relative.
    np.testing.assert_allclose(camera.pick(scene, 5.5, 5.5), [9, 0, 0], atol=1e-5)
    assert camera.pick(scene, 0, 0) is None


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(width=0), "size"),
        (dict(position=[0, float("nan"), 0]), "position must be finite"),
        (dict(up=[1, 0, 0]), "not parallel"),
        (dict(look_at=[0, 0, 0]), "look_at must differ"),
        (dict(vfov=180), "vfov"),
    ],
)
def test_bad_cameras_raise_value_errors(kwargs, message):
    args = dict(position=[0, 0, 0], look_at=[1, 0, 0], up=[0, 1, 0], vfov=45, width=4, height=4)
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        refracta.Camera(**args)


def test_bad_scene_input_raises_value_errors():
    scene = refracta.Scene()
    with pytest.raises(ValueError, match="kd must be in"):
        scene.add_box([0, 0, 0], [1, 1, 1], kd=(2, 0, 0))
    with pytest.raises(ValueError, match="refers to vertex 7"):
        scene.add_mesh(np.zeros((3, 3)), [[0, 1, 7]])
    with pytest.raises(ValueError, match="add_sphere: radius must be > 0"):
        scene.add_sphere([0, 0, 0], -1.0)
    with pytest.raises(ValueError, match="vertices"):
        scene.add_mesh(np.array([[0, 0, np.inf], [1, 0, 0], [0, 1, 0]]), [[0, 1, 2]])
    camera = refracta.Camera([0, 0, 0], [1, 0, 0], width=4, height=4)
    with pytest.raises(ValueError, match="method must be"):
        refracta.render(scene, camera, method="raytrace", progress=False)
    with pytest.raises(ValueError, match="spp"):
        refracta.render(scene, camera, spp=0, progress=False)


def test_image_files_round_trip(tmp_path):
    image = np.random.default_rng(1).uniform(0, 4, size=(6, 5, 3)).astype(np.float32)
    refracta.io.write_image(tmp_path / "a.exr", image)
    np.testing.assert_array_equal(refracta.io.read_image(tmp_path / "a.exr"), image)  # linear float kept
    flat = np.ones((2, 3, 3), np.float32)
    # Reinhard at exposure 1: 1 -> 0.5, sRGB: 0.7354 -> 188/255.
    refracta.io.write_image(tmp_path / "a.png", flat, exposure=1.0, tonemap="reinhard")
    # 8-bit PNG: half a level, plus float slack.
    np.testing.assert_allclose(refracta.io.read_image(tmp_path / "a.png"), 188 / 255, atol=0.6 / 255)
    refracta.io.write_image(tmp_path / "b.png", flat * 0.25, tonemap="linear", gamma="linear", exposure=2.0)
    # 8-bit PNG: half a level, plus float slack.
    np.testing.assert_allclose(refracta.io.read_image(tmp_path / "b.png"), 128 / 255, atol=0.6 / 255)
    # linear=True: a PNG whose gAMA chunk says linear (gamma="linear") as stored; 8-bit: half a
    # level, plus float slack.
    np.testing.assert_allclose(refracta.io.read_image(tmp_path / "b.png", linear=True), 128 / 255, atol=0.6 / 255)
    # An sRGB PNG decoded from sRGB (IEC 61966-2-1: 0.21586 -> 0.50196 -> 0.21586).
    refracta.io.write_image(tmp_path / "s.png", flat * 0.21586, tonemap="linear", exposure=1.0)
    # 8-bit: half a level's slope there (0.0021 per level), plus float slack.
    np.testing.assert_allclose(refracta.io.read_image(tmp_path / "s.png", linear=True), 0.21586, atol=1.1e-3)
    # A float file is linear already.
    np.testing.assert_array_equal(refracta.io.read_image(tmp_path / "a.exr", linear=True), image)


def test_read_image_linear_keeps_alpha(tmp_path):
    rgba = np.full((2, 3, 4), 0.5, np.float32)
    rgba[..., :3] = 0.21586
    refracta.io.write_image(tmp_path / "c.png", rgba, tonemap="linear", exposure=1.0)
    linear = refracta.io.read_image(tmp_path / "c.png", linear=True)
    # Colour sRGB-encoded and decoded (0.2159 -> 128/255 -> 0.2159; half a level's slope, plus
    # float slack), alpha as stored.
    np.testing.assert_allclose(linear[..., :3], 0.21586, atol=1.1e-3)
    # The alpha: 8-bit, half a level plus float slack.
    np.testing.assert_allclose(linear[..., 3], 128 / 255, atol=0.6 / 255)
    with pytest.raises(ValueError, match="linear must be True or False"):
        refracta.io.read_image(tmp_path / "c.png", linear=1)


def test_image_file_errors(tmp_path):
    with pytest.raises(refracta.IoError, match="no such image file"):
        refracta.io.read_image(tmp_path / "missing.exr")
    with pytest.raises(refracta.IoError):
        refracta.io.write_image(tmp_path / "no" / "dir" / "x.png", np.zeros((2, 2, 3)))
    with pytest.raises(ValueError, match="finite"):
        refracta.io.write_image(tmp_path / "x.exr", np.full((2, 2, 3), np.nan))
    with pytest.raises(ValueError, match="tonemap"):
        refracta.io.write_image(tmp_path / "x.png", np.zeros((2, 2, 3)), tonemap="filmic")
    (tmp_path / "bad.png").write_text("not an image")
    with pytest.raises(refracta.IoError):
        refracta.io.read_image(tmp_path / "bad.png")


def test_pick_rejects_non_finite_pixels():
    scene = refracta.Scene()
    camera = refracta.Camera([0, 0, 0], [1, 0, 0], width=4, height=4)
    with pytest.raises(ValueError, match="finite"):
        camera.pick(scene, float("nan"), 1.0)


def test_image_functions_name_a_renders_image_and_aovs_pair(tmp_path):
    # A trial passed render(aovs=...)'s (image, aovs) to write_image: numpy's "inhomogeneous shape".
    pair = (np.ones((4, 6, 3), np.float32), {"albedo": np.ones((4, 6, 3), np.float32)})
    for call in (
        lambda: refracta.io.write_image(tmp_path / "a.png", pair),
        lambda: refracta.io.to_display(pair),
        lambda: refracta.io.exposure_of(pair),
    ):
        with pytest.raises(ValueError, match=r"got render's \(image, aovs\) pair, not an image"):
            call()
    refracta.io.write_image(tmp_path / "a.png", pair[0])  # its image is written


def test_a_list_pair_is_named_too():
    pair = [np.ones((4, 6, 3), np.float32), {"albedo": np.ones((4, 6, 3), np.float32)}]
    with pytest.raises(ValueError, match=r"got render's \(image, aovs\) pair"):
        refracta.io.to_display(pair)
