"""Film and tone mapping (shared/SHADING.md section 8): closed forms, Reinhard's log-average,
monotonicity, the transfer curves' inverses, and no NaN for huge values."""

import struct

import numpy as np
import pytest

import refracta

# The display values are float32: a few ulps of 1.
FLOAT_TOLERANCE = 2e-7
# Reinhard's delta = 1e-6 inside the log-average: on a constant image of luminance Lw the scaled
# L is a Lw / (delta + Lw), a within 1e-6 / Lw relative.
REINHARD_DELTA = 1e-6
LUMA = np.array([0.2126, 0.7152, 0.0722])  # Y row of the IEC 61966-2-1 matrix (colour-science)


def display(image, **kwargs):
    kwargs.setdefault("gamma", "linear")
    return refracta.io.to_display(np.asarray(image, np.float32), **kwargs)


def srgb_decode(v):
    return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)


def test_linear_and_film_closed_forms():
    x = np.array([[0.0, 0.1, 0.5, 1.0, 2.0, 10.0]], np.float32)
    for c in (0.5, 1.0, 3.0):
        np.testing.assert_allclose(
            display(x, exposure=c, tonemap="linear")[..., 0], np.minimum(c * x, 1.0), atol=FLOAT_TOLERANCE
        )
        np.testing.assert_allclose(
            display(x, exposure=c, tonemap="film")[..., 0], 1.0 - np.exp(-c * x), atol=FLOAT_TOLERANCE
        )


def test_reinhard_closed_forms_on_grey():
    # Without a key L = c Lw; eq. 3 Ld = L/(1+L), eq. 4 Ld = L(1 + L/W^2)/(1+L) (clamped at 1).
    x = np.array([[0.0, 0.25, 1.0, 3.0, 9.0]], np.float32)
    # exposure=1: a manual exposure (the default is automatic, tests/shading/test_exposure.py).
    np.testing.assert_allclose(display(x, tonemap="reinhard", exposure=1.0)[..., 0], x / (1 + x), atol=FLOAT_TOLERANCE)
    w = 3.0
    expected = np.minimum(x * (1 + x / w**2) / (1 + x), 1.0)
    np.testing.assert_allclose(
        display(x, tonemap="reinhard", white=w, exposure=1.0)[..., 0], expected, atol=FLOAT_TOLERANCE
    )
    assert display(x, tonemap="reinhard", white=w, exposure=1.0)[0, 3, 0] == pytest.approx(1.0)  # L = W maps to white


@pytest.mark.parametrize("luminance", [0.01, 1.0, 1000.0])
def test_reinhard_log_average_of_a_constant_image_is_the_key(luminance):
    image = np.full((4, 5, 3), luminance, np.float32)
    key = 0.18
    exposure = 7.0  # cancels in L = (a / Lw_bar) Lw, but for delta
    out = display(image, tonemap="reinhard", key=key, exposure=exposure)
    lw = exposure * luminance
    delta = REINHARD_DELTA * lw  # in the image's units: times its mean luminance
    scaled = key * lw / (delta + lw)  # L = a exactly, up to delta
    assert scaled == pytest.approx(key, rel=delta / lw * 1.01)
    np.testing.assert_allclose(out, scaled / (1 + scaled), rtol=1e-6)  # float32 output: a few ulps


def test_reinhard_log_average_of_two_levels():
    # Half the pixels at 1, half at 100: Lw_bar = sqrt((1+d)(100+d)) ~ 10, d = REINHARD_DELTA times
    # the mean luminance (50.5).
    image = np.ones((2, 2, 1), np.float32)
    image[1] = 100.0
    lbar = np.exp(np.mean(np.log(REINHARD_DELTA * image.mean() + image)))
    scaled = 0.18 / lbar * image
    # Float32 output: a few ulps.
    np.testing.assert_allclose(display(image, tonemap="reinhard", key=0.18), scaled / (1 + scaled), rtol=1e-6)


def test_reinhard_scales_colour_by_the_luminance_ratio():
    rgb = np.array([[[0.8, 0.4, 0.1]]], np.float32)
    lw = LUMA @ rgb[0, 0]
    out = display(rgb, tonemap="reinhard", exposure=1.0)[0, 0]
    np.testing.assert_allclose(out, rgb[0, 0] * (1 / (1 + lw)), rtol=1e-5)  # Ld/Lw = 1/(1+Lw)
    np.testing.assert_allclose(out / out[0], rgb[0, 0] / rgb[0, 0, 0], rtol=1e-5)  # hue kept


def test_reinhard_white_keeps_the_hue_of_a_colour_above_it():
    # (3, 1, 0.2) with white=1: L >= white, so Ld = 1 and the colour is scaled by 1/Lw, its red
    # channel then clamped: shown (1, 0.731, 0.146), not burnt to white (the docstring's promise).
    rgb = np.array([[[3.0, 1.0, 0.2]]], np.float32)
    lw = LUMA @ rgb[0, 0]
    out = display(rgb, tonemap="reinhard", exposure=1.0, white=1.0)[0, 0]
    np.testing.assert_allclose(out, np.minimum(rgb[0, 0] / lw, 1.0), rtol=1e-5)  # float32 output


def png_colour_chunks(path) -> dict:
    data, at, chunks = path.read_bytes(), 8, {}
    while at < len(data):
        (length,) = struct.unpack(">I", data[at : at + 4])
        kind = data[at + 4 : at + 8].decode()
        chunks[kind] = data[at + 8 : at + 8 + length]
        at += 12 + length
    return {k: v for k, v in chunks.items() if k in ("sRGB", "gAMA", "iCCP")}


def test_a_png_says_which_transfer_curve_encodes_it(tmp_path):
    # A viewer that reads the PNG's colour chunks decodes it as written: the sRGB chunk for the sRGB
    # curve, gAMA 1/g (in units of 1e-5) for a gamma, 1 for linear output.
    image = np.full((2, 2, 3), 0.5, np.float32)
    for gamma, expected in (("srgb", {"sRGB", "gAMA"}), ("linear", {"gAMA"}), (2.2, {"gAMA"})):
        refracta.io.write_image(tmp_path / "a.png", image, gamma=gamma)
        chunks = png_colour_chunks(tmp_path / "a.png")
        assert set(chunks) == expected, gamma
        (gama,) = struct.unpack(">I", chunks["gAMA"])
        assert gama == {"srgb": 45455, "linear": 100000, 2.2: 45455}[gamma]  # the PNG spec's integer 1e5/g


@pytest.mark.parametrize("tonemap", ["linear", "film", "reinhard", "aces"])
def test_operators_are_monotone_and_bounded(tonemap):
    x = np.geomspace(1e-6, 1e6, 400, dtype=np.float32)[None, :]
    for gamma in ("srgb", "linear", 2.2):
        y = display(x, tonemap=tonemap, gamma=gamma)[0, :, 0]
        assert np.all(np.diff(y) >= 0.0) and y.min() >= 0.0 and y.max() <= 1.0


def test_gamma_and_srgb_curves_invert():
    x = np.linspace(0.0, 1.0, 101, dtype=np.float32)[None, :]
    for g in (1.0, 1.7, 2.2, 3.0):
        p = display(x, tonemap="linear", gamma=g, exposure=1.0)[0, :, 0]
        np.testing.assert_allclose(p.astype(float) ** g, x[0], atol=1e-6)  # float32 output raised to g: a few ulps
    p = display(x, tonemap="linear", gamma="srgb", exposure=1.0)[0, :, 0]
    # Float32 output through the sRGB decode: a few ulps.
    np.testing.assert_allclose(srgb_decode(p.astype(float)), x[0], atol=1e-6)


def test_huge_values_and_exposures_never_give_nan():
    image = np.array([[[3e38, 1.0, 0.0], [3e38, 3e38, 3e38], [0.0, 0.0, 0.0]]], np.float32)
    for tonemap in ("linear", "film", "reinhard", "aces"):
        for exposure in (1.0, 1e10, 1e300):
            for kwargs in ({}, {"key": 0.18}) + (({"white": 2.0},) if tonemap == "reinhard" else ()):
                out = display(image, tonemap=tonemap, exposure=exposure, **kwargs)
                assert np.all(np.isfinite(out)) and out.min() >= 0.0 and out.max() <= 1.0
    assert display(image, tonemap="linear", exposure=1e300)[0, 1].tolist() == [1.0, 1.0, 1.0]


def test_alpha_is_untouched_and_png_matches_to_display(tmp_path):
    image = np.random.default_rng(4).uniform(0, 5, size=(3, 4, 4)).astype(np.float32)
    out = refracta.io.to_display(image, tonemap="reinhard", key=0.18)
    np.testing.assert_array_equal(out[..., 3], image[..., 3])
    refracta.io.write_image(tmp_path / "a.png", image[..., :3], tonemap="reinhard", key=0.18)
    # 8-bit PNG: half a level, plus float slack.
    np.testing.assert_allclose(refracta.io.read_image(tmp_path / "a.png"), out[..., :3], atol=0.51 / 255)
    # EXR stays linear: the manual exposure applies, the tone curve and key do not, and say so.
    with pytest.warns(UserWarning, match="a float format is written linear: tonemap, key shape only displayed"):
        refracta.io.write_image(tmp_path / "a.exr", image, exposure=2.0, tonemap="reinhard", key=0.18)
    exposed = image.copy()
    exposed[..., :3] *= 2.0  # the colours; alpha is a coverage, not light
    np.testing.assert_array_equal(refracta.io.read_image(tmp_path / "a.exr"), exposed)


@pytest.mark.parametrize(
    "fields, named",
    [
        (dict(gamma=1.8), "gamma"),
        (dict(gamma="linear"), "gamma"),
        (dict(tonemap="reinhard", white=4.0), "tonemap, white"),
        (dict(white_balance="daylight"), "white_balance"),
        (dict(display=refracta.DisplaySettings(tonemap="film")), "tonemap"),
    ],
)
def test_a_float_file_names_each_display_setting_it_leaves_unused(tmp_path, fields, named):
    image = np.ones((2, 2, 3), np.float32)
    with pytest.warns(UserWarning, match=f": {named} shape only displayed"):
        refracta.io.write_image(tmp_path / "a.exr", image, **fields)


def test_a_float_file_with_exposure_only_or_defaults_warns_of_nothing(tmp_path):
    image = np.ones((2, 2, 3), np.float32)
    refracta.io.write_image(tmp_path / "a.exr", image, exposure=2.0, ev100=None)  # warnings are errors here
    refracta.io.write_image(tmp_path / "b.exr", image, display=refracta.DisplaySettings())


def test_bad_options_raise_value_error():
    image = np.ones((2, 2, 3), np.float32)
    with pytest.raises(ValueError, match=r"gamma must be in \[1, 3\] \(got 5\)"):
        refracta.io.to_display(image, gamma=5.0)
    with pytest.raises(ValueError, match="gamma must be 'srgb'"):
        refracta.io.to_display(image, gamma="rec709")
    with pytest.raises(ValueError, match=r"key must be > 0.*white must be > 0"):  # every problem listed
        refracta.io.to_display(image, tonemap="reinhard", key=-1.0, white=0.0)
    with pytest.raises(ValueError, match="exposure"):
        refracta.io.to_display(image, exposure=0.0)
