"""White balance in the display path (refracta.io white_balance=, C++ shading/tonemap.h): a grey lit
by the named light shows neutral, the adaptation is colour-science's Bradford von Kries transform,
the kelvin and preset whites are the Planckian and CIE daylight loci, and bad values are
ValueErrors naming white_balance."""

import pickle

import colour
import numpy as np
import pytest

import refracta
from refracta import io

SHAPE = colour.SpectralShape(360, 830, 1)  # refracta's CIE tables: 1 nm over [360, 830] nm
CMFS = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(SHAPE)
SRGB = colour.RGB_COLOURSPACES["sRGB"]
# refracta's Planck uses the exact SI 2019 second radiation constant h c / k; colour-science's
# default is the CIE's rounded 1.4388e-2 m K (which moves a 3200 K white by ~1e-5 in XYZ).
C2 = 6.62607015e-34 * 299792458.0 / 1.380649e-23
# Both integrate the same 1 nm tables (colour-science's sum against refracta's trapezoid: the end
# samples, where the colour-matching functions are ~1e-4 of their peak, weigh half): measured 5e-7
# relative at most (2856 K's blue gain); 1e-5 relative (1e-6 absolute for entries near 0) leaves room.
MATRIX_RTOL, MATRIX_ATOL = 1e-5, 1e-6
# The display path runs in float32 (the image and the balanced pixel): relative 1e-6 per channel.
FLOAT32_TOLERANCE = 3e-6


def blackbody_xyz(kelvin: float) -> np.ndarray:
    """XYZ (Y = 1) of Planck's radiator at `kelvin` by colour-science."""
    sd = colour.SpectralDistribution(
        dict(zip(SHAPE.wavelengths, colour.colorimetry.planck_law(SHAPE.wavelengths * 1e-9, kelvin, c2=C2)))
    )
    xyz = colour.sd_to_XYZ(sd, CMFS, method="Integration")
    return xyz / xyz[1]


def reference_matrix(light_xyz: np.ndarray) -> np.ndarray:
    """colour-science's Bradford adaptation of `light_xyz` to the sRGB white, in linear sRGB, the
    light taken at the white's luminance (so a white's luminance is kept)."""
    display_white = np.linalg.solve(SRGB.matrix_XYZ_to_RGB, np.ones(3))
    light = np.asarray(light_xyz) * display_white[1] / light_xyz[1]
    adapt = colour.adaptation.matrix_chromatic_adaptation_VonKries(light, display_white, transform="Bradford")
    return SRGB.matrix_XYZ_to_RGB @ adapt @ np.linalg.inv(SRGB.matrix_XYZ_to_RGB)


PLAIN = dict(exposure=1.0, tonemap="linear", gamma="linear")  # display values = the balanced radiance


def test_01_a_grey_card_lit_by_a_3200k_blackbody_is_neutral_at_3200k():
    card = 0.18 * (SRGB.matrix_XYZ_to_RGB @ blackbody_xyz(3200.0))  # a 18 % grey under that light
    assert card[0] / card[2] > 5.0  # unbalanced: deep orange
    # As a colour temperature, as an RGB white (the card's own pixel: a custom white balance) and as
    # the 'tungsten' preset: neutral, its luminance Y kept (the sRGB white (1, 1, 1) has Y 0.99996
    # in the standard's 4-decimal matrix, so the grey shows at 0.18 / 0.99996).
    for balance in (3200, tuple(card), "tungsten"):
        shown = io.to_display(np.tile(card, (2, 2, 1)), white_balance=balance, **PLAIN)[0, 0].astype(np.float64)
        np.testing.assert_allclose(shown / shown.mean(), 1.0, rtol=FLOAT32_TOLERANCE)
        np.testing.assert_allclose(np.linalg.inv(SRGB.matrix_XYZ_to_RGB)[1] @ shown, 0.18, rtol=FLOAT32_TOLERANCE)


@pytest.mark.parametrize("kelvin", [1500.0, 2856.0, 3200.0, 4000.0, 5500.0, 10000.0, 40000.0])
def test_02_kelvin_is_bradford_from_the_planckian_white_as_colour_science(kelvin):
    matrix = io.white_balance_of(np.ones((1, 1, 3)), kelvin)
    np.testing.assert_allclose(matrix, reference_matrix(blackbody_xyz(kelvin)), rtol=MATRIX_RTOL, atol=MATRIX_ATOL)


@pytest.mark.parametrize(("preset", "cct"), [("daylight", 5503.0), ("cloudy", 6504.0), ("shade", 7504.0)])
def test_03_presets_are_the_cie_daylight_illuminants(preset, cct):
    xy = colour.temperature.CCT_to_xy_CIE_D(cct)  # CIE 015:2004 daylight locus
    matrix = io.white_balance_of(np.ones((1, 1, 3)), preset)
    np.testing.assert_allclose(matrix, reference_matrix(colour.xy_to_XYZ(xy)), rtol=MATRIX_RTOL, atol=MATRIX_ATOL)
    # The tabulated illuminant's chromaticity: its y (D55 0.34744) lies 1.1e-4 below the locus'
    # value at 5503 K (the CIE derived the tables' spectra from the locus and rounded them).
    tabulated = colour.CCS_ILLUMINANTS["CIE 1931 2 Degree Standard Observer"][
        {5503.0: "D55", 6504.0: "D65", 7504.0: "D75"}[cct]
    ]
    np.testing.assert_allclose(xy, tabulated, atol=2e-4)  # the 1.1e-4 rounding above


def test_04_none_is_the_identity_and_cloudy_nearly():
    image = np.random.default_rng(1).random((4, 5, 3)).astype(np.float32) * 3.0
    assert np.array_equal(io.to_display(image), io.to_display(image, white_balance="none"))
    np.testing.assert_array_equal(io.white_balance_of(image), np.eye(3))
    # D65 by the daylight locus (x 0.31271, y 0.32912) against sRGB's 4-decimal white: 8e-4 apart.
    np.testing.assert_allclose(io.white_balance_of(image, "cloudy"), np.eye(3), atol=1e-3)


def test_05_auto_is_grey_world():
    rng = np.random.default_rng(2)
    light = np.array([1.0, 0.69, 0.36])  # the cold sea's 10-deg sun
    # Greys and tints (+-20 % per channel) under that light, dim enough that no balanced channel
    # clips at 1 or goes below 0 (the linear display below shows the balanced radiance itself).
    image = (light * rng.uniform(0.1, 0.3, (16, 24, 1)) * rng.uniform(0.8, 1.2, (16, 24, 3))).astype(np.float32)
    mean = image.reshape(-1, 3).astype(np.float64).mean(axis=0)
    np.testing.assert_allclose(
        io.white_balance_of(image, "auto"),
        reference_matrix(np.linalg.solve(SRGB.matrix_XYZ_to_RGB, mean)),
        rtol=MATRIX_RTOL,
        atol=MATRIX_ATOL,
    )
    balanced = io.to_display(image, white_balance="auto", **PLAIN).reshape(-1, 3).astype(np.float64).mean(axis=0)
    # The mean shows grey: float32 pixels summed in double, 1e-5 for their rounding.
    np.testing.assert_allclose(balanced / balanced.mean(), 1.0, atol=1e-5)
    # Grey images and black ones are left as they are.
    np.testing.assert_array_equal(io.white_balance_of(np.zeros((3, 3, 3)), "auto"), np.eye(3))
    np.testing.assert_array_equal(io.white_balance_of(np.ones((3, 3, 1)), 3200), np.eye(3))


def test_06_the_setting_travels_and_pickles_and_the_exposure_meters_before_it():
    settings = refracta.DisplaySettings(white_balance=(1.0, 0.7, 0.4))
    assert settings.white_balance == (1.0, 0.7, 0.4)
    assert pickle.loads(pickle.dumps(settings)).white_balance == (1.0, 0.7, 0.4)
    assert refracta.DisplaySettings(white_balance=4000).white_balance == 4000.0
    assert refracta.DisplaySettings().white_balance == "none"
    image = np.random.default_rng(4).random((6, 6, 3)) * [1.0, 0.7, 0.4]
    assert io.exposure_of(image) == io.exposure_of(image, display=settings)
    a = io.to_display(image, display=settings)
    assert np.array_equal(a, io.to_display(image, white_balance=(1.0, 0.7, 0.4)))


@pytest.mark.parametrize(
    "bad",
    [
        float("nan"),
        0.0,
        -3200.0,
        999.0,
        40001.0,
        float("inf"),
        "sunset",
        (0.0, 0.0, 0.0),  # no light
        (1.0, -1.0, 1.0),  # Y < 0: no light's colour
        (1.0, float("nan"), 1.0),
        (1.0, 1.0, -1.0),  # Z < 0
    ],
)
def test_07_bad_white_balance_is_a_value_error_naming_it(bad):
    with pytest.raises(ValueError, match="white_balance"):
        io.to_display(np.ones((2, 2, 3)), white_balance=bad)
    with pytest.raises(ValueError, match="white_balance"):
        refracta.DisplaySettings(white_balance=bad)
