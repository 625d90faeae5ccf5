"""Spectral colour (shared/SHADING.md section 7): CIE tables, RGB <-> spectrum, white, black bodies."""

import colour
import numpy as np
import pytest

from refracta import spectrum

LAM_1NM = np.arange(360.0, 831.0)

# The .inc holds colour-science's CMFs at 1 nm printed with 11 significant digits.
TABLE_TOLERANCE = 1e-9
# D65 above 780 nm is the D-series formula (colour-science's table stops at 780): compared below only.
D65_TABLE_TOLERANCE = 1e-7
# colour-science's matrix is the IEC 4-decimal one; the .inc prints it exactly.
MATRIX_TOLERANCE = 1e-6
# The IEC matrix assumes the white (0.3127, 0.3290); the 1 nm D65 table integrates to
# (0.312727, 0.329023): reflectance-1 under illuminant(1,1,1) is (1.00001, 1.00008, 0.99983).
WHITE_TOLERANCE = 2.5e-4
# SHADING.md section 7: RGB -> spectrum -> RGB to 1e-3 for in-gamut colours.
ROUND_TRIP_TOLERANCE = 1e-3
# Monte Carlo white with 2^16 stratified hero samples: within 5 standard errors of the mean
# (computed from the samples; stratification makes the true error far smaller, ~2e-5 measured).
MC_SIGMAS = 5.0
# Planck at 6504 K vs D65 (a daylight, not a black body): measured xy (0.31346, 0.32357) vs
# (0.31273, 0.32902): the CIE daylight locus lies 0.0055 above the Planckian one in y.
BLACKBODY_D65_XY_TOLERANCE = 0.008


def srgb_matrix():
    return colour.RGB_COLOURSPACES["sRGB"].matrix_XYZ_to_RGB


def test_cie_tables_match_colour_science():
    rng = np.random.default_rng(1)
    lam = np.sort(rng.choice(LAM_1NM, 20, replace=False))
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    # TABLE_TOLERANCE; 1e-15 absolute where the CMFs are 0.
    np.testing.assert_allclose(spectrum.cie_xyz(lam), cmfs[lam], rtol=TABLE_TOLERANCE, atol=1e-15)
    lam_d65 = np.sort(rng.choice(np.arange(360.0, 781.0), 20, replace=False))
    reference = colour.SDS_ILLUMINANTS["D65"].copy().align(colour.SpectralShape(360, 780, 1))[lam_d65]
    np.testing.assert_allclose(spectrum.d65(lam_d65), reference, rtol=D65_TABLE_TOLERANCE)
    assert spectrum.d65(560.0) == pytest.approx(100.0, rel=D65_TABLE_TOLERANCE)
    assert spectrum.cie_xyz(300.0).tolist() == [0.0, 0.0, 0.0]  # 0 outside [360, 830]


def test_xyz_to_srgb_matrix_is_iec_61966():
    np.testing.assert_allclose(spectrum.xyz_to_linear_srgb(np.eye(3)).T, srgb_matrix(), atol=MATRIX_TOLERANCE)


def test_white_reflectance_under_d65_illuminant_is_srgb_white_by_quadrature():
    emission = spectrum.rgb_to_spectrum([1.0, 1.0, 1.0], LAM_1NM, kind="illuminant")
    # The same D65 table and normalisation: rounding.
    np.testing.assert_allclose(emission, spectrum.d65(LAM_1NM, normalised=True), rtol=1e-12)
    white = spectrum.rgb_to_spectrum([1.0, 1.0, 1.0], LAM_1NM)  # reflectance 1
    assert np.all(white == 1.0)
    np.testing.assert_allclose(spectrum.spectrum_to_rgb(LAM_1NM, white * emission), 1.0, atol=WHITE_TOLERANCE)


def test_white_by_the_hero_wavelength_monte_carlo_estimate():
    n = 1 << 16
    u = (np.arange(n) + np.random.default_rng(2).uniform(size=n)) / n  # stratified
    lam, pdf = spectrum.sample_wavelengths(u)
    radiance = spectrum.rgb_to_spectrum([1.0, 1.0, 1.0], lam.ravel(), kind="illuminant").reshape(lam.shape)
    rgb = spectrum.to_linear_srgb(radiance, lam, pdf)
    mean, err = rgb.mean(0), rgb.std(0) / np.sqrt(n)
    np.testing.assert_allclose(mean, 1.0, atol=MC_SIGMAS * err.max() + WHITE_TOLERANCE)
    # Terminated secondaries: the hero alone, weighted by 4, estimates the same white.
    lam_t, pdf_t = spectrum.sample_wavelengths(u, terminate_secondary=True)
    # Numpy's default 1e-5/1e-8: a constant pdf, rounding only.
    assert np.all(pdf_t[:, 1:] == 0.0) and np.allclose(pdf_t[:, 0], 1.0 / 470.0 / 4.0)
    rgb_t = spectrum.to_linear_srgb(radiance, lam_t, pdf_t)
    np.testing.assert_allclose(rgb_t.mean(0), 1.0, atol=MC_SIGMAS * rgb_t.std(0).max() / np.sqrt(n) + WHITE_TOLERANCE)


def test_hero_wavelengths_rotate_over_the_whole_range():
    u = np.linspace(0.0, 1.0, 4001, endpoint=False)
    lam, pdf = spectrum.sample_wavelengths(u)
    assert lam.min() >= 360.0 and lam.max() <= 830.0  # the sampled domain, 360-830 nm, exactly
    np.testing.assert_allclose(pdf, 1.0 / 470.0)
    gaps = np.diff(np.sort(lam, axis=1), axis=1)  # the four are a quarter of the range apart
    np.testing.assert_allclose(gaps, 470.0 / 4, atol=1e-9)
    # Every wavelength slot is uniform over the range: each quarter holds a quarter of each.
    for i in range(4):
        counts = np.histogram(lam[:, i], bins=4, range=(360, 830))[0]
        np.testing.assert_allclose(counts, len(u) // 4, atol=1)  # +-1: u on a bin's edge


def in_gamut_colours():
    rng = np.random.default_rng(3)
    special = [
        [1, 0, 0],
        [0, 1, 0],
        [0, 0, 1],
        [1, 1, 0],
        [0, 1, 1],
        [1, 0, 1],
        [0.5, 0.5, 0.5],
        [0.18, 0.18, 0.18],
        [0.0, 0.0, 0.0],
        [1, 1, 1],
        [0.9, 0.9, 0.9],
        [0.02, 0.03, 0.01],
    ]
    return np.vstack([special, rng.uniform(size=(300, 3))])


@pytest.mark.parametrize("method", ["fit", "table"])
def test_rgb_to_spectrum_to_rgb_round_trip(method):
    rgb = in_gamut_colours()
    spectra = spectrum.rgb_to_spectrum(rgb, LAM_1NM, method=method)
    assert spectra.min() >= 0.0 and spectra.max() <= 1.0  # reflectances stay physical
    back = np.array([spectrum.spectrum_to_rgb(LAM_1NM, s, kind="reflectance") for s in spectra])
    # The matrix's white is 1.7e-4 off D65's (WHITE_TOLERANCE); the fit matches the rgb's own XYZ.
    np.testing.assert_allclose(back, rgb, atol=ROUND_TRIP_TOLERANCE)


def test_table_agrees_with_the_direct_fit():
    rgb = in_gamut_colours()
    fit = spectrum.rgb_to_spectrum(rgb, LAM_1NM, method="fit")
    table = spectrum.rgb_to_spectrum(rgb, LAM_1NM, method="table")
    back_fit = np.array([spectrum.spectrum_to_rgb(LAM_1NM, s, kind="reflectance") for s in fit])
    back_table = np.array([spectrum.spectrum_to_rgb(LAM_1NM, s, kind="reflectance") for s in table])
    np.testing.assert_allclose(back_table, back_fit, atol=ROUND_TRIP_TOLERANCE)


def test_unbounded_and_illuminant_scale():
    rgb = np.array([4.0, 2.0, 0.5])
    s = spectrum.rgb_to_spectrum(rgb, LAM_1NM, kind="unbounded")
    assert s.max() <= 2.0 * rgb.max() + 1e-12  # scale 2 max(rgb) times a sigmoid in [0, 1]
    np.testing.assert_allclose(spectrum.spectrum_to_rgb(LAM_1NM, s, kind="unbounded"), rgb, rtol=ROUND_TRIP_TOLERANCE)
    emission = spectrum.rgb_to_spectrum(rgb, LAM_1NM, kind="illuminant")
    np.testing.assert_allclose(
        spectrum.spectrum_to_rgb(LAM_1NM, emission), rgb, rtol=ROUND_TRIP_TOLERANCE + WHITE_TOLERANCE
    )


def test_tabulated_spectrum_rgb_matches_colour_science():
    # A smooth reflectance sampled every 10 nm; colour-science integrates it under D65 at 1 nm.
    lam = np.arange(360.0, 831.0, 10.0)
    values = 0.5 + 0.4 * np.sin((lam - 360.0) / 80.0)
    rgb = spectrum.spectrum_to_rgb(lam, values, kind="reflectance")
    shape = colour.SpectralShape(360, 830, 1)
    sd = colour.SpectralDistribution(dict(zip(lam, values))).interpolate(shape, interpolator=colour.LinearInterpolator)
    illuminant = colour.SpectralDistribution(dict(zip(LAM_1NM, spectrum.d65(LAM_1NM))))
    xyz = (
        colour.sd_to_XYZ(sd, colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"], illuminant, method="Integration")
        / 100.0
    )
    # colour-science sums 1 nm samples (no half weights at the ends): ~1e-6 difference.
    np.testing.assert_allclose(rgb, srgb_matrix() @ xyz, atol=1e-5)


def test_blackbody_planck_and_d65_chromaticity():
    # Planck's law at 5778 K, 500 nm: 2hc^2/lambda^5 / (e^(hc/(lambda k T)) - 1), by hand in SI.
    h, c, k = 6.62607015e-34, 299792458.0, 1.380649e-23
    lam = 500e-9
    expected = 2 * h * c**2 / lam**5 / np.expm1(h * c / (lam * k * 5778.0)) * 1e-9
    # Planck's law in double on both sides: rounding.
    assert spectrum.blackbody(5778.0, 500.0) == pytest.approx(expected, rel=1e-12)
    s = spectrum.blackbody(6504.0, LAM_1NM, luminance=1.0)
    xyz = np.linalg.solve(srgb_matrix(), spectrum.spectrum_to_rgb(LAM_1NM, s))
    # Luminance=1 by construction; the 1 nm quadrature and the 3x3 solve round.
    assert xyz[1] == pytest.approx(1.0, rel=1e-9)
    xy_bb = xyz[:2] / xyz.sum()
    d65_xyz = np.linalg.solve(srgb_matrix(), spectrum.spectrum_to_rgb(LAM_1NM, spectrum.d65(LAM_1NM)))
    xy_d65 = d65_xyz[:2] / d65_xyz.sum()
    assert np.abs(xy_bb - xy_d65).max() < BLACKBODY_D65_XY_TOLERANCE
    # Colour-science's Planckian xy at 6504 K (its own CMF integration) agrees to the table's precision.
    shape = colour.SpectralShape(360, 830, 1)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape)
    reference = colour.XYZ_to_xy(colour.sd_to_XYZ(colour.sd_blackbody(6504.0, shape), cmfs, method="Integration"))
    # The 1 nm tables' 6 significant digits, integrated two ways.
    np.testing.assert_allclose(xy_bb, reference, atol=1e-5)


def test_bad_input_raises_value_error():
    with pytest.raises(ValueError, match=r"reflectance must be .* \[0, 1\] \(got 1.5\)"):
        spectrum.rgb_to_spectrum([1.5, 0.0, 0.0], LAM_1NM)
    with pytest.raises(ValueError, match="rgb"):
        spectrum.rgb_to_spectrum([0.5, 0.5], LAM_1NM)
    with pytest.raises(ValueError, match="finite"):
        spectrum.rgb_to_spectrum([0.5, 0.5, np.nan], LAM_1NM)
    with pytest.raises(ValueError, match="temperature"):
        spectrum.blackbody(-1.0, LAM_1NM)
    with pytest.raises(ValueError, match="increasing"):
        spectrum.spectrum_to_rgb([500.0, 400.0], [1.0, 1.0])
    with pytest.raises(ValueError, match="kind"):
        spectrum.rgb_to_spectrum([0.5, 0.5, 0.5], LAM_1NM, kind="paint")


def test_batch_functions_check_their_names_ranges_and_shapes():
    # The checks of shading/spectrum_batch.cpp, reached through the wrappers.
    with pytest.raises(ValueError, match="method must be 'fit' or 'table' \\(got 'paint'\\)"):
        spectrum.rgb_to_spectrum([0.5, 0.5, 0.5], LAM_1NM, method="paint")
    with pytest.raises(ValueError, match="method='table' serves reflectances only"):
        spectrum.rgb_to_spectrum([0.5, 0.5, 0.5], LAM_1NM, kind="unbounded", method="table")
    with pytest.raises(ValueError, match=r"rgb must be in \[0, 1\] for a reflectance \(got 1.5\)"):
        spectrum.rgb_to_spectrum([1.5, 0.5, 0.5], LAM_1NM, method="table")
    with pytest.raises(ValueError, match=r"u must be in \[0, 1\) \(got 1"):
        spectrum.sample_wavelengths([0.5, 1.0])
    lam, pdf = spectrum.sample_wavelengths([0.1, 0.2, 0.3])
    with pytest.raises(ValueError, match="same shape"):
        spectrum.to_linear_srgb(np.ones((2, 4)), lam, pdf)
    with pytest.raises(ValueError, match="radiance must have shape"):
        spectrum.to_linear_srgb(np.ones((3, 3)), lam, pdf)
