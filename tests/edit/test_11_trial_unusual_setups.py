"""An edit trial in setups earlier ones left out (a distant ship over a CurvedEarth, global nlopt
algorithms, camera parameters with 3D destinations, paths that end on the ground): what it found."""

import numpy as np
import pytest

import refracta
from refracta.edit import PointPair, distances, solve

EARTH_RADIUS = 6371000.0  # [m]
INVERSION = ["inversion_dt", "inversion_base"]


@pytest.fixture(scope="module")
def ship():
    """A ship's point 12 m up, 20 km away over a cold sea under an inversion (the trial's), the eye 5 m
    up, a destination 0.0424 deg up, and a start off the truth."""
    truth = refracta.CurvedEarth(
        refracta.PhysicalAtmosphere(t_ground=278.15, inversion_dt=10.0, inversion_base=20.0, inversion_thickness=10.0),
        EARTH_RADIUS,
    )
    eye = (0.0, 5.0, 0.0)
    e = np.radians(0.0424)
    pair = PointPair(
        (1000.0 * np.cos(e), 5.0 + 1000.0 * np.sin(e), 0.0), (20000.0, float(truth.flat_height(12.0)), 0.0)
    )
    return truth, truth.with_params(inversion_dt=5.0, inversion_base=25.0), eye, pair


@pytest.mark.parametrize("strategy, evaluations", [("auto", 3000), ("local", 300)])
def test_a_global_nlopt_algorithm_never_returns_above_its_start(ship, strategy, evaluations):
    # GN_DIRECT searches the box and never evaluates the start: it returned 512 m^2 from a start of
    # 123 m^2 (and from a design point of 0.24 m^2). A stage now measures its start first.
    _, start, eye, pair = ship
    backend = "nlopt:GN_DIRECT"
    result = solve(start, eye, [pair], free=INVERSION, backend=backend, max_evaluations=evaluations, strategy=strategy)
    assert result.cost <= result.initial_cost
    if strategy == "auto":
        lowest_design = float(result.stages[1].split("lowest cost ")[1].split(" m^2")[0])
        # The design's cost is measured at the coarse design tolerance: a stage from its point ends
        # within that tolerance of it or below (measured: 0.23599 against 0.23605 m^2).
        assert result.cost <= 1.01 * lowest_design


def test_a_stage_cap_is_not_called_the_solve_s_evaluation_limit(ship):
    _, start, eye, pair = ship
    result = solve(start, eye, [pair], free=INVERSION, backend="nlopt:GN_DIRECT")
    capped = [stage for stage in result.stages if "stage's own cap of evaluations" in stage]
    assert capped  # the quick first stage has its own share of the evaluations
    assert not any("stage's own cap" in stage and "stopped by the evaluation limit" in stage for stage in capped)
    if not result.stopped_by:  # the solve's own limits did not stop it
        assert "stopped by the evaluation limit" not in result.message


def test_vertex_distance_needs_fixed_steps(ship):
    # rk45's nodes lie hundreds of metres apart at 20 km: the nearest node missed by 3 131 m an image
    # met to 2 um. rk4 with fixed steps is the measure's own integrator (the original editor's).
    truth, _, eye, pair = ship
    with pytest.raises(ValueError, match="distance='vertex' needs trace='rk4'"):
        distances(truth, eye, [pair], distance="vertex")
    with pytest.raises(ValueError, match="distance='vertex' needs trace='rk4'"):
        solve(truth, eye, [pair], free=INVERSION, distance="vertex")
    # Half a 1 m step at most, plus the continuous miss (2 um).
    assert distances(truth, eye, [pair], distance="vertex", trace="rk4", step=1.0)[0] <= 0.5


def test_a_camera_parameter_no_pair_depends_on_is_named_as_such():
    # A 3D destination does not turn with the camera: freeing the yaw moves nothing, and the message
    # advised freeing the yaw.
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere())
    camera = refracta.Camera((0, 5, 0), (20000, 5, 0), (0, 1, 0), 1.0, 160, 60)
    result = solve(field, camera, [PointPair((20000.0, 10.0, 50.0), (20000.0, 10.0, 0.0))], free=["camera_yaw"])
    assert not result.success
    assert list(result.insensitive) == ["camera_yaw"]
    assert "No pair depends on camera_yaw" in result.message and "PointPair((u, v), source)" in result.message
    assert "free the camera's yaw" not in result.message


def test_a_path_that_ends_on_the_ground_is_said_to_end_short():
    # Aimed 1 deg down from 1.5 m, the path meets the road about 86 m out; the source is 500 m away.
    eye = np.array([0.0, 1.5, 0.0])
    e = np.radians(-1.0)
    pair = PointPair(tuple(eye + np.array([np.cos(e), np.sin(e), 0.0])), (500.0, 1.0, 0.0))
    road = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.2)
    result = solve(road, eye, [pair], free=["surface_dt"], stop_height=0.0)
    assert not result.success
    assert "m short of the source" in result.message and "on the ground, stop_height" in result.message


def test_several_cameras_are_refused_by_name():
    camera = refracta.Camera((0, 5, 0), (20000, 5, 0), (0, 1, 0), 1.0, 160, 60)
    pair = PointPair((80.5, 30.5), (20000.0, 10.0, 0.0))
    with pytest.raises(ValueError, match="one Camera or one eye point"):
        solve(refracta.PhysicalAtmosphere(), [camera, camera], [pair], free=["camera_yaw"])
    with pytest.raises(ValueError, match="one Camera or one eye point"):
        distances(refracta.PhysicalAtmosphere(), [camera, camera], [pair])
