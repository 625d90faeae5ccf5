"""The noise of a pixel at 16 spp on the demo scenes' hardest crops (bench_denoise's, with 16 and
8 pixels more each side): each pixel's variance over 8 seeds relative to its mean squared (plus
0.01, as relative MSE), summarised by its median over the pixels (the typical pixel) and by its
mean over the 99 % least noisy pixels (edges and glints keep their own noise), and the CPU seconds
of the 8 renders. No reference is needed: the seeds' spread is the noisy image's error.

The figures the README compares: this script on the build before the sampler stratified its
draws over a pixel's samples (core/rng.h; baaf9d3) and after.

    python benchmarks/bench_sampling.py [--seeds 8] [--only SCENE ...]  -> benchmarks/results/sampling.json
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from _common import write_results
from bench_denoise import SCENES, scene_setup

import refracta

SPP = 16
WIDEN = (16, 8)  # [px] more each side of each crop, horizontally and vertically


def pixel_noise(name: str, seeds: int) -> dict:
    config = SCENES[name]
    scene, camera, field, options = scene_setup(name, config["size"])
    x0, y0, x1, y1 = config["crop"]
    bounds = (x0 - WIDEN[0], y0 - WIDEN[1], x1 + WIDEN[0], y1 + WIDEN[1])
    start = time.process_time()
    images = np.stack(
        [
            np.asarray(
                refracta.render(
                    scene, camera, field, spp=SPP, seed=100 + seed, pixel_bounds=bounds, progress=False, **options
                )
            )[..., :3]
            for seed in range(seeds)
        ]
    )
    cpu = time.process_time() - start
    relative = (images.var(axis=0, ddof=1) / (images.mean(axis=0) ** 2 + 0.01)).mean(axis=-1).ravel()
    least_noisy = np.sort(relative)[: int(0.99 * relative.size)]
    median, mean_99 = float(np.median(relative)), float(least_noisy.mean())
    return dict(median=median, mean_99=mean_99, cpu_seconds=cpu, pixels=relative.size)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=8)
    parser.add_argument("--only", nargs="*", default=list(SCENES))
    args = parser.parse_args()
    results = {}
    for name in args.only:
        results[name] = pixel_noise(name, args.seeds)
        print(name, results[name], flush=True)
    path = write_results("sampling", dict(spp=SPP, seeds=args.seeds, scenes=results))
    print("wrote", path)


if __name__ == "__main__":
    main()
