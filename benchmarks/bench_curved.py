"""Curved rays near the cost of straight ones (issue 21, goals 2, 4 and 5).

Each case renders the same scene and camera twice -- through its air ('curved') and without it
('straight', or the height-only air for the hot spot) -- alternately in one process, `repeat`
pairs, and reports the median of the pairwise time ratios (the machine is shared: ratios measured
side by side, not absolute times), beside it the median ratio of their CPU time (both threads':
what other work on a shared machine lengthens least), the chords per sample (Embree queries of the
curved render) and the goal beside it; the goal is judged on the wall-time ratio.

  hot_road_1280x720   examples.hot_road, 'direct', 1 spp              goal <= 3x straight (moonshot 2x)
  hot_road_640x240    the same at 640 x 240                           goal <= 3x
  hot_road_path       examples.hot_road 320 x 120, 'path', 4 spp      goal <= 3x straight
  hot_spot_320x120    one compact hot spot (the issue's case: radius 300 m, 25 K, 350 m down the
                      hot road, over 2 K ground) / that height-only air, 'direct', 1 spp   goal <= 3x
  hot_spot_1280x720   the same at 1280 x 720                          goal <= 3x
  hot_spot_stretch    examples.hot_spot 320 x 120 (the demo's local lake: a row of 52 narrow compact
                      spots) / its height-only air, 'direct', 1 spp  no goal: reported beside them
  portland            a synthetic stand-in for the original editor's Portland scene (below),
                      960 x 480, 'direct', 1 spp, through a 15 K hot road    goal <= 4x straight
  green_flash         examples.green_flash's frame at -0.74 deg, 64 x 64, spectral, 48 spp  goal <= 3x
  cold_sea            examples.cold_sea 240 x 80, 'direct', 16 spp    goal <= 3x straight (the issue's
                      480 x 160 takes minutes a render through the air: a quarter of its pixels)

The Portland stand-in (no downloads): a 12 x 12 km terrain mesh of smooth hills rising to 1.8 km
2-6 km from the eye, a city of 400 boxes (10-60 m tall) on the valley floor around the road, a
15 K hot road under the eye (1.5 m), sun 35 deg high and a physical sky: every light's shadow
rays from the city and the hills rise through 1.8 km of air before they leave every object.

    python benchmarks/bench_curved.py [--repeat 3] [--only CASE ...] [--quick]
        -> benchmarks/results/curved.json (--only merges into the existing file)
"""

from __future__ import annotations

import argparse
import json
import statistics
import time

import numpy as np
from _common import RESULTS, write_results

GOALS: dict[str, float | None] = {
    "hot_road_1280x720": 3.0,
    "hot_road_640x240": 3.0,
    "hot_road_path": 3.0,
    "hot_spot_320x120": 3.0,
    "hot_spot_1280x720": 3.0,
    "hot_spot_stretch": None,
    "portland": 4.0,
    "green_flash": 3.0,
    "cold_sea": 3.0,
}


def portland_standin(width: int, height: int):
    """(scene, camera, field, max_length) of the synthetic Portland stand-in (module docstring)."""
    import refracta
    from refracta import _core, examples, shading

    scene = _core.Scene()
    examples.set_physical_sky(scene, examples.sun_direction(35.0, 30.0))
    # Terrain: a 12 x 12 km grid of 241 x 241 vertices (50 m), the valley floor at 0 m around the
    # eye, smooth hills up to 1.8 km beyond 2 km.
    n = 241
    xs = np.linspace(-2000.0, 10000.0, n)
    zs = np.linspace(-6000.0, 6000.0, n)
    x, z = np.meshgrid(xs, zs, indexing="ij")
    r = np.hypot(x - 500.0, z)
    rise = np.clip((r - 2000.0) / 4000.0, 0.0, 1.0)
    ridges = 0.6 + 0.25 * np.sin(x / 900.0) * np.cos(z / 700.0) + 0.15 * np.sin(z / 350.0 + x / 1300.0)
    y = 1800.0 * rise * rise * (3.0 - 2.0 * rise) * ridges - 0.05
    vertices = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="ij")
    a = (i * n + j).ravel()
    b, c, d = a + n, a + 1, a + n + 1
    triangles = np.concatenate([np.stack([a, c, b], 1), np.stack([c, d, b], 1)])
    scene.add_mesh(vertices, triangles, material=shading.Diffuse((0.3, 0.32, 0.22)))
    # The road along +x under the eye and a city of boxes on the valley floor.
    scene.add_box((1000.0, -0.024, 0.0), (2000.0, 0.052, 8.0), material=shading.Diffuse((0.06, 0.06, 0.065)))
    rng = np.random.default_rng(7)
    for _ in range(400):
        bx, bz = rng.uniform(150.0, 1800.0), rng.uniform(-900.0, 900.0)
        if abs(bz) < 15.0:
            continue
        h = rng.uniform(10.0, 60.0)
        grey = rng.uniform(0.3, 0.7)
        scene.add_box(
            (bx, h / 2, bz), (rng.uniform(15, 40), h, rng.uniform(15, 40)), material=shading.Diffuse((grey,) * 3)
        )
    field = refracta.PhysicalAtmosphere(surface_dt=15.0, surface_depth=0.1)
    eye = np.array([0.0, 1.5, 0.0])
    camera = refracta.Camera(eye, eye + [1.0, np.tan(np.radians(3.0)), 0.0], vfov=30.0, width=width, height=height)
    return scene, camera, field, 12000.0


def setup(case: str, quick: bool):
    """(scene, camera, curved field, reference field or None, render keywords)."""
    from refracta import examples

    scale = 4 if quick else 1
    if case.startswith("hot_road_") and "x" in case:
        w, h = (int(v) for v in case.removeprefix("hot_road_").split("x"))
        ex = examples.hot_road(w // scale, h // scale)
        return ex.scene, ex.camera, ex.field, None, dict(max_length=ex.max_length)
    if case == "hot_road_path":
        ex = examples.hot_road(320 // scale, 120 // scale)
        return ex.scene, ex.camera, ex.field, None, dict(max_length=ex.max_length, transport="path", spp=4)
    if case == "hot_spot_stretch":
        ex = examples.hot_spot(320 // scale, 120 // scale)
        return ex.scene, ex.camera, ex.field, ex.field.height_only_part, dict(max_length=ex.max_length)
    if case.startswith("hot_spot_"):
        import refracta

        w, h = (int(v) for v in case.removeprefix("hot_spot_").split("x"))
        ex = examples.hot_road(w // scale, h // scale)
        spot = refracta.HotSpot(350.0, 0.0, 300.0, 25.0, footprint="compact")
        field = refracta.PhysicalAtmosphere(surface_dt=2.0, surface_depth=0.1, hot_spots=[spot])
        return ex.scene, ex.camera, field, field.height_only_part, dict(max_length=ex.max_length)
    if case == "portland":
        scene, camera, field, max_length = portland_standin(960 // scale, 480 // scale)
        return scene, camera, field, None, dict(max_length=max_length)
    if case == "green_flash":
        import refracta

        size = 64 // scale
        ex = examples.green_flash(size, size, -0.74)
        look = np.radians(-0.05)
        eye = ex.camera.position
        camera = refracta.Camera(eye, eye + [np.cos(look), np.sin(look), 0.0], vfov=0.7, width=size, height=size)
        return ex.scene, camera, ex.field, None, dict(max_length=ex.max_length, spectral=True, spp=48)
    if case == "cold_sea":
        ex = examples.cold_sea(240 // scale, 80 // scale)
        return ex.scene, ex.camera, ex.field, None, dict(max_length=ex.max_length, spp=16)
    raise ValueError(f"unknown case {case!r}")


def run_case(case: str, repeat: int, quick: bool) -> dict:
    import refracta

    scene, camera, field, reference, options = setup(case, quick)

    cpu = {}  # CPU seconds of the last render by label: the process's, both threads'

    def render(air, method):
        start, start_cpu = time.perf_counter(), time.process_time()
        image, stats = refracta.render(scene, camera, air, method=method, progress=False, return_stats=True, **options)
        cpu[method if air is field else "reference"] = time.process_time() - start_cpu
        return time.perf_counter() - start, image, stats

    render(field, "curved")  # warm-up: the physical sky's tables, first-touch memory
    pairs, cpu_ratios = [], []
    for _ in range(repeat):
        t_ref, ref_image, _ = render(reference, "curved") if reference else render(None, "straight")
        t_cur, image, stats = render(field, "curved")
        pairs.append((t_cur, t_ref))
        cpu_ratios.append(cpu["curved"] / cpu["reference"])
    ratios = [c / r for c, r in pairs]
    ratio = statistics.median(ratios)
    goal = GOALS[case]
    row = {
        "reference": "height-only air" if reference else "straight",
        "size": [camera.width, camera.height],
        "options": {k: v for k, v in options.items() if k != "max_length"},
        "curved_seconds": [c for c, _ in pairs],
        "reference_seconds": [r for _, r in pairs],
        "ratios": ratios,
        "ratio_median": ratio,
        # CPU time of both threads: what a loaded machine's other work does not lengthen (its wall
        # time does, unevenly between the two renders of a pair).
        "cpu_ratios": cpu_ratios,
        "cpu_ratio_median": statistics.median(cpu_ratios),
        "chords_per_sample": stats.chords / stats.samples,
        "mean_radiance": float(np.mean(image)),
        "reference_mean_radiance": float(np.mean(ref_image)),
        "goal": goal,
        "met": None if goal is None else ratio <= goal,
    }
    verdict = "no goal" if goal is None else f"goal <= {goal:g}x: {'met' if row['met'] else 'NOT met'}"
    print(
        f"{case:20s} curved/{row['reference']:16s} {ratio:6.2f}x (pairs {', '.join(f'{r:.2f}' for r in ratios)}; "
        f"{verdict}), CPU {row['cpu_ratio_median']:.2f}x, chords/sample {row['chords_per_sample']:.2f}",
        flush=True,
    )
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--only", nargs="*", choices=list(GOALS))
    parser.add_argument("--quick", action="store_true", help="a quarter of each size: a smoke run")
    args = parser.parse_args()
    cases = args.only or list(GOALS)
    previous = {}
    path = RESULTS / "curved.json"
    if args.only and path.exists():
        previous = json.loads(path.read_text()).get("cases", {})
    rows = dict(previous)
    for case in cases:
        rows[case] = run_case(case, args.repeat, args.quick)
    print("->", write_results("curved", {"repeat": args.repeat, "quick": args.quick, "cases": rows}))


if __name__ == "__main__":
    main()
