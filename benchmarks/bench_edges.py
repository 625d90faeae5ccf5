"""Edge aliasing in the demo images (issue 19 section 5: pictures that look like photographs).

The demo's staircases and combs come from too few point samples on the edges between surfaces: at
1 spp a pixel is one sample at its centre, at 4 spp a sub-pixel pole is weighed by 4. Edge
refinement (RenderOptions.edge_spp, cpp/refracta/render/film.h EdgeRefinement) renders the pixels
at such edges again with edge_spp samples. Per scene, the demo's view (examples at 640 px,
'direct', denoised as render(denoise=True) does) is rendered with each variant (uniform spp, and
base spp + edge_spp), alternated in PAIRS rounds in one process (CPU seconds, process time of all
threads, and wall); the crop holding the scene's thin edges is compared with a REFERENCE_SPP
reference of another seed (render's pixel_bounds: every pixel as in the whole image): relative MSE
(squared error over reference^2 + 0.01, per channel, averaged) and mean HDR-FLIP (flip-evaluator).
The cold sea's reference holds a few sun-glint fireflies (single glint samples on the far sea, ~8x
the pixels around them at 256 spp) that no render of the demo's budget shows: pixels above twice
their 3 x 3 neighbourhood's median take that median there (firefly_free), and the count is written.

    python benchmarks/bench_edges.py [--quick]  -> benchmarks/results/edges.json
(--quick: 64-spp references and one round, a smoke run, not the published numbers.)
Measured (2026-12-04, load 5-17, 256-spp references; CPU s of one 640 px view):
hot road poles crop: 4 spp 0.0146 / FLIP 0.045 / 8.9-10.6 s; 8 spp 0.0055 / 0.028 / 17.8 s;
16 spp 0.0015 / 0.0185 / 33.4 s; 2 spp + 32 at edges (the demo's) 0.0011 / 0.019 / 12.4-14.1 s.
cold sea cranes crop: 1 spp 0.0054 / 0.055 / 4.8-5.2 s; 2 spp 0.0038 / 0.040 / 10.6 s; 4 spp
0.0018 / 0.031 / 20.3 s; 1 spp + 16 at edges (the demo's) 0.0017 / 0.029 / 10.4-12.7 s.
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from _common import write_results
from bench_denoise import flip_mean, relative_mse

REFERENCE_SPP = 256
PAIRS = 2  # rounds of all variants, alternated (timings on a shared machine are noisy)
# Per scene: the crop (x0, y0, x1, y1) with its thin edges, and the variants (RenderOptions fields).
SCENES = {
    "hot_road": dict(
        crop=(190, 20, 290, 160),  # the telegraph poles and cross-arms toward the vanishing point
        variants=[dict(spp=4), dict(spp=8), dict(spp=16), dict(spp=2, edge_spp=16), dict(spp=2, edge_spp=32)],
        firefly_free=False,
    ),
    "cold_sea": dict(
        crop=(460, 104, 572, 176),  # the harbour's cranes and booms, erect and inverted
        variants=[dict(spp=1), dict(spp=2), dict(spp=4), dict(spp=1, edge_spp=16)],
        firefly_free=True,
    ),
}
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])


def firefly_free(reference):
    """`reference` with the pixels whose luminance exceeds twice their 3 x 3 median's replaced by
    that median (per channel), and how many there were."""
    height, width = reference.shape[:2]
    padded = np.pad(reference, ((1, 1), (1, 1), (0, 0)), mode="edge")
    around = np.stack(
        [padded[1 + dy : 1 + dy + height, 1 + dx : 1 + dx + width] for dy in (-1, 0, 1) for dx in (-1, 0, 1)]
    )
    median = np.median(around, axis=0)
    bright = reference @ LUMINANCE > 2.0 * (median @ LUMINANCE)
    out = reference.copy()
    out[bright] = median[bright]
    return out, int(bright.sum())


def measure(name: str, reference_spp: int, pairs: int) -> dict:
    import refracta
    from refracta import examples

    setup = SCENES[name]
    example = getattr(examples, name)()
    x0, y0, x1, y1 = setup["crop"]

    def render(**options):
        return refracta.render(
            example.scene,
            example.camera,
            example.field,
            max_length=example.max_length,
            transport="direct",
            progress=False,
            **options,
        )

    start = time.process_time()
    reference = np.asarray(render(spp=reference_spp, seed=12345, pixel_bounds=setup["crop"]))[..., :3]
    out: dict = {"crop": list(setup["crop"]), "reference_spp": reference_spp}
    out["reference_cpu_seconds"] = time.process_time() - start
    if setup["firefly_free"]:
        reference, out["reference_fireflies_replaced"] = firefly_free(reference)
    rows: dict = {}
    for _ in range(pairs):
        for options in setup["variants"]:
            label = ", ".join(f"{key}={value}" for key, value in options.items())
            cpu, wall = time.process_time(), time.perf_counter()
            image = render(denoise=True, **options)
            cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
            crop = np.ascontiguousarray(image[y0:y1, x0:x1, :3])
            row = rows.setdefault(label, {"cpu_seconds": [], "wall_seconds": []})
            row["cpu_seconds"].append(cpu)
            row["wall_seconds"].append(wall)
            row["relative_mse"] = relative_mse(crop, reference)  # the same each round (seeded)
            row["flip"] = flip_mean(crop, reference)
    for label, row in rows.items():
        print(
            f"{name} {label}: relMSE {row['relative_mse']:.5f}, FLIP {row['flip']:.4f}, CPU "
            + ", ".join(f"{s:.1f}" for s in row["cpu_seconds"])
            + " s",
            flush=True,
        )
    out["variants"] = rows
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="64-spp references, one round: a smoke run")
    args = parser.parse_args()
    reference_spp, pairs = (64, 1) if args.quick else (REFERENCE_SPP, PAIRS)
    results = {name: measure(name, reference_spp, pairs) for name in SCENES}
    print(write_results("edges" + ("_quick" if args.quick else ""), results))


if __name__ == "__main__":
    main()
