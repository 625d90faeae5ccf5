"""Child process of test_01_ctrl_c.py: runs each named long operation in turn, printing
`start <name>` just before the call and `stopped <name>` when KeyboardInterrupt ends it (or
`finished <name>` if it ran to the end). Every operation would run for many seconds."""

import sys

import numpy as np

import refracta
from refracta import examples
from refracta.edit import PointPair, solve


def road_field():
    return refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)


def setup(name):
    """A zero-argument callable doing the long work, with its inputs built beforehand."""
    if name == "trace_rays":
        e = np.radians(np.linspace(-0.5, 0.5, 200_000))
        directions = np.c_[np.cos(e), np.sin(e), 0 * e]
        return lambda: refracta.trace_rays(road_field(), [0, 1.5, 0], directions, tol=1e-10, max_length=2000.0)
    if name == "trace_ray":  # 9 million rk4 steps
        return lambda: refracta.trace_ray(road_field(), [0, 1.5, 0], [1, 0, 0], method="rk4", step=1e-3,
                                          max_length=9000.0)
    if name.startswith("render_"):
        road = examples.hot_road(640, 240)
        method = name[len("render_"):]
        if method == "table":  # the eye's ElevationTable, rays climbing 10 000 km
            return lambda: refracta.render(road.scene, road.camera, road.field, max_length=1e7, progress=False)
        if method == "raster":
            return lambda: refracta.render_raster(road.scene, road.camera.resized(2560, 960), resolution=8192,
                                                  kernel=33)
        return lambda: refracta.render(road.scene, road.camera, road.field, method=method, spp=4096,
                                       max_length=road.max_length, progress=False)
    if name == "solve":
        truth = road_field()
        eye = np.array([0.0, 1.4, 0.0])
        pairs = []
        for elevation, distance in zip([-0.22, -0.2, -0.12, 0.05], [400.0, 500.0, 600.0, 300.0]):
            e = np.radians(elevation)
            direction = np.array([np.cos(e), np.sin(e), 0.0])
            source, _ = refracta.trace_ray(truth, eye, direction, max_length=distance + 10, stop_height=0.0).point_at(distance)
            pairs.append(PointPair(destination=eye + direction, source=source))
        start = truth.with_params(surface_dt=3.0, surface_depth=0.5)
        return lambda: solve(start, eye, pairs, free=["surface_dt", "surface_depth"], backend="nlopt:GN_CRS2_LM",
                             ground=0.0, max_evaluations=10_000_000, max_iterations=10_000_000, starts=50,
                             function_tolerance=0.0, parameter_tolerance=0.0)
    if name == "sweep":
        road = examples.hot_road(320, 120)

        def one(surface_dt):
            return refracta.render(road.scene, road.camera, road.field.with_params(surface_dt=surface_dt), spp=4096,
                                   max_length=road.max_length, progress=False)
        return lambda: refracta.sweep(one, {"surface_dt": [5.0, 10.0, 15.0]}, progress=False)
    raise ValueError(f"unknown operation {name!r}")


def main(names):
    for name in names:
        work = setup(name)
        print(f"start {name}", flush=True)
        try:
            work()
        except KeyboardInterrupt:
            print(f"stopped {name}", flush=True)
        else:
            print(f"finished {name}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
