"""An atmospheric-optics trial of dispersion and humid air (7 December): a field dispersed from a
base without a wavelength parameter, a reference wavelength given as 0, vapour beyond the air's
pressure."""

import numpy as np
import pytest

import refracta


def n_minus_1(field, height=0.5):
    return float(field.ior([[0.0, height, 0.0]])[0]) - 1.0


@pytest.mark.parametrize(
    "base", [refracta.LogisticProfile(), refracta.LinearSquaredProfile(), refracta.PhysicalAtmosphere()]
)
def test_a_dispersed_field_stands_for_its_wavelength_and_disperses_from_it(base):
    blue = refracta.dispersed_field(base, 450.0)
    assert refracta.field_reference_wavelength(blue) == 450.0  # a LogisticProfile's said 550
    twice = refracta.dispersed_field(blue, 650.0)
    once = refracta.dispersed_field(base, 650.0)
    # Both the same scale of the base's n - 1 (air_dispersion_scale(650, 550)): to rounding (the
    # trial's twice-dispersed one was 1.0097x, air_dispersion_scale(450)'s factor, too much).
    assert n_minus_1(twice) == pytest.approx(n_minus_1(once), rel=1e-12)


@pytest.mark.parametrize("reference", [0.0, -1.0, -1e9, float("nan")])
def test_a_reference_wavelength_is_checked_as_given(reference):
    # 0 and negative ones were taken as "the field's own" (the C++ marker for none).
    with pytest.raises(ValueError, match="reference wavelength"):
        refracta.dispersed_field(refracta.PhysicalAtmosphere(), 500.0, reference)


def test_vapour_beyond_the_airs_pressure_is_refused():
    # Relative humidity 1 at 400 K is 258 kPa of vapour in 101 kPa of air: water boiling.
    with pytest.raises(ValueError, match="humidity 1 at the ground's warmest 400 K .*the water would boil"):
        refracta.PhysicalAtmosphere(t_ground=400.0, humidity=1.0)
    with pytest.raises(ValueError, match="hot spots included"):
        refracta.PhysicalAtmosphere(humidity=1.0, hot_spots=[refracta.HotSpot(0.0, 0.0, 5.0, 120.0)])
    # Saturated air at 30 C over a road 30 K warmer: 20 kPa, allowed.
    assert np.isfinite(n_minus_1(refracta.PhysicalAtmosphere(t_ground=303.15, surface_dt=30.0, humidity=1.0)))
