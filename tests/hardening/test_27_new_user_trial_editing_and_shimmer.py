"""What a new user's trial of editing, hot spots and the cheap shimmer found (5 December): a
multi-start solve that reported a drawn parameter as held fixed, traces too coarse to tell a met
pair, a reach whose paths collapsed the steps, hot spots too small or deep to evaluate, and a noise
map whose FFT grid the OS killed. (rk45 stepping over hot spots: tests/media/test_hot_spots.py.)"""

import pytest

import refracta
from refracta._animate import geometric_noise_map
from refracta.edit import PointPair, solve

EYE = (0.0, 1.5, 0.0)
PAIRS = [
    PointPair(destination=(1000.0, 1.2, 0.0), source=(1000.0, 3.0, 0.0)),
    PointPair(destination=(800.0, 1.0, 0.0), source=(800.0, 2.5, 0.0)),
]


def test_every_parameter_that_changed_is_reported_as_changed_whichever_start_won():
    # The trial's solve: a random start drew h_ciso from 1 to 87, found no pair depending on it
    # there, and held it: the report listed it as held fixed, parameter_changes() left it out.
    result = solve(refracta.LogisticProfile(), EYE, PAIRS, free=["k_s", "h_ciso"], strategy="local", starts=3, seed=1)
    changed = {name for name, value in result.field.params.items() if value != result.start.params[name]}
    assert changed  # the solve moved something
    assert changed <= set(result.free)
    assert not changed & set(result.insensitive)
    assert {name for name, *_ in result.parameter_changes()} >= changed


@pytest.mark.parametrize(
    "options, match",
    [
        (dict(tol=1e3), "more than pair 0 may miss its source by .*lower tol"),  # "met" at 5e-10 m, off by 2.4 m
        (dict(trace="rk4", step=1e300), "longer than pair 0's range .*rk4 cannot follow"),
        (dict(reach=1e6), r"reach must be in \[1, 100\]"),  # 1e9 m paths: "step size collapsed ... singular"
    ],
)
def test_traces_too_coarse_or_long_to_judge_a_pair_are_refused(options, match):
    with pytest.raises(ValueError, match=match):
        solve(refracta.LogisticProfile(), EYE, PAIRS[:1], free=["k_s"], **options)


def test_a_noise_correlation_far_longer_than_the_image_is_refused_before_its_grid_is_made():
    # 9999 pixels asked for a ~40000^2 FFT grid: the OS killed the process.
    with pytest.raises(ValueError, match="correlation_pixels=9999.0 .* needs a 40000x40000 FFT grid"):
        geometric_noise_map(2, 4, 1e-3, 9999.0)
    assert geometric_noise_map(2, 4, 1e-3, 500.0).shape == (2, 4, 2)  # long, but within the grid


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: PointPair((1.0, 2.0, 3.0), (4.0, 5.0, 6.0), weight=True), "PointPair weight must be a number"),
        (lambda: PointPair((1.0, 2.0, 3.0), (4.0, 5.0, 6.0), weight="2"), "PointPair weight must be a number"),
        # An optional number field (None by default) took True as a ground 1 m up.
        (
            lambda: solve(refracta.LogisticProfile(), EYE, PAIRS[:1], free=["k_s"], stop_height=True),
            "stop_height must be a number",
        ),
        (
            lambda: refracta.trace_rays(refracta.LogisticProfile(), [EYE], [(1.0, 0.0, 0.0)], stop_height=True),
            "stop_height must be a number",
        ),
        # The settings object given for the wrong argument was blamed on "options".
        (
            lambda: solve(refracta.LogisticProfile(), EYE, PAIRS[:1], settings=refracta.edit.PairOptions()),
            "settings must be a refracta.edit.SolveSettings or None",
        ),
    ],
)
def test_bools_strings_and_the_wrong_options_object_are_refused_by_name(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_an_edit_result_is_read_only():
    # result.cost = 5 was taken, and result.cost then disagreed with result.summary.cost.
    result = solve(refracta.LogisticProfile(), EYE, PAIRS[:1], free=["k_s"])
    with pytest.raises(AttributeError):
        result.cost = 5.0  # type: ignore[misc]
    with pytest.raises(AttributeError):
        result.field = None  # type: ignore[misc]
    assert result.cost == result.summary.cost


def _animate_checks(tmp_path, **kwargs):
    scene = refracta.Scene()
    scene.add_ground(0.0, 100.0)
    camera = refracta.Camera((0.0, 1.0, 0.0), (10.0, 1.0, 0.0), vfov=10.0, width=8, height=4)
    noise = {"rms": 1e-4, "correlation_pixels": 2.0}
    return refracta.animate(scene, camera, refracta.PhysicalAtmosphere(), noise=noise, progress=False, **kwargs)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(times=[True, False]), "animate: times must be numbers"),  # were 1 s and 0 s
        (dict(times="abc"), "animate: times must be numbers"),  # numpy's message named nothing
        # A GIF's delays are whole hundredths of a second: 5000 fps was written with no delay at all.
        (dict(times=[0.0, 1.0], path="f.gif", fps=5000.0), "at most 50 fps .*got 5000"),
        (dict(times=[0.0, 0.01], path="f.gif"), "at most 50 fps .*got 100, from the times"),
    ],
)
def test_animate_refuses_times_and_gif_rates_it_cannot_honour(tmp_path, kwargs, match):
    if "path" in kwargs:
        kwargs["path"] = tmp_path / kwargs["path"]
    with pytest.raises(ValueError, match=match):
        _animate_checks(tmp_path, **kwargs)
