"""Terrain from elevation data (issue 20, section 1): a 3601 x 3601 SRTM tile, memory and speed.

A synthetic 1-arc-second SRTM tile (N46E007.hgt, 3601 x 3601 big-endian int16, ridges up to ~4 km
and a few voids; written to a temporary folder, nothing downloaded) is added with
Scene.add_terrain(path, frame=LocalFrame(45.75, 7.5)) -- an observer 28 km south of the tile's
southern edge, 1500 m up -- and rendered at 1280 x 720, 'direct', 1 spp, through a height-only
field over a curved Earth (CurvedEarth(PhysicalAtmosphere(), radius=frame.earth_radius)), under a
sun and a physical sky. Beside it examples.hot_road at the same size, in the same process,
alternately, `repeat` pairs; the median of the pairwise time ratios is reported.

Memory: the peak resident set (getrusage ru_maxrss) of a fresh process that loads the tile and
renders it (the render's own image buffers included), goal <= 1 GB; also the time to load the tile.

  terrain_1280x720   goal <= 10x the hot road's time; peak memory <= 1 GB

    python benchmarks/bench_terrain.py [--repeat 3] [--quick] -> benchmarks/results/terrain.json
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np
from _common import write_results

GOAL_RATIO = 10.0
GOAL_PEAK_BYTES = 1 << 30
TILE = "N46E007.hgt"
TILE_SIZE = 3601
OBSERVER = (45.75, 7.5)  # lat, lon [deg]: 28 km south of the tile
EYE_HEIGHT = 1500.0  # [m]


def write_tile(folder: str, size: int = TILE_SIZE) -> str:
    """A synthetic SRTM tile: smooth ridges (0.2-4 km) rising northward, 64 void samples (-32768)."""
    lat = np.linspace(47.0, 46.0, size)[:, None]
    lon = np.linspace(7.0, 8.0, size)[None, :]
    rise = np.clip((lat - 46.0) * 1.5, 0.0, 1.0)
    ridges = 0.55 + 0.25 * np.sin(lon * 37.0) * np.cos(lat * 29.0) + 0.2 * np.sin(lon * 91.0 + lat * 53.0) ** 2
    heights = (200.0 + 3800.0 * rise * ridges).astype(">i2")
    rng = np.random.default_rng(1)
    heights[rng.integers(0, size, 64), rng.integers(0, size, 64)] = -32768
    path = os.path.join(folder, TILE)
    heights.tofile(path)
    return path


def terrain_setup(path: str, width: int, height: int):
    """(scene, camera, field, max_length, load seconds) of the tile seen from OBSERVER."""
    import refracta
    from refracta import examples, geo

    frame = geo.LocalFrame(*OBSERVER, earth_radius=geo.radius_of_curvature(OBSERVER[0], 0.0))
    scene = refracta.Scene()
    examples.set_physical_sky(scene, examples.sun_direction(40.0, 150.0))
    start = time.perf_counter()
    scene.add_terrain(path, frame=frame)
    load = time.perf_counter() - start
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius=frame.earth_radius)
    eye = np.array([0.0, frame.flat_height(EYE_HEIGHT), 0.0])
    north = np.array([0.0, np.tan(np.radians(2.0)), -1.0])  # 2 deg up, toward the tile
    camera = refracta.Camera(eye, eye + north, vfov=20.0, width=width, height=height)
    return scene, camera, field, 150000.0, load  # the tile's far edge is 139 km away


def memory_child(path: str, width: int, height: int) -> None:
    """Run in a fresh process: load and render the tile, print the peak RSS and load time as JSON."""
    import resource

    import refracta

    scene, camera, field, max_length, load = terrain_setup(path, width, height)
    after_load = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    refracta.render(scene, camera, field, max_length=max_length, progress=False)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024  # Linux: kilobytes
    print(json.dumps({"peak_rss_bytes": peak, "peak_rss_after_load_bytes": after_load, "load_seconds": load}))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--quick", action="store_true", help="320 x 180, one pair")
    parser.add_argument("--memory-child", nargs=3, metavar=("PATH", "W", "H"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.memory_child:
        memory_child(args.memory_child[0], int(args.memory_child[1]), int(args.memory_child[2]))
        return
    import refracta
    from refracta import examples

    width, height = (320, 180) if args.quick else (1280, 720)
    repeat = 1 if args.quick else args.repeat
    with tempfile.TemporaryDirectory() as folder:
        path = write_tile(folder)
        child = subprocess.run(
            [sys.executable, __file__, "--memory-child", path, str(width), str(height)],
            capture_output=True,
            text=True,
            check=True,
        )
        memory = json.loads(child.stdout.strip().splitlines()[-1])
        scene, camera, field, max_length, _ = terrain_setup(path, width, height)
        road = examples.hot_road(width, height)

        def render_terrain():
            return refracta.render(scene, camera, field, max_length=max_length, progress=False)

        def render_road():
            return refracta.render(road.scene, road.camera, road.field, max_length=road.max_length, progress=False)

        render_terrain(), render_road()  # warm-up: sky tables, first-touch memory
        ratios, terrain_times, road_times = [], [], []
        for _ in range(repeat):
            start = time.perf_counter()
            image = render_terrain()
            t = time.perf_counter() - start
            start = time.perf_counter()
            render_road()
            r = time.perf_counter() - start
            terrain_times.append(t), road_times.append(r), ratios.append(t / r)
        if not np.isfinite(image).all():
            raise RuntimeError("terrain render has non-finite pixels")
    ratio = statistics.median(ratios)
    result = {
        "terrain_1280x720" if not args.quick else "terrain_quick": {
            "size": [width, height],
            "terrain_seconds": statistics.median(terrain_times),
            "hot_road_seconds": statistics.median(road_times),
            "ratio": ratio,
            "goal_ratio": GOAL_RATIO,
            "peak_rss_bytes": memory["peak_rss_bytes"],
            "peak_rss_after_load_bytes": memory["peak_rss_after_load_bytes"],
            "goal_peak_bytes": GOAL_PEAK_BYTES,
            "load_seconds": memory["load_seconds"],
            "met": bool(ratio <= GOAL_RATIO and memory["peak_rss_bytes"] <= GOAL_PEAK_BYTES),
        }
    }
    print(json.dumps(result, indent=2))
    if not args.quick:
        print("wrote", write_results("terrain", result))


if __name__ == "__main__":
    main()
