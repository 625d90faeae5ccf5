"""The refractive index of water (shading.water_ior) against the IAPWS release's own check values,
the density table of Tanaka et al. 2001 and the sea water of Quan & Fry 1995."""

import numpy as np
import pytest

from refracta import shading

# IAPWS R9-97 evaluated at IAPWS-95's density for 25 C and 0.1 MPa (997.047435 kg/m^3); the library
# uses Tanaka et al.'s fit, which differs from IAPWS-95 by under 1e-3 kg/m^3 in 0-40 C, and
# dn/drho = 3.4e-4 per kg/m^3 here: 3.4e-7 in n.
DENSITY_FIT = 5e-7
IAPWS_CHECKS = [(589.3, 1.3328581926), (226.5, 1.39277824)]  # (nm, n at 25 C, 997.047435 kg/m^3)


@pytest.mark.parametrize("wavelength, expected", IAPWS_CHECKS)
def test_pure_water_matches_the_iapws_check_values(wavelength, expected):
    assert shading.water_ior(wavelength, 25.0) == pytest.approx(expected, abs=DENSITY_FIT)


def test_density_follows_tanakas_table():
    # Tanaka et al. 2001, table 5 (air-free water, 101 325 Pa), printed to 1e-4 kg/m^3.
    TABLE_ROUNDING = 5e-5
    assert shading.water_density(20.0) == pytest.approx(998.2067, abs=TABLE_ROUNDING)
    assert shading.water_density(25.0) == pytest.approx(997.0470, abs=TABLE_ROUNDING)
    # The fit's maximum, a5 = 999.974950 kg/m^3 at t = -a1 = 3.983035 C.
    t = np.linspace(3.9, 4.1, 2001)
    assert t[np.argmax(shading.water_density(t))] == pytest.approx(3.983035, abs=1e-4)  # the 1e-4 C grid step of t


def test_water_disperses_and_thins_with_heat():
    # Normal dispersion over the visible range and dn/dT < 0 (about -1e-4 per K near 20 C).
    wavelengths = np.linspace(380.0, 780.0, 41)
    assert np.all(np.diff(shading.water_ior(wavelengths)) < 0)
    dn_dt = (shading.water_ior(589.3, 21.0) - shading.water_ior(589.3, 19.0)) / 2.0
    assert -1.2e-4 < dn_dt < -0.8e-4


def test_sea_water_adds_quan_and_frys_salinity_terms():
    # At 20 C and 589.3 nm: 35 g/kg raises n by (n1 + n2 t + n3 t^2) S + n6 S / lambda = 6.40e-3,
    # the textbook 1.3330 -> 1.3394 relative to air (x 1.000273 to vacuum).
    pure, sea = shading.water_ior(589.3, 20.0), shading.water_ior(589.3, 20.0, 35.0)
    TEXTBOOK_DIGITS = 1e-4  # the 1.3330 / 1.3394 are quoted to four decimals
    assert pure / 1.000273 == pytest.approx(1.3330, abs=TEXTBOOK_DIGITS)
    assert sea / 1.000273 == pytest.approx(1.3394, abs=TEXTBOOK_DIGITS)
    # Linear in S.
    half = shading.water_ior(589.3, 20.0, 17.5)
    assert half - pure == pytest.approx((sea - pure) / 2, rel=1e-12)  # linear in S by construction: rounding


@pytest.mark.parametrize(
    "arguments, name",
    [
        ((100.0,), "wavelength"),
        ((float("nan"),), "wavelength"),
        ((550.0, -5.0), "temperature_c"),
        ((550.0, 60.0), "temperature_c"),
        ((550.0, float("nan")), "temperature_c"),
        ((550.0, 20.0, -1.0), "salinity"),
        ((550.0, 20.0, float("nan")), "salinity"),
    ],
)
def test_values_outside_the_formulas_ranges_are_refused(arguments, name):
    with pytest.raises(ValueError, match=name):
        shading.water_ior(*arguments)


def test_an_arctic_sea_at_its_freezing_point_is_water():
    # Sea water of 35 g/kg freezes at -1.9 C; the cold seas of superior mirages sit there (a new
    # user's trial: Water(temperature_c=-1.5, salinity=35) was refused). Near 0 C n changes by
    # ~3e-5 per K (the table of IAPWS R9-97), so 1.5 K below 0 C stays within 1e-4 of it.
    cold, zero = shading.water_ior(589.3, -1.5, 35.0), shading.water_ior(589.3, 0.0, 35.0)
    # Near 0 C pure water's n barely moves (its density peaks at 4 C: -6e-6 from 0 to -1.5 C) and
    # the salt's increment grows as it cools (Quan & Fry's -1.05e-6 t S: +5.5e-5 at 35 g/kg):
    # together +5e-5, so between 2e-5 and 1e-4 (margin for both).
    assert 2e-5 < cold - zero < 1e-4
    assert shading.Water(temperature_c=-1.5, salinity=35.0).temperature_c == -1.5
