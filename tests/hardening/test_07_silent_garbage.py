"""Inputs that gave NaN or garbage without a word (issue 13) now give the right value or a
ValueError naming the parameter."""

import numpy as np
import pytest

import refracta


def test_flat_height_below_the_earths_centre_is_refused():
    earth = refracta.CurvedEarth(refracta.PhysicalAtmosphere())
    with pytest.raises(ValueError, match=r"true height h must be > -radius = -6371000 m \(got -7000000 m\)"):
        earth.flat_height(-7e6)
    # Just above the centre it is finite: y = R ln(1 + h/R).
    assert np.isfinite(earth.flat_height(-6.37e6))
    with pytest.raises(ValueError, match="no finite true height"):
        earth.true_height(1e12)


def test_a_camera_at_the_edge_of_double_range_aims_correctly():
    # position and look_at 2e308 apart: look_at - position overflowed and every ray was NaN. A
    # position that far is now refused (scene coordinates end at the scene's reach, 1e7 m); a
    # look_at -1e308 away still overflows the difference.
    with pytest.raises(ValueError, match=r"Camera: position must be finite and within 10000000 m"):
        refracta.Camera([1e308, 0, 0], [-1e308, 0, 0])
    far = refracta.Camera([1, 0, 0], [-1e308, 0, 0])
    near = refracta.Camera([1, 0, 0], [-1, 0, 0])
    for u, v in [(1, 1), (320.5, 180.5), (639, 359)]:
        # The same direction from both cameras: double rounding.
        np.testing.assert_allclose(far.ray(u, v)[1], near.ray(u, v)[1], atol=1e-15)


def test_to_display_of_huge_radiance_is_white_and_png_writes_white(tmp_path):
    image = np.full((2, 2, 3), 3e38, np.float32)  # times exposure 10 overflows float32
    for tonemap in ("reinhard", "film", "linear"):
        display = refracta.io.to_display(image, exposure=10.0, tonemap=tonemap)
        np.testing.assert_allclose(display, 1.0, atol=1e-6)  # saturated white in float32: a few ulps of 1
    refracta.io.write_image(tmp_path / "white.png", image, exposure=10.0)
    # Default rtol 1e-7: saturated white is exactly 255/255 in the PNG.
    np.testing.assert_allclose(refracta.io.read_image(tmp_path / "white.png"), 1.0)


def test_a_ground_texture_repeating_beyond_float_precision_is_refused(tmp_path):
    texture = tmp_path / "t.png"
    refracta.io.write_image(texture, np.full((4, 4, 3), 0.5, np.float32))
    scene = refracta.Scene()
    with pytest.raises(ValueError, match=r"texture_size must be > 0 and at least size / 2e6 = 0.01 m \(got 1e-40\)"):
        scene.add_ground(texture=str(texture), texture_size=1e-40)
    scene.add_ground(texture=str(texture), texture_size=0.01)  # 1e6 repeats: the bound itself


def write_pfm(path, pixels):
    """A Portable Float Map (bottom row first, little-endian): write_image refuses NaN, files may not."""
    height, width, _ = pixels.shape
    path.write_bytes(f"PF\n{width} {height}\n-1.0\n".encode() + pixels[::-1].astype("<f4").tobytes())


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_a_texture_with_non_finite_texels_is_refused(tmp_path, bad):
    # NaN texels were filtered into the MIP levels and rendered as -65504 (half-float's limit).
    pixels = np.full((4, 4, 3), 0.5, np.float32)
    pixels[1, 2, 0] = bad
    write_pfm(tmp_path / "bad.pfm", pixels)
    with pytest.raises(refracta.IoError, match="has 1 NaN or infinite texel values"):
        refracta.Scene().add_ground(texture=str(tmp_path / "bad.pfm"))
