"""refracta.set_threads limits oneTBB; results do not depend on the number of threads (each
parallel loop writes every item to its own slot, every pixel has its own seed)."""

import numpy as np
import pytest

import refracta
from refracta import examples
from refracta.edit import PointPair, solve


@pytest.fixture
def threads():
    """Calls fn() with 1 and then 2 threads; restores the default (every core) afterwards."""

    def with_threads(fn):
        results = []
        for n in (1, 2):
            refracta.set_threads(n)
            assert refracta.get_threads() == n
            results.append(fn())
        return results

    yield with_threads
    refracta.set_threads(None)


def test_set_threads_none_or_zero_restores_every_core():
    import os

    cores = len(os.sched_getaffinity(0))
    refracta.set_threads(1)
    assert refracta.get_threads() == 1
    refracta.set_threads(0)
    assert refracta.get_threads() == cores
    refracta.set_threads(1)
    refracta.set_threads(None)
    assert refracta.get_threads() == cores


def test_set_threads_rejects_negative():
    with pytest.raises(ValueError, match=r"n must be in \[0, 256\] or None \(got -1"):
        refracta.set_threads(-1)


@pytest.mark.slow
def test_curved_render_is_bit_identical_with_one_and_two_threads(threads):
    road = examples.hot_road(48, 20)
    one, two = threads(
        lambda: refracta.render(road.scene, road.camera, road.field, max_length=road.max_length, spp=2, progress=False)
    )
    assert np.array_equal(one, two)
    assert np.isfinite(one).all() and one.max() > 0.0


def test_trace_rays_is_bit_identical_with_one_and_two_threads(threads, hot_road):
    e = np.radians(np.linspace(-0.5, 0.3, 257))
    directions = np.c_[np.cos(e), np.sin(e), 0 * e]
    for method in ("rk45", "stratified"):
        one, two = threads(
            lambda method=method: refracta.trace_rays(
                hot_road, [0, 1.5, 0], directions, trace=method, max_length=800.0, stop_height=0.0, progress=False
            )
        )
        for a, b in zip(one, two):
            assert np.array_equal(a, b), method


def test_render_raster_is_bit_identical_with_one_and_two_threads(threads):
    road = examples.hot_road(64, 24)
    one, two = threads(
        lambda: refracta.render_raster(road.scene, road.camera, shadows="msm_hamburger", resolution=256, progress=False)
    )
    assert np.array_equal(one, two)


def test_solve_is_identical_with_one_and_two_threads(threads):
    truth = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    start = refracta.PhysicalAtmosphere(surface_dt=7.0, surface_depth=0.13)
    eye = np.array([0.0, 1.4, 0.0])
    pairs = []
    for elevation, distance in zip((-0.22, -0.12, 0.05), (300.0, 450.0, 600.0)):
        direction = np.array([np.cos(np.radians(elevation)), np.sin(np.radians(elevation)), 0.0])
        path = refracta.trace_ray(truth, eye, direction, tol=1e-11, max_length=distance + 10.0, stop_height=0.0)
        pairs.append(PointPair(eye + direction, path.point_at(distance)[0]))
    one, two = threads(lambda: solve(start, eye, pairs, free=["surface_dt", "surface_depth"], stop_height=0.0))
    assert one.success and two.success
    assert one.field.params == two.field.params
    assert one.iterations == two.iterations and one.cost == two.cost
    assert np.array_equal(one.history, two.history)
