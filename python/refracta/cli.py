"""The `refracta` command line: `refracta demo --out DIR [--size WxH]`,
`refracta render scene.toml -o out.exr --method curved --size 1280x720` and
`refracta edit scene.toml --pairs pairs.json -o solved.toml`."""

from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from pathlib import Path
from typing import Any


def _size(text: str):
    try:
        width, height = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size must look like 640x240 (got {text!r})") from None
    if width < 1 or height < 1:
        raise argparse.ArgumentTypeError(f"size must be at least 1x1 (got {text!r})")
    return width, height


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (no usage block): `refracta render: error: ... (see --help)`."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def _metres(text: str) -> float:
    """argparse type: a finite length > 0 [m]."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be a length in metres (got {text!r})") from None
    if not (0.0 < value < math.inf):
        raise argparse.ArgumentTypeError(f"must be > 0 m and finite (got {text!r})")
    return value


def _count(minimum: int):
    """argparse type: a whole number >= minimum."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"must be a whole number (got {text!r})") from None
        if value < minimum:
            raise argparse.ArgumentTypeError(f"must be >= {minimum} (got {value})")
        return value

    return parse


# How the demo renders each example at its default size (640 px wide): transport, samples per
# pixel, each image denoised (render(denoise=True): Open Image Denoise with the albedo and normal
# of the first hit). Over the sea every camera path is a curved ray 20-40 km long (~60-140 us a
# sample on the shared 2-core machine), so those take one sample and lean on the denoiser. The
# whole demo takes 156 s of CPU (user time) and 84.6 s of wall time on two quiet cores (a fresh
# clone, 4 December; it prints its time).
# Edges between surfaces -- poles, wires, booms, hulls -- are rendered again with edge_spp samples
# per pixel (RenderOptions.edge_spp: the pixels whose first hits' albedo or normal differ from a
# neighbour's, 7-13 % of them): one sample at a pixel's centre draws them as staircases, and a few
# a sub-pixel pole as a comb. Hot road poles, 640x320 denoised, against 256 spp (relative MSE,
# FLIP; CPU s at load 9-12): 4 spp 0.0146, 0.045, 10.6 s; 2 spp + 32 at edges 0.0011, 0.019,
# 14.1 s (16 spp: 0.0015, 0.0185, 33.4 s). Cold sea cranes: 1 spp 0.0054, 0.055, 5.0 s; 1 spp + 16
# at edges 0.0017, 0.029, 12.7 s (4 spp: 0.0018, 0.031, 20.3 s). The hot spot's poles: 8 at edges,
# 21.7 s a view against 10.2 s (16: 36.2 s, little better to the eye). The Fata Morgana keeps one
# sample: its textured cliffs put 23 % of its pixels at edges (16 there: 29.5 s against 6.2 s).
# The demo's parts (cli.demo narrowed, CPU at load 10-17): hot road and cold sea 30.3 -> 46.6 s,
# hot spot 27.8 -> 57.8 s: +46 s of CPU, ~+23 s of wall on two free cores.
DEMO_SETTINGS: dict[str, dict[str, Any]] = {
    "hot_road": dict(transport="direct", spp=2, edge_spp=32),
    "hot_spot": dict(transport="direct", spp=1, edge_spp=8),  # three views
    "cold_sea": dict(transport="direct", spp=1, edge_spp=16),
    "fata_morgana": dict(transport="direct", spp=1),
}
# The automatic exposure's key per example (the log-average luminance maps to it; refracta.io):
# middle grey by day, and for the cold sea once balanced on its sunlight (_demo_white_balance; it
# had 0.22 while it showed sepia, at 0.15 muddy brown): at 0.18 its sky shows at 0.50 and the sea at
# 0.30, and the glitter keeps its gradation (9 % of the bottom 40 rows above 0.9 against 12 % at
# 0.22, where 2 % reached 0.95); the Fata Morgana a little darker: its dark sea fills two thirds
# of the frame and pulls the log-average down (at
# 0.14 no pixel of its stacked band clips, the sky shows light and the sea blue-grey; at 0.09, the
# key of the flat-faced cliffs that then showed near white, the frame looked murky).
DEMO_KEYS = {"hot_road": 0.18, "hot_spot": 0.18, "cold_sea": 0.18, "fata_morgana": 0.14}


# White balance (refracta.io's white_balance) per example, as its photographer would set it. The
# cold sea is balanced on the sunlight that lights it: the 10-deg sun through 80 km visibility is
# 1 : 0.69 : 0.36 in linear RGB (CCT ~4040 K), so with the render's own white the whole frame --
# sky, haze, sea and glitter, all that sun's light scattered or mirrored -- showed one sepia; as a
# grey card facing the sun (or an eye adapted to that light) sets it, the glitter shows white, the
# haze toward the sun silver and the shade the skylight fills blue-grey. ('auto', grey world, gave
# ~3780 K there, near it; on the desert demos it turned the sand grey, so it is no default.) The
# others are sunlit scenes in a sun 15-30 deg high, shot on a camera's 'daylight' (CIE D55): with
# the render's own D65 white (a camera's 'cloudy') the hot road's asphalt showed brown and its
# hazy sky toward the sun beige (linear 1 : 0.84 : 0.70 at the horizon); on 'daylight' the asphalt
# is grey, the sky a pale grey, the Fata Morgana's sea and sky blue-grey.
def _demo_white_balance(name: str) -> str | tuple[float, float, float]:
    """The demo's white balance for an example: the cold sea's sunlight at the ground (linear RGB of
    its physical sky's sun, refracta.spectrum.PhysicalSky.sun_radiance_rgb; ~1.3 s CPU to build the
    sky), else 'daylight'."""
    from refracta import examples, spectrum

    if name != "cold_sea":
        return "daylight"
    sun = examples.sun_direction(*examples.COLD_SEA_SUN)
    rgb = spectrum.PhysicalSky(sun, visibility=examples.COLD_SEA_VISIBILITY).sun_radiance_rgb().ravel()
    return (float(rgb[0]), float(rgb[1]), float(rgb[2]))


# The hot spot's extra view: the camera walks this far [m] toward the patch; its "lake" stays on
# the same stretch of road (it belongs to the ground), only nearer and lower in the frame. (Walk
# much farther and rays reach it steeper than its critical angle: the lake goes.)
HOT_SPOT_WALK = 60.0


def _moved(camera, distance: float, width: int, height: int):
    """The hot road's photographic camera carried `distance` [m] along +x (the road)."""
    import numpy as np

    import refracta
    from refracta import examples

    step = np.array([distance, 0.0, 0.0])
    return refracta.Camera.photographic(
        np.asarray(camera.position) + step,
        np.asarray(camera.look_at) + step,
        examples.HOT_ROAD_FOCAL_LENGTH,
        width=width,
        height=height,
    )


def demo(out: Path, size=None) -> int:
    """Each example scene without and with its atmosphere, one above the other (`out`/<name>.png,
    tone mapped by refracta.io's default ACES curve, exposed by DEMO_KEYS[name] on the pair's joint
    log-average; the hot spot adds a third view, the camera HOT_SPOT_WALK m nearer), the linear
    renders (`out`/<name>.exr, through the atmosphere; <name>_straight.exr without), the ray
    fans (`out`/rays_<name>.png), a sunset with a green flash (`out`/green_flash.png) and the hot
    road shimmering (`out`/shimmer.gif, physical turbulence; shimmer_noise.gif, geometric noise).
    size: (width, height) for every example (None: each example's default, 640 px wide). Every
    render is denoised. Prints each image's render time and the total."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    import refracta
    from refracta import examples, plot

    if out.exists() and not out.is_dir():  # mkdir said "[Errno 17] File exists"
        raise ValueError(f"--out {out} is a file: give a folder for the demo's images")
    out.mkdir(parents=True, exist_ok=True)
    total = time.perf_counter()
    for name, make in examples.EXAMPLES.items():
        example = make() if size is None else make(*size)
        width, height = example.camera.width, example.camera.height
        # The reference: no atmosphere, but the same (curved or flat) Earth.
        reference_field = refracta.without_refraction(example.field)
        settings = DEMO_SETTINGS.get(name, dict(transport="direct", spp=4))
        render = dict(progress=False, max_length=example.max_length, denoise=True, **settings)
        views = [
            (example.camera, reference_field, "without the atmosphere"),
            (example.camera, example.field, "through the atmosphere"),
        ]
        if name == "hot_spot":
            views.append(
                (
                    _moved(example.camera, HOT_SPOT_WALK, width, height),
                    example.field,
                    f"through the atmosphere, {HOT_SPOT_WALK:.0f} m nearer",
                )
            )
        edges = f" ({settings['edge_spp']} at edges)" if "edge_spp" in settings else ""
        images = []
        for camera, field, label in views:
            start = time.perf_counter()
            images.append(refracta.render(example.scene, camera, field, **render))
            print(
                f"{name}, {label}: {width}x{height}, {settings['transport']}, {settings['spp']} spp{edges}, denoised: "
                f"{time.perf_counter() - start:.1f} s",
                flush=True,
            )
        refracta.io.write_image(out / f"{name}_straight.exr", images[0])
        refracta.io.write_image(out / f"{name}.exr", images[1])
        # One exposure for all views (the log-average of them together), so they compare.
        both = refracta.io.to_display(
            np.concatenate(images, axis=0), key=DEMO_KEYS.get(name), white_balance=_demo_white_balance(name)
        )
        displays = np.split(both, len(images), axis=0)
        # One figure pixel per image pixel: the panels keep the renders' own resolution.
        dpi = 100
        figure, axes = plt.subplots(len(images), 1, figsize=(width / dpi, len(images) * (height / dpi + 0.3)), dpi=dpi)
        for ax, display, (_, _, label) in zip(np.atleast_1d(axes), displays, views):
            ax.imshow(display, interpolation="none")
            ax.set_title(f"{name}: {label}", fontsize=_title_points(f"{name}: {label}", width, 9))
            ax.axis("off")
        figure.subplots_adjust(
            left=0, right=1, bottom=0, top=1 - 0.3 / (height / dpi + 0.3) / len(images), hspace=0.3 / (height / dpi)
        )
        figure.savefig(out / f"{name}.png", dpi=dpi)
        plt.close(figure)
        print(f"wrote {out / (name + '.png')}, {name}.exr, {name}_straight.exr")
    for name, make_atmosphere in examples.ATMOSPHERES.items():
        atmosphere, eye, elevations, length = make_atmosphere()
        figure = plot.ray_fan(atmosphere, eye, elevations, length, title=f"{name}: {atmosphere.type_name}")
        figure.savefig(out / f"rays_{name}.png", dpi=110)
        plt.close(figure)
        print(f"wrote {out / ('rays_' + name + '.png')}")
    scale = 1.0 if size is None else size[0] / 640  # the extras follow the asked size (the tests' small demo: seconds)
    _demo_green_flash(out, size=max(16, round(GREEN_FLASH_SIZE * scale)))
    _demo_shimmer(
        out,
        size=(max(24, round(120 * scale)), max(8, round(40 * scale))),
        noise_size=(max(32, round(320 * scale)), max(12, round(120 * scale))),
    )
    print(f"demo: {time.perf_counter() - total:.1f} s")
    return 0


# The green flash sequence (examples.green_flash): the sun's centre [deg] above the true horizon in
# each frame, and the frames' fields of view [deg]. The warm sea's mirage folds the sky at apparent
# -0.026 deg (the vertex line: true -0.5131 deg at 530 nm, -0.5083 at 700, -0.5176 at 450;
# refracta.astronomical_refraction over the air of examples.green_flash); what of the sun lies above
# that true elevation is seen twice, erect above the line and inverted below it, and the rays below
# the mirage down to -0.14 deg see the inverted sky, the sea beneath. The frames: the flattening disc
# cut by the mirage (-0.45); the sun's top and its inverted image merged into an orange lens floating
# above the inverted sky (-0.74: every wavelength's cap 0.033-0.043 deg tall); the lens shrinking,
# orange inside a green rim (-0.768: 700 nm's cap 0.0053 deg, 530's 0.0101); the last gleam, red and
# yellow gone (-0.776: 560 nm's cap 0.0009 deg, 530's 0.0021, 450's 0.0066). Each wavelength's lens is
# the chord of its cap (width 2 sqrt(2 R h)) stretched by the mirage (height 2 sqrt(h / k), k = 9.98 per
# deg at the vertex): ellipses of one shape, the bluer the larger, so the colours nest around the
# vertex -- green around orange, a faint blue around the green, at the sides as above and below.
# 0.35 deg (a ~4000 mm lens on full frame) shows the last gleam ~100 px wide and the sea below it.
GREEN_FLASH_FRAMES = [(-0.45, 0.7), (-0.74, 0.7), (-0.768, 0.35), (-0.776, 0.35)]
# [deg]: where each zoom looks (the fold is at -0.026). At 0.7 deg the first frame's flattened
# disc spans apparent -0.140 (the mirage's cut, where the sea begins) to +0.306 deg: looking at
# +0.02 leaves 0.06 deg (44 px at 512) of sky above it and 0.19 deg of sea with the sun's glitter
# path below (at -0.05 its top was cut off by the frame).
GREEN_FLASH_LOOK = {0.7: 0.02, 0.35: -0.02}
GREEN_FLASH_SIZE = 512  # [px] each frame, square (issue 19: at least 512 px)
# Two spectral samples a pixel: each carries one hero wavelength through its own dispersed air
# (no eye table), ~70 us of CPU a sample over the 1500 km paths; the denoiser and the chroma
# filter (examples_chroma) remove the noise the single wavelengths leave. At 1 spp the -0.768 frame's
# lens had a ragged orange edge on one side (the denoised luminance's blotches at the orange/green
# boundary, which the chroma filter follows); at 2 spp both sides are smooth, as at 4 (its frame
# 12.8 s, 14.3 s, 26.6 s of wall time at 1, 2, 4 spp).
GREEN_FLASH_SPP = 2
# The frames' exposure, metered on the sun as photographers of the green flash meter: the brightest
# channel of the sequence (the 99.9th percentile of each pixel's largest channel over all frames:
# the first frame's disc, its red) at 6 on the film's response 1 - e^(-x), just saturated (0.998),
# its green at ~1.1 (0.67) and blue at ~0.09: an orange disc. (Exposed for the sky instead, two stops
# below its middle grey with Reinhard's hue-kept curve as before, the last gleam's faint blue ring --
# ~1/10 of the gleam's green radiance, but ~20x the sky's luminance -- was shown at full saturation,
# as bright as the green.) At 3 the disc showed red-orange and the gleam a dim green; at 16 the disc
# yellow.
GREEN_FLASH_SUN_EXPOSURE = 6.0
# The encoding's gamma: the sky and sea lie ~11.6 stops below the disc's red (sky 9.4, disc ~30 000),
# under sRGB's linear toe (3/255 and darker, one black); a display gamma of 2.6 (DCI cinema's, a flat
# picture profile's lift) shows them dark brown and dark grey, so the sea horizon under the mirage's
# inverted sky stays visible (sRGB ~0.09 sky, ~0.05 sea at 512 px), the disc still orange.
GREEN_FLASH_GAMMA = 2.6


def green_flash_display(frames):
    """The display values of the green flash frames, one exposure for all, as a photograph: a
    film's response per channel, 1 - e^(-c L) (refracta.io tonemap='film'), so every colour is shown
    by its own radiance -- a colour 10x fainter than another is 10x darker on the film's straight
    part, whatever its hue -- with the exposure c metered on the sun (GREEN_FLASH_SUN_EXPOSURE over
    the sequence's brightest channel) and encoded by a display gamma of GREEN_FLASH_GAMMA. The
    frames span ~12 stops (the disc ~3000 times the sky beside it in red: ~38 air masses dim the
    sun); the disc's red saturates, its green does not (orange), the sky shows dark."""
    import numpy as np

    import refracta

    joint = np.concatenate(frames, axis=1)
    brightest = float(np.percentile(joint.max(axis=2), 99.9))
    exposure = GREEN_FLASH_SUN_EXPOSURE / brightest if brightest > 0 else 1.0
    shown = refracta.io.to_display(joint, exposure=exposure, tonemap="film", gamma=GREEN_FLASH_GAMMA)
    return np.split(shown, len(frames), axis=1)


def green_flash_frame(elevation: float, vfov: float, size: int = GREEN_FLASH_SIZE, spp: int = GREEN_FLASH_SPP):
    """One frame of the green flash demo: examples.green_flash with the sun's centre `elevation`
    [deg] above the true horizon, seen through `vfov` [deg] looking at GREEN_FLASH_LOOK[vfov],
    `size` x `size`, spectral at `spp`, denoised (linear RGB, >= 0)."""
    import numpy as np

    import refracta
    from refracta import examples, examples_chroma

    example = examples.green_flash(size, size, elevation)
    look = np.radians(GREEN_FLASH_LOOK[vfov])
    eye = example.camera.position
    camera = refracta.Camera(eye, eye + [np.cos(look), np.sin(look), 0.0], vfov=vfov, width=size, height=size)
    # No auxiliary images: the frames are the sun and sky seen directly (an emitter has no albedo;
    # with the sea's albedo and normal beside it OIDN left the disc mottled). OIDN gives the
    # luminance, denoising the samples' own luminance as a grey image: a sample's Y is >= 0 even
    # where its single wavelength lies outside the sRGB gamut, and its colour noise is left out
    # (fed the colour clipped to >= 0, OIDN left the sky's luminance varying by 5.7-6.7 % between
    # neighbourhoods of the demo's second frame, rows 20-150, each row to its mean, and 7 % too
    # bright; fed the grey luminance, 1.7 %). The colour, one wavelength a sample, is averaged over
    # pixels of the same brightness (examples_chroma.chroma_filter: what left the disc mottled
    # after OIDN alone), then brought into the gamut with its luminance kept (gamut_map).
    image = refracta.render(
        example.scene, camera, example.field, max_length=example.max_length, spectral=True, spp=spp, progress=False
    )
    luminance = np.maximum(image.astype(np.float64) @ examples_chroma.LUMINANCE, 0.0)
    grey = np.repeat(luminance[..., None], 3, axis=2).astype(np.float32)
    denoised = refracta.denoise(grey) @ examples_chroma.LUMINANCE
    return examples_chroma.gamut_map(examples_chroma.chroma_filter(image, denoised))


def _title_points(text: str, width: int, largest: float) -> float:
    """A title's font size [pt] that fits `width` pixels at 100 dpi (a character is about 0.6 em
    wide): `largest` for the demo's own sizes, smaller for `refracta demo --size 160x60`, whose
    titles were cut off at both ends."""
    return max(3.0, min(largest, width * 72.0 / (0.6 * 100.0 * len(text))))


def _demo_green_flash(out: Path, size: int = GREEN_FLASH_SIZE, spp: int = GREEN_FLASH_SPP) -> None:
    """Sunset over a warm sea, spectral and denoised: out/green_flash.png, `size` x `size` frames
    (green_flash_frame) side by side, one exposure for all (green_flash_display), one figure pixel
    per rendered pixel."""
    import matplotlib.pyplot as plt

    start = time.perf_counter()
    frames = [green_flash_frame(elevation, vfov, size, spp) for elevation, vfov in GREEN_FLASH_FRAMES]
    shown = green_flash_display(frames)
    dpi, gap = 100, 0.08
    figure, axes = plt.subplots(1, len(frames), figsize=(len(frames) * (size / dpi + gap), size / dpi + 0.7), dpi=dpi)
    for ax, frame, (elevation, vfov) in zip(axes, shown, GREEN_FLASH_FRAMES):
        ax.imshow(frame, interpolation="none")
        label = f"sun {elevation:+.3f} deg, {vfov * 60:.0f}' field"
        ax.set_title(label, fontsize=_title_points(label, size, 9))
        ax.axis("off")
    title = "Sunset over a warm sea (spectral): flattening, the mirage's cut, the lens shrinking, the green flash"
    figure.suptitle(title, fontsize=_title_points(title, len(frames) * size, 10))
    figure.subplots_adjust(left=0, right=1, bottom=0, top=size / (size + 70), wspace=gap * dpi / size)
    figure.savefig(out / "green_flash.png", dpi=dpi)
    plt.close(figure)
    print(
        f"wrote {out / 'green_flash.png'} ({len(frames)} frames {size}x{size}, spectral, {spp} spp, denoised: "
        f"{time.perf_counter() - start:.1f} s)",
        flush=True,
    )


# The turbulent rays end (and see the sky in their last direction) after 1.5 km, where the
# shimmering band's rays have crossed the hot layer. They are followed by turbulence_trace
# 'perturbed' (render/shimmer_cast.h: as deviations from the calm rays, within 0.037 of the
# turbulence's effect of the strict trace, bench_realism.py shimmer_fast): 0.55 ms a pixel-frame
# against the strict rk45 trace's 5 ms (one core, 96 x 32 and 48 x 16 here), so the GIF went from 3
# frames of 48 x 16 (12.7 s) to 8 of 120 x 40 (~11 s wall on two cores), each denoised so that only
# the shimmer moves, not the sampling noise.
SHIMMER_LENGTH = 1500.0  # [m]
SHIMMER_FRAMES = 8


def _demo_shimmer(out: Path, size=(120, 40), noise_size=(320, 120)) -> None:
    """The hot road shimmering: out/shimmer.gif (physical turbulence in the hot layer, carried by
    the wind; `size` WxH) and out/shimmer_noise.gif (the geometric noise stand-in, not physical)."""
    import numpy as np

    import refracta
    from refracta import examples

    road = examples.hot_road()
    start = time.perf_counter()
    # The mirage band, narrow and small: every ray there crosses ~300 m of turbulent layer, traced
    # in steps of a few 10 cm cells (refracta.Turbulence: 128^3 cells of 10 cm, a 12.8 m tile).
    camera = refracta.Camera(road.camera.position, road.camera.look_at, vfov=0.6, width=size[0], height=size[1])
    air = refracta.Turbulence(cells=128, spacing=0.1, depth=0.1, seed=1)
    refracta.animate(
        road.scene,
        camera,
        road.field,
        np.arange(SHIMMER_FRAMES) * 0.1,
        out / "shimmer.gif",
        turbulence=air,
        progress=False,
        max_length=SHIMMER_LENGTH,
        turbulence_trace="perturbed",
        denoise=True,
    )
    print(
        f"wrote {out / 'shimmer.gif'} ({SHIMMER_FRAMES} frames {size[0]}x{size[1]} through refracta.Turbulence: "
        f"{time.perf_counter() - start:.1f} s)",
        flush=True,
    )
    start = time.perf_counter()
    refracta.animate(
        road.scene,
        road.camera.resized(*noise_size),
        road.field,
        np.arange(12) * 0.08,
        out / "shimmer_noise.gif",
        noise=dict(rms=4e-5, correlation_pixels=6.0, speed=(30.0, 0.0)),
        progress=False,
        max_length=road.max_length,
    )
    print(
        f"wrote {out / 'shimmer_noise.gif'} (12 frames {noise_size[0]}x{noise_size[1]}, geometric noise, "
        f"not physical: {time.perf_counter() - start:.1f} s)",
        flush=True,
    )


def _aov_list(text: str) -> list[str]:
    """--aovs distance,position,...: the names, checked by render (a bad one lists the valid names)."""
    names = [name.strip() for name in text.split(",")]
    if not any(names):
        raise argparse.ArgumentTypeError(f"names no readout (got {text!r}): e.g. --aovs distance,position")
    if not all(names):  # ',distance' or 'distance,,position': a readout left out by mistake?
        raise argparse.ArgumentTypeError(
            f"has an empty name (got {text!r}): readout names separated by single commas, e.g. --aovs distance,position"
        )
    return names


def _output_path(text: str) -> Path:
    """-o/--output: a file name; an empty one (Path('') is '.', 'a folder') refused as empty."""
    if not text.strip():
        raise argparse.ArgumentTypeError(f"is empty (got {text!r}): give a file name")
    return Path(text)


def _option(text: str) -> tuple[str, object]:
    """--set NAME=VALUE: a render option by its RenderOptions name, the value read as TOML reads
    one (1e5, true, "rk45", [0, 0, 64, 32]; Python's (0, 0, 64, 32) as that array; True / False as
    true / false), else as a string (rk45); render checks both."""
    from refracta.scene_file import tomllib  # tomli before Python 3.11

    name, equals, value = text.partition("=")
    if not equals or not name.strip().isidentifier():
        raise argparse.ArgumentTypeError(f"must be NAME=VALUE, a RenderOptions field (got {text!r})")
    value = value.strip()
    if value.startswith("(") and value.endswith(")"):  # a Python tuple: pixel_bounds=(10,5,50,30) (a trial)
        value = "[" + value[1:-1] + "]"
    try:
        parsed = tomllib.loads(f"v = {value}")["v"]
    except tomllib.TOMLDecodeError:
        # Python's True / False (and TRUE ...) too: TOML's true / false alone was the trap of a trial.
        parsed = {"true": True, "false": False}.get(value.strip().lower(), value.strip())
    return name.strip(), parsed


# RenderOptions fields the render command sets by its own flags: --set NAME would give them twice.
_SET_BY_FLAGS = {
    "method": "--method",
    "transport": "--transport",
    "spp": "--spp",
    "max_depth": "--max-depth",
    "max_length": "--max-length",
    "spectral": "--spectral",
    "seed": "--seed",
}


def _options_given(pairs: list) -> dict:
    """--set's NAME=VALUE pairs as keywords: not render's own keywords (scene, progress,
    return_stats, aovs, denoise ...: the command's to set), not a field with a flag of its own, and
    not one given twice (the last would win). Other names reach RenderOptions, which names a wrong one."""
    from refracta._render import own_keywords

    own = own_keywords()
    options: dict = {}
    for name, value in pairs:
        if name in _SET_BY_FLAGS:
            raise ValueError(f"--set {name}: give it as {_SET_BY_FLAGS[name]}")
        if name in own:
            raise ValueError(f"--set {name}: not a refracta.RenderOptions field (the command sets render's {name})")
        if name in options:
            raise ValueError(f"--set {name} is given twice")
        options[name] = value
    return options


def _white_balance(text: str):
    """--white-balance: a number is a colour temperature [K], three comma-separated numbers an RGB
    white, anything else a name (checked by refracta.io: a bad one raises ValueError naming it)."""
    parts = text.split(",")
    try:
        values = [float(part) for part in parts]
    except ValueError:
        return text.strip()
    if len(values) == 1:
        return values[0]
    if len(values) == 3:
        return tuple(values)
    raise argparse.ArgumentTypeError(f"must be a temperature, a name or R,G,B (got {text!r})")


def _check_output(output: Path, scene_file: bool = False) -> None:
    """Refuses an output path that cannot be written before the work that would fill it: an image
    OpenImageIO writes (x.xyz failed after the render), or with scene_file a .toml file."""
    output = Path(output)
    if output.is_dir():
        raise ValueError(f"the output {output} is a folder: give a file name (e.g. {output / 'image.png'})")
    if not output.absolute().parent.is_dir():
        raise ValueError(f"the folder of the output {output} does not exist")
    if output.exists() and not output.is_file():  # a FIFO or a device: writing waits for a reader
        raise ValueError(f"the output {output} is not a regular file")
    if scene_file:
        if output.suffix.lower() != ".toml":
            raise ValueError(f"the output {output} must be a scene file (.toml): edit writes the scene's text")
        return
    from refracta import _core

    _core._check_image_format(str(output))


# Samples per pixel from which a spectral render's colour noise no longer tints a displayed image
# (a trial's flat sky, mean of the PNG against the RGB render's: 1 spp (183, 176, 86), 4 spp
# (195, 189, 128), 16 spp (193, 198, 199) against (193, 198, 204)).
_SPECTRAL_CLEAN_SPP = 16


def render_file(
    scene_path: Path,
    output: Path,
    method: str | None,
    size,
    spp: int | None,
    exposure=None,
    transport: str | None = None,
    max_depth=None,
    spectral: bool = False,
    tonemap=None,
    key=None,
    ev100=None,
    aovs=None,
    white_balance=None,
    max_length: float | None = None,
    denoise: bool = False,
    seed: int | None = None,
    options: dict | None = None,
) -> int:
    """Render a TOML scene file to an image (EXR stays linear; PNG/JPEG are tone mapped).

    exposure, ev100, key, tonemap, white_balance: as refracta.io.write_image (None: its defaults,
    automatic exposure, the ACES curve, no white balance). method, spp, transport, max_depth,
    max_length [m]: None keeps RenderOptions' own.
    aovs: names of render's per-pixel outputs (refracta.render's aovs: distance, position, ...),
    written after R, G, B as layers of the EXR (refracta.io.write_layers: distance.Y, position.X,
    ...; hidden_height.geometric and .refracted; geographic.lat, .lon, .height, which needs the
    scene file's [geographic] table); the output must then be an EXR. denoise: refracta.render's
    (Open Image Denoise with the first hit's albedo and normal); seed: RenderOptions.seed;
    options: further RenderOptions fields by name (--set chord=200000), checked by render.
    """
    import refracta

    _check_output(output)
    loaded = refracta.load_scene(scene_path, size=size)  # a lens fits its sensor at the size asked for
    scene, camera, field = loaded
    start = time.perf_counter()
    display = dict(exposure=exposure, tonemap=tonemap, key=key, ev100=ev100, white_balance=white_balance)
    refracta.io.settings(**display)  # a bad display option is refused before a long render, not after
    if aovs and Path(output).suffix.lower() != ".exr":
        raise ValueError(f"--aovs writes EXR layers: the output must be a .exr file (got {output})")
    if aovs and "geographic" in aovs and loaded.frame is None:
        raise ValueError(
            f"--aovs geographic needs the scene's place on the Earth: add a [geographic] table "
            f"(lat, lon [deg] of the scene's origin) to {scene_path}"
        )
    samples = spp or refracta.RenderOptions().spp
    displayed = not refracta._core._is_float_format(str(output))  # a float file is written linear, unclipped
    if spectral and not denoise and displayed and samples < _SPECTRAL_CLEAN_SPP:
        warnings.warn(
            f"render: a spectral render at {samples} spp is noisy in colour (each sample one set of "
            f"wavelengths), and a PNG clips each pixel's noise, which shifts the picture's colour: use "
            f"--spp {_SPECTRAL_CLEAN_SPP} or more, or --denoise (an EXR keeps the unbiased linear values)",
            stacklevel=2,
        )
    result = refracta.render(
        scene,
        camera,
        field,
        method=method,
        transport=transport,
        spp=spp,
        max_depth=max_depth,
        max_length=max_length,
        spectral=spectral,
        seed=seed,
        progress=True,
        aovs=aovs or None,
        frame=loaded.frame if aovs and "geographic" in aovs else None,
        denoise=denoise,
        **(options or {}),
    )
    if aovs:
        image, layers = result
        if exposure is not None or ev100 is not None:  # as write_image does for float files: manual only
            image = image * refracta.io.exposure_of(image, exposure=exposure, ev100=ev100)
        # Said as write_image says it for a float file (it was silently ignored here).
        unused = [f"--{name.replace('_', '-')}" for name in ("key", "tonemap", "white_balance") if display[name]]
        if unused:
            warnings.warn(
                f"render: {output} is written linear: {', '.join(unused)} shape only displayed images "
                "(PNG, JPEG) and are not applied",
                stacklevel=2,
            )
        refracta.io.write_layers(output, image, layers)  # readouts named as io.READOUT_CHANNELS
    else:
        refracta.io.write_image(output, result, **display)
    defaults = refracta.RenderOptions()
    method, transport = method or defaults.method, transport or defaults.transport
    written = (result[0] if aovs else result).shape  # pixel_bounds: a part of the camera's image
    print(f"wrote {output} ({written[1]}x{written[0]}, {method}, {transport}, {time.perf_counter() - start:.1f} s)")
    return 0


def edit_file(scene_path: Path, pairs_path: Path, output: Path, backend: str | None = None) -> int:
    """Solve the scene's atmosphere for the pairs file; write the scene with the solved atmosphere
    (and the solved camera where the pairs file frees camera parameters)."""
    import refracta
    from refracta import edit
    from refracta.scene_file import read_scene_text, relocate, with_atmosphere, with_camera

    _check_output(output, scene_file=True)
    loaded = refracta.load_scene(scene_path)
    # Its file names rewritten to name the same files from the output's folder, before the solve
    # (a name that cannot be rewritten fails now, not after minutes of solving).
    text = relocate(read_scene_text(scene_path), Path(scene_path).absolute().parent, Path(output).absolute().parent)
    scene, camera, field = loaded
    if field is None:
        raise ValueError(f"{scene_path}: has no [atmosphere] table to edit")
    pairs, options = edit.load_pairs(pairs_path, scene, camera, field)
    if not pairs:  # (a file the editor saved before any pair was placed)
        raise ValueError(f"{pairs_path}: 'pairs' is empty: give at least one pair to solve for")
    if backend is not None:
        options["backend"] = backend
    result = edit.solve(field, camera, pairs, progress=True, **options)
    print(result.report())
    # The solved field carries the file's turbulence (if any): written with its settings again.
    text = with_atmosphere(text, result.field, loaded.turbulence)
    if len(result.camera_values) and result.camera is not None:  # camera parameters free: as solved (was dropped)
        text = with_camera(text, result.camera)
    output.write_text(text, encoding="utf-8")  # as scene files are read (the locale's lost a solve to "°C")
    if result.success:
        print(f"wrote {output}")
        return 0
    print(f"the solve FAILED (report above); wrote its best atmosphere to {output} anyway, to inspect (exit status 1)")
    return 1


def main(argv=None) -> int:
    """Runs a command. A user error (a missing or malformed file, a bad value: ValueError, OSError
    and refracta.IoError, refracta.NumericalError) prints one line `refracta: error: ...` to stderr
    and returns 1; Ctrl-C returns 130; anything else is a bug and keeps its traceback. Command-line
    syntax errors (an unknown command or option, a missing or malformed argument, --seed -1) are
    argparse's: usage and the error on stderr, then SystemExit(2), as --help exits with 0."""
    import refracta

    shown = warnings.formatwarning
    warnings.formatwarning = _format_warning  # as shown; recorded warnings (pytest.warns, logging) unchanged
    try:
        return _run(argv)
    except (ValueError, OSError, refracta.NumericalError) as error:
        message = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
        print(f"refracta: error: {message}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("refracta: interrupted", file=sys.stderr)
        return 130
    finally:
        warnings.formatwarning = shown


def _format_warning(message, category, filename, lineno, line=None) -> str:
    """A warning as a command-line user reads it (`refracta: SceneWarning: ...`), without the
    Python file, line and source it came from."""
    del filename, lineno, line  # warnings.formatwarning's signature; none of them is shown
    return f"refracta: {category.__name__}: {message}\n"


def _run(argv=None) -> int:
    import refracta

    parser = _Parser(prog="refracta", description="Physically based mirages.")
    parser.add_argument("--version", action="version", version=f"refracta {refracta.__version__}")
    parser.add_argument(
        "--threads", type=_count(0), default=None, help="threads the work may use (default, or 0: every core)"
    )
    commands = parser.add_subparsers(dest="command", required=True)
    demo_parser = commands.add_parser("demo", help="render the example mirages and ray fans")
    demo_parser.add_argument("--out", type=Path, default=Path("out"), help="output folder (default: out)")
    demo_parser.add_argument(
        "--size",
        type=_size,
        default=None,
        help=(
            "the examples' image size WxH (default: each example's own, 640 px wide); the green flash's "
            "square frames and the shimmer GIFs scale with its width"
        ),
    )
    render_parser = commands.add_parser("render", help="render a TOML scene file")
    render_parser.add_argument("scene", type=Path, help="scene file (.toml)")
    render_parser.add_argument(
        "-o", "--output", type=_output_path, default=Path("out.exr"), help="image file (default out.exr)"
    )
    render_parser.add_argument(
        "--method", choices=["curved", "straight", "raster_march"], default=None, help="default: RenderOptions'"
    )
    render_parser.add_argument("--size", type=_size, default=None, help="WxH (default: the file's camera size)")
    render_parser.add_argument(
        "--spp", type=_count(1), default=None, help="samples per pixel (default: RenderOptions')"
    )
    render_parser.add_argument(
        "--exposure",
        type=float,
        default=None,
        help="manual exposure: a scale of the radiance (default: automatic, the image's "
        "log-average luminance to --key)",
    )
    render_parser.add_argument(
        "--ev100",
        type=float,
        default=None,
        help="manual exposure in EV100 (scale 683 / (1.2 2^EV100), radiance in W/(m^2 sr); Lagarde & de Rousiers)",
    )
    render_parser.add_argument(
        "--transport", choices=["direct", "path"], default=None, help="light transport (default: RenderOptions')"
    )
    render_parser.add_argument("--max-depth", type=_count(0), default=None, help="scattering events per path")
    render_parser.add_argument(
        "--max-length",
        type=_metres,
        default=None,
        help="how far the rays reach [m] (default: RenderOptions', 5 km; a coast or terrain farther away needs more)",
    )
    render_parser.add_argument("--spectral", action="store_true", help="hero-wavelength spectral rendering")
    render_parser.add_argument(
        "--denoise",
        action="store_true",
        help="Open Image Denoise, guided by the first hit's albedo and normal (refracta.render's denoise)",
    )
    render_parser.add_argument(
        "--seed", type=_count(0), default=None, help="the samples' random seed (default: RenderOptions')"
    )
    render_parser.add_argument(
        "--set",
        type=_option,
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="any other render option by its refracta.RenderOptions name, e.g. --set chord=200000 --set tol=1e-4 "
        "(repeatable; see help(refracta.RenderOptions))",
    )
    render_parser.add_argument(
        "--tonemap",
        choices=["aces", "reinhard", "linear", "film"],
        default=None,
        help="display curve for PNG/JPEG output (default: aces, filmic)",
    )
    render_parser.add_argument(
        "--key",
        type=float,
        default=None,
        help="automatic exposure's key: the log-average luminance shows as this grey "
        "(default 0.18; overrides --exposure/--ev100)",
    )
    render_parser.add_argument(
        "--white-balance",
        type=_white_balance,
        default=None,
        help="the light shown white in PNG/JPEG output: a colour temperature [K], daylight, cloudy, shade, "
        "tungsten, auto (grey world), none (default) or a linear RGB white R,G,B (refracta.io's white_balance)",
    )
    render_parser.add_argument(
        "--aovs",
        type=_aov_list,
        default=None,
        help="per-pixel readouts written as EXR layers, comma-separated: distance, position, object_id, "
        "apparent_elevation, apparent_azimuth, true_elevation, hidden_height, images, albedo, normal, samples, "
        "geographic (needs the file's [geographic] table) (refracta.render's aovs)",
    )
    edit_parser = commands.add_parser(
        "edit",
        help="solve a scene's atmosphere for point pairs (JSON)",
        description="Solve a scene's atmosphere for point pairs and write the scene with it. Exit status 0 "
        "when every pair is met; 1 when the solve fails, the best atmosphere it found written all the same.",
    )
    edit_parser.add_argument("scene", type=Path, help="scene file (.toml) with an [atmosphere] table")
    edit_parser.add_argument(
        "--pairs", type=Path, required=True, help="pairs file (.json), see refracta.edit.load_pairs"
    )
    edit_parser.add_argument("-o", "--output", type=_output_path, required=True, help="scene file to write (.toml)")
    edit_parser.add_argument("--backend", default=None, help="ceres (default) or nlopt:<ALGORITHM>")
    args = parser.parse_args(argv)
    if args.threads is not None:
        refracta.set_threads(args.threads)
    if args.command == "demo":
        return demo(args.out, args.size)
    if args.command == "render":
        return render_file(
            args.scene,
            args.output,
            args.method,
            args.size,
            args.spp,
            args.exposure,
            args.transport,
            args.max_depth,
            args.spectral,
            args.tonemap,
            args.key,
            args.ev100,
            args.aovs,
            args.white_balance,
            args.max_length,
            args.denoise,
            args.seed,
            _options_given(args.set),
        )
    if args.command == "edit":
        return edit_file(args.scene, args.pairs, args.output, args.backend)
    parser.error(f"unknown command {args.command}")
    return 2


if __name__ == "__main__":
    sys.exit(main())
