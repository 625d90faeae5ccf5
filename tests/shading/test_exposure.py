"""Exposure in photographic units and automatic exposure (refracta.io; C++ shading/tonemap.h),
and the filmic ACES curve: closed forms, the defaults a new user gets, and refused settings."""

import math

import numpy as np
import pytest

import refracta
from refracta import io

# Display values are float32: a few ulps of 1.
FLOAT_TOLERANCE = 2e-7
# The log-average adds delta = 1e-6 times the mean luminance to each: an image of uniform
# luminance L gets a / (L (1 + 1e-6)) instead of a / L, 1e-6 relative at any L.
DELTA_REL = 1.1e-6
LUMA = np.array([0.2126, 0.7152, 0.0722])

# Hill's fit of the ACES RRT + sRGB ODT (BakingLab ACES.hlsl), with three.js's 1/0.6 boost:
# typed here from the source as the test's own reference.
ACES_IN = np.array([[0.59719, 0.35458, 0.04823], [0.07600, 0.90834, 0.01566], [0.02840, 0.13383, 0.83777]])
ACES_OUT = np.array([[1.60475, -0.53108, -0.07367], [-0.10208, 1.10813, -0.00605], [-0.00327, -0.07276, 1.07602]])


def aces_reference(rgb):
    v = (np.asarray(rgb, float) / 0.6) @ ACES_IN.T
    fitted = (v * (v + 0.0245786) - 0.000090537) / (v * (0.983729 * v + 0.4329510) + 0.238081)
    return np.clip(fitted @ ACES_OUT.T, 0.0, 1.0)


def test_01_ev100_of_camera_settings():
    # EV100 = log2(N^2 / t) - log2(S / 100): sunny 16 is f/16 at 1/100 s, ISO 100.
    # The same double formula: a few ulps.
    assert io.ev100(16.0, 1 / 100) == pytest.approx(math.log2(256 * 100), rel=1e-15)
    # The same double formula: a few ulps.
    assert io.ev100(16.0, 1 / 100, iso=400) == pytest.approx(math.log2(25600) - 2.0, rel=1e-15)
    assert io.ev100(1.0, 1.0) == 0.0


@pytest.mark.parametrize("ev", [-4.0, 0.0, 3.5, 15.0])
def test_02_ev100_gives_the_saturation_based_exposure(ev):
    # Lagarde & de Rousiers 2014: exposure = 1 / L_max, L_max = 1.2 x 2^EV100 [cd/m^2]; an image
    # value of 1 is 683 cd/m^2 by default (W m^-2 sr^-1 of photometric radiance), K if given.
    image = np.full((2, 3, 3), 0.7, np.float32)
    # Double closed form on both sides: a few ulps.
    assert io.exposure_of(image, ev100=ev) == pytest.approx(683.0 / (1.2 * 2.0**ev), rel=1e-15)
    # Double closed form on both sides: a few ulps.
    assert io.exposure_of(image, ev100=ev, luminous_efficacy=1.0) == pytest.approx(1.0 / (1.2 * 2.0**ev), rel=1e-15)
    np.testing.assert_array_equal(
        io.to_display(image, ev100=ev), io.to_display(image, exposure=683.0 / (1.2 * 2.0**ev))
    )


def test_03_camera_settings_are_their_ev100():
    image = np.random.default_rng(3).uniform(0, 2, size=(4, 5, 3)).astype(np.float32)
    ev = io.ev100(8.0, 1 / 250, iso=200)
    # The same EV100 reached two ways in double: a few ulps.
    assert io.exposure_of(image, f_number=8.0, shutter=1 / 250, iso=200) == pytest.approx(
        io.exposure_of(image, ev100=ev), rel=1e-15
    )
    # A stop more light (half the f-number squared... twice the time) is twice the exposure.
    assert io.exposure_of(image, f_number=8.0, shutter=1 / 125) == pytest.approx(
        2 * io.exposure_of(image, f_number=8.0, shutter=1 / 250), rel=1e-12
    )


@pytest.mark.parametrize("luminance", [0.01, 1.0, 5000.0])
def test_04_automatic_exposure_is_the_default_and_puts_the_log_average_at_middle_grey(luminance):
    image = np.full((4, 5, 3), luminance, np.float32)
    assert io.exposure_of(image) == pytest.approx(0.18 / luminance, rel=DELTA_REL)
    # Any brightness displays the same, ACES of middle grey (exactly: of 0.18 L / (L + delta), delta
    # 1e-6 of the mean luminance).
    scaled = 0.18 * luminance / (luminance + 1e-6 * luminance)
    np.testing.assert_allclose(
        io.to_display(image, gamma="linear")[0, 0], aces_reference([scaled] * 3), atol=FLOAT_TOLERANCE
    )
    np.testing.assert_array_equal(io.to_display(image), io.to_display(image, key=0.18))


def test_05_automatic_exposure_ignores_the_image_scale():
    image = np.random.default_rng(5).uniform(0.1, 3.0, size=(6, 7, 3)).astype(np.float32)
    for scale in (10.0, 1e4):
        # The scaled image's display: c scales inversely, up to delta (1e-6 / L <= 1e-5 relative for
        # L >= 0.1) and float32 rounding of the display values.
        np.testing.assert_allclose(io.to_display(image * np.float32(scale)), io.to_display(image), atol=2e-5)


def test_06_a_key_overrides_a_manual_exposure_and_manual_overrides_automatic():
    image = np.random.default_rng(6).uniform(0.0, 3.0, size=(4, 4, 3)).astype(np.float32)
    log_average = math.exp(np.mean(np.log(1e-6 + image.astype(float) @ LUMA)))
    # Measured 3.6e-7: the C++ Y row (normalised sRGB matrix) vs LUMA's 4 digits.
    assert io.exposure_of(image) == pytest.approx(0.18 / log_average, rel=1e-6)
    assert io.exposure_of(image, key=0.09) == pytest.approx(0.09 / log_average, rel=1e-6)  # as above (3.6e-7 measured)
    assert io.exposure_of(image, exposure=3.0) == 3.0
    # With a key the manual exposure has no say: the image itself is metered.
    # As above (3.6e-7 measured).
    assert io.exposure_of(image, exposure=3.0, key=0.09) == pytest.approx(0.09 / log_average, rel=1e-6)


def test_06b_a_key_overrides_a_manual_exposure_also_over_black_pixels():
    # A trial's case: half black, half white. Metered after exposure=1000, the black pixels' delta
    # (set in the scaled units) made the exposure 22x that of the key alone (254.6 vs 5692).
    image = np.zeros((8, 8, 3), np.float32)
    image[:, 4:] = 1.0
    alone = io.exposure_of(image, key=0.18)
    assert alone == pytest.approx(0.18 / math.sqrt(1e-6 * 0.5), rel=1e-6)  # delta = 1e-6 x mean 0.5; as above
    for manual in ({"exposure": 1000.0}, {"ev100": 0.0}, {"exposure": 1e-3}):
        assert io.exposure_of(image, key=0.18, **manual) == alone  # the same arithmetic: bit-equal
    np.testing.assert_array_equal(io.to_display(image, key=0.18, exposure=1000.0), io.to_display(image, key=0.18))


def test_07_aces_is_hills_fit():
    rgb = np.array(
        [[[0.0, 0.0, 0.0], [0.18, 0.18, 0.18], [0.8, 0.4, 0.1], [5.0, 1.0, 0.2], [100.0, 100.0, 100.0]]], np.float32
    )
    out = io.to_display(rgb, exposure=1.0, tonemap="aces", gamma="linear")
    np.testing.assert_allclose(out[0], aces_reference(rgb[0].astype(float)), atol=1e-6)  # float32 output
    # Middle grey displays at ~0.5 after the sRGB curve (the 1/0.6 boost), huge values at white.
    grey = io.to_display(rgb[:, 1:2], exposure=1.0, tonemap="aces")[0, 0, 0]
    assert 0.45 < grey < 0.55  # middle grey after ACES and sRGB is ~0.5 (Hill's fit); 0.05 off is another curve
    assert io.to_display(rgb[:, 4:5], exposure=1.0, tonemap="aces", gamma="linear")[0, 0, 0] == 1.0
    # Grey images take the same curve on their one channel.
    np.testing.assert_allclose(
        io.to_display(rgb[..., :1], exposure=1.0, tonemap="aces", gamma="linear")[0, :, 0],
        aces_reference(np.repeat(rgb[0, :, :1], 3, axis=1).astype(float))[:, 0],
        atol=2e-5,
    )


def test_08_float_files_take_the_manual_exposure_only(tmp_path):
    image = np.random.default_rng(8).uniform(0, 4, size=(3, 4, 3)).astype(np.float32)
    io.write_image(tmp_path / "auto.exr", image)  # no automatic exposure in linear files
    np.testing.assert_array_equal(io.read_image(tmp_path / "auto.exr"), image)
    io.write_image(tmp_path / "ev.exr", image, ev100=0.0, luminous_efficacy=1.0)
    # EXR stores float32: a few ulps of 1 after the division.
    np.testing.assert_allclose(io.read_image(tmp_path / "ev.exr"), image / np.float32(1.2), rtol=1e-6)
    io.write_image(tmp_path / "auto.png", image)
    # 8-bit PNG: rounding to the nearest 1/255, plus float slack.
    np.testing.assert_allclose(io.read_image(tmp_path / "auto.png"), io.to_display(image), atol=0.51 / 255)


@pytest.mark.parametrize(
    "arguments, name",
    [
        (dict(ev100=float("nan")), "ev100"),
        (dict(exposure=-1.0), "exposure"),
        (dict(shutter=0.0, f_number=8.0), "shutter"),
        (dict(shutter=0.01, f_number=-8.0), "f_number"),
        (dict(shutter=0.01, f_number=8.0, iso=0.0), "iso"),
        (dict(shutter=0.01), "f_number"),
        (dict(exposure=2.0, ev100=3.0), "one manual exposure"),
        (dict(ev100=3.0, shutter=0.01, f_number=4.0), "one manual exposure"),
        (dict(key=float("nan")), "key"),
        (dict(ev100=10.0, luminous_efficacy=0.0), "luminous_efficacy"),
    ],
)
def test_09_bad_exposure_settings_are_refused_naming_them(arguments, name):
    image = np.ones((2, 2, 3), np.float32)
    with pytest.raises(ValueError, match=name):
        io.to_display(image, **arguments)
    with pytest.raises(ValueError, match=name):
        io.write_image("unused.png", image, **arguments)
    with pytest.raises(ValueError, match="f_number"):
        io.ev100(0.0, 0.01)


def test_10_example_scenes_are_well_exposed_by_default():
    # A new user's first picture: hot_road and cold_sea written with no exposure argument. Well
    # exposed: the median displayed luminance within a stop-ish of middle grey (0.3-0.7 after
    # sRGB; the old default, exposure 1 with Reinhard, gave 0.88 and 0.83: washed out), at most
    # 2 % of pixels clipped to white and 2 % crushed to black.
    from refracta import examples

    for example in (examples.hot_road(width=160, height=60), examples.cold_sea(width=160, height=60)):
        image = refracta.render(
            example.scene, example.camera, example.field, max_length=example.max_length, progress=False
        )
        shown = io.to_display(image) @ LUMA
        assert 0.3 < np.median(shown) < 0.7, example.name  # the bounds argued in the comment above
        # The bounds argued in the comment above.
        assert np.mean(shown > 0.99) < 0.02 and np.mean(shown < 0.02) < 0.02, example.name


def test_11_a_sunlit_example_is_well_exposed_near_sunny_16():
    # The examples' unit is W m^-2 sr^-1 (photometric Y), 683 cd/m^2 each: their automatic
    # exposure is a real camera's. Sunny 16 (f/16, 1/100 s, ISO 100: EV100 14.6) for a sunlit
    # scene of dark asphalt: the automatic exposure within 2 stops of it (measured: EV100 13.3).
    from refracta import examples

    road = examples.hot_road(width=160, height=60)
    image = refracta.render(road.scene, road.camera, road.field, max_length=road.max_length, progress=False)
    automatic_ev100 = math.log2(683.0 / (1.2 * io.exposure_of(image)))
    assert abs(automatic_ev100 - io.ev100(16.0, 1 / 100)) < 2.0  # the 2 stops argued in the comment above
