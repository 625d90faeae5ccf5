"""A ray that grazes a height for a few tens of metres inside one integrator step: in the linear
n^2 air (LinearSquaredProfile, n^2 = n0^2 + alpha y) the path is exactly a parabola, so where it
dips through the ground and out again is known in closed form. rk45's ~3 km steps hid a 1.6 mm,
80 m dip from stop_height and from RayPath.at_height / crossings (16 and 32 samples a step), found
by a new-user physics trial: the critical angle came out 1e-3 high."""

import numpy as np
import pytest

import refracta

N0 = 1.000277
ALPHA = 2.0 * N0 * 2e-6  # dn/dh = 2e-6 1/m at the ground: a hot road's gradient
EYE = 1.5
# Crossings against the exact parabola: measured 3e-8 to 1e-7 m (rk45 and stratified to their
# default tol of 1e-6 m in height; rk4's 0.1 m steps about as close). At the crossing's slope of
# 8e-5 a height error of 1e-6 m would move x by 1.25 cm: the agreement is the integrators', not
# the tolerance's; 1e-5 m leaves a margin of 100 over the measured error.
CROSSING_TOLERANCE = 1e-5


def parabola_crossings(elevation):
    """x where the ray launched down at `elevation` [rad] from (0, EYE, 0) meets y = 0:
    y'' = alpha / (2 C^2) with C = n(EYE) cos(elevation) (Bouguer's invariant in a plane air)."""
    c = np.sqrt(N0**2 + ALPHA * EYE) * np.cos(elevation)
    k, t = ALPHA / (4.0 * c * c), np.tan(elevation)
    root = np.sqrt(t * t - 4.0 * k * EYE)
    return np.array([(t - root) / (2.0 * k), (t + root) / (2.0 * k)])


@pytest.mark.parametrize("trace", ["rk45", "rk4", "stratified"])
def test_a_brief_dip_below_the_ground_is_found(trace):
    field = refracta.LinearSquaredProfile(n0=N0, alpha=ALPHA)
    elevation = np.radians(0.1404)  # 0.00007 deg below critical: 1.6 mm under the road for 80 m
    start, direction = [0.0, EYE, 0.0], [np.cos(elevation), -np.sin(elevation), 0.0]
    expected = parabola_crossings(elevation)
    path = refracta.trace_ray(field, start, direction, max_length=5000.0, trace=trace)
    crossings = path.at_height(0.0)
    assert crossings.shape == (2, 3)
    np.testing.assert_allclose(crossings[:, 0], expected, atol=CROSSING_TOLERANCE)
    stopped = refracta.trace_ray(field, start, direction, max_length=5000.0, stop_height=0.0, trace=trace)
    assert stopped.stop == "stop_height"
    np.testing.assert_allclose(stopped.points[-1][:2], [expected[0], 0.0], atol=CROSSING_TOLERANCE)


def test_a_ray_just_above_the_ground_is_not_stopped():
    field = refracta.LinearSquaredProfile(n0=N0, alpha=ALPHA)
    elevation = np.radians(0.1403)  # just above critical: turns 0.55 mm over the road
    path = refracta.trace_ray(
        field, [0.0, EYE, 0.0], [np.cos(elevation), -np.sin(elevation), 0.0], max_length=5000.0, stop_height=0.0
    )
    assert path.stop == "max_length"
    assert path.at_height(0.0).shape == (0, 3)
