"""Automatic derivatives (ceres::Jet through the integrator and the closest-approach solve) agree
with central differences of the traced misses, for every model."""

import numpy as np
import pytest

import refracta
from refracta.edit import PointPair, jacobian

from .conftest import pairs_from

# Central differences (relative step 1e-5) carry O(step^2) truncation and the trace's
# tolerance-level noise divided by the step: ~1e-6 of the largest entry.
JACOBIAN_REL = 2e-5

CASES = {
    "logistic": (
        refracta.LogisticProfile(k_s=11.0, h_ciso=1.2),
        (0.0, 1.5, 0.0),
        [-0.5, 0.3],
        [50.0, 40.0],
        ["k_s", "h_ciso", "n_inv", "a_inv", "n_hot", "a_hot"],
    ),
    "physical": (
        refracta.PhysicalAtmosphere(surface_dt=8.0, surface_depth=0.12),
        (0.0, 1.4, 0.0),
        [-0.22, -0.1],
        [400.0, 300.0],
        ["surface_dt", "surface_depth", "t_ground", "lapse_rate", "pressure"],
    ),
    "sounding": (
        refracta.TemperatureProfile([0.0, 5.0, 20.0, 60.0], [283.0, 286.0, 289.0, 288.5]),
        (0.0, 10.0, 0.0),
        [-0.2, 0.05],
        [2000.0, 1500.0],
        ["t0", "t1", "t2", "pressure"],
    ),
    "linear_squared": (
        refracta.LinearSquaredProfile(alpha=5e-6),
        (0.0, 1.5, 0.0),
        [0.0, -0.05],
        [800.0, 900.0],
        ["alpha", "n0"],
    ),
    "curved_earth": (
        refracta.CurvedEarth(
            refracta.PhysicalAtmosphere(inversion_dt=5.0, inversion_base=0.0, inversion_thickness=40.0)
        ),
        (0.0, 5.0, 0.0),
        [0.01, -0.01],
        [20000.0, 15000.0],
        ["inversion_dt", "inversion_thickness"],
    ),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_jacobian_matches_central_differences(case):
    field, eye, elevations, distances, free = CASES[case]
    # Sources 2 cm off the generating paths, so that the misses are not zero.
    pairs = [
        PointPair(p.destination, np.asarray(p.source) + (0.0, 0.02, 0.0))
        for p in pairs_from(field, eye, elevations, distances)
    ]
    residuals, automatic, names = jacobian(field, eye, pairs, free=free, derivatives="automatic")
    residuals_numeric, numeric, _ = jacobian(field, eye, pairs, free=free, derivatives="numeric")
    assert names == free
    # Same misses from both evaluation paths, within the trace tolerance (1e-13 per metre of path).
    np.testing.assert_allclose(residuals, residuals_numeric, rtol=0, atol=1e-13 * 1.5 * max(distances) + 1e-9)
    scale = np.abs(numeric).max(axis=0)
    assert np.all(np.abs(automatic - numeric) <= JACOBIAN_REL * scale + 1e-14), (automatic - numeric) / scale


def test_the_miss_is_perpendicular_to_the_path():
    field = refracta.LogisticProfile()
    eye = np.array([0.0, 1.5, 0.0])
    pair = PointPair((1.0, 1.5, 0.0), (50.0, 2.0, 0.3))
    residuals, _, _ = jacobian(field, eye, [pair], free=["k_s"])
    path = refracta.trace_ray(field, eye, (1.0, 0.0, 0.0), tol=1e-10, max_length=80.0)
    point, distance, s = path.closest_point(pair.source)
    _, tangent = path.point_at(s)
    # The residual is the closest point's: perpendicular to the tangent up to the 1e-9 query tolerance.
    assert abs(np.dot(residuals, tangent)) < 1e-9
    assert np.linalg.norm(residuals) == pytest.approx(distance, abs=1e-9)  # as above: path queries are solved to 1e-9 m
    # Two closest-point solves (C++ residual, Python query) at 1e-9 m each, with margin.
    np.testing.assert_allclose(residuals, point - np.asarray(pair.source), atol=1e-8)
