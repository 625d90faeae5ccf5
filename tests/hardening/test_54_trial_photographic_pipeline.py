"""A photographer's trial of the camera and the image files (7 December): alpha where a format
cannot keep it, WebP's alpha, small JPEG 2000 files, PNG transfer curves read back, automatic
exposure across units, portrait sensors, the scene file's lens camera, framing's message and
Radiance HDR's negative values."""

import math
import warnings

import numpy as np
import pytest
from PIL import Image

import refracta
from refracta import io
from refracta.scene_file import load_scene

# One 8-bit step: what quantising a display value to a byte may change.
BYTE = 1.0 / 255.0


def grey(channels, value=0.5, alpha=1.0):
    image = np.full((8, 8, channels), value, np.float32)
    if channels in (2, 4):
        image[..., -1] = alpha
    return image


def test_a_grey_image_with_alpha_writes_a_grey_jpeg(tmp_path):
    # The trial's case: JPEG keeps no alpha, and a grey image's alpha was stored as green.
    path = tmp_path / "grey.jpg"
    io.write_image(path, grey(2, alpha=0.5), exposure=1.0, tonemap="linear")
    stored = Image.open(path)
    assert stored.mode == "L"
    expected = round(io.to_display(grey(1), exposure=1.0, tonemap="linear")[0, 0, 0] * 255)
    # JPEG of a flat image: within one byte of the display value (measured exact).
    assert abs(stored.getpixel((4, 4)) - expected) <= 1


@pytest.mark.parametrize("alpha", [0.75, 0.5, 0.25])
def test_webp_keeps_straight_colour_under_alpha(tmp_path, alpha):
    # OIIO 2.4's WebP writer divides by alpha (0.5 grey at alpha 0.5 was stored white) and its
    # reader multiplies by it: Pillow (an independent reader) and read_image see the PNG's colour.
    image = grey(4, alpha=alpha)
    io.write_image(tmp_path / "a.webp", image, exposure=1.0, tonemap="linear")
    io.write_image(tmp_path / "a.png", image, exposure=1.0, tonemap="linear")
    png = np.asarray(Image.open(tmp_path / "a.png"), float)[4, 4]
    webp = np.asarray(Image.open(tmp_path / "a.webp"), float)[4, 4]
    # WebP is lossy at quality 100, and undoing the writer's division amplifies the rounding by
    # alpha^(-1/2.2) <= 1.9: measured within 1 byte; 3 bytes allowed.
    np.testing.assert_allclose(webp[:3], png[:3], atol=3)
    assert webp[3] == pytest.approx(png[3], abs=1)  # alpha: lossless in WebP; 1 byte of rounding
    read = io.read_image(tmp_path / "a.webp")
    np.testing.assert_allclose(read[4, 4, :3], io.read_image(tmp_path / "a.png")[4, 4, :3], atol=3 * BYTE)  # as above


def test_jpeg_2000_refuses_images_it_would_write_empty(tmp_path):
    # OpenJPEG's default resolution levels need 32 pixels a side: smaller ones became a 77-byte file.
    with pytest.raises(ValueError, match="JPEG 2000 needs at least 32 pixels"):
        io.write_image(tmp_path / "small.jp2", np.full((20, 15, 3), 0.5, np.float32))
    assert not (tmp_path / "small.jp2").exists()
    io.write_image(tmp_path / "ok.jp2", np.full((32, 32, 3), 0.5, np.float32), exposure=1.0, tonemap="linear")
    assert io.read_image(tmp_path / "ok.jp2").shape == (32, 32, 3)


@pytest.mark.parametrize("gamma", ["linear", 2.2, "srgb"])
def test_read_image_linear_decodes_the_transfer_the_png_names(tmp_path, gamma):
    values = np.array([0.2, 0.5, 0.8], np.float32)
    image = np.repeat(values[None, :, None], 3, axis=2)
    io.write_image(tmp_path / "v.png", image, exposure=1.0, tonemap="linear", gamma=gamma)
    # Each value quantised to a byte in the encoded space, decoded: within half a byte (1/510)
    # times the decoding curve's slope, at most ~2.0 (gamma 2.2 at 0.8: 2.2 x 0.904^1.2): 4e-3.
    np.testing.assert_allclose(io.read_image(tmp_path / "v.png", linear=True)[0, :, 0], values, atol=4e-3)


def test_a_texture_from_a_linear_png_lights_as_the_srgb_png_of_the_same_values(tmp_path):
    # Textures decode by the same rule: before, the linear PNG's 128 was decoded from sRGB (0.216).
    def textured_render(gamma):
        path = tmp_path / f"half_{gamma}.png"
        io.write_image(path, np.full((16, 16, 3), 0.5, np.float32), exposure=1.0, tonemap="linear", gamma=gamma)
        scene = refracta.Scene()
        scene.add_ground(height=0.0, size=40.0, texture=str(path), texture_size=4.0)
        scene.set_environment(1.0)
        camera = refracta.Camera((0, 5, 0.01), (0, 0, 0), vfov=20, width=8, height=8)
        return refracta.render(scene, camera, None, method="straight", spp=16, transport="direct").mean()

    # 0.5 stored as 128 (linear: 0.5020) and 188 (sRGB: 0.5029): 0.2 % apart, 3e-3 allowed.
    assert textured_render("linear") == pytest.approx(textured_render("srgb"), rel=3e-3)


def test_automatic_exposure_scales_exactly_with_the_units_over_black_pixels():
    # The trial's case: 5 % black pixels; the exposure times the scale moved 1.39 -> 2.33 from 1 to 1e5.
    image = np.random.default_rng(0).uniform(0.1, 1.0, (20, 20, 3)).astype(np.float32)
    image[:1] = 0.0
    reference = io.exposure_of(image)
    for scale in (1e-3, 10.0, 683.0, 1e5):
        # float32 sums of the scaled luminances: 1e-6 relative.
        assert io.exposure_of(image * np.float32(scale)) * scale == pytest.approx(reference, rel=1e-6)


@pytest.mark.parametrize(
    "sensor, size",
    # 960 px along the sensor's longer side, the other side its shape (17.3 / 13 x 721 = 959.4).
    [((36.0, 24.0), (960, 640)), ((24.0, 36.0), (640, 960)), ((17.3, 13.0), (960, 721))],
)
def test_a_photographic_camera_without_a_size_takes_the_whole_sensor(sensor, size):
    camera = refracta.Camera.photographic((0, 1, 0), (0, 1, -10), 50.0, sensor_mm=sensor)
    assert (camera.width, camera.height) == size
    # The whole sensor height: 2 atan(h / 2f); within the image's rounding to whole pixels (721
    # for 720.8 crops the sensor's height by up to one pixel in 720: 1.4e-3).
    assert camera.vfov == pytest.approx(math.degrees(2 * math.atan(sensor[1] / 100.0)), rel=1.4e-3)


def test_a_scene_files_lens_camera_frames_as_camera_photographic(tmp_path):
    path = tmp_path / "lens.toml"
    path.write_text("[camera]\nposition = [0, 1, 0]\nlook_at = [0, 1, -10]\nfocal_length_mm = 50\n")
    loaded = load_scene(path).camera
    direct = refracta.Camera.photographic((0, 1, 0), (0, 1, -10), 50.0)
    assert loaded == direct
    path.write_text("[camera]\nposition = [0, 1, 0]\nlook_at = [0, 1, -10]\n")
    assert load_scene(path).camera == refracta.Camera((0, 1, 0), (0, 1, -10))  # Camera's own defaults


def test_framing_names_a_vfov_too_narrow_for_the_scenes_reach():
    with pytest.raises(ValueError, match="vfov of 0.001 deg .* give a wider vfov"):
        refracta.Camera.framing(((0, 0, 0), (1000, 1000, 1000)), vfov=0.001)


def test_radiance_hdr_warns_of_the_negative_values_it_cannot_keep(tmp_path):
    image = np.full((4, 4, 3), 0.5, np.float32)
    image[0, 0, 0] = -1.0
    with pytest.warns(UserWarning, match="Radiance HDR stores no negative values: 1 written as 0"):
        io.write_image(tmp_path / "n.hdr", image)
    assert io.read_image(tmp_path / "n.hdr")[0, 0, 0] == 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        io.write_image(tmp_path / "n.exr", image)  # EXR keeps them, with no warning
    assert io.read_image(tmp_path / "n.exr")[0, 0, 0] == -1.0


def test_webp_refuses_a_grey_image_with_alpha_by_name(tmp_path):
    # Its colour is not premultiplied as a 4-channel image's (that read past a 2-channel image's end).
    with pytest.raises(refracta.IoError, match="webp does not support 2-channel images"):
        io.write_image(tmp_path / "g.webp", grey(2, alpha=0.5), exposure=1.0, tonemap="linear")
