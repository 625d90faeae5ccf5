"""Scale-out on dask.distributed (issue 13): a sweep of 8 renders and one render split into tiles,
on a LocalCluster of 2 worker processes (1 thread each) against the same work in this process.

Sweep: examples.hot_road(320, 120), spp 8, surface_dt over 8 values (each render ~2.5 s on 2
cores). Modes: in-process with oneTBB on every core (refracta's default: each render is already
parallel), in-process on 1 thread (the work one worker does per render), and the cluster with each
worker's oneTBB limited to 1 thread (refracta.set_threads(1) on the workers: one render per core)
or left at every core (2 workers x 2 threads: oversubscribed). Tiles: one 640 x 240, spp 8 render
locally vs tiles=(4, 2) on the cluster. Every mode's images are checked equal (bit for bit) to
the in-process ones. The cluster's start-up (~2 s) is not counted; the first sweep on a fresh
cluster pays the workers' imports, so each cluster mode runs once to warm up, then is timed.

    python benchmarks/bench_scale.py     -> benchmarks/results/scale.json
"""

from __future__ import annotations

import numpy as np
from _common import timed, write_results

import refracta
from refracta import examples

SURFACE_DT = [2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 14.0, 16.0]  # [K]
SPP = 8


def road_render(surface_dt, width=320, height=120):
    road = examples.hot_road(width, height)
    return refracta.render(
        road.scene,
        road.camera,
        road.field.with_params(surface_dt=surface_dt),
        spp=SPP,
        progress=False,
        max_length=road.max_length,
    )


def main():
    from distributed import Client, LocalCluster

    grid = {"surface_dt": SURFACE_DT}
    results = {"renders": len(SURFACE_DT), "image": "hot_road 320 x 120", "spp": SPP}
    reference, results["serial_all_cores_s"] = timed(refracta.sweep, road_render, grid, progress=False)
    refracta.set_threads(1)
    one_thread, results["serial_one_thread_s"] = timed(refracta.sweep, road_render, grid, progress=False)
    refracta.set_threads(None)
    assert all(np.array_equal(a, b) for a, b in zip(one_thread, reference))

    with (
        LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) as cluster,
        Client(cluster) as client,
    ):
        for label, threads in (("dask_2_workers_1_thread_s", 1), ("dask_2_workers_tbb_all_cores_s", None)):
            client.run(refracta.set_threads, threads)
            refracta.sweep(road_render, grid, executor=client, progress=False)  # warm-up: imports, first tables
            images, results[label] = timed(refracta.sweep, road_render, grid, executor=client, progress=False)
            assert all(np.array_equal(a, b) for a, b in zip(images, reference)), label

        client.run(refracta.set_threads, 1)
        road = examples.hot_road(640, 240)
        args = (road.scene, road.camera, road.field)
        options = dict(spp=SPP, progress=False, max_length=road.max_length)
        local, results["tiles_local_all_cores_s"] = timed(refracta.render, *args, **options)
        refracta.render(*args, executor=client, tiles=(4, 2), **options)  # warm-up
        split, results["tiles_dask_4x2_s"] = timed(refracta.render, *args, executor=client, tiles=(4, 2), **options)
        assert np.array_equal(split, local)

    serial = results["serial_all_cores_s"]
    results["speedup_vs_serial_all_cores"] = serial / results["dask_2_workers_1_thread_s"]
    results["speedup_vs_serial_one_thread"] = results["serial_one_thread_s"] / results["dask_2_workers_1_thread_s"]
    results["tiles_speedup"] = results["tiles_local_all_cores_s"] / results["tiles_dask_4x2_s"]
    results["identical_images"] = True
    path = write_results("scale", results)
    for key, value in results.items():
        print(f"{key:34s} {value:.3f}" if isinstance(value, float) else f"{key:34s} {value}")
    print(f"-> {path}")


if __name__ == "__main__":
    main()
