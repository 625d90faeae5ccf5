"""refracta.sweep without a cluster: grid order, failures reported with their parameters while
every other result is kept, progress, and the same results from thread and process pools."""

import concurrent.futures
import multiprocessing
import pickle
import signal
import subprocess
import sys

import numpy as np
import pytest

import refracta
from refracta import SweepError, sweep
from refracta._sweep import grid_points

from tests.scale import scenes


def mirage_end_height(surface_dt, eye):
    """Height [m] where a ray launched 0.2 deg down from the eye is after 600 m over a hot road."""
    road = refracta.PhysicalAtmosphere(surface_dt=surface_dt, surface_depth=0.2)
    e = np.radians(-0.2)
    return refracta.trace_ray(road, [0, eye, 0], [np.cos(e), np.sin(e), 0], max_length=600.0).points[-1, 1]


def fails_when_hot(surface_dt, eye):
    if surface_dt > 9:
        raise ValueError(f"too hot: {surface_dt}")
    return surface_dt * eye


def test_a_dict_grid_is_the_cartesian_product_with_the_last_key_fastest():
    points = grid_points({"a": [1, 2], "b": ["x", "y", "z"]})
    assert points == [{"a": 1, "b": "x"}, {"a": 1, "b": "y"}, {"a": 1, "b": "z"},
                      {"a": 2, "b": "x"}, {"a": 2, "b": "y"}, {"a": 2, "b": "z"}]
    assert grid_points([{"a": 3}, {"a": 1, "b": 2}]) == [{"a": 3}, {"a": 1, "b": 2}]


def test_serial_sweep_returns_results_in_grid_order():
    grid = {"surface_dt": [2.0, 8.0, 15.0], "eye": [1.2, 1.6]}
    result = sweep(mirage_end_height, grid, progress=False)
    expected = [mirage_end_height(**p) for p in grid_points(grid)]
    assert list(result) == expected and result.points == grid_points(grid) and result.ok
    # The physics orders them: a hotter road bends the same ray further up (higher end point).
    assert result[0] < result[2] < result[4] and result[1] < result[3] < result[5]


@pytest.mark.parametrize("pool", ["threads", "processes"])
def test_pools_give_the_serial_results(pool):
    grid = {"surface_dt": [2.0, 8.0, 15.0], "eye": [1.2, 1.6]}
    serial = sweep(mirage_end_height, grid, progress=False)
    if pool == "threads":
        executor = concurrent.futures.ThreadPoolExecutor(2)
    else:
        executor = concurrent.futures.ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn"))
    with executor:
        parallel = sweep(mirage_end_height, grid, executor=executor, progress=False)
    assert list(parallel) == list(serial)


def test_failed_points_are_reported_with_their_parameters_and_the_rest_kept():
    grid = {"surface_dt": [5.0, 10.0, 3.0, 12.0], "eye": [2.0]}
    with pytest.raises(SweepError, match=r"2 of 4 sweep points failed: point 1 \{'surface_dt': 10.0, 'eye': 2.0\}") as caught:
        sweep(fails_when_hot, grid, progress=False)
    error = caught.value
    assert [f.index for f in error.failures] == [1, 3]
    assert error.failures[1].point == {"surface_dt": 12.0, "eye": 2.0}
    assert isinstance(error.failures[0].error, ValueError) and "too hot: 10.0" in error.failures[0].traceback
    assert list(error.results) == [10.0, None, 6.0, None]
    kept = sweep(fails_when_hot, grid, progress=False, errors="keep")
    assert list(kept) == [10.0, None, 6.0, None] and not kept.ok and len(kept.failures) == 2
    copy = pickle.loads(pickle.dumps(error))  # travels back from workers / to other processes
    assert [f.point for f in copy.failures] == [f.point for f in error.failures]


def test_progress_reports_every_finished_point():
    calls = []
    sweep(fails_when_hot, {"surface_dt": [1.0, 2.0, 3.0], "eye": [1.0]}, progress=lambda d, t: calls.append((d, t)))
    assert calls == [(0, 3), (1, 3), (2, 3), (3, 3)]


def test_a_sweep_of_renders_equals_the_renders():
    grid = [{"surface_dt": 4.0}, {"surface_dt": 14.0}]
    images = sweep(render_road, grid, progress=False)
    for point, image in zip(grid, images):
        assert np.array_equal(image, render_road(**point))
    assert not np.array_equal(images[0], images[1])  # the mirage differs


def render_road(surface_dt):
    scene = refracta.Scene()
    scene.add_ground(0.0, 400.0, kd=(0.2, 0.2, 0.2))
    scene.add_box((120.0, 1.0, 0.0), (2.0, 2.0, 4.0), kd=(0.8, 0.1, 0.1))
    scene.set_sky(horizon=(0.8, 0.85, 0.9), zenith=(0.3, 0.4, 0.8))
    camera = refracta.Camera((0.0, 1.2, 0.0), (120.0, 0.9, 0.0), vfov=3.0, width=scenes.WIDTH, height=scenes.HEIGHT)
    field = refracta.PhysicalAtmosphere(surface_dt=surface_dt, surface_depth=0.2)
    return refracta.render(scene, camera, field, progress=False, max_length=400.0)


@pytest.mark.parametrize("bad, message", [
    (dict(function=5, grid={"a": [1]}), "callable"),
    (dict(function=fails_when_hot, grid={"a": 3}), "list of values"),
    (dict(function=fails_when_hot, grid=[1, 2]), "dict of parameter names"),
    (dict(function=fails_when_hot, grid={"a": [1]}, errors="ignore"), "errors must be"),
    (dict(function=fails_when_hot, grid={"a": [1]}, executor="cluster"), "executor must be"),
    (dict(function=fails_when_hot, grid={"a": [1]}, progress=3), "progress must be"),
])
def test_bad_arguments_raise_value_errors(bad, message):
    with pytest.raises(ValueError, match=message):
        sweep(**bad)


# A bound against a hang, not a timing assertion: the interrupted sweep below would otherwise
# render for minutes.
INTERRUPT_WAIT = 20.0

_INTERRUPTED_SWEEP = """
import sys
import refracta
from refracta import examples

def long_render(surface_dt):
    road = examples.hot_road(160, 60)
    print("ready", flush=True)
    return refracta.render(road.scene, road.camera, road.field.with_params(surface_dt=surface_dt),
                           spp=4096, progress=False, max_length=road.max_length)

refracta.sweep(long_render, {"surface_dt": [5.0, 10.0, 15.0]}, progress=False)
"""


def test_ctrl_c_stops_a_sweep():
    process = subprocess.Popen([sys.executable, "-c", _INTERRUPTED_SWEEP], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True)
    try:
        assert process.stdout.readline().strip() == "ready"
        process.send_signal(signal.SIGINT)
        _, stderr = process.communicate(timeout=INTERRUPT_WAIT)
    finally:
        process.kill()
    assert process.returncode != 0 and "KeyboardInterrupt" in stderr
