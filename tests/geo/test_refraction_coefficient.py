"""refracta.refraction_coefficient (issue 20): the surveyors' k of traced rays against the physics
of a uniform gradient, and the drop and hidden height of a distant target."""

import math

import numpy as np
import pytest

import refracta

T0 = 288.15  # [K] at the ground
EYE = 10.0  # [m]


def linear_air(gradient):
    """Air whose temperature falls (or rises) at `gradient` [K/m] over the lowest 100 m."""
    return refracta.TemperatureProfile([0.0, 100.0], [T0, T0 + 100.0 * gradient])


@pytest.mark.parametrize("gradient", [-0.0065, 0.0, 0.05])
def test_k_of_a_uniform_gradient_is_minus_r_dn_dh_over_n(gradient):
    air = linear_air(gradient)
    result = refracta.refraction_coefficient(air, EYE, 5000.0)
    eye = np.array([0.0, EYE, 0.0])
    n, dn_dh = float(air.ior(eye)), float(air.grad_ior(eye)[1])
    # A horizontal ray's curvature is -(dn/dh)/n (Bouguer); k is it in units of the Earth's 1/R.
    # Over 5 km the ray rises 1.2 to 1.6 m above the eye, where dn/dh differs by about 2e-4 of itself
    # (the pressure scale height is 8 km); the formula's neglected 5 phi^2 / 12 is 3e-7.
    assert result.k == pytest.approx(-result.earth_radius * dn_dh / n, rel=5e-4)  # dn/dh over the ray's 1.6 m rise
    # The surveyors' rule, k = 503 P / T^2 (0.0343 + dT/dh), P [hPa], T [K] (Bomford, Geodesy;
    # Hirt et al. 2010): its constants are rounded to three figures (503 holds R (n - 1) T / P with
    # (n - 1) = 79e-6 P / T, this air's 79.01e-6 at 550 nm; 0.0343 K/m is g / R_air = 0.03417),
    # which moves k by up to 0.5 % for these gradients.
    temperature, pressure = float(air.temperature(EYE)), float(air.pressure(EYE)) / 100.0
    surveyors = 503.0 * pressure / temperature**2 * (0.0343 + gradient)
    assert result.k == pytest.approx(surveyors, rel=1e-2)  # the rule's three-figure constants
    # ... and the drop is the surveyors' formula with that k, by its definition.
    assert result.drop_refracted == pytest.approx(
        (1 - result.k) * 5000.0**2 / (2 * result.earth_radius), rel=1e-12
    )  # rounding only


def test_k_rises_with_an_inversion_to_one_where_the_ray_follows_the_earth():
    ks = [refracta.refraction_coefficient(linear_air(g), EYE, 5000.0).k for g in (-0.0065, 0.0, 0.05, 0.2)]
    assert ks == sorted(ks) and ks[-1] > 1.0  # a strong inversion ducts: the ray bends more than the Earth


def test_without_air_k_is_the_formulas_truncation_and_nothing_is_bent():
    vacuum = refracta.CurvedEarth(refracta.LinearSquaredProfile(1.0, 0.0))
    result = refracta.refraction_coefficient(vacuum, 2.0, 30000.0, target_height=50.0)
    radius, phi = result.earth_radius, 30000.0 / result.earth_radius
    # A straight horizontal line is (R + h0) (1 / cos phi - 1) above the eye at phi = d / R: the
    # surveyors' d^2 / (2R) leaves k = -(h0 / R + 5 phi^2 / 12) (-9.6e-6 here) for no air at all.
    assert result.k == pytest.approx(-(2.0 / radius + 5 * phi**2 / 12), rel=1e-3)  # phi^4 terms of 1/cos
    assert result.drop_refracted == pytest.approx(result.drop_straight, abs=1e-6)  # the tracer's tol, 1e-6 m
    assert result.hidden_height_refracted == pytest.approx(result.hidden_height_straight, abs=1e-6)  # tracer tol
    assert result.apparent_elevation == pytest.approx(
        result.true_elevation, abs=1e-9
    )  # 1e-9 deg: tracer tol over 30 km
    # The exact hidden height: (d - sqrt(2 R h0))^2 / (2R) to first order.
    assert result.hidden_height_straight == pytest.approx(
        (30000.0 - math.sqrt(2 * radius * 2.0)) ** 2 / (2 * radius), rel=1e-4
    )  # first order in phi


def test_standard_atmosphere_lifts_a_distant_target_by_k_d_over_2r():
    air = refracta.PhysicalAtmosphere()
    d = 30000.0
    result = refracta.refraction_coefficient(air, 2.0, d, target_height=50.0)
    assert 0.16 < result.k < 0.18  # 503 P / T^2 (0.0343 - 0.0065) = 0.171 at sea level
    lift = math.radians(result.apparent_elevation - result.true_elevation)
    # A ray of constant curvature k / R meets its chord at k d / (2R). The chord climbs from 2 m to
    # 50 m, where k is 0.3 % smaller (P / T^2 along the lapse rate): 1 % covers it.
    assert lift == pytest.approx(result.k * d / (2 * result.earth_radius), rel=1e-2)  # k along the chord vs at the eye
    # Refraction hides less: the bulge of an Earth of radius R / (1 - k) (the surveyors' rule).
    effective = result.earth_radius / (1 - result.k)
    rule = (d - math.sqrt(2 * effective * 2.0)) ** 2 / (2 * effective)
    assert result.hidden_height_refracted < result.hidden_height_straight
    assert result.hidden_height_refracted == pytest.approx(rule, rel=1e-2)  # k near the ground vs along the graze
    # A target lower than the hidden height has no apparent elevation.
    hidden = refracta.refraction_coefficient(air, 2.0, d, target_height=20.0)
    assert hidden.true_elevation is not None and hidden.apparent_elevation is None


def test_a_flat_field_is_measured_over_curved_earths_default():
    air = linear_air(-0.0065)
    flat = refracta.refraction_coefficient(air, EYE, 2000.0)
    curved = refracta.refraction_coefficient(refracta.CurvedEarth(air), EYE, 2000.0)
    assert flat == curved
    assert flat.earth_radius == refracta.CurvedEarth(air).radius
    other = refracta.refraction_coefficient(air, EYE, 2000.0, earth_radius=6.4e6)
    assert other.earth_radius == 6.4e6 and other.k != flat.k
    # 2 km is within the horizon: the limiting ray meets the surface there (to the tracer's tol).
    assert flat.hidden_height_refracted == pytest.approx(0.0, abs=1e-6)  # the tracer's tol, 1e-6 m
    assert flat.hidden_height_straight == 0.0 and flat.target_height is None


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"eye_height": math.nan}, "eye_height"),
        ({"eye_height": -1.0}, "eye_height"),
        ({"distance": 0.0}, "distance"),
        ({"distance": 1e8}, "distance"),
        ({"target_height": math.inf}, "target_height"),
        ({"earth_radius": 6.4e6, "field": refracta.CurvedEarth(refracta.PhysicalAtmosphere())}, "earth_radius"),
        ({"field": refracta.CustomField(np.ones_like, np.zeros_like)}, "height only"),
        ({"max_length": 10.0}, "max_length"),
    ],
)
def test_bad_arguments(kwargs, match):
    arguments = {"field": refracta.PhysicalAtmosphere(), "eye_height": 2.0, "distance": 1000.0, **kwargs}
    with pytest.raises(ValueError, match=match):
        refracta.refraction_coefficient(**arguments)


def test_from_the_ground_the_hidden_height_is_the_horizontal_rays():
    # An eye on the surface sees no farther than its horizontal ray: what that ray passes over at
    # the distance is hidden, with the air (drop_refracted) and without it (drop_straight).
    result = refracta.refraction_coefficient(refracta.PhysicalAtmosphere(), 0.0, 20000.0, target_height=40.0)
    assert result.hidden_height_refracted == pytest.approx(result.drop_refracted, abs=1e-6)  # the tracer's tol
    assert result.hidden_height_straight == pytest.approx(result.drop_straight, rel=1e-9)  # two forms of one formula
    assert result.apparent_elevation > result.true_elevation > 0.0
