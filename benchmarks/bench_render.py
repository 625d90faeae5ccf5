"""Rendering the hot_road example at 1280x720, 1 spp, 2 threads (renderer issue benchmark).

Time, peak memory and chords per pixel (each method in a fresh process) for straight ray casting, curved rays
served by the ElevationTable (the default for height-only fields), curved rays with rk45 forced
per pixel (standing for fields that are not height-only: no tabulation, no invariant shortcuts),
raster_march with rk45, and raster_march with the original editor's settings (rk4, step 0.3 m,
1000 steps); and a 4K (3840x2160) curved frame, whose memory growth during the render is compared
with its image. Goals (speed issue): curved (table) at most 3x straight, rk45 per pixel at most
20x; the renderer issue's: curved >= 50x faster than raster_march with the original settings.

    python benchmarks/bench_render.py [--size 1280x720]   -> benchmarks/results/render.json
"""

from __future__ import annotations

import argparse
import json
import resource
import subprocess
import sys
import time

from _common import write_results

METHODS = {
    "straight": dict(method="straight"),
    "curved_table": dict(method="curved"),
    "curved_rk45_per_pixel": dict(method="curved", trace="rk45", table=False),
    "raster_march_rk45": dict(method="raster_march", march="rk45"),
    "raster_march_original": dict(method="raster_march", march="rk4", step=0.3, max_steps=1000),
}


FOUR_K = (3840, 2160)


def run_one(name: str, width: int, height: int) -> dict:
    import refracta
    from refracta import examples

    if name == "curved_table_4k":
        width, height = FOUR_K
    example = examples.hot_road(width, height)
    field = None if name == "straight" else example.field
    before_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    start = time.perf_counter()
    image, counts = refracta.render(
        example.scene,
        example.camera,
        field,
        progress=False,
        max_length=example.max_length,
        return_stats=True,
        **METHODS.get(name, METHODS["curved_table"]),
    )
    seconds = time.perf_counter() - start
    return {
        "seconds": seconds,
        "peak_rss_mb": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0,
        "peak_before_render_mb": before_mb,
        "image_mb": image.nbytes / 2**20,
        "size": [width, height],
        "mean_radiance": float(image.mean()),
        "us_per_pixel": 1e6 * seconds / (width * height),
        "chords_per_pixel": counts.chords / counts.samples if counts.chords else None,
    }


def main(width: int, height: int) -> dict:
    rows = {}
    for name in [*METHODS, "curved_table_4k"]:
        output = subprocess.run(
            [sys.executable, __file__, "--one", name, "--size", f"{width}x{height}"],
            check=True,
            capture_output=True,
            text=True,
        ).stdout
        rows[name] = json.loads(output.strip().splitlines()[-1])
        print(
            f"{name:24s} {rows[name]['seconds']:8.2f} s  {rows[name]['us_per_pixel']:7.2f} us/pixel  "
            f"peak {rows[name]['peak_rss_mb']:.0f} MB  chords/pixel {rows[name]['chords_per_pixel']}"
        )
    four_k = rows["curved_table_4k"]
    ratios = {
        "curved_table_over_straight": rows["curved_table"]["seconds"] / rows["straight"]["seconds"],
        "rk45_per_pixel_over_straight": rows["curved_rk45_per_pixel"]["seconds"] / rows["straight"]["seconds"],
        "rk45_per_pixel_over_table": rows["curved_rk45_per_pixel"]["seconds"] / rows["curved_table"]["seconds"],
        "curved_4k_memory_growth_over_image": (four_k["peak_rss_mb"] - four_k["peak_before_render_mb"])
        / four_k["image_mb"],
        "raster_march_original_over_curved_table": rows["raster_march_original"]["seconds"]
        / rows["curved_table"]["seconds"],
    }
    print("ratios", ratios)
    return {
        "setup": {"scene": "examples.hot_road", "size": [width, height], "spp": 1},
        "methods": rows,
        "ratios": ratios,
        "goals": {
            "curved_within_3x_of_straight": ratios["curved_table_over_straight"] <= 3,
            "rk45_per_pixel_within_20x_of_straight": ratios["rk45_per_pixel_over_straight"] <= 20,
            "curved_50x_faster_than_original_raster_march": ratios["raster_march_original_over_curved_table"] >= 50,
        },
    }


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--one", help=argparse.SUPPRESS)
    args = parser.parse_args()
    w, h = (int(v) for v in args.size.split("x"))
    if args.one:
        print(json.dumps(run_one(args.one, w, h)))
    else:
        print("->", write_results("render", main(w, h)))
