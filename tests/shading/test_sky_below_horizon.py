"""The physical sky continued below the horizon (below_horizon='horizon', physical_sky.h): the
radiance at e < 0 is the horizon's at the same azimuth, and the light's importance sampling then
covers the whole sphere consistently with that radiance (sample_li pdf == pdf_li, chi-square)."""

import numpy as np
import pytest

import refracta
from refracta import spectrum
from refracta.testing import chi2

# The table's lowest row (e = 9.6e-5 rad) against direct integration along e = 0 with 4x the
# steps: measured worst relative difference 6.3e-3 over the test azimuths (TABLE_TOLERANCE of
# test_sky_physical.py, 3e-2, is the table's bound over the whole sky).
HORIZON_TABLE_TOLERANCE = 3e-2
# sample_li's pdf against pdf_li re-derived from the sampled direction: the (x, t) <-> direction
# round trip in double (measured worst 7.5e-14).
PDF_ROUND_TRIP = 1e-9
# Chi-square significance of the sampling test (one test).
CHI2_SIGNIFICANCE = 0.01
# Standard errors allowed for the Monte Carlo estimate of the integral of Y over the sphere.
SIGMAS = 4.0
# The independent quadrature (midpoints, 1024 x 2048 in (elevation, azimuth)) against power()'s
# cell-centre sum over the 128 x 128 (x, t) cells: measured 5.6e-5 apart.
QUADRATURE_TOLERANCE = 5e-4
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Y of linear sRGB (IEC 61966-2-1)
SUN = (0.0, np.sin(np.radians(20.0)), np.cos(np.radians(20.0)))  # 20 deg up, azimuth 90 deg


def unit(elevation_deg, azimuth_deg):
    e, a = np.radians(elevation_deg), np.radians(azimuth_deg)
    return np.stack(np.broadcast_arrays(np.cos(e) * np.cos(a), np.sin(e), np.cos(e) * np.sin(a)), axis=-1)


@pytest.fixture(scope="module")
def sky():
    return spectrum.PhysicalSky(SUN, below_horizon="horizon")


AZIMUTHS = np.array([0.0, 37.0, 90.0, 91.3, 180.0, 250.0, 333.3])
BELOW = np.array([-1e-4, -0.5, -5.0, -30.0, -75.0, -89.0])


def test_below_the_horizon_is_the_horizon_at_the_same_azimuth(sky):
    lam = np.array([380.0, 455.0, 550.0, 700.0])
    for azimuth in AZIMUTHS:
        horizon = unit(0.0, azimuth)[None]
        below = unit(BELOW, azimuth)
        np.testing.assert_array_equal(sky.radiance(below, lam), np.repeat(sky.radiance(horizon, lam), len(BELOW), 0))
        np.testing.assert_array_equal(sky.rgb_radiance(below), np.repeat(sky.rgb_radiance(horizon), len(BELOW), 0))
        # Continuous across the horizon: just above it the same value.
        np.testing.assert_array_equal(sky.rgb_radiance(unit(1e-4, azimuth)[None]), sky.rgb_radiance(horizon))
        # ... which is the scattering integral along the horizontal at that azimuth.
        direct = sky.radiance(below[:1], lam, direct=True)
        np.testing.assert_allclose(sky.radiance(below[:1], lam), direct, rtol=HORIZON_TABLE_TOLERANCE)
        assert np.all(direct > 0.0)
    # Brighter toward the sun's azimuth (Mie forward peak): not one constant below the horizon.
    toward, away = sky.rgb_radiance(unit(-10.0, np.array([90.0, 270.0])))
    assert toward @ LUMINANCE > 1.5 * (away @ LUMINANCE)


def test_the_ground_mode_is_unchanged():
    ground = spectrum.PhysicalSky(SUN)  # below_horizon='ground' by default
    assert np.all(ground.rgb_radiance(unit(BELOW, 90.0)) == 0.0)
    assert np.all(ground.pdf_li(unit(BELOW, 90.0)) == 0.0)


def test_sample_li_pdf_equals_pdf_li_below_the_horizon(sky):
    dirs, pdf, rgb = sky.sample_li(np.random.default_rng(11).random((4000, 2)))
    below = dirs[:, 1] < 0.0
    assert below.mean() > 0.3  # the lower hemisphere shows the bright horizon (its share: the test below)
    assert np.all(pdf > 0.0)
    np.testing.assert_allclose(sky.pdf_li(dirs), pdf, rtol=PDF_ROUND_TRIP)
    # The same radiance lookup for the sampled direction: rounding.
    np.testing.assert_allclose(sky.rgb_radiance(dirs), rgb, rtol=1e-12)
    # pdf_li below the horizon is positive wherever the radiance is.
    assert np.all(sky.pdf_li(unit(BELOW, 90.0)) > 0.0)


def t_of(dirs):
    """The whole-sphere sampling coordinates (physical_sky.h): x = azimuth / 2 pi, t = (1 + s) / 2,
    s = sign(e) sqrt(|e| / (pi/2))."""
    x = np.mod(np.arctan2(dirs[:, 2], dirs[:, 0]), 2 * np.pi) / (2 * np.pi)
    e = np.arctan2(dirs[:, 1], np.hypot(dirs[:, 0], dirs[:, 2]))
    return x, 0.5 * (1.0 + np.sign(e) * np.sqrt(np.abs(e) / (np.pi / 2)))


def test_whole_sphere_sampling_matches_its_pdf(sky):
    # As test_sky_physical.test_light_sampling_matches_its_pdf, on the 128 x 128 cells of (x, t)
    # where the density is piecewise constant: bins of 4 x 4 cells, a cell's probability
    # pdf_li(centre) x its solid angle 4 pi^2 |s| cos(e) / (nx nt).
    nx, nt, group = 128, 128, 4
    xx, tt = np.meshgrid((np.arange(nx) + 0.5) / nx, (np.arange(nt) + 0.5) / nt)
    s = 2 * tt - 1
    e = np.pi / 2 * s * np.abs(s)
    centres = np.stack([np.cos(e) * np.cos(2 * np.pi * xx), np.sin(e), np.cos(e) * np.sin(2 * np.pi * xx)], -1)
    p_cell = sky.pdf_li(centres.reshape(-1, 3)).reshape(nt, nx) * 4 * np.pi**2 * np.abs(s) * np.cos(e) / (nx * nt)
    # A normalised pdf summed over a fine grid with the exact Jacobian: rounding of many terms.
    assert p_cell.sum() == pytest.approx(1.0, rel=1e-9)
    p_bin = p_cell.reshape(nt // group, group, nx // group, group).sum(axis=(1, 3)).ravel()
    n = 200_000
    dirs, _, _ = sky.sample_li(np.random.default_rng(12).random((n, 2)))
    x, t = t_of(dirs)
    bins = (np.minimum((t * nt).astype(int), nt - 1) // group) * (nx // group) + np.minimum(
        (x * nx).astype(int), nx - 1
    ) // group
    observed = np.bincount(bins, minlength=p_bin.size)
    expected = n * p_bin
    keep = expected >= 5
    statistic = np.sum((observed[keep] - expected[keep]) ** 2 / expected[keep])
    if (~keep).any():
        statistic += (observed[~keep].sum() - expected[~keep].sum()) ** 2 / max(expected[~keep].sum(), 1e-300)
    dof = int(keep.sum() + (1 if (~keep).any() else 0) - 1)
    p_value = chi2.chi2_survival(statistic, dof)
    assert p_value > CHI2_SIGNIFICANCE, (statistic, dof, p_value)


def test_sampling_integrates_the_radiance_over_the_sphere(sky):
    # E[Y(L) / pdf] over sample_li = integral of Y(Le) over the sphere (unbiased where pdf > 0 wherever
    # Le > 0), against an independent midpoint quadrature in (elevation, azimuth) and power() / pi.
    n = 200_000
    dirs, pdf, rgb = sky.sample_li(np.random.default_rng(13).random((n, 2)))
    f = (rgb @ LUMINANCE) / pdf
    estimate, error = f.mean(), f.std(ddof=1) / np.sqrt(n)
    ne, na = 1024, 2048
    e = (np.arange(ne) + 0.5) / ne * np.pi - np.pi / 2
    a = (np.arange(na) + 0.5) / na * 360.0
    y = sky.rgb_radiance(unit(np.degrees(e)[:, None], a[None, :]).reshape(-1, 3)).reshape(ne, na, 3) @ LUMINANCE
    quadrature = np.sum(y * np.cos(e)[:, None]) * (np.pi / ne) * (2 * np.pi / na)
    assert abs(estimate - quadrature) <= SIGMAS * error + QUADRATURE_TOLERANCE * quadrature, (
        estimate,
        error,
        quadrature,
    )
    # The share of samples below the horizon is the lower hemisphere's share of the integral
    # (pdf proportional to Y(Le); measured 0.71), within binomial noise and the cells' piecewise constancy.
    lower = np.sum((y * np.cos(e)[:, None])[e < 0]) * (np.pi / ne) * (2 * np.pi / na) / quadrature
    fraction = np.mean(dirs[:, 1] < 0.0)
    assert abs(fraction - lower) <= SIGMAS * np.sqrt(lower * (1 - lower) / n) + QUADRATURE_TOLERANCE, (fraction, lower)
    sky.preprocess([0, 0, 0], 1.0)
    assert sky.power() / np.pi == pytest.approx(quadrature, rel=QUADRATURE_TOLERANCE)


def test_scene_set_physical_sky_continues_the_horizon_by_default():
    scene = refracta.Scene()
    scene.set_physical_sky(SUN, scale=2.0)  # the scaled sky: a refracta Light with Le / sample_li / pdf_li
    light = next(light for light in scene.lights if repr(light).startswith("PhysicalSky("))
    assert "below_horizon='horizon'" in repr(light)
    for azimuth in AZIMUTHS:
        np.testing.assert_array_equal(
            light.Le(unit(BELOW, azimuth)), np.repeat(light.Le(unit(0.0, azimuth)[None]), len(BELOW), 0)
        )
    reference = spectrum.PhysicalSky(SUN, below_horizon="horizon")
    # The horizon's radiance mirrored below it, times 2: rounding.
    np.testing.assert_allclose(light.Le(unit(BELOW, 37.0)), 2.0 * reference.rgb_radiance(unit(BELOW, 37.0)), rtol=1e-12)
    n = 2000
    points, u = np.zeros((n, 3)), np.random.default_rng(14).random((n, 2))
    wi, L, pdf, _ = light.sample_li(points, None, u)
    assert (wi[:, 1] < 0).any() and np.all(pdf > 0)
    np.testing.assert_allclose(light.pdf_li(points, None, wi), pdf, rtol=PDF_ROUND_TRIP)
    # The same radiance lookup for the sampled direction: rounding.
    np.testing.assert_allclose(light.Le(wi), L, rtol=1e-12)
    # 'ground' keeps the Lambertian ground (black with albedo 0).
    scene.set_physical_sky(SUN, scale=2.0, below_horizon="ground")
    light = next(light for light in scene.lights if repr(light).startswith("PhysicalSky("))
    assert np.all(light.Le(unit(BELOW, 90.0)) == 0.0)


def test_bad_below_horizon_raises_value_error():
    with pytest.raises(ValueError, match="below_horizon must be 'ground' or 'horizon' \\(got 'sky'\\)"):
        spectrum.PhysicalSky(SUN, below_horizon="sky")
    with pytest.raises(ValueError, match="below_horizon"):
        refracta.Scene().set_physical_sky(SUN, below_horizon="Horizon")
    with pytest.raises(ValueError, match="ground_albedo must be 0 with below_horizon horizon"):
        refracta.Scene().set_physical_sky(SUN, ground_albedo=0.3)
    refracta.Scene().set_physical_sky(SUN, ground_albedo=0.3, below_horizon="ground")


def test_a_sun_just_below_the_horizon_shines_by_the_grazing_column_and_one_further_down_not_at_all():
    # On the ground a sun 0.5 deg below the horizon kept 1.8e-3 of its light at 700 nm (its column ran
    # through the planet, read as ever denser air) while the aerial perspective gave it none (a
    # trial). Within the horizon's refraction (33', astronomical_refraction of the standard air at
    # 550 nm) the render's curved rays still reach it, so its light is the grazing column's: equal
    # to a sun on the horizon's, in the sky and the aerial perspective alike; further down, none.
    def sun(elevation_deg):
        e = np.radians(elevation_deg)
        return (np.cos(e), np.sin(e), 0.0)

    lam = [450.0, 550.0, 700.0]
    horizon = spectrum.PhysicalSky(sun(0.0), multiple_scattering=False).sun_transmittance(lam)
    assert np.all(horizon > 0.0)
    for elevation in (-0.2, -0.5):
        sky = spectrum.PhysicalSky(sun(elevation), multiple_scattering=False)
        # Both integrate the same horizontal column by the same rule: equal to rounding.
        np.testing.assert_allclose(sky.sun_transmittance(lam), horizon, rtol=1e-12)
        perspective = spectrum.AerialPerspective(sky)
        # The aerial perspective's tabulated column at the ground: its table's interpolation (1e-3).
        assert perspective.sun_transmittance(0.0, elevation, 700.0) == pytest.approx(horizon[2], rel=1e-3)
    below = spectrum.PhysicalSky(sun(-0.6), multiple_scattering=False)
    assert np.all(below.sun_transmittance(lam) == 0.0)
    assert spectrum.AerialPerspective(below).sun_transmittance(0.0, -0.6, 700.0) == 0.0
