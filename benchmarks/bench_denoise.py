"""Denoising on the demo scenes (issue 19 section 4: the denoised error at least 5x below the
noisy image's, no bias in flat regions).

Each scene of `make demo` (refracta.examples at its demo width of 640 px; the green flash as the
demo's 512 x 512 frame on the sun) is rendered 'direct' (as the demo renders) at 16 spp, and
compared with a >= 4096-spp reference of another seed on a crop of it: render's pixel_bounds,
every pixel exactly as in the whole image; the crops hold each scene's hardest part (edges of
poles and cars, the ships and the coast, the sun's rim) and are small enough to keep the
references' cost bearable on a shared 2-core machine (576-2048 pixels: ~9 min of CPU in all on an
idle machine; 20-25 min wall under load 4-8). The noisy images
are rendered on the crop and 32 pixels around it (the denoiser's context), then cut to the crop.

Beside each hardest crop, a representative sample of the whole image: one 8 x 8 tile at a
uniformly random place in each cell of a 4 x 2 cut of the image (tiles(); a fixed seed, never
chosen), 512 pixels (0.2-0.4 % of the image) with their own 4096-spp references, rendered with
16 pixels of context, measured as one image.

Per crop and per tile set: relative MSE (squared error over reference^2 + 0.01, per channel,
averaged), mean HDR-FLIP (flip-evaluator's own exposure bracket from the reference: a tile's score
depends on the tiles beside it) and mean FLIP as displayed (LDR-FLIP of refracta.io.to_display's
output at the whole image's automatic exposure, one for all crops, tiles and variants: what a
viewer of the demo sees) of each variant (variants(): noisy, denoised =
render(denoise=True), then with refracta.denoise's guided filter, with guides from 64 samples of
their own, 32 spp denoised at the guide pass's cost, the green flash's demo pipeline), each
one's ratio to the noisy image's error, beside the goal (5x); the
reference's own noise (16/4096 of the noisy image's variance) is left in; their CPU seconds.
Flat-region bias: over the pixels whose reference differs from its 8 neighbours by under 2 %
(smooth areas), the relative difference of each image's and the reference's means, the noisy
image's own (unbiased) difference beside it as the scale of chance.

    python benchmarks/bench_denoise.py [--quick] [--only SCENE ...]  -> benchmarks/results/denoise.json
(--quick: 256-spp references, a smoke run, not the published numbers.)
    python benchmarks/bench_denoise.py --noise-law
(noise_law(): what FLIP ratio a pure noise reduction of relative MSE k buys, and the cap a
reference's own noise puts on it; printed, not written.)
"""

from __future__ import annotations

import argparse
import time

import numpy as np
from _common import write_results

GOAL = 5.0  # the issue's: denoised error at least 5x below the noisy image's
MARGIN = 32  # pixels of context around each crop and tile for the denoiser
# The representative sample beside the hardest crops: one TILE x TILE tile at a random place in
# each cell of a TILE_GRID (columns, rows) cut of the image (tiles(): 8 x 64 = 512 pixels, the
# references' cost of a crop).
TILE, TILE_GRID = 8, (4, 2)
TILE_MARGIN = 16  # pixels of context around each tile (32 would cost 3x the tiles' 16-spp renders)
# Crops (x0, y0, x1, y1) at the demo size: the hardest parts of each scene (what the denoiser
# must keep: sub-pixel edges), sized for the reference's cost (~60 us of CPU a sample for the
# curved-Earth scenes and hot spots, ~11 us for the hot road).
SCENES = {
    "hot_road": dict(size=(640, 320), crop=(248, 104, 312, 136)),
    "hot_spot": dict(size=(640, 320), crop=(308, 140, 332, 164)),
    "cold_sea": dict(size=(640, 240), crop=(304, 108, 328, 132)),
    "fata_morgana": dict(size=(640, 240), crop=(308, 108, 332, 132)),
    "green_flash": dict(size=(512, 512), crop=(244, 244, 268, 268)),
}


def relative_mse(image, reference) -> float:
    return float(np.mean((image - reference) ** 2 / (reference**2 + 1e-2)))


def flip_mean(image, reference) -> float:
    """HDR-FLIP: flip-evaluator's own exposure bracket (ACES), chosen from `reference`'s luminance,
    so a tile's score depends on the tiles measured beside it."""
    import flip_evaluator as flip

    return float(flip.evaluate(reference, np.ascontiguousarray(image), "HDR", applyMagma=False)[1])


def flip_display(image, reference, exposure: float) -> float:
    """LDR-FLIP of the images as refracta.io.to_display shows them (its default tone map and sRGB)
    at one `exposure`, the whole image's (what a viewer of the demo sees; the same for every crop
    and tile)."""
    import flip_evaluator as flip

    from refracta import io

    def shown(x):
        return io.to_display(np.ascontiguousarray(np.maximum(x, 0.0), dtype=np.float32), exposure=exposure)

    return float(flip.evaluate(shown(reference), shown(image), "LDR", applyMagma=False)[1])


def flat_pixels(reference, tolerance=0.02):
    """Pixels whose reference luminance is within `tolerance` (relative) of each of its 8
    neighbours' (the crop's border excluded)."""
    lum = reference @ np.array([0.2126, 0.7152, 0.0722])
    flat = np.zeros(lum.shape, bool)
    inner = lum[1:-1, 1:-1]
    ok = np.ones(inner.shape, bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            shifted = lum[1 + dy : lum.shape[0] - 1 + dy, 1 + dx : lum.shape[1] - 1 + dx]
            ok &= np.abs(shifted - inner) <= tolerance * np.abs(inner)
    flat[1:-1, 1:-1] = ok
    return flat


def scene_setup(name, size):
    from refracta import examples

    if name != "green_flash":
        example = getattr(examples, name)(*size)
        return example.scene, example.camera, example.field, dict(max_length=example.max_length)
    # The demo's last sunset frame (refracta.cli's _demo_green_flash): the green gleam at 12', spectral.
    import refracta
    from refracta import cli

    elevation, vfov = cli.GREEN_FLASH_FRAMES[-1]
    example = examples.green_flash(*size, elevation)
    look, eye = np.radians(cli.GREEN_FLASH_LOOK[vfov]), example.camera.position
    camera = refracta.Camera(eye, eye + [np.cos(look), np.sin(look), 0.0], vfov=vfov, width=size[0], height=size[1])
    return example.scene, camera, example.field, dict(max_length=example.max_length, spectral=True)


def _window(bounds, width, height, margin=MARGIN):
    """`bounds` (x0, y0, x1, y1) widened by `margin` pixels of context (inside the image), and the
    slices that cut `bounds` back out of it."""
    x0, y0, x1, y1 = bounds
    window = (max(0, x0 - margin), max(0, y0 - margin), min(width, x1 + margin), min(height, y1 + margin))
    return window, (slice(y0 - window[1], y1 - window[1]), slice(x0 - window[0], x1 - window[0]))


def tiles(width, height, columns=TILE_GRID[0], rows=TILE_GRID[1], size=TILE, seed=0):
    """The representative sample: the image cut into columns x rows strata, one size x size tile
    at a uniformly random place inside each (numpy's generator of `seed`: fixed, never chosen)."""
    rng = np.random.default_rng(seed)
    out = []
    for j in range(rows):
        for i in range(columns):
            sx0, sx1 = i * width // columns, (i + 1) * width // columns
            sy0, sy1 = j * height // rows, (j + 1) * height // rows
            x0 = int(rng.integers(sx0, sx1 - size + 1))
            y0 = int(rng.integers(sy0, sy1 - size + 1))
            out.append((x0, y0, x0 + size, y0 + size))
    return out


def variants(name, render, bounds, width, height, spp, spectral=False):
    """The images compared, each cut to `bounds` from a render of it with context around:
      noisy              render(spp=16)
      denoised           render(spp=16, denoise=True): Open Image Denoise with the render's own
                         albedo and normal (in RGB the noise-free sky kept)
      guided             the same, then refracta.denoise's guided filter (guided=True)
      guides64           render(spp=16, guide_spp=64, denoise=True): guides from 64 samples of
                         their own, Open Image Denoise and the guided filter
      equal_cost         render(spp=32, denoise=True): the guide pass's CPU spent on image samples
      equal_cost_guided  the same 32 spp with the guided filter on its own guides
    and for the spectral green flash, the demo's own pipeline (refracta.cli._demo_green_flash):
      demo_chroma        Open Image Denoise on the colour alone for the luminance, the colour by
                         examples_chroma.chroma_filter.
    Also the CPU seconds of each render."""
    import refracta

    small = bounds[2] - bounds[0] <= TILE and bounds[3] - bounds[1] <= TILE
    window, cut = _window(bounds, width, height, TILE_MARGIN if small else MARGIN)
    images, seconds = {}, {}

    def run(label, **kw):
        start = time.process_time()
        image, aovs = render(pixel_bounds=window, aovs=["albedo", "normal"], **kw)
        seconds[label] = time.process_time() - start
        return np.maximum(image, 0.0), aovs  # spectral renders leave the gamut (render(denoise=True) clips too)

    def denoised(image, aovs, guided=False):  # as render(denoise=True) does (refracta/_render.py)
        clean = refracta.denoise(image, aovs["albedo"], aovs["normal"], guided=guided)
        if not spectral:  # RGB: the noise-free sky kept; spectral: noisy in colour, denoised
            sky = ~np.any(aovs["normal"], axis=2)
            clean[sky] = image[sky]
        return clean

    noisy, aovs = run("noisy", spp=spp)
    images["noisy"], images["denoised"] = noisy, denoised(noisy, aovs)
    images["guided"] = denoised(noisy, aovs, guided=True)
    image, aovs = run("guides64", spp=spp, guide_spp=64)
    images["guides64"] = denoised(image, aovs, guided=True)
    image, aovs = run("equal_cost", spp=2 * spp)
    images["equal_cost"] = denoised(image, aovs)
    images["equal_cost_guided"] = denoised(image, aovs, guided=True)
    if name == "green_flash":
        from refracta import examples_chroma

        luminance = refracta.denoise(noisy) @ examples_chroma.LUMINANCE
        images["demo_chroma"] = np.maximum(examples_chroma.chroma_filter(noisy, luminance), 0.0)
    return {label: image[cut] for label, image in images.items()}, seconds


def compare(images, reference, exposure: float) -> dict:
    """Relative MSE, HDR-FLIP and FLIP as displayed (at `exposure`) of each image, its ratio to the
    noisy image's, flat-region bias."""
    row = {}
    base_mse, base_flip = relative_mse(images["noisy"], reference), flip_mean(images["noisy"], reference)
    base_shown = flip_display(images["noisy"], reference, exposure)
    for label, image in images.items():
        row[f"{label}_relative_mse"] = mse = relative_mse(image, reference)
        row[f"{label}_flip"] = flip = flip_mean(image, reference)
        row[f"{label}_flip_display"] = shown = flip_display(image, reference, exposure)
        row[f"{label}_mse_ratio"] = base_mse / mse
        row[f"{label}_flip_ratio"] = base_flip / flip
        row[f"{label}_flip_display_ratio"] = base_shown / shown
    flat = flat_pixels(reference)
    row["flat_share"] = float(flat.mean())
    mean = float(reference[flat].mean()) if flat.any() else 0.0
    if mean > 0.0:  # (a black flat region, as the green flash's night sea, has no relative bias)
        for label in images:
            row[f"{label}_flat_bias"] = float(images[label][flat].mean()) / mean - 1.0
    return row


def measure(name, size, crop, spp=16, reference_spp=4096) -> dict:
    import refracta
    from refracta import io

    scene, camera, field, options = scene_setup(name, size)
    options = dict(progress=False, transport="direct", **options)
    width, height = camera.width, camera.height

    def render(**kw):
        return refracta.render(scene, camera, field, **options, **kw)

    out = {"size": [width, height]}
    # The display's exposure: to_display's automatic one (log-average luminance) of the whole image
    # at 1 spp (hot road: 0.0434, against 0.0425 from 16 spp denoised; one exposure for all variants).
    out["display_exposure"] = exposure = io.exposure_of(np.maximum(render(spp=1, seed=2), 0.0))
    # The hardest crop.
    start = time.perf_counter()
    reference = np.maximum(render(spp=reference_spp, seed=1, pixel_bounds=crop), 0.0)
    row = {"crop": list(crop), "window": list(_window(crop, width, height)[0])}
    row["reference_seconds"] = time.perf_counter() - start
    spectral = options.get("spectral", False)
    images, row["cpu_seconds"] = variants(name, render, crop, width, height, spp, spectral)
    row.update(compare(images, reference, exposure))
    out["crop"] = row
    # The representative tiles, measured as one image (their pixels side by side).
    boxes = tiles(width, height)
    start = time.perf_counter()
    references = [np.maximum(render(spp=reference_spp, seed=1, pixel_bounds=box), 0.0) for box in boxes]
    row = {"tiles": [list(box) for box in boxes], "share": len(boxes) * TILE * TILE / (width * height)}
    row["reference_seconds"] = time.perf_counter() - start
    parts = [variants(name, render, box, width, height, spp, spectral)[0] for box in boxes]
    joined = {label: np.concatenate([part[label] for part in parts], axis=1) for label in parts[0]}
    row.update(compare(joined, np.concatenate(references, axis=1), exposure))
    out["tiles"] = row
    for part in ("crop", "tiles"):
        r = out[part]
        print(
            f"{name} {width}x{height} {part}, {spp} spp vs {reference_spp}: "
            f"relMSE noisy {r['noisy_relative_mse']:.3e}, "
            + ", ".join(f"{label} x{r[label + '_mse_ratio']:.2f}" for label in images if label != "noisy")
            + f"; FLIP noisy {r['noisy_flip']:.4f}, "
            + ", ".join(f"{label} x{r[label + '_flip_ratio']:.2f}" for label in images if label != "noisy")
            + f"; FLIP as displayed noisy {r['noisy_flip_display']:.4f}, "
            + ", ".join(f"{label} x{r[label + '_flip_display_ratio']:.2f}" for label in images if label != "noisy")
            + f"; flat bias denoised {r.get('denoised_flat_bias', float('nan')):+.4f} "
            f"(noisy {r.get('noisy_flat_bias', float('nan')):+.4f}); reference {r['reference_seconds']:.0f} s",
            flush=True,
        )
    out["goal_met"] = bool(out["crop"]["denoised_mse_ratio"] >= GOAL)
    out["tiles_goal_met"] = bool(out["tiles"]["denoised_mse_ratio"] >= GOAL)
    return out


def noise_law(sigma=0.025, reductions=(5, 25, 100, 400), seed=0) -> dict:
    """What FLIP ratio a pure noise reduction buys (issue 19 section 4's two goals side by side).

    A smooth image (the hot road at 160 x 80, 64 spp, denoised) plus Gaussian noise of relative
    standard deviation `sigma` (16 spp 'direct' on the hot road's tiles: ~0.025) is the "noisy"
    image; the same plus sigma / sqrt(k) noise the "denoised" one (relative MSE k times lower);
    each against the smooth image itself and against a "reference" carrying 16/4096 of the noisy
    image's variance (a 4096-spp reference's own noise; and 16/1024). Returns the FLIP ratios
    (HDR and as displayed) per k, and the relative MSE ratio a 5x FLIP ratio takes (interpolated
    in log-log against the noise-free reference)."""
    import refracta
    from refracta import examples, io

    example = examples.hot_road(160, 80)
    smooth = refracta.render(
        example.scene,
        example.camera,
        example.field,
        spp=64,
        transport="direct",
        max_length=example.max_length,
        denoise=True,
        progress=False,
    )
    smooth = np.ascontiguousarray(np.maximum(smooth, 0.0), dtype=np.float32)
    exposure = io.exposure_of(smooth)
    rng = np.random.default_rng(seed)

    def noisy(s):
        return np.ascontiguousarray(np.maximum(smooth * (1.0 + s * rng.standard_normal(smooth.shape)), 0.0), np.float32)

    out: dict = {"sigma": sigma}
    for reference_spp in (None, 4096, 1024):
        reference = smooth if reference_spp is None else noisy(sigma * np.sqrt(16 / reference_spp))
        base = noisy(sigma)
        hdr0, shown0 = flip_mean(base, reference), flip_display(base, reference, exposure)
        rows = {}
        # A perfect denoiser (k infinite) only against a noisy reference: against its own it scores 0.
        for k in (*reductions, *([] if reference_spp is None else [np.inf])):
            image = smooth if k == np.inf else noisy(sigma / np.sqrt(k))
            rows[str(k)] = dict(
                flip_ratio=hdr0 / flip_mean(image, reference),
                flip_display_ratio=shown0 / flip_display(image, reference, exposure),
            )
        key = "noise_free_reference" if reference_spp is None else f"reference_{reference_spp}_spp"
        out[key] = rows
        print(
            f"{key}: relMSE ratio k -> FLIP ratio HDR / as displayed: "
            + ", ".join(f"{k}: {r['flip_ratio']:.2f}x / {r['flip_display_ratio']:.2f}x" for k, r in rows.items()),
            flush=True,
        )
    ks = np.array(reductions, float)
    for metric in ("flip_ratio", "flip_display_ratio"):
        ratios = np.array([out["noise_free_reference"][str(k)][metric] for k in reductions])
        out[f"mse_ratio_for_5x_{metric}"] = float(np.exp(np.interp(np.log(GOAL), np.log(ratios), np.log(ks))))
    print(
        f"a 5x FLIP ratio takes a relative MSE ratio of {out['mse_ratio_for_5x_flip_ratio']:.0f}x (HDR), "
        f"{out['mse_ratio_for_5x_flip_display_ratio']:.0f}x (as displayed) for a pure noise reduction",
        flush=True,
    )
    return out


def main(quick: bool = False, names=tuple(SCENES)) -> dict:
    """The scenes `names`, each written to results/denoise.json as it is measured (merged into the
    file's other scenes) unless quick."""
    import json

    from _common import RESULTS

    out = {"spp": 16, "reference_spp": 256 if quick else 4096, "transport": "direct", "goal": GOAL}
    previous = RESULTS / "denoise.json"
    if not quick and previous.exists():
        kept = json.loads(previous.read_text())
        # Only scenes measured by this form of the benchmark (a crop and the tiles).
        out.update({name: kept[name] for name in SCENES if "tiles" in kept.get(name, {}) and name not in names})
    for name in names:
        setting = SCENES[name]
        out[name] = measure(name, setting["size"], setting["crop"], reference_spp=out["reference_spp"])
        if not quick:
            write_results("denoise", out)
    return out


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--only", nargs="+", choices=sorted(SCENES), default=list(SCENES), help="these scenes only")
    parser.add_argument("--noise-law", action="store_true", help="only the synthetic FLIP-vs-noise study (noise_law)")
    args = parser.parse_args()
    if args.noise_law:
        noise_law()
        raise SystemExit(0)
    main(args.quick, tuple(args.only))
    print("(--quick: not written)" if args.quick else "-> results/denoise.json")
