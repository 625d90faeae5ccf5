"""Realism benchmarks of issue 10: what areal hot spots cost to render, and optical turbulence
(refracta.Turbulence) -- its cost, its statistics against Kolmogorov's, the angle of arrival of
traced rays, and a shimmer frame.

Sections (one function each, each a dict in results/realism.json):
  hot_spot_render        the hot road at 1280 x 720 with one hot spot (compact and gaussian)
                         against the height-only field (the issue's goals: at most 3x and 10x)
  turbulence_generation  synthesis time and memory of 128^3 and 256^3 grids, their inertial ranges
  structure_function     D_n(r) / (C_n^2 r^(2/3)) measured through the C++ evaluator across the
                         default grid's inertial range (4 realisations), beside the ensemble formula
  angle_of_arrival       rays traced through 4 realisations against the realisations' expectation,
                         with the continuous spectrum's closed forms beside it; what tiling
                         does to a 300 m hot-road path off and along a lattice axis; the vertical
                         over the horizontal tilt of level paths (isotropy)
  shimmer_render         examples.hot_road(160, 60) with the default turbulence in its hot layer
                         (depth 0.1 m), traced strictly, against the calm air
  shimmer_fast           the same through turbulence_trace 'perturbed' (issue 21 goal 1): its
                         cost beside the calm frame's, its image against the strict trace's
  water_render           examples.cold_sea with its sea plane a shading.Water (Cox-Munk Beckmann
                         interface over the deep water body) against the Plastic it has, path
                         traced, through the cold-sea air and straight (issue 19 section 2)
  aerial_perspective_render  hot road and cold sea with and without aerial perspective (section 1)
  denoise_quality        16-spp demo renders denoised, against a 512-spp reference (section 4)

    python benchmarks/bench_realism.py [--quick] [--only SECTION]  -> benchmarks/results/realism.json
(--quick: 320 x 180 hot spots, 128^3 only, fewer rays, a 64 x 24 frame: a smoke run, not the
published numbers. --only SECTION: that section alone, merged into the existing results file.)
"""

from __future__ import annotations

import argparse
import math
import pickle
import time

import numpy as np
from _common import timed, write_results


def turbulence_generation(sizes=(128, 256)) -> dict:
    import refracta

    rows = {}
    for cells in sizes:
        air, seconds = timed(refracta.Turbulence, cells=cells)  # the synthesis is C++'s (memory_needed_mb)
        start = time.perf_counter()
        r_min, r_max = air.inertial_range
        statistics_seconds = time.perf_counter() - start
        rows[str(cells)] = {
            "cells": cells,
            "spacing_m": air.spacing,
            "tile_m": air.size,
            "seconds": seconds,
            "coefficients_mb": 4 * cells**3 / 1e6,
            "memory_needed_mb": air.memory_needed(cells) / 1e6,
            "inertial_range_m": [r_min, r_max],
            "inertial_range_cells": [r_min / air.spacing, r_max / air.spacing],
            "inertial_width": r_max / r_min,
            "statistics_seconds": statistics_seconds,
        }
        print(
            f"{cells}^3: {seconds:.2f} s, {4 * cells**3 / 1e6:.0f} MB of coefficients, "
            f"inertial range {r_min:.3f}-{r_max:.3f} m (x{r_max / r_min:.1f}), statistics {statistics_seconds:.1f} s"
        )
    return rows


def structure_function(cells=256, seeds=4, pairs=40_000) -> dict:
    import refracta

    rng = np.random.default_rng(7)
    first = refracta.Turbulence(cells=cells, depth=None, seed=0)
    r_min, r_max = first.inertial_range
    r = np.geomspace(r_min, r_max, 7)
    kolmogorov = first.cn2 * r ** (2 / 3)
    per_seed = []
    for seed in range(seeds):
        air = first if seed == 0 else refracta.Turbulence(cells=cells, depth=None, seed=seed)
        row = []
        for v in r:
            x = rng.uniform(0.0, air.size, (pairs, 3))
            u = rng.normal(size=(pairs, 3))
            u /= np.linalg.norm(u, axis=1)[:, None]
            a, _ = air.layer.evaluate(x)
            b, _ = air.layer.evaluate(x + v * u)
            row.append(float(np.mean((b - a) ** 2)))
        per_seed.append(np.array(row) / kolmogorov)
    mean = np.mean(per_seed, axis=0)
    ensemble = first.structure_function(r) / kolmogorov
    print("D / (Cn2 r^2/3) over the inertial range:", np.round(mean, 3), " ensemble:", np.round(ensemble, 3))
    return {
        "cells": cells,
        "r_m": r.tolist(),
        "measured_mean_ratio": mean.tolist(),
        "measured_ratio_per_seed": [p.tolist() for p in per_seed],
        "ensemble_ratio": ensemble.tolist(),
        "worst_mean_ratio_error": float(np.max(np.abs(mean - 1))),
        "within_20_percent": bool(np.all(np.abs(mean - 1) <= 0.2)),
    }


def angle_of_arrival(seeds=4, rays=1500, along_x_cells=256) -> dict:
    import refracta
    from refracta import turbulence as tb

    cn2, length, spacing = 1e-8, 2.0, 0.05
    t = np.array([1.0, 0.3, 0.2]) / np.linalg.norm([1.0, 0.3, 0.2])
    e1 = np.array([0.0, 1.0, 0.0]) - t[1] * t
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(t, e1)
    calm = refracta.PhysicalAtmosphere(surface_dt=0.0)
    measured, expected = [], []
    for seed in range(seeds):
        air = refracta.Turbulence(cn2, cells=64, spacing=spacing, depth=None, seed=seed)
        field = refracta.PhysicalAtmosphere(surface_dt=0.0, turbulence=air)
        origins = np.random.default_rng(100 + seed).uniform(0.0, air.size, (rays, 3)) + [0.0, 10.0, 0.0]
        directions = np.tile(t, (rays, 1))
        stirred = refracta.trace_rays(field, origins, directions, tol=1e-10, step=spacing / 2, max_length=length)
        still = refracta.trace_rays(calm, origins, directions, tol=1e-10, max_length=length)
        turn = stirred.end_directions - still.end_directions
        measured.append(0.5 * (np.mean((turn @ e1) ** 2) + np.mean((turn @ e2) ** 2)))
        expected.append(air.angle_of_arrival_variance(length, direction=t))
    scatter = air.angle_of_arrival_scatter(length, direction=t)
    sigma = math.sqrt(scatter**2 + 1.0 / rays) / math.sqrt(seeds)
    ratio = float(np.mean(measured) / np.mean(expected))
    closed = {
        "point_l0_5mm": tb.tilt_variance(cn2, length, inner_scale=0.005),
        "point_l0_one_cell": tb.tilt_variance(cn2, length, inner_scale=spacing),
        "point_l0_two_cells": tb.tilt_variance(cn2, length, inner_scale=2 * spacing),
        "g_tilt_aperture_one_cell": tb.tilt_variance(cn2, length, aperture=spacing),
        "plane_wave_2.91_aperture_one_cell": tb.plane_wave_tilt_variance(cn2, length, spacing),
    }
    print(
        f"angle of arrival: measured {np.mean(measured):.3e} rad^2, expected {np.mean(expected):.3e} "
        f"(ratio {ratio:.3f} +- {sigma:.3f}); closed forms {', '.join(f'{k} {v:.3e}' for k, v in closed.items())}"
    )
    # A hot-road path: 300 m along +x through the default grid (31.7 deg off the lattice's axes, its
    # default yaw), against the continuous spectrum; and along a lattice axis (yaw 0), where the
    # 12.8 m tile repeats along the path and its modes add coherently.
    road = refracta.Turbulence(cells=along_x_cells, depth=None)
    on_axis = refracta.Turbulence(cells=along_x_cells, depth=None, yaw_deg=0.0).angle_of_arrival_variance(300.0)
    start = time.perf_counter()
    along_x = {
        str(L): {
            "discrete": road.angle_of_arrival_variance(L),
            "continuous_l0_one_cell": tb.tilt_variance(road.cn2, L, inner_scale=road.spacing),
        }
        for L in (6.4, 300.0)
    }
    off_axis = road.angle_of_arrival_variance(300.0, direction=(1.0, 0.0, math.tan(math.radians(2.0))))
    seconds = (time.perf_counter() - start) / 3
    for row in along_x.values():
        row["discrete_over_continuous"] = row["discrete"] / row["continuous_l0_one_cell"]
    print(
        f"along x through the {along_x_cells}^3 default grid: discrete / continuous at 6.4 m "
        f"{along_x['6.4']['discrete_over_continuous']:.2f}, "
        f"at 300 m {along_x['300.0']['discrete_over_continuous']:.2f}; "
        f"2 deg off the axis at 300 m {off_axis / along_x['300.0']['continuous_l0_one_cell']:.2f} "
        f"({seconds:.1f} s per expectation)"
    )
    return {
        "setup": {
            "cn2": cn2,
            "path_m": length,
            "cells": 64,
            "spacing_m": spacing,
            "seeds": seeds,
            "rays": rays,
            "direction": t.tolist(),
        },
        "measured_rad2": float(np.mean(measured)),
        "expected_rad2": float(np.mean(expected)),
        "measured_over_expected": ratio,
        "standard_deviation_of_ratio": sigma,
        "realisation_scatter": scatter,
        "per_seed_measured": [float(m) for m in measured],
        "continuous_closed_forms_rad2": closed,
        "hot_road_path_along_x": along_x,
        "hot_road_path_2deg_off_axis_over_continuous": off_axis / along_x["300.0"]["continuous_l0_one_cell"],
        "hot_road_path_on_a_lattice_axis_over_continuous": on_axis / along_x["300.0"]["continuous_l0_one_cell"],
        "level_path_tilt_vertical_over_horizontal": level_path_tilts(road),
        "expectation_seconds_256": seconds,
    }


def shimmer_render(width=160, height=60) -> dict:
    import refracta
    from refracta import examples

    road = examples.hot_road(width, height)
    calm_image, calm_seconds = timed(
        refracta.render, road.scene, road.camera, road.field, progress=False, max_length=road.max_length, repeat=3
    )
    air = refracta.Turbulence(depth=0.1)
    field = refracta.PhysicalAtmosphere(**road.field.params, turbulence=air)
    start = time.perf_counter()
    strict = dict(progress=False, max_length=road.max_length, return_stats=True, turbulence_trace="strict")
    image, stats = refracta.render(road.scene, road.camera, field, **strict)
    seconds = time.perf_counter() - start
    difference = float(np.mean(np.abs(image - calm_image)) / np.mean(calm_image))
    changed = float(np.mean(np.abs(image - calm_image).max(axis=2) > 0.05 * calm_image.max()))
    print(
        f"hot_road {width}x{height}: calm {calm_seconds:.3f} s, with turbulence {seconds:.1f} s "
        f"(x{seconds / calm_seconds:.0f}), chords/pixel {stats.chords / stats.samples:.0f}, "
        f"mean |change| {difference:.3f} of the mean, pixels changed > 5% of the peak: {changed:.2f}"
    )
    return {
        "size": [width, height],
        "turbulence": repr(air),
        "calm_seconds": calm_seconds,
        "turbulent_seconds": seconds,
        "slowdown": seconds / calm_seconds,
        "chords_per_pixel": stats.chords / stats.samples,
        "mean_relative_change": difference,
        "fraction_of_pixels_changed": changed,
    }


def shimmer_fast(timing=(160, 60), accuracy=(48, 18), frames=48, accuracy_spp=(1, 8)) -> dict:
    """Issue 21 goal 1: RenderOptions.turbulence_trace 'perturbed' (camera rays followed as
    deviations from the exactly traced calm rays, their lighting rays through the calm air,
    render/shimmer_cast.h) on the hot road through
    the default turbulence (depth 0.1 m). Timing: calm, perturbed (and the frames-long animation it
    implies) side by side at `timing`; accuracy: mean |perturbed - strict| over mean |strict - calm|
    at `accuracy` (the strict rk45 trace being the reference), per row as well, at each of
    `accuracy_spp` samples per pixel: at 1 sample a pixel on an object's edge is a point sample that
    a sub-millimetre difference can flip (the hot road at 48 x 18 has one such pixel carrying 16 %
    of the turbulence's whole effect), with more samples the pixel is its coverage. Also the pixel
    carrying the most error and its share. Goals: a frame at most 3x calm at 640x240, 48 frames in
    2 minutes on 2 cores, accuracy at most 0.1."""
    import refracta
    from refracta import examples

    air = refracta.Turbulence(depth=0.1)

    def frame(size, field, **options):
        road = examples.hot_road(*size)
        start = time.perf_counter()
        image = refracta.render(
            road.scene, road.camera, field(road), progress=False, max_length=road.max_length, **options
        )
        return image, time.perf_counter() - start

    calm = lambda road: road.field  # noqa: E731
    turbulent = lambda road: refracta.PhysicalAtmosphere(**road.field.params, turbulence=air)  # noqa: E731
    # Side by side, alternating, so that the shared machine's load drifts into both alike.
    calm_seconds, fast_seconds = [], []
    for _ in range(2):
        calm_seconds.append(frame(timing, calm)[1])
        fast_seconds.append(frame(timing, turbulent, turbulence_trace="perturbed")[1])
    ratio = [f / c for f, c in zip(fast_seconds, calm_seconds)]
    out = {
        "timing_size": list(timing),
        "calm_seconds": calm_seconds,
        "perturbed_seconds": fast_seconds,
        "perturbed_over_calm": ratio,
        "goal_perturbed_over_calm_at_640x240": 3.0,
        f"{frames}_frames_seconds_estimate": frames * min(fast_seconds),
        "accuracy_size": list(accuracy),
        "goal_error_over_effect": 0.1,
        "accuracy": {},
    }
    for spp in accuracy_spp:
        calm_image, _ = frame(accuracy, calm, spp=spp)
        fast_image, fast_small = frame(accuracy, turbulent, turbulence_trace="perturbed", spp=spp)
        strict_image, strict_small = frame(accuracy, turbulent, turbulence_trace="strict", spp=spp)
        effect = np.abs(strict_image - calm_image)
        error = np.abs(fast_image - strict_image)
        rows = [float(e.mean() / m.mean()) if m.mean() > 0 else 0.0 for e, m in zip(error, effect)]
        worst = np.unravel_index(int(np.argmax(error.sum(axis=2))), error.shape[:2])
        out["accuracy"][str(spp)] = {
            "strict_seconds": strict_small,
            "perturbed_seconds": fast_small,
            "error_over_effect": float(error.mean() / effect.mean()),
            "error_over_effect_per_row": rows,
            "worst_pixel": [int(worst[0]), int(worst[1])],
            "worst_pixel_share_of_error": float(error[worst].sum() / error.sum()),
            "worst_pixel_share_of_effect": float(effect[worst].sum() / effect.sum()),
        }
    print(
        f"shimmer fast path {timing[0]}x{timing[1]}: calm {min(calm_seconds):.2f} s, perturbed "
        f"{min(fast_seconds):.1f} s (x{min(ratio):.0f}; goal x3 at 640x240); {accuracy[0]}x{accuracy[1]} "
        + "; ".join(
            f"{spp} spp: strict {a['strict_seconds']:.1f} s, perturbed {a['perturbed_seconds']:.2f} s, "
            f"|perturbed - strict| / |strict - calm| {a['error_over_effect']:.3f} (goal 0.1; pixel "
            f"{a['worst_pixel']}: {a['worst_pixel_share_of_error']:.2f} of the error)"
            for spp, a in out["accuracy"].items()
        )
    )
    return out


def hot_spot_render(width=1280, height=720, repeat=3) -> dict:
    """examples.hot_spot's camera and scene (the hot road) through the height-only road (2 K) with
    one spot 16 K hotter, 330 m down the road: compact (Wendland, R = 110 m) and gaussian (sigma =
    45 m, about the same half-width), against the height-only field alone. Rays that never enter a
    compact spot's cylinder come from the eye's table; inside, rk45 through the full field."""
    import refracta
    from refracta import examples

    example = examples.hot_spot(width, height)
    base = dict(surface_dt=2.0, surface_depth=0.1)
    fields = {
        "height_only": refracta.PhysicalAtmosphere(**base),
        "compact": example.field,
        "gaussian": refracta.PhysicalAtmosphere(
            **base, hot_spots=[refracta.HotSpot(330.0, 0.0, 45.0, 16.0, footprint="gaussian")]
        ),
    }
    out = {"size": [width, height], "spp": 1, "transport": "direct"}
    for name, field in fields.items():
        (_, stats), seconds = timed(
            refracta.render,
            example.scene,
            example.camera,
            field,
            progress=False,
            max_length=example.max_length,
            repeat=repeat,
            return_stats=True,
        )
        out[name] = {"seconds": seconds, "chords_per_sample": stats.chords / max(stats.samples, 1)}
    for name in ("compact", "gaussian"):
        out[f"{name}_over_height_only"] = out[name]["seconds"] / out["height_only"]["seconds"]
    print(
        f"hot spot {width}x{height}: height-only {out['height_only']['seconds']:.2f} s, "
        f"compact x{out['compact_over_height_only']:.2f} (goal <= 3), "
        f"gaussian x{out['gaussian_over_height_only']:.2f} (goal <= 10)",
        flush=True,
    )
    return out


def water_render(width=320, height=120, spp=8, repeat=2) -> dict:
    """examples.cold_sea (a superior mirage over a cold sea, physical sky, ships, a coast) path traced at spp samples:
    the sea plane as shading.Water() (5 m/s, 20 C, 35 g/kg; Beckmann interface, body term) against
    the example's Plastic (GGX coat over a Lambertian base, alpha 0.25), and a Plastic as rough as the
    water (alpha = Water().alpha = 0.17), which separates the narrower lobe's longer grazing paths
    from the material's own cost; through the looming air and straight (field=None: the shading's
    share of the time is larger there). Same seeds, same scene otherwise. Ratios of CPU seconds (all
    threads), the best of `repeat` runs each; wall seconds beside them."""
    import refracta
    from refracta import examples, shading

    example = examples.cold_sea(width, height)
    plastic = example.scene.material(0)  # the sea plane, the example's first geometry
    water = shading.Water()
    materials = {
        "plastic": plastic,
        "water": water,
        "plastic_as_rough_as_water": shading.Plastic((0.01, 0.03, 0.04), ior=1.333, alpha=water.alpha),
    }
    out = {"size": [width, height], "spp": spp, "transport": "path", **{k: repr(m) for k, m in materials.items()}}
    for air, field in (("curved", example.field), ("straight", None)):
        seconds, cpu = {}, {}
        for name, material in materials.items():
            example.scene.set_material(0, material)
            cpu[name] = float("inf")
            for _ in range(repeat):  # CPU time of all threads: steadier than wall time on a shared machine
                start = time.process_time()
                _, wall = timed(
                    refracta.render,
                    example.scene,
                    example.camera,
                    field,
                    transport="path",
                    spp=spp,
                    progress=False,
                    max_length=example.max_length,
                )
                cpu[name] = min(cpu[name], time.process_time() - start)
                seconds[name] = min(seconds.get(name, float("inf")), wall)
        out[air] = {f"{name}_seconds": t for name, t in seconds.items()}
        out[air].update({f"{name}_cpu_seconds": t for name, t in cpu.items()})
        out[air]["water_over_plastic"] = cpu["water"] / cpu["plastic"]
        out[air]["water_over_plastic_as_rough"] = cpu["water"] / cpu["plastic_as_rough_as_water"]
        print(
            f"cold sea {width}x{height} {spp} spp path, {air} (CPU s): plastic {cpu['plastic']:.2f}, "
            f"water {cpu['water']:.2f} (x{out[air]['water_over_plastic']:.2f}), plastic as rough as the water "
            f"{cpu['plastic_as_rough_as_water']:.2f} (water x{out[air]['water_over_plastic_as_rough']:.2f})",
            flush=True,
        )
    example.scene.set_material(0, plastic)
    return out


def aerial_perspective_render(width=640, height=240, repeat=3) -> dict:
    """The cost of aerial perspective (issue 19 section 1, goal: at most 1.5x): examples.hot_road
    and examples.cold_sea rendered 'direct' at 1 spp with Scene.set_physical_sky's
    aerial_perspective on and off (the same sky otherwise), through their fields. CPU seconds of
    all threads (steadier than wall time on a shared machine), the best of `repeat` runs, the two
    renders alternating."""
    import refracta
    from refracta import examples

    out = {"size": [width, height], "spp": 1, "transport": "direct"}
    for name in ("hot_road", "cold_sea"):
        example = getattr(examples, name)(width, height)
        air = example.scene.aerial_perspective
        if air is None:
            raise RuntimeError(f"examples.{name} has no aerial perspective to measure")
        plain = pickle.loads(pickle.dumps(example.scene))  # the same scene without the air
        plain.set_aerial_perspective(False)
        cpu = {"with": float("inf"), "without": float("inf")}
        for _ in range(repeat):
            for key, scene in (("with", example.scene), ("without", plain)):
                start = time.process_time()
                refracta.render(scene, example.camera, example.field, progress=False, max_length=example.max_length)
                cpu[key] = min(cpu[key], time.process_time() - start)
        out[name] = {
            "with_cpu_seconds": cpu["with"],
            "without_cpu_seconds": cpu["without"],
            "ratio": cpu["with"] / cpu["without"],
            "goal": 1.5,
        }
        print(
            f"{name} {width}x{height}: aerial perspective {cpu['with']:.2f} CPU s, without {cpu['without']:.2f} "
            f"(x{out[name]['ratio']:.2f}, goal <= 1.5)",
            flush=True,
        )
    return out


def denoise_quality(
    width=320, height=120, spp=16, reference_spp=512, names=("hot_road", "cold_sea"), crops=None
) -> dict:
    """render(denoise=True) on the demo scenes (issue 19 section 4, goal: error at least 5x below
    the noisy image's): the noisy image at `spp`, denoised with colour alone, with the albedo and
    normal guides trusted as noise-free (render(denoise=True), which keeps the noise-free sky
    pixels) and with Open Image Denoise prefiltering them (clean_aux=False), against a
    `reference_spp` render of another seed ('direct', as the demo renders). crops: name -> pixel
    bounds (x0, y0, x1, y1): the reference is rendered there only (render's pixel_bounds: each
    pixel exactly as in the whole image) and every image is compared there, the rest of the
    noisy image still feeding the denoiser. Relative MSE (squared error over reference^2 + 0.01)
    and mean FLIP (flip-evaluator, HDR). The reference's own noise adds about
    spp / reference_spp of the noisy image's variance to every measured error: its estimate
    noisy_mse * k / (1 + k), k = spp / reference_spp (both unbiased, the same per-sample variance,
    stratified alike), is subtracted for the *_reference_noise_subtracted ratios (FLIP has no
    such correction). worst_tenth_share: the part of the guided image's relative MSE in its worst
    10 % of pixels (antialiasing of sub-pixel edges, which a denoiser does not resolve)."""
    import flip_evaluator as flip

    import refracta
    from refracta import examples

    def squared_errors(image, reference):
        return np.mean((image - reference) ** 2 / (reference**2 + 1e-2), axis=2)

    def flip_mean(image, reference):
        return float(flip.evaluate(reference, np.ascontiguousarray(image), "HDR", applyMagma=False)[1])

    crops = crops or {}
    out = {"size": [width, height], "spp": spp, "reference_spp": reference_spp, "transport": "direct"}
    k = spp / reference_spp
    for name in names:
        example = getattr(examples, name)(width, height)
        options = dict(progress=False, max_length=example.max_length)
        bounds = crops.get(name)
        # render(pixel_bounds=...) returns just those pixels; the other images are cropped to them.
        window = (
            (slice(None), slice(None)) if bounds is None else (slice(bounds[1], bounds[3]), slice(bounds[0], bounds[2]))
        )
        reference, reference_seconds = timed(
            refracta.render,
            example.scene,
            example.camera,
            example.field,
            spp=reference_spp,
            seed=1,
            pixel_bounds=None if bounds is None else tuple(bounds),
            **options,
        )
        (noisy, aovs), noisy_seconds = timed(
            refracta.render, example.scene, example.camera, example.field, spp=spp, aovs=["albedo", "normal"], **options
        )
        alone, alone_seconds = timed(refracta.denoise, noisy)
        _, guided_seconds = timed(refracta.denoise, noisy, aovs["albedo"], aovs["normal"])
        guided = refracta.render(example.scene, example.camera, example.field, spp=spp, denoise=True, **options)
        sky = ~np.any(aovs["normal"], axis=2)  # as render(denoise=True): pure-sky pixels kept
        prefiltered = refracta.denoise(noisy, aovs["albedo"], aovs["normal"], clean_aux=False)
        prefiltered[sky] = noisy[sky]
        row = {
            "crop": None if bounds is None else list(bounds),
            "render_seconds": noisy_seconds,
            "reference_seconds": reference_seconds,
            "denoise_seconds": guided_seconds,
            "colour_only_denoise_seconds": alone_seconds,
        }
        labels = (("noisy", noisy), ("colour_only", alone), ("guided", guided), ("prefiltered_guides", prefiltered))
        for label, image in labels:
            errors = squared_errors(image[window], reference)
            row[f"{label}_relative_mse"] = float(errors.mean())
            row[f"{label}_flip"] = flip_mean(image[window], reference)
            if label == "guided":
                worst = np.sort(errors.ravel())[::-1][: errors.size // 10]
                row["worst_tenth_share"] = float(worst.sum() / errors.sum())
        reference_noise = row["noisy_relative_mse"] * k / (1 + k)
        row["reference_noise_relative_mse"] = reference_noise
        for label, _ in labels[1:]:
            row[f"{label}_improvement"] = row["noisy_relative_mse"] / row[f"{label}_relative_mse"]
            row[f"{label}_improvement_reference_noise_subtracted"] = (
                row["noisy_relative_mse"] - reference_noise
            ) / max(row[f"{label}_relative_mse"] - reference_noise, 1e-12)
            row[f"{label}_flip_improvement"] = row["noisy_flip"] / row[f"{label}_flip"]
        row["relative_mse_improvement"] = row["guided_improvement"]
        row["flip_improvement"] = row["guided_flip_improvement"]
        out[name] = row
        print(
            f"{name} {width}x{height} crop {bounds} {spp} spp vs {reference_spp}: "
            f"relMSE {row['noisy_relative_mse']:.2e} -> "
            f"{row['guided_relative_mse']:.2e} (x{row['relative_mse_improvement']:.2f}, reference noise subtracted "
            f"x{row['guided_improvement_reference_noise_subtracted']:.2f}; colour only "
            f"x{row['colour_only_improvement']:.2f}; prefiltered guides x{row['prefiltered_guides_improvement']:.2f}), "
            f"FLIP {row['noisy_flip']:.4f} -> {row['guided_flip']:.4f} (x{row['flip_improvement']:.2f}), worst 10 % of "
            f"pixels {100 * row['worst_tenth_share']:.0f} % of the error, denoise {guided_seconds:.2f} s, "
            f"render {noisy_seconds:.1f} s",
            flush=True,
        )
    return out


# The hot road at the demo's own size (examples' 640 x 240), its reference rendered on a crop
# holding the far poles, the cars, their mirage and the road (render's pixel_bounds): a full
# 640 x 240 reference costs 4x the 320 x 120 one (152 s at 512 spp on an idle 2-core machine).
# As fractions of the width and height: pixels [200, 360) x [60, 140) at 640 x 240.
DEMO_SIZE_CROPS = {"hot_road": (0.3125, 0.25, 0.5625, 7 / 12)}


def denoise_quality_demo_size(width=640, height=240, spp=16, reference_spp=512, names=("hot_road",)) -> dict:
    """denoise_quality at the demo's size, compared on DEMO_SIZE_CROPS."""
    crops = {
        name: tuple(round(f * size) for f, size in zip(DEMO_SIZE_CROPS[name], (width, height, width, height)))
        for name in names
    }
    return denoise_quality(width, height, spp, reference_spp, names, crops)


def level_path_tilts(air, lengths=(12.8, 100.0, 300.0), seeds=3, paths=40) -> dict:
    """The vertical over the horizontal tilt variance of level paths of each length through `air`'s
    settings (refracta.testing.tilts), at random places, headings and seeds: 1 for isotropic
    turbulence (it grew as L^2 while the lattice held modes constant along every level path)."""
    import refracta
    from refracta.testing.tilts import level_path_tilts as tilts

    rng = np.random.default_rng(11)
    out = {}
    for length in lengths:
        vertical, horizontal = [], []
        for seed in range(seeds):
            layer = refracta.Turbulence(air.cn2, cells=air.cells, depth=None, seed=seed).layer
            v, h = tilts(layer, length, paths, rng, step=air.spacing / 2)
            vertical.extend(v)
            horizontal.extend(h)
        out[str(length)] = float(np.var(vertical) / np.var(horizontal))
    print("level paths, vertical / horizontal tilt variance:", {k: round(v, 2) for k, v in out.items()})
    return out


# Sections that --only runs on their own (with their published arguments).
SECTIONS = {
    "turbulence_generation": turbulence_generation,
    "structure_function": structure_function,
    "angle_of_arrival": angle_of_arrival,
    "water_render": water_render,
    "aerial_perspective_render": aerial_perspective_render,
    "denoise_quality": denoise_quality,
    "denoise_quality_demo_size": denoise_quality_demo_size,
    "shimmer_fast": shimmer_fast,
}


def main(quick: bool = False) -> dict:
    results = {
        "hot_spot_render": hot_spot_render(*((320, 180, 1) if quick else (1280, 720, 3))),
        "turbulence_generation": turbulence_generation((128,) if quick else (128, 256)),
        "structure_function": structure_function(cells=128 if quick else 256, seeds=2 if quick else 4),
        "angle_of_arrival": angle_of_arrival(
            seeds=2 if quick else 4, rays=500 if quick else 1500, along_x_cells=128 if quick else 256
        ),
        "shimmer_render": shimmer_render(*((64, 24) if quick else (160, 60))),
        "shimmer_fast": shimmer_fast(*(((64, 24), (32, 12), 48, (1, 2)) if quick else ())),
        "water_render": water_render(*((64, 24, 2, 1) if quick else ())),
        "aerial_perspective_render": aerial_perspective_render(*((160, 60, 1) if quick else ())),
        "denoise_quality": denoise_quality(*((96, 36, 4, 64) if quick else ())),
        "denoise_quality_demo_size": denoise_quality_demo_size(*((192, 72, 4, 16) if quick else ())),
    }
    return results


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--only", choices=sorted(SECTIONS), help="run one section and merge it into the results file")
    args = parser.parse_args()
    if args.only:
        import json

        from _common import RESULTS

        previous = RESULTS / "realism.json"
        payload = json.loads(previous.read_text()) if previous.exists() else {}
        payload.pop("machine", None), payload.pop("date", None)
        payload[args.only] = SECTIONS[args.only]()
        print("->", write_results("realism", payload))
        raise SystemExit(0)
    payload = main(args.quick)
    if args.quick:
        print("(--quick: not written)")
    else:
        print("->", write_results("realism", payload))
