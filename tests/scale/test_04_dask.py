"""dask.distributed end to end, on a LocalCluster of 2 worker processes started here: a sweep of
renders equals the serial results, a worker killed mid-sweep loses nothing (dask re-runs its
task elsewhere), and a render split into tiles across the workers equals the local render."""

import os
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import refracta
from tests.scale import scenes

distributed = pytest.importorskip("distributed")

# Upper bound on waiting for a worker to start the watched task (seconds): a bound against a
# hang, not a timing assertion; the task starts within a second on an idle machine.
START_WAIT = 60.0


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None)
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


@pytest.fixture(scope="module")
def texture(tmp_path_factory):
    return scenes.write_texture(tmp_path_factory.mktemp("dask") / "checker.exr")


def road_render(surface_dt, eye, texture):
    """A small render of the every-kind scene through a hot road of `surface_dt` [K], eye at `eye` [m]."""
    scene = scenes.every_kind_scene(texture, "gradient")
    camera = refracta.Camera((0.0, eye, 0.3), (8.0, 0.9, -0.2), vfov=60.0, width=scenes.WIDTH, height=scenes.HEIGHT)
    field = refracta.PhysicalAtmosphere(surface_dt=surface_dt, surface_depth=0.3)
    return scenes.render_quietly(scene, camera, field, transport="path", spp=2)


def watched_render(surface_dt, eye, texture, folder):
    """road_render, leaving a 'started-<dt>-<eye>-<pid>' file; the point (10 K, 1 m) then waits
    for 'release' so that it is certainly running when the test kills its worker."""
    Path(folder, f"started-{surface_dt:g}-{eye:g}-{os.getpid()}").touch()
    if (surface_dt, eye) == (10.0, 1.0):
        deadline = time.monotonic() + START_WAIT
        while not Path(folder, "release").exists() and time.monotonic() < deadline:
            time.sleep(0.02)
    return road_render(surface_dt, eye, texture)


GRID = {"surface_dt": [4.0, 10.0, 16.0], "eye": [1.0, 1.6]}


def test_a_sweep_on_the_cluster_equals_the_serial_sweep(client, texture):
    grid = dict(GRID, texture=[texture])
    serial = refracta.sweep(road_render, grid, progress=False)
    done = []
    remote = refracta.sweep(road_render, grid, executor=client, progress=lambda d, t: done.append(d))
    assert len(remote) == 6 and done[-1] == 6
    for a, b in zip(remote, serial):
        assert np.array_equal(a, b)
    assert not np.array_equal(serial[0], serial[4])  # different atmospheres, different images


def test_a_worker_killed_mid_sweep_loses_nothing(client, texture, tmp_path):
    grid = dict(GRID, texture=[texture], folder=[str(tmp_path)])
    outcome = {}
    sweeping = threading.Thread(
        target=lambda: outcome.update(
            result=refracta.sweep(watched_render, grid, executor=client, progress=False, errors="keep")
        )
    )
    sweeping.start()
    deadline = time.monotonic() + START_WAIT
    while not list(tmp_path.glob("started-10-1-*")) and time.monotonic() < deadline:
        time.sleep(0.02)
    started = list(tmp_path.glob("started-10-1-*"))
    assert started, "the watched task never started"
    victim = int(started[0].name.rsplit("-", 1)[1])
    assert victim in client.run(os.getpid).values()  # a worker process of this cluster
    os.kill(victim, signal.SIGKILL)
    (tmp_path / "release").touch()
    sweeping.join(START_WAIT * 2)
    assert not sweeping.is_alive()
    result = outcome["result"]
    assert result.ok, [str(f) for f in result.failures]
    for point, image in zip(result.points, result):
        assert np.array_equal(image, road_render(point["surface_dt"], point["eye"], texture))
    # The killed point ran again, in another worker process (the survivor or the restarted one).
    runs = [int(p.name.rsplit("-", 1)[1]) for p in tmp_path.glob("started-10-1-*")]
    assert victim in runs and any(pid != victim for pid in runs)


def test_a_render_split_across_workers_equals_the_local_render(client, texture):
    scene, camera, field = scenes.every_kind_scene(texture, "environment"), scenes.camera(), scenes.hot_road()
    for transport in ("direct", "path"):
        local = scenes.render_quietly(scene, camera, field, transport=transport, spp=4)
        split, stats = refracta.render(
            scene,
            camera,
            field,
            transport=transport,
            spp=4,
            executor=client,
            tiles=(2, 2),
            progress=False,
            return_stats=True,
        )
        assert np.array_equal(split, local)
        assert stats.samples == camera.width * camera.height * 4


def cold_only(surface_dt):
    if surface_dt > 10.0:
        raise ValueError(f"no table for {surface_dt} K")
    return refracta.PhysicalAtmosphere(surface_dt=surface_dt).ior([0.0, 0.0, 0.0])


def test_a_failing_point_on_a_worker_is_reported_with_its_parameters(client):
    with pytest.raises(
        refracta.SweepError, match=r"1 of 3 sweep points failed: point 2 \{'surface_dt': 12.0\}"
    ) as caught:
        refracta.sweep(cold_only, {"surface_dt": [2.0, 6.0, 12.0]}, executor=client, progress=False)
    failure = caught.value.failures[0]
    assert isinstance(failure.error, ValueError) and "no table for 12.0 K" in failure.traceback
    results = caught.value.results
    assert results[:2] == [cold_only(2.0), cold_only(6.0)] and results[2] is None


def render_scene(scene, surface_dt):
    return scenes.render_quietly(scene, scenes.camera(), refracta.PhysicalAtmosphere(surface_dt=surface_dt), spp=2)


def test_a_scattered_scene_in_the_grid_reaches_the_workers(client, texture):
    """The documented way to send a large object once: scatter it and put the future in the grid."""
    scene = scenes.every_kind_scene(texture, "constant")
    future = client.scatter(scene, broadcast=True)
    remote = refracta.sweep(
        render_scene, {"scene": [future], "surface_dt": [3.0, 12.0]}, executor=client, progress=False
    )
    for image, dt in zip(remote, [3.0, 12.0]):
        assert np.array_equal(image, render_scene(scene, dt))


def returns_a_generator(x):
    return (i for i in range(x)) if x == 1 else x


def test_a_result_that_cannot_travel_fails_its_own_point_only(client):
    # A trial: the Client's own executor never finished such a point's future, and the sweep hung.
    result = refracta.sweep(returns_a_generator, {"x": [0, 1, 2]}, executor=client, progress=False, errors="keep")
    assert list(result) == [0, None, 2]
    assert [f.index for f in result.failures] == [1]


def number_or_zero(x):
    return x if isinstance(x, int) else 0


def test_a_grid_value_that_cannot_travel_fails_its_own_point_only(client):
    # A trial: its submit's serialisation error aborted the whole sweep, naming no point.
    grid = {"x": [0, threading.Lock(), 2, 3]}
    result = refracta.sweep(number_or_zero, grid, executor=client, progress=False, errors="keep")
    assert list(result) == [0, None, 2, 3]
    assert [f.index for f in result.failures] == [1]
