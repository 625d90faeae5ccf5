"""Moment shadow maps against PCF, moment-based OIT against the sorted composite (issue 12).

A 1024^2 shadow map of the sun over a small scene of boxes, rendered at 512 x 320 with
render_raster(output='shadow'): for kernels 3x3 ... 31x31, the time to build the map (rasterize,
moments, separable box filter, storage) and the whole render (lookups included) for PCF and the
moment methods, and their errors against PCF with the same kernel (refracta.compare.shadows).
Goals: MSM's cost flat in the kernel size and below PCF's from 9x9 on (Hamburger and Hausdorff).
Transparency: a view through 8 and 32 tilted transparent sheets (8 and 32 fragments per pixel),
each OIT method's time (render_raster with shadows off, shading included) and bytes per pixel,
and its error against the exact sorted composite (refracta.compare.transparency), at 256^2
(--oit-size); then the issue's case, 1024^2 x 32 fragments, timed for the exact composite and
MBOIT with 4, 6 and 8 power moments (best of two). Goal: MBOIT 4 at most 1.5x the exact time.
The sheets are lit by the sun alone: a sky (an environment light) is sampled 64 times per shaded
fragment by render_raster (light_strata 8), which would swamp the compositing compared here.

    python benchmarks/bench_moments.py              -> benchmarks/results/moments.json
    python benchmarks/bench_moments.py --oit-ratio  MBOIT 4 vs exact at 1024^2 x 32 only (printed)
"""

from __future__ import annotations

import numpy as np
from _common import write_results

import refracta
from refracta import compare
from refracta._raster_render import shadow_fields_for

KERNELS = (3, 5, 9, 15, 21, 31)
METHODS = ("pcf", "vsm", "msm_hamburger", "msm_hausdorff")


def scene_and_camera():
    scene = refracta.Scene()
    scene.set_sun((-0.5, 0.6, 0.3), (2e4, 2e4, 2e4))
    scene.set_sky((0.5, 0.6, 0.8), (0.2, 0.3, 0.7))
    scene.add_ground(0.0, 200.0)
    for i in range(6):
        for j in range(4):
            scene.add_box(
                (4.0 + 5.0 * i, 0.5 + 0.4 * ((i + j) % 4), -8.0 + 5.0 * j), (1.5, 1.0 + 0.8 * ((i + j) % 4), 1.5)
            )
    camera = refracta.Camera((-6, 12, -18), (14, 0, 0), (0, 1, 0), 50, 512, 320)
    return scene, camera


def glass_stack(layers: int, size: int):
    """`layers` tilted transparent sheets filling a size^2 view (one fragment each per pixel, at
    depths that vary across the image), in front of a wall."""
    rng = np.random.default_rng(1)
    scene = refracta.Scene()
    scene.set_sun((-0.5, 0.6, 0.3), (2e4, 2e4, 2e4))
    scene.add_box((80.0, 0.0, 0.0), (1.0, 300.0, 300.0), kd=(0.8, 0.8, 0.8))
    for i in range(layers):
        x0, ty, tz = 8.0 + 2.0 * i, rng.uniform(-0.15, 0.15), rng.uniform(-0.15, 0.15)
        corners = [(x0 + ty * y + tz * z, y, z) for y, z in ((-60, -60), (60, -60), (60, 60), (-60, 60))]
        scene.add_mesh(
            corners, [[0, 1, 2], [0, 2, 3]], kd=tuple(rng.uniform(0.1, 0.9, 3)), alpha=float(rng.uniform(0.1, 0.5))
        )
    camera = refracta.Camera((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0, 1, 0), 40, size, size)
    return scene, camera


def transparency_rows(size: int) -> list:
    rows = []
    for layers in (8, 32):
        scene, camera = glass_stack(layers, size)
        table, _ = compare.transparency(
            scene,
            camera,
            methods=(
                "peel 4",
                "wboit eq7",
                "mboit 4",
                "mboit 6",
                "mboit 8",
                "mboit trig 2",
                "mboit trig 3",
                "mboit trig 4",
                "mboit 4 unorm16",
                "mboit 6 unorm16",
                "mboit 8 unorm16",
                "mboit trig 3 unorm16",
            ),
            figure=False,
            shadows="none",
        )
        for row in table:
            row["fragments_per_pixel"] = layers
            row["image"] = [size, size]
            rows.append(row)
            print(
                f"{layers:2d} fragments  {row['method']:14s} {row['seconds']:7.3f} s  "
                f"{row['bytes_per_pixel']:6.1f} B/px  mean error {row['mean_error']:.4f}  p99 {row['p99_error']:.4f}"
            )
    return rows


def best_seconds(scene, camera, repeats: int, **options) -> float:
    """The shortest of `repeats` render_raster times (single runs on 2 busy cores scatter by ~30 %)."""
    best = None
    for _ in range(repeats):
        _, counts = refracta.render_raster(scene, camera, shadows="none", return_stats=True, **options)
        best = counts.seconds if best is None else min(best, counts.seconds)
    return best


OIT_RATIO_METHODS = ("mboit 4", "mboit 6", "mboit 8")


def oit_ratio_rows(size: int = 1024, layers: int = 32, methods=OIT_RATIO_METHODS, repeats: int = 2) -> list:
    """Exact composite and MBOIT at size^2 x `layers` fragments: time and time / exact."""
    scene, camera = glass_stack(layers, size)
    exact = best_seconds(scene, camera, repeats, transparency="exact")
    rows = [
        {"method": "exact", "seconds": exact, "over_exact": 1.0, "image": [size, size], "fragments_per_pixel": layers}
    ]
    for method in methods:
        seconds = best_seconds(scene, camera, repeats, **compare.TRANSPARENCY_METHODS[method])
        rows.append(
            {
                "method": method,
                "seconds": seconds,
                "over_exact": seconds / exact,
                "image": [size, size],
                "fragments_per_pixel": layers,
            }
        )
    for row in rows:
        print(
            f"{size}^2 x {layers} fragments  {row['method']:8s} {row['seconds']:7.2f} s  "
            f"{row['over_exact']:5.2f}x exact"
        )
    return rows


def main(oit_size: int = 256) -> dict:
    scene, camera = scene_and_camera()
    rows = []
    for storage in ("fp32", "unorm16"):
        table, _ = compare.shadows(
            scene, camera, methods=METHODS, kernels=KERNELS, figure=False, resolution=1024, storage=storage
        )
        for row in table:
            row["storage"] = storage
            best = None
            for _ in range(3):  # the best of three: single runs on 2 busy cores scatter by ~30 %
                fields = shadow_fields_for(row["method"], dict(kernel=row["kernel"], resolution=1024, storage=storage))
                _, counts = refracta.render_raster(
                    scene,
                    camera,
                    shadows=row["method"],
                    output="shadow",
                    return_stats=True,
                    **fields,
                )
                if best is None or counts.seconds < best.seconds:
                    best = counts
            row["build_seconds"] = best.shadow_build_seconds
            row["lookup_seconds"] = best.seconds - best.shadow_build_seconds
            rows.append(row)
            print(
                f"{storage:8s} {row['method']:14s} {row['kernel']:3d}  build {row['build_seconds']:.3f} s  "
                f"lookups {row['lookup_seconds']:.3f} s  mean error {row['mean_error']:.4f}  p99 {row['p99_error']:.3f}"
            )
    fp32 = [r for r in rows if r["storage"] == "fp32"]
    total = {(r["method"], r["kernel"]): r["build_seconds"] + r["lookup_seconds"] for r in fp32}
    msm = [total[("msm_hamburger", k)] for k in KERNELS]
    oit_rows = oit_ratio_rows()
    ratio = {r["method"]: r["over_exact"] for r in oit_rows}
    goals = {
        "msm_cost_ratio_31_over_3": msm[-1] / msm[0],
        "msm_over_pcf_per_kernel": {
            method: {str(k): total[(method, k)] / total[("pcf", k)] for k in KERNELS}
            for method in ("msm_hamburger", "msm_hausdorff")
        },
        "msm_below_pcf_from_9x9": all(
            total[(m, k)] < total[("pcf", k)] for m in ("msm_hamburger", "msm_hausdorff") for k in KERNELS if k >= 9
        ),
        "mboit4_over_exact_1024_32": ratio["mboit 4"],
        "mboit6_over_exact_1024_32": ratio["mboit 6"],
        "mboit8_over_exact_1024_32": ratio["mboit 8"],
        "mboit4_at_most_1.5x_exact": ratio["mboit 4"] <= 1.5,
    }
    print(goals)
    payload = {
        "setup": {"shadow_map": 1024, "image": [camera.width, camera.height], "kernels": KERNELS},
        "rows": rows,
        "goals": goals,
        "transparency": transparency_rows(oit_size),
        "oit_1024": oit_rows,
    }
    print(f"wrote {write_results('moments', payload)}")
    return payload


if __name__ == "__main__":
    import argparse

    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--oit-size", type=int, default=256, help="transparency image size (default 256)")
    parser.add_argument(
        "--oit-ratio",
        action="store_true",
        help="only time MBOIT 4 against the exact composite at 1024^2 x 32 fragments (no JSON)",
    )
    args = parser.parse_args()
    if args.oit_ratio:
        oit_ratio_rows(methods=("mboit 4",))
    else:
        main(args.oit_size)
