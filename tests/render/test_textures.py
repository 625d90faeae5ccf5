"""Textures through OpenImageIO's TextureSystem, filtered over ray-cone footprints; OBJ map_Kd,
billboards and environment-map skies."""

import numpy as np
import pytest

import refracta

SKY = (1.0, 1.0, 1.0)


def write_checkerboard(path, checks=8, pixels_per_check=8):
    """Black and white checks (0 and 1 survive the sRGB round trip exactly)."""
    index = np.arange(checks * pixels_per_check) // pixels_per_check
    board = ((index[:, None] + index[None, :]) % 2).astype(np.float32)
    refracta.io.write_image(path, np.repeat(board[:, :, None], 3, axis=2), tonemap="linear")
    return path


def checkerboard_scene(tmp_path):
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)  # no sun: a ground point's radiance is texture x kd x 1
    scene.add_ground(
        0.0, 4000.0, kd=(1.0, 1.0, 1.0), texture=str(write_checkerboard(tmp_path / "checks.png")), texture_size=8.0
    )  # 1 m checks
    return scene


def test_a_distant_checkerboard_does_not_alias(tmp_path):
    """Against a 16 x 16 supersampled point-sampled reference (the pixel's box average), the
    filtered 1-sample image is far closer than the point-sampled 1-sample image, which aliases
    into moire toward the horizon."""
    scene = checkerboard_scene(tmp_path)
    camera = refracta.Camera((0.0, 1.5, 0.0), (100.0, -3.0, 10.0), (0, 1, 0), 30.0, 64, 48)
    render = dict(method="straight", progress=False)
    reference = refracta.render(scene, camera, None, spp=256, texture_filter=False, **render)
    filtered = refracta.render(scene, camera, None, **render)
    point = refracta.render(scene, camera, None, texture_filter=False, **render)
    ground = reference[..., 0] < 0.999  # rows that see the ground (the sky is exactly 1)
    ground &= np.arange(48)[:, None] < 30  # the far half: footprints of many checks
    error_filtered = np.abs(filtered - reference)[ground].mean()
    error_point = np.abs(point - reference)[ground].mean()
    # The filtered board's mean error vs a 256-spp reference: 0.1 of a 0-1 check (aliasing gives >3x).
    assert error_filtered < 0.1
    assert error_point > 3.0 * error_filtered
    # Far away the filtered board converges to its mean (0.5), as the reference does.
    assert abs(filtered[ground][:, 0].mean() - reference[ground][:, 0].mean()) < 0.05


def test_a_magnified_edge_is_a_bilinear_ramp_one_texel_wide(tmp_path):
    """Looking straight down at a check's edge, 10 pixels a texel: the lookup is bilinear between
    texels (pbrt-v4's and Mitsuba 3's default), so the edge is a straight ramp across one texel. A
    trial against Mitsuba 3 found OpenImageIO's default (smart bicubic: a B-spline) spreading it
    over ~3 texels; with or without the footprint filter the magnified lookup is the same."""
    scene = checkerboard_scene(tmp_path)  # 8 texels a check of 1 m: 0.125 m a texel
    half_width = 0.4  # [m] 64 pixels over 0.8 m, 6.4 texels: 10 pixels a texel
    vfov = 2 * np.degrees(np.arctan(half_width * 8 / 64 / 10.0))
    camera = refracta.Camera((0.0, 10.0, 0.5), (0.0, 0.0, 0.5), (0, 0, -1), vfov, 64, 8)
    render = dict(method="straight", progress=False, spp=16)
    image = refracta.render(scene, camera, None, **render)
    np.testing.assert_array_equal(image, refracta.render(scene, camera, None, texture_filter=False, **render))
    profile = image[4, :, 0]  # across the checks' edge near x = 0, at z = 0.5 (mid-check)
    ends = sorted((profile[:10].mean(), profile[-10:].mean()))  # a black and a white check, either way round
    assert ends == [pytest.approx(0.0, abs=1e-3), pytest.approx(1.0, abs=1e-3)]  # the checks' own values
    ramp = np.nonzero((profile > 0.01) & (profile < 0.99))[0]
    # Bilinear: the ramp spans the texel centres either side of the edge, 10 pixels (the pixel's own
    # width blurs each end by up to one more); the B-spline spread it over ~30.
    assert 9 <= len(ramp) <= 11
    steps = np.abs(np.diff(profile[ramp[0] : ramp[-1] + 1]))
    # A straight ramp: each step the same, 0.1 of the swing a pixel, to the 16 samples' spread over
    # a pixel of a linear ramp (none: a pixel's mean of a line is its centre's value) and float.
    np.testing.assert_allclose(steps, 0.1, atol=2e-3)


def test_a_near_texel_is_reproduced_exactly(tmp_path):
    """Looking straight down at a check, the filtered value is the check's own value."""
    scene = checkerboard_scene(tmp_path)
    camera = refracta.Camera((0.3, 1.0, 0.3), (0.3, 0.0, 0.31), (1, 0, 0), 10.0, 8, 8)
    image = refracta.render(scene, camera, None, method="straight", progress=False)
    # One check fills the view: uniform up to float and filter rounding.
    assert np.allclose(image, image[0, 0], atol=1e-3)
    # That check's value, 0 or 1, up to float and filter rounding.
    assert image[0, 0, 0] in (pytest.approx(0.0, abs=1e-3), pytest.approx(1.0, abs=1e-3))


def test_obj_diffuse_maps_are_applied(tmp_path):
    """An OBJ quad with map_Kd: left half red, right half blue, as the texture says."""
    texture = np.zeros((4, 8, 3), np.float32)
    texture[:, :4] = (1.0, 0.0, 0.0)
    texture[:, 4:] = (0.0, 0.0, 1.0)
    refracta.io.write_image(tmp_path / "sign.png", texture, tonemap="linear")
    (tmp_path / "sign.mtl").write_text("newmtl sign\nKd 1 1 1\nmap_Kd sign.png\n")
    (tmp_path / "sign.obj").write_text(
        "mtllib sign.mtl\nv 10 -1 -2\nv 10 -1 2\nv 10 1 2\nv 10 1 -2\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl sign\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
    )
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_obj(str(tmp_path / "sign.obj"))
    camera = refracta.Camera((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0, 1, 0), 10.0, 40, 20)
    image = refracta.render(scene, camera, None, method="straight", progress=False)
    # +z is to the camera's right when it looks along +x with y up.
    left, right = image[10, 12], image[10, 28]
    # Saturated red vs blue: 0.9 / 0.05 leave room for the filter's blend at the texel edge.
    assert left[0] > 0.9 and left[2] < 0.05
    assert right[2] > 0.9 and right[0] < 0.05  # as above


def test_a_billboard_shows_its_picture_upright(tmp_path):
    picture = np.zeros((8, 8, 3), np.float32)
    picture[:4] = (0.0, 1.0, 0.0)  # top half green
    picture[4:] = (1.0, 1.0, 0.0)  # bottom half yellow
    refracta.io.write_image(tmp_path / "ship.png", picture, tonemap="linear", exposure=1.0)
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_billboard((50.0, 0.0, 0.0), 20.0, 10.0, str(tmp_path / "ship.png"))
    camera = refracta.Camera((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0, 1, 0), 8.0, 32, 32)
    image = refracta.render(scene, camera, None, method="straight", progress=False)
    top, bottom = image[4, 16], image[28, 16]  # 2.6 m above and below the centre (texels are 1.25 m)
    assert top[1] > 0.9 and top[0] < 0.05
    assert bottom[0] > 0.9 and bottom[1] > 0.9  # as above, white (all channels) below the red-green boundary


def test_an_environment_map_sky_follows_its_conventions(tmp_path):
    """Equirectangular, y up, Mitsuba 3's orientation (refracta.lights.EnvironmentLight): u = 1/4
    looks along +x, u = 3/4 along -x, the top row up. A map red around u = 1/4, blue elsewhere,
    white in its top rows."""
    env = np.zeros((64, 128, 3), np.float32)
    u = (np.arange(128) + 0.5) / 128
    facing_x = np.abs(u - 0.25) < 0.25  # the half of the columns around +x
    env[:, facing_x] = (1.0, 0.0, 0.0)
    env[:, ~facing_x] = (0.0, 0.0, 1.0)
    env[:4] = (1.0, 1.0, 1.0)
    refracta.io.write_image(tmp_path / "sky.exr", env)
    scene = refracta.Scene()
    scene.set_sky(environment=str(tmp_path / "sky.exr"))
    views = {(1.0, 0.0, 0.0): (1, 0, 0), (-1.0, 0.0, 0.0): (0, 0, 1), (0.0, 1.0, 0.0001): (1, 1, 1)}
    for look, expected in views.items():
        camera = refracta.Camera((0.0, 0.0, 0.0), look, (0, 1, 0) if look[1] == 0 else (1, 0, 0), 5.0, 8, 8)
        image = refracta.render(scene, camera, None, method="straight", progress=False)
        # The map's 64x128 texels blended over the 5 deg pixel footprint at a colour boundary: 2 %.
        np.testing.assert_allclose(image[4, 4], expected, atol=0.02)


def test_missing_textures_raise_io_error_naming_the_file(tmp_path):
    scene = refracta.Scene()
    with pytest.raises(refracta.IoError, match="nowhere.png"):
        scene.add_ground(texture=str(tmp_path / "nowhere.png"))
    with pytest.raises(refracta.IoError, match="nosky.exr"):
        scene.set_sky(environment=str(tmp_path / "nosky.exr"))
    (tmp_path / "a.mtl").write_text("newmtl a\nKd 1 1 1\nmap_Kd gone.png\n")
    (tmp_path / "a.obj").write_text(
        "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\nf 1/1 2/2 3/3\n"
    )
    with pytest.raises(refracta.IoError, match="gone.png"):
        scene.add_obj(str(tmp_path / "a.obj"))


def test_bad_uvs_raise_value_error():
    scene = refracta.Scene()
    with pytest.raises(ValueError, match="uvs"):
        scene.add_mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], uvs=[[0, 0], [1, 0]])


def test_scene_files_take_textures_billboards_and_environments(tmp_path):
    write_checkerboard(tmp_path / "checks.png")
    refracta.io.write_image(tmp_path / "sky.exr", np.full((8, 16, 3), 0.5, np.float32))
    (tmp_path / "scene.toml").write_text("""
[camera]
position = [0.0, 1.5, 0.0]
look_at = [100.0, 0.0, 0.0]
vfov = 20.0
size = [32, 16]

[sky]
environment = "sky.exr"

[[objects]]
type = "ground"
texture = "checks.png"
texture_size = 8.0

[[objects]]
type = "billboard"
centre = [60.0, 3.0, 0.0]
width = 6.0
height = 4.0
texture = "checks.png"
""")
    scene, camera, _ = refracta.load_scene(tmp_path / "scene.toml")
    image = refracta.render(scene, camera, None, method="straight", progress=False)
    assert np.allclose(image[0, 0], 0.5, atol=1e-3)  # the environment's sky
    # Far ground: kd 0.3 (add_ground's) x the checks' filtered mean 0.5 x the sky's 0.5 (untextured: 0.15).
    np.testing.assert_allclose(image[-1].mean(), 0.075, atol=0.03)
