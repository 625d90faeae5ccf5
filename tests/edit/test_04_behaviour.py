"""What an artist meets: impossible requests, weights, defaults for degenerate parameters,
multi-start, the report, and bad input."""

import pickle

import numpy as np
import pytest

import refracta
from refracta.edit import PointPair, distances, solve

from .conftest import pairs_from


def test_an_impossible_request_fails_with_a_message():
    """An image 600 m above the horizon at 1 km needs alpha = 2.4e-3, outside its bounds (+-1e-3)."""
    result = solve(
        refracta.LinearSquaredProfile(),
        (0.0, 1.5, 0.0),
        [PointPair((1.0, 1.5, 0.0), (1000.0, 600.0, 0.0))],
        free="alpha",
    )
    assert not result.success
    assert "pair 0 misses its source" in result.message
    assert result.distances[0] > 1.0


def test_a_heavier_weight_pulls_its_pair_closer():
    """Two pairs no single alpha satisfies: the weight decides the compromise."""
    field, eye = refracta.LinearSquaredProfile(), (0.0, 1.5, 0.0)
    a, b = (1000.0, 3.0, 0.0), (1000.0, 2.5, 0.0)
    misses = []
    for weight in (1.0, 100.0):
        pairs = [PointPair((1.0, 1.5, 0.0), a, weight=weight), PointPair((1.0, 1.5, 0.0), b)]
        misses.append(solve(field, eye, pairs, free="alpha").distances)
    assert misses[1][0] < 0.05 * misses[0][0]
    assert misses[1][1] > misses[0][1]


def test_the_logistic_gauge_amplitude_is_fixed_by_default():
    field = refracta.LogisticProfile()
    pairs = pairs_from(field.with_params(k_s=12.0), (0.0, 1.5, 0.0), [-0.3, 0.3], [50.0, 50.0])
    result = solve(field, (0.0, 1.5, 0.0), pairs, max_iterations=30)
    assert "n_bg" not in result.free
    assert result.field.params["n_bg"] == field.params["n_bg"]


def test_parameters_no_pair_depends_on_are_reported_and_kept():
    """An inversion layer at 100-110 m cannot touch rays that stay below 2 m."""
    truth = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    pairs = pairs_from(truth, (0.0, 1.4, 0.0), [-0.2, -0.12], [500.0, 600.0], stop_height=0.0)
    start = truth.with_params(surface_dt=8.0)
    result = solve(
        start, (0.0, 1.4, 0.0), pairs, free=["surface_dt", "inversion_dt", "inversion_base"], stop_height=0.0
    )
    assert set(result.insensitive) == {"inversion_dt", "inversion_base"}
    assert result.free == ["surface_dt"]
    assert result.field.params["inversion_base"] == start.params["inversion_base"]
    assert result.success, result.message


def test_multistart_keeps_the_best_of_its_starts():
    truth = refracta.LogisticProfile(k_s=12.0, h_ciso=2.0, n_inv=0.5)
    eye = (0.0, 1.5, 0.0)
    pairs = pairs_from(truth, eye, [-0.5, -0.2, 0.1, 0.6], [50.0, 50.0, 50.0, 50.0])
    start = refracta.LogisticProfile()
    free = ["k_s", "h_ciso", "n_inv"]
    single = solve(start, eye, pairs, free=free)
    multi = solve(start, eye, pairs, free=free, starts=6, seed=3)
    assert multi.cost <= single.cost
    assert multi.starts == 6 and multi.evaluations > single.evaluations


def test_the_report_names_the_outcome_and_the_parameters(road_pairs):
    truth, eye, pairs = road_pairs
    result = solve(truth.with_params(surface_dt=8.0), eye, pairs, free=["surface_dt"], stop_height=0.0)
    text = str(result)
    assert "success" in text and "surface_dt" in text and "ceres" in text
    assert "EditResult(success=True" in repr(result)
    assert len(result.history) == result.iterations + 1
    assert len(result.paths()) == len(pairs)
    # By identity: hash() raised "unhashable type: 'list'" and == compared fields that have no value
    # equality (a trial); results can key a dict of runs.
    assert {result: "run"}[result] == "run" and result == result and result != pickle.loads(pickle.dumps(result))


def test_vertex_distance_never_beats_the_continuous_one():
    """The original editor's node distance is an upper bound of the true closest approach."""
    field = refracta.LogisticProfile()
    pairs = [PointPair((1.0, 1.5, 0.0), (50.0 + 0.07 * k, 1.9, 0.0)) for k in range(5)]
    continuous = distances(field, (0.0, 1.5, 0.0), pairs)
    vertex = distances(field, (0.0, 1.5, 0.0), pairs, distance="vertex", trace="rk4", step=0.3)
    assert np.all(vertex >= continuous - 1e-9)
    assert np.max(vertex - continuous) > 1e-4


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(pairs=[]), "pairs is empty"),
        (dict(pairs=[PointPair((1.0, 1.5, 0.0), (50.0, 2.0, 0.0))], free=["nope"]), "unknown parameter"),
        (dict(backend="nlopt:LN_NOPE"), "unknown nlopt algorithm"),
        (dict(backend="scipy"), "backend must be"),
        (dict(pairs=[PointPair((10.0, 20.0), (50.0, 2.0, 0.0))]), "pixel destination"),
        (dict(eye_or_camera=(0.0, np.nan, 0.0)), "eye_or_camera"),
        (dict(free=[]), "free is empty"),
        (dict(bounds={"k_s": (20.0, 30.0)}, free=["k_s"]), "outside its bounds"),
        (dict(loss="huber", backend="nlopt:LN_BOBYQA"), "robust loss"),
        (dict(trace="stratified"), "trace"),
    ],
)
def test_bad_input_raises_value_error(kwargs, match):
    args = dict(
        field=refracta.LogisticProfile(),
        eye_or_camera=(0.0, 1.5, 0.0),
        pairs=[PointPair((1.0, 1.5, 0.0), (50.0, 2.0, 0.0))],
    )
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        solve(**args)


@pytest.mark.parametrize(
    "destination, source, weight",
    [
        ((np.nan, 1.0, 0.0), (1.0, 1.0, 1.0), 1.0),
        ((1.0, 1.0, 0.0), (1.0, np.inf, 1.0), 1.0),
        ((1.0, 1.0, 0.0), (1.0, 1.0), 1.0),
        ((1.0, 1.0, 0.0), (1.0, 1.0, 1.0), 0.0),
    ],
)
def test_bad_point_pairs_raise_value_error(destination, source, weight):
    with pytest.raises(ValueError, match="PointPair"):
        PointPair(destination, source, weight)


def test_a_field_that_cannot_trace_raises_numerical_error():
    """n^2 < 0 below y = -n0^2/alpha: an eye there cannot launch a ray."""
    field = refracta.LinearSquaredProfile(alpha=1e-3)
    with pytest.raises(refracta.NumericalError, match="n = nan"):
        solve(field, (0.0, -2000.0, 0.0), [PointPair((1.0, -2000.0, 0.0), (100.0, -2000.0, 0.0))], free="alpha")


def test_a_robust_loss_lets_the_consistent_pairs_win_over_an_outlier():
    """Three pairs from one alpha and one far off: Cauchy's loss keeps the three nearly met."""
    truth = refracta.LinearSquaredProfile(alpha=4e-6)
    eye = (0.0, 1.5, 0.0)
    pairs = pairs_from(truth, eye, [0.0, -0.02, 0.02], [800.0, 900.0, 1000.0])
    pairs.append(PointPair((1.0, 1.5, 0.0), (900.0, 6.0, 0.0)))  # the outlier
    plain = solve(truth.with_params(alpha=1e-6), eye, pairs, free="alpha")
    robust = solve(truth.with_params(alpha=1e-6), eye, pairs, free="alpha", loss="cauchy", loss_scale=0.01)
    assert np.max(robust.distances[:3]) < 0.01 * np.max(plain.distances[:3])
    assert robust.field.params["alpha"] == pytest.approx(4e-6, rel=1e-3)


def test_an_error_raised_by_the_progress_callback_stops_the_solve():
    class Stop(Exception):
        pass

    def progress(done, total):
        raise Stop()

    with pytest.raises(Stop):
        solve(
            refracta.LogisticProfile(),
            (0.0, 1.5, 0.0),
            [PointPair((1.0, 1.5, 0.0), (50.0, 2.0, 0.0))],
            free="k_s",
            progress=progress,
        )


def test_auto_lets_a_solve_still_closing_in_finish_instead_of_going_global():
    # LM needs 18 iterations here (benchmarks/bench_edit.py's 4-pair logistic case): its cost still
    # falls steeply after the 15 quick ones, so 'auto' goes on from LM's trust region -- the same
    # iterations as the plain local solve, and no global stage.
    truth = refracta.LogisticProfile(k_s=11.0, h_ciso=1.2, n_inv=0.3, n_hot=0.2)
    start = refracta.LogisticProfile(k_s=10.0, h_ciso=1.1, n_inv=0.25, n_hot=0.15)
    eye = np.array([0.0, 1.5, 0.0])
    pairs = pairs_from(truth, eye, np.linspace(-0.6, 0.8, 4), np.linspace(40.0, 60.0, 4))
    common = dict(free=["k_s", "h_ciso", "n_inv", "n_hot"], target_cost=1e-12)
    local = solve(start, eye, pairs, strategy="local", **common)
    auto = solve(start, eye, pairs, **common)
    assert local.iterations > 15 and local.success
    assert auto.success and not any(stage.startswith("global") for stage in auto.stages), auto.stages
    assert "continued (the cost still fell)" in auto.stages[1]
    assert auto.iterations == local.iterations


def test_a_source_behind_the_eye_is_named_as_such():
    # A trial: a source 400 m behind the camera was reported as "its path passes 1 m above the
    # source" (the path's nearest point to it is the eye itself).
    example = refracta.examples.hot_road(160, 60)
    result = solve(
        example.field,
        example.camera,
        [PointPair((80.0, 40.0), (-400.0, 0.5, 0.0))],
        free=["surface_dt"],
        stop_height=0.0,
    )
    assert not result.success
    assert "its source lies 400.00125 m from the eye, behind it as seen toward its destination" in result.message


def test_a_result_on_a_bound_of_the_search_says_so():
    """The impossible request above ends on alpha's upper bound (1e-3): the summary lists it and
    the message names the bound and how to widen it (a trial's marine layer fitted 10 m, the
    default upper bound of surface_depth, and reported success without a word). A result inside
    its bounds lists nothing."""
    result = solve(
        refracta.LinearSquaredProfile(),
        (0.0, 1.5, 0.0),
        [PointPair((1.0, 1.5, 0.0), (1000.0, 600.0, 0.0))],
        free="alpha",
    )
    assert result.at_bounds == ["alpha"]
    assert result.field.params["alpha"] == pytest.approx(1e-3, rel=1e-5)  # the unit box's 1e-6 of its width
    assert "lies on a bound of the search: alpha = " in result.message
    assert "(its upper bound 0.001)" in result.message and "bounds={'alpha': (lower, upper)}" in result.message
    inside = solve(
        refracta.LinearSquaredProfile(),
        (0.0, 1.5, 0.0),
        [PointPair((1.0, 1.5, 0.0), (1000.0, 3.0, 0.0))],
        free="alpha",
    )
    assert inside.success and inside.at_bounds == [] and "bound of the search" not in inside.message


def test_pixel_destinations_a_fraction_of_a_pixel_apart_are_reported_in_pixels():
    """Two destinations 0.3 px off their sources' images, in opposite directions: no alpha meets
    both within pixel_tolerance (0.1 px), and the least-squares optimum splits the difference, each
    0.3 px off. That was reported as an atmosphere none of the solve's samples found (a trial's
    photograph, read to half a pixel); now in pixels, with what to do."""
    camera = refracta.Camera((0.0, 1.5, 0.0), (1000.0, 1.5, 0.0), vfov=2.0, width=200, height=100)
    pairs = []
    for source, shift in zip([(1000.0, 3.0, 0.0), (1000.0, 1.0, 5.0)], (0.3, -0.3)):
        u, v, _ = camera.project(source)
        pairs.append(PointPair((u, v + shift), source))
    result = solve(refracta.LinearSquaredProfile(), camera, pairs, free="alpha")
    assert not result.success
    assert "The fit converged with every pair within a pixel of its place" in result.message
    assert "None of the atmospheres" not in result.message
    rms = float(result.message.split("(rms ")[1].split(" px")[0])
    # The two shifts are symmetric, so each pair ends 0.3 px off: alpha bends both paths alike to
    # 1e-4 px over 2 m of height at 1 km.
    assert rms == pytest.approx(0.3, abs=1e-3)
    # As the message advises: a pixel_tolerance of the reading error; then uncertainty() gives the spread.
    assert "EditResult.uncertainty(pixel_sigma)" in result.message
    tolerant = solve(refracta.LinearSquaredProfile(), camera, pairs, free="alpha", pixel_tolerance=0.5)
    assert tolerant.success and 0.0 < tolerant.uncertainty(0.3)["alpha"] < np.inf


def test_a_start_that_already_meets_every_pair_is_said_to():
    """A margin of 1 m around a source the start's path passes 0.4 m from: met before any step, so
    the pairs cannot tell the start's alpha from the solved one (a trial's success moved surface_dt
    by 3.4 K chasing sub-millimetre misses, without a word)."""
    eye, field = (0.0, 1.5, 0.0), refracta.LinearSquaredProfile()
    pair = PointPair((1.0, 1.5, 0.0), (1000.0, 1.9, 0.0), margin=1.0)
    assert distances(field, eye, [pair])[0] < 1.0
    result = solve(field, eye, [pair], free="alpha")
    assert result.success and "The start already met every pair" in result.message
    unmet_start = solve(field, eye, [PointPair((1.0, 1.5, 0.0), (1000.0, 3.0, 0.0))], free="alpha")
    assert unmet_start.success and "already met" not in unmet_start.message
