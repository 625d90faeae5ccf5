"""The index of air and the standard atmosphere against published values (ORACLES.md, 'The air')."""

import numpy as np
import pytest

import refracta

# Ciddor (1996), Edlen (1966) and Birch & Downs (1993) agree within 1e-8 on n - 1.
AIR_INDEX_AGREEMENT = 1e-8
# Edlen's compressibility term makes n - 1 not exactly proportional to P/T: 0.3 % at most near
# the ground, so laws derived from n - 1 = K P / T hold to 1 %.
GAS_LAW_TOLERANCE = 0.01

R_D = 8314.32 / 28.9644  # [J/(kg K)], USSA 1976: R* / M0
G = 9.80665
R0 = 6356766.0  # [m], USSA 1976's radius for geopotential height


def geopotential(h):
    """USSA 1976: geopotential height H [m'] of geometric height h [m]."""
    return R0 * h / (R0 + h)


def test_index_of_air_at_standard_conditions():
    air = refracta.PhysicalAtmosphere()
    assert air.ior([0.0, 0.0, 0.0]) - 1.0 == pytest.approx(2.7784e-4, abs=AIR_INDEX_AGREEMENT)


def test_dispersion_rises_one_and_a_half_percent_from_red_to_blue():
    red = refracta.PhysicalAtmosphere(wavelength=650.0).ior([0, 0, 0]) - 1
    blue = refracta.PhysicalAtmosphere(wavelength=450.0).ior([0, 0, 0]) - 1
    # Ciddor: +1.5 %; K(450)/K(650) = 7.978/7.858 = 1.01527 from the ORACLES table.
    assert blue / red == pytest.approx(7.978 / 7.858, rel=5e-4)


def test_index_temperature_derivative_is_minus_n_minus_one_over_t():
    t, dt = 288.15, 0.01
    n = lambda temp: refracta.PhysicalAtmosphere(t_ground=temp).ior([0, 0, 0])  # noqa: E731
    derivative = (n(t + dt) - n(t - dt)) / (2 * dt)
    assert derivative == pytest.approx(-(n(t) - 1) / t, rel=GAS_LAW_TOLERANCE)
    assert derivative == pytest.approx(-9.6e-7, rel=0.01)  # -9.6e-7 /K quoted to 2 digits: 1 %


def test_standard_atmosphere_temperature_and_pressure():
    air = refracta.PhysicalAtmosphere()
    heights = np.array([0.0, 500.0, 1000.0, 5000.0, 10000.0])
    H = geopotential(heights)
    # A linear closed form in double: rounding of 288.15 K, far below 1e-9 K.
    np.testing.assert_allclose(air.temperature(heights), 288.15 - 0.0065 * H, rtol=0, atol=1e-9)
    # USSA 1976 troposphere closed form in geopotential height, (1 - (L/T0) H)^(g0/(R L)); the
    # hydrostatic table integrates the same equation in geometric height, to 1e-9 relative.
    closed_form = 101325.0 * (1.0 - 0.0065 / 288.15 * H) ** (G / (R_D * 0.0065))
    # The integration's 1e-9 relative (comment above).
    np.testing.assert_allclose(air.pressure(heights), closed_form, rtol=1e-9)


# U.S. Standard Atmosphere 1976 (NOAA-S/T 76-1562), its layer bases: geopotential height [m'],
# temperature [K], pressure [Pa] as tabulated (7 digits), up to the 86 km top (84 852 m').
USSA_1976_BASES = [
    (11000.0, 216.65, 22632.06),
    (20000.0, 216.65, 5474.889),
    (32000.0, 228.65, 868.0187),
    (47000.0, 270.65, 110.9063),
    (51000.0, 270.65, 66.93887),
    (71000.0, 214.65, 3.956420),
    (84852.0, 186.946, 0.3733836),
]
# The tables round to 7 significant digits (relative 5e-7); refracta's table of ln P integrates
# the profile to 1e-12, so it agrees to the rounding.
USSA_TABLE_ROUNDING = 1e-6


@pytest.mark.parametrize("base, temperature, pressure", USSA_1976_BASES)
def test_standard_atmosphere_matches_the_1976_tables_to_86_km(base, temperature, pressure):
    air = refracta.PhysicalAtmosphere()
    h = R0 * base / (R0 - base)  # geometric height of the layer base
    assert air.temperature(h) == pytest.approx(temperature, abs=1e-9)
    assert air.pressure(h) == pytest.approx(pressure, rel=USSA_TABLE_ROUNDING)


def test_hydrostatic_pressure_through_an_inversion_layer():
    # Isothermal check: with zero lapse rate, P = P0 exp(-g0 H / (R_d T)) exactly (H geopotential).
    air = refracta.PhysicalAtmosphere(lapse_rate=0.0, t_ground=270.0)
    h = np.array([10.0, 100.0, 2000.0])
    # Isothermal column: the same hydrostatic integration, 1e-10 relative (tighter than the lapse case).
    np.testing.assert_allclose(air.pressure(h), 101325.0 * np.exp(-G * geopotential(h) / (R_D * 270.0)), rtol=1e-10)


# The column's table of ln P against an independent adaptive quadrature of the hydrostatic law: the
# table is built to 1e-12 (hydrostatic_column.h), the reference converges to ~1e-13.
COLUMN_ACCURACY = 1e-11


@pytest.mark.parametrize(
    "layers",
    [
        dict(inversion_dt=8.0, inversion_base=20.0, inversion_thickness=15.0),
        dict(surface_dt=10.0, surface_depth=0.1),
        dict(surface_dt=-5.0, surface_depth=3.0, inversion_dt=6.0, inversion_base=10.0, inversion_thickness=2.0),
    ],
)
def test_hydrostatic_pressure_matches_an_independent_quadrature(layers):
    # ln P(h) = ln P0 - (g0 / R_d) integral of (R0 / (R0 + z))^2 / T(z) dz over [0, h].
    from scipy.integrate import quad

    air = refracta.PhysicalAtmosphere(**layers)
    integrand = lambda z: (R0 / (R0 + z)) ** 2 / air.temperature(z)  # noqa: E731
    edges = np.concatenate([np.linspace(0.0, 4.0, 161), np.linspace(5.0, 60.0, 12)])
    for height in (0.03, 0.5, 1.5, 5.0, 21.0, 27.5, 34.0, 60.0):
        cuts = np.append(edges[edges < height], height)
        integral = sum(quad(integrand, a, b, epsabs=0.0, epsrel=1e-12)[0] for a, b in zip(cuts[:-1], cuts[1:]))
        expected = 101325.0 * np.exp(-G / R_D * integral)
        assert air.pressure(height) == pytest.approx(expected, rel=COLUMN_ACCURACY)


@pytest.mark.parametrize("height", [0.05, 1.0, 22.0, 27.5, 31.0, 300.0])
def test_vertical_index_gradient_follows_the_hydrostatic_law(height):
    # dn/dh = -((n - 1)/T)(dT/dh + g/R_d) (ORACLES.md), inside a hot surface layer and an inversion.
    air = refracta.PhysicalAtmosphere(
        surface_dt=8.0, surface_depth=0.2, inversion_dt=6.0, inversion_base=20.0, inversion_thickness=10.0
    )
    step = 1e-4
    dt_dh = (air.temperature(height + step) - air.temperature(height - step)) / (2 * step)
    n = air.ior([0.0, height, 0.0])
    expected = -((n - 1) / air.temperature(height)) * (dt_dh + G / R_D)
    assert air.grad_ior([0.0, height, 0.0])[1] == pytest.approx(expected, rel=GAS_LAW_TOLERANCE)


def test_standard_near_ground_gradient():
    # ORACLES.md: dn/dh ~ -2.67e-8 1/m near the ground in the standard atmosphere.
    assert refracta.PhysicalAtmosphere().grad_ior([0, 1.0, 0])[1] == pytest.approx(-2.67e-8, rel=0.02)


def test_ducting_inversion_bends_rays_with_the_earth():
    # dn/dh = -n / R_E ~ -1.57e-7 1/m for an inversion of about +0.13 K/m at 15 C (ORACLES.md).
    air = refracta.PhysicalAtmosphere(lapse_rate=-0.13)
    # "about" 0.13 K/m (ORACLES.md): 1/R_E is reached at 0.13 K/m within 3 %.
    assert air.grad_ior([0, 1.0, 0])[1] == pytest.approx(-1.0 / 6371e3, rel=0.03)


def test_humidity_lowers_the_index_slightly():
    dry = refracta.PhysicalAtmosphere().ior([0, 0, 0])
    humid = refracta.PhysicalAtmosphere(humidity=1.0).ior([0, 0, 0])
    # Saturated at 15 C: e_s = 1705 Pa; water term -(3.7345 - 0.0401 sigma^2) 1e-10 per Pa.
    sigma2 = 1 / 0.55**2
    # The water term's coefficients and e_s are quoted to 4-5 digits: 1 %.
    assert humid - dry == pytest.approx(-1705.0 * (3.7345 - 0.0401 * sigma2) * 1e-10, rel=0.01)


def test_surface_layer_temperature_profile():
    air = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    h = np.array([0.0, 0.1, 0.3])
    # The closed form in double: rounding of 288 K, far below 1e-9 K.
    np.testing.assert_allclose(air.temperature(h), 288.15 - 0.0065 * h + 10.0 * np.exp(-h / 0.1), atol=1e-9)
