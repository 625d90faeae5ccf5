"""Child process of test_01_ctrl_c.py: runs each named long operation in turn, printing
`start <name>` once the work is under way -- at the first call of its progress callback, which
run_interruptible makes only after its C++ work has run for one polling period, or (trace_ray,
which has no progress) at the first evaluation of its Python field by the C++ work; then
`stopped <name>` when KeyboardInterrupt ends it, or `finished <name>` if it ran to the end. Every
operation is sized to run for minutes to days on an idle machine, so no machine can finish one
before the signal arrives."""

import signal
import sys

import numpy as np

import refracta
from refracta import examples
from refracta.edit import PointPair, solve

# Ctrl-C as a terminal delivers it: a process started from a background job of a non-interactive
# shell (`make test &` in a script) inherits SIGINT ignored, and Python then installs no
# KeyboardInterrupt handler.
signal.signal(signal.SIGINT, signal.default_int_handler)

UNBOUNDED_SPP = 1_000_000  # samples per pixel: days at 640x240 on any machine


def road_field():
    return refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)


class Started:
    """A progress callback announcing the work's start at its first call."""

    def __init__(self, name):
        self.name = name
        self.announced = False

    def __call__(self, done, total):
        if not self.announced:
            self.announced = True
            announce(self.name)


def announce(name):
    print(f"start {name}", flush=True)


def setup(name):
    """A zero-argument callable doing the long work, with its inputs built beforehand; it prints
    `start <name>` itself once under way."""
    started = Started(name)
    if name == "trace_rays":  # 2 million rays: ~9 minutes on 2 idle cores (200 000 took 52 s)
        e = np.radians(np.linspace(-0.5, 0.5, 2_000_000))
        directions = np.c_[np.cos(e), np.sin(e), 0 * e]
        return lambda: refracta.trace_rays(
            road_field(), [0, 1.5, 0], directions, tol=1e-10, max_length=2000.0, progress=started
        )
    if name == "trace_ray":  # 9 million rk4 steps, each calling back into Python 4 times: minutes
        # No progress callback: the field's first evaluation, made by the C++ work, announces it.
        def ior(points):
            started(0, 1)
            return 1.0 + 1e-6 * points[:, 1]

        field = refracta.CustomField(ior, lambda p: np.tile([0.0, 1e-6, 0.0], (len(p), 1)))
        return lambda: refracta.trace_ray(field, [0, 1.5, 0], [1, 0, 0], trace="rk4", step=1e-3, max_length=9000.0)
    if name.startswith("render_"):
        road = examples.hot_road(640, 240)
        method = name[len("render_") :]
        if method == "table":  # the eye's ElevationTable, rays climbing 9 000 km (within the scene's reach of 1e7 m)
            return lambda: refracta.render(
                road.scene, road.camera, road.field, max_length=9e6, spp=UNBOUNDED_SPP, progress=started
            )
        if method == "raster":  # one frame of a 8192 shadow map and 2560x960 pixels: 98 s on 2 cores
            return lambda: refracta.render_raster(
                road.scene, road.camera.resized(2560, 960), resolution=8192, kernel=33, progress=started
            )
        if method == "turbulent_path":  # one tile of slow pixels: rays through turbulence, path traced
            air = refracta.Turbulence(1e-10, depth=0.1, seed=3, cells=64)
            field = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1, turbulence=air)
            return lambda: refracta.render(
                road.scene,
                road.camera,
                field,
                transport="path",
                spp=UNBOUNDED_SPP,
                max_length=road.max_length,
                progress=started,
            )
        return lambda: refracta.render(
            road.scene,
            road.camera,
            road.field,
            method=method,
            spp=UNBOUNDED_SPP,
            max_length=road.max_length,
            progress=started,
        )
    if name == "solve":
        truth = road_field()
        eye = np.array([0.0, 1.4, 0.0])
        pairs = []
        for elevation, distance in zip([-0.22, -0.2, -0.12, 0.05], [400.0, 500.0, 600.0, 300.0]):
            e = np.radians(elevation)
            direction = np.array([np.cos(e), np.sin(e), 0.0])
            path = refracta.trace_ray(truth, eye, direction, max_length=distance + 10, stop_height=0.0)
            source, _ = path.point_at(distance)
            pairs.append(PointPair(destination=eye + direction, source=source))
        start = truth.with_params(surface_dt=3.0, surface_depth=0.5)
        return lambda: solve(
            start,
            eye,
            pairs,
            free=["surface_dt", "surface_depth"],
            backend="nlopt:GN_CRS2_LM",
            ground=0.0,
            max_evaluations=10_000_000,
            max_iterations=10_000_000,
            starts=50,
            function_tolerance=0.0,
            parameter_tolerance=0.0,
            progress=started,
        )
    if name == "sweep":
        road = examples.hot_road(320, 120)

        def one(surface_dt):
            return refracta.render(
                road.scene,
                road.camera,
                road.field.with_params(surface_dt=surface_dt),
                spp=UNBOUNDED_SPP,
                max_length=road.max_length,
                progress=started,
            )

        return lambda: refracta.sweep(one, {"surface_dt": [5.0, 10.0, 15.0]}, progress=False)
    raise ValueError(f"unknown operation {name!r}")


def main(names):
    for name in names:
        work = setup(name)
        try:
            work()
        except KeyboardInterrupt:
            print(f"stopped {name}", flush=True)
        else:
            print(f"finished {name}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
