"""Recovering a known atmosphere from pairs it generated, with every back-end the issue names."""

import numpy as np
import pytest

import refracta
from refracta.edit import PointPair, solve

from .conftest import pairs_from

MISS = 1e-6  # [m] the bound on the solved distances
PARAM_REL = 1e-6  # identifiable parameters: misses of 1e-6 m over hundreds of metres pin them far tighter


@pytest.mark.parametrize(
    "backend", ["ceres", "nlopt:LN_BOBYQA", "nlopt:LN_NELDERMEAD", "nlopt:LN_SBPLX", "nlopt:LD_LBFGS", "nlopt:LD_MMA"]
)
def test_hot_road_recovered(road_pairs, backend):
    truth, eye, pairs = road_pairs
    start = refracta.PhysicalAtmosphere(surface_dt=7.0, surface_depth=0.13)
    result = solve(start, eye, pairs, free=["surface_dt", "surface_depth"], backend=backend, stop_height=0.0)
    assert result.success, result.message
    assert np.max(result.distances) < MISS
    for name in ("surface_dt", "surface_depth"):
        assert result.field.params[name] == pytest.approx(truth.params[name], rel=PARAM_REL)
    assert result.cost < result.initial_cost


def test_logistic_profile_recovered():
    truth = refracta.LogisticProfile(k_s=11.0, h_ciso=1.2, n_inv=0.3, n_hot=0.2)
    eye = (0.0, 1.5, 0.0)
    pairs = pairs_from(truth, eye, [-0.6, -0.3, -0.1, 0.2, 0.5, 0.8], [50.0, 60.0, 40.0, 50.0, 45.0, 55.0])
    start = refracta.LogisticProfile(k_s=10.0, h_ciso=1.1, n_inv=0.25, n_hot=0.15)
    result = solve(start, eye, pairs, free=["k_s", "h_ciso", "n_inv", "n_hot"])
    assert result.success, result.message
    assert np.max(result.distances) < MISS
    for name in ("k_s", "h_ciso", "n_inv", "n_hot"):
        assert result.field.params[name] == pytest.approx(truth.params[name], rel=1e-5)


def test_temperature_profile_temperatures_are_parameters():
    heights, temps = [0.0, 5.0, 20.0, 60.0], [283.0, 286.0, 289.0, 288.5]
    truth = refracta.TemperatureProfile(heights, temps)
    eye = (0.0, 10.0, 0.0)
    pairs = pairs_from(truth, eye, [-0.3, -0.15, 0.0, 0.1], [2000.0, 3000.0, 2500.0, 2000.0])
    start = truth.with_params(t1=285.0, t2=290.0)
    result = solve(start, eye, pairs, free=["t1", "t2"])
    assert result.success, result.message
    assert result.field.params["t1"] == pytest.approx(286.0, abs=1e-6)
    assert result.field.params["t2"] == pytest.approx(289.0, abs=1e-6)


def test_inversion_over_the_curved_earth_lifts_an_image():
    """Looming (ORACLES.md): an inversion over the curved Earth; solve its strength from one pair."""
    truth = refracta.CurvedEarth(
        refracta.PhysicalAtmosphere(t_ground=278.15, inversion_dt=6.0, inversion_base=0.0, inversion_thickness=50.0)
    )
    eye = (0.0, 5.0, 0.0)
    pairs = pairs_from(truth, eye, [0.02], [25000.0])
    start = truth.with_params(inversion_dt=3.0)
    result = solve(start, eye, pairs, free=["inversion_dt"])
    assert result.success, result.message
    assert result.field.params["inversion_dt"] == pytest.approx(6.0, rel=1e-7)
    assert result.derivatives == "automatic"


def test_a_camera_pixel_destination_is_met_by_the_rendered_ray():
    """The solved field sends the camera's pixel ray through the source, checked independently
    with trace_ray and RayPath.closest_point."""
    camera = refracta.Camera(
        (0.0, 1.4, 0.0), (300.0, 1.4 - 300.0 * np.tan(np.radians(0.15)), 0.0), (0, 1, 0), 2.2, 320, 120
    )
    pixel = (160.5, 63.0)  # 0.2 deg below the horizon: inside the hot road's mirage band
    origin, direction = camera.ray(*pixel)
    truth = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    source, _ = refracta.trace_ray(truth, origin, direction, tol=1e-10, max_length=500.0, stop_height=0.0).point_at(
        450.0
    )
    result = solve(
        truth.with_params(surface_dt=8.0), camera, [PointPair(pixel, source)], free=["surface_dt"], stop_height=0.0
    )
    assert result.success, result.message
    assert result.field.params["surface_dt"] == pytest.approx(10.0, rel=1e-7)
    path = refracta.trace_ray(result.field, origin, direction, tol=1e-10, max_length=700.0, stop_height=0.0)
    _, distance, _ = path.closest_point(source)
    assert distance < 1e-6


def test_numeric_derivatives_drive_the_same_solve():
    """derivatives='numeric' (what fields without a templated model get) reaches the same answer."""
    start = refracta.LinearSquaredProfile()
    result = solve(
        start,
        (0.0, 1.5, 0.0),
        [PointPair((1.0, 1.5, 0.0), (1000.0, 3.0, 0.0))],
        free="alpha",
        derivatives="numeric",
        tol=1e-11,
    )
    assert result.derivatives == "numeric"
    assert result.success, result.message
    assert result.field.params["alpha"] == pytest.approx(6.0033784907804e-06, rel=1e-8)


# Algorithms that run a local optimiser inside a global or augmented-Lagrangian one: nlopt leaves
# it unset (and crashed the interpreter); refracta sets LD_LBFGS for gradient variants, else LN_BOBYQA.
COMPOSITE = [
    "GN_MLSL",
    "GD_MLSL",
    "GN_MLSL_LDS",
    "GD_MLSL_LDS",
    "G_MLSL",
    "G_MLSL_LDS",
    "LN_AUGLAG",
    "LD_AUGLAG",
    "LN_AUGLAG_EQ",
    "LD_AUGLAG_EQ",
    "AUGLAG",
    "AUGLAG_EQ",
]


@pytest.mark.parametrize("algorithm", COMPOSITE)
def test_composite_nlopt_algorithms_run_with_a_local_optimiser(road_pairs, algorithm):
    truth, eye, pairs = road_pairs
    start = refracta.PhysicalAtmosphere(surface_dt=7.0, surface_depth=0.13)
    result = solve(
        start,
        eye,
        pairs,
        free=["surface_dt", "surface_depth"],
        backend=f"nlopt:{algorithm}",
        stop_height=0.0,
        max_evaluations=400,
    )
    assert result.cost < result.initial_cost, result.message  # it ran and improved
    assert np.all(np.isfinite(result.distances))
