"""An ocean-optics trial of the water (7 December): the interface's transmittance at grazing, a
body under another medium, wind directions of any scale, reprs that read back."""

import math

import numpy as np
import pytest

import refracta
from refracta import shading


def view(degrees_from_zenith, azimuth_sign=1.0):
    theta = math.radians(degrees_from_zenith)
    return np.array([azimuth_sign * math.sin(theta), 0.0, math.cos(theta)])


@pytest.mark.parametrize("wind", [0.0, 5.0])
def test_transmittance_keeps_its_grazing_limit(wind):
    # The rough interface's visible normals tilt toward light at grazing: T levels off instead of
    # falling to 0 (its table's mu = 0 node was taken as 0, so T(2e-4) read 0.114 for T(1e-3) 0.25).
    water = shading.Water(wind_speed=wind)
    grazing = [water.transmittance(mu, 550.0) for mu in (0.0, 2e-4, 5e-4, 1e-3)]
    assert grazing[0] > 0.2  # 0.25 at 0 m/s, 0.55 at 5 m/s by the trial's own quadrature
    # Flat to 1 % over the first 1e-3 of mu (measured 0.8 % at 0 m/s, 0.2 % at 5 m/s).
    np.testing.assert_allclose(grazing, grazing[-1], rtol=0.01)


def test_a_body_under_a_denser_medium_sees_no_light_beyond_total_internal_reflection():
    # Relative index 1.333 / 1.5 = 0.89: light at 75 deg from the zenith cannot enter, and almost
    # none at 75 deg leaves; the body term was 1.7e-3 /sr (the table clamped eta to 1.31).
    water = shading.Water(wind_speed=0.0)
    f = water.f(view(75.0), view(20.0, -1.0), eta_outside=1.5)
    # The bare interface's transmission there is ~1e-13 (the trial's quadrature): the body's
    # product of two such crossings and its albedo is below 1e-9.
    assert np.all(f < 1e-9)


def test_the_body_is_continuous_where_the_wide_table_takes_over():
    # Relative indices 1.3117 (the near table, 1.31-1.37) and 1.3085 (the wide one, 0.5-2, built on
    # demand) are 0.24 % apart: the body term moves by about that much, not by a table's error.
    water = shading.Water(wind_speed=5.0)
    n = water.ior(550.0)
    inside = water.f(view(40.0), view(30.0, -1.0), eta_outside=n / 1.3117, wavelengths=[[550.0] * 4])
    outside = water.f(view(40.0), view(30.0, -1.0), eta_outside=n / 1.3085, wavelengths=[[550.0] * 4])
    # The wide table's nodes are 0.05 apart: its bilinear error on T (smooth in eta) stays below
    # 1 %; the body term changes 0.3 % across the step.
    np.testing.assert_allclose(outside, inside, rtol=0.02)


@pytest.mark.parametrize("scale", [1e200, 1e-170])
def test_a_wind_direction_counts_by_its_direction_alone(scale):
    # (1e200, 0) overflowed its norm to a flat sea; (1e-170, 0) underflowed and was refused.
    scaled = refracta.OceanWaves(5.0, wind_direction=(scale, 0.0), resolution=16)
    unit = refracta.OceanWaves(5.0, wind_direction=(1.0, 0.0), resolution=16)
    np.testing.assert_array_equal(scaled.heights(), unit.heights())


def test_reprs_read_back_exactly():
    water = shading.Water(wind_speed=5.123456789012, temperature_c=0.1 + 0.2, salinity=1.0 / 3.0)
    again = eval("shading." + repr(water))
    assert (again.wind_speed, again.temperature_c, again.salinity) == (
        water.wind_speed,
        water.temperature_c,
        water.salinity,
    )
    assert again.roughness == water.roughness
    waves = refracta.OceanWaves(5.0 + 1e-12, wind_direction=(0.1, 0.7), patch_size=100.0 / 3.0, resolution=16)
    copy = eval("refracta." + repr(waves))
    np.testing.assert_array_equal(copy.heights(), waves.heights())
