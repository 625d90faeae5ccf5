"""The `refracta` command line: `refracta demo --out DIR [--size WxH]`,
`refracta render scene.toml -o out.exr --method curved --size 1280x720` and
`refracta edit scene.toml --pairs pairs.json -o solved.toml`."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path


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


# How the demo renders each example at its default size (480 x 160): transport, samples per
# pixel. Measured on 2 cores (see demo's printout): the hot road path-traces; over the sea every
# glossy reflection is another curved ray tens of km long, so those use 'direct' (first-bounce
# lighting, specular chains followed).
DEMO_SETTINGS = {
    "hot_road": dict(transport="path", spp=16),
    "hot_spot": dict(transport="path", spp=16),
    "cold_sea": dict(transport="direct", spp=16),
    "fata_morgana": dict(transport="direct", spp=8),
}
# The automatic exposure's key per example (the log-average luminance maps to it; refracta.io):
# middle grey by day, darker at sunset, as photographers underexpose a sunset to keep its colour.
DEMO_KEYS = {"hot_road": 0.18, "hot_spot": 0.18, "cold_sea": 0.08, "fata_morgana": 0.14}


def demo(out: Path, size=(480, 160)) -> int:
    """Each example scene without and with its atmosphere, side by side (`out`/<name>.png, tone
    mapped by refracta.io's default ACES curve, exposed by DEMO_KEYS[name] on the pair's joint
    log-average), the linear
    renders (`out`/<name>.exr, through the atmosphere; <name>_straight.exr without), the ray
    fans (`out`/rays_<name>.png), a sunset with a green flash (`out`/green_flash.png) and the hot
    road shimmering (`out`/shimmer.gif, physical turbulence; shimmer_noise.gif, geometric noise).
    Prints each image's render time."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    import refracta
    from refracta import examples, plot

    out.mkdir(parents=True, exist_ok=True)
    total = time.perf_counter()
    for name, make in examples.EXAMPLES.items():
        example = make(*size)
        # The reference: no atmosphere, but the same (curved or flat) Earth.
        reference_field = refracta.without_refraction(example.field)
        settings = DEMO_SETTINGS.get(name, dict(transport="direct", spp=4))
        render = dict(progress=False, max_length=example.max_length, **settings)
        images = []
        for field, label in ((reference_field, "without the atmosphere"), (example.field, "through the atmosphere")):
            start = time.perf_counter()
            images.append(refracta.render(example.scene, example.camera, field, **render))
            print(f"{name}, {label}: {example.camera.width}x{example.camera.height}, {settings['transport']}, "
                  f"{settings['spp']} spp: {time.perf_counter() - start:.1f} s", flush=True)
        refracta.io.write_image(out / f"{name}_straight.exr", images[0])
        refracta.io.write_image(out / f"{name}.exr", images[1])
        # One exposure for both (the log-average of the pair), so they compare.
        both = refracta.io.to_display(np.concatenate(images, axis=0), key=DEMO_KEYS.get(name))
        displays = np.split(both, 2, axis=0)
        figure, axes = plt.subplots(2, 1, figsize=(9, 2 * 9 * size[1] / size[0] + 1.2), constrained_layout=True)
        for ax, display, label in zip(axes, displays, ("without the atmosphere", "through the atmosphere")):
            ax.imshow(display)
            ax.set_title(f"{name}: {label}", fontsize=10)
            ax.axis("off")
        figure.savefig(out / f"{name}.png", dpi=110)
        plt.close(figure)
        print(f"wrote {out / (name + '.png')}, {name}.exr, {name}_straight.exr")
    for name, make in examples.ATMOSPHERES.items():
        field, eye, elevations, length = make()
        figure = plot.ray_fan(field, eye, elevations, length, title=f"{name}: {field.type_name}")
        figure.savefig(out / f"rays_{name}.png", dpi=110)
        plt.close(figure)
        print(f"wrote {out / ('rays_' + name + '.png')}")
    scale = size[1] / 160  # the extras follow the asked size (the tests' 72x24 demo: a few seconds)
    _demo_green_flash(out, size=max(16, round(64 * scale)))
    _demo_shimmer(out, size=(max(24, round(96 * scale)), max(8, round(32 * scale))),
                  noise_size=(max(32, round(320 * scale)), max(12, round(120 * scale))))
    print(f"demo: {time.perf_counter() - total:.1f} s")
    return 0


# The green flash sequence (examples.green_flash): the sun's centre [deg] above the true horizon in
# each frame, and the frames' fields of view [deg] -- the flattening setting sun whole, then the
# last gleam at the fold of the warm sea's mirage (true -0.512 deg for the upper rim), where the
# blue-green end of the spectrum, lifted most, is seen last.
GREEN_FLASH_FRAMES = [(-0.45, 0.7), (-0.65, 0.7), (-0.74, 0.7), (-0.772, 0.08), (-0.774, 0.08), (-0.776, 0.08)]
GREEN_FLASH_LOOK = {0.7: -0.05, 0.08: -0.02}  # [deg]: where each zoom looks (the fold is at -0.025)


def _demo_green_flash(out: Path, size: int = 64, spp: int = 48) -> None:
    """Sunset over a warm sea, spectral: out/green_flash.png, one exposure for every frame."""
    import matplotlib.pyplot as plt
    import numpy as np

    import refracta
    from refracta import examples

    start = time.perf_counter()
    frames = []
    for elevation, vfov in GREEN_FLASH_FRAMES:
        example = examples.green_flash(size, size, elevation)
        look = np.radians(GREEN_FLASH_LOOK[vfov])
        eye = example.camera.position
        camera = refracta.Camera(eye, eye + [np.cos(look), np.sin(look), 0.0], vfov=vfov, width=size, height=size)
        frames.append(refracta.render(example.scene, camera, example.field, max_length=example.max_length,
                                      spectral=True, spp=spp, progress=False))
    # One exposure for every frame (the whole disc's bright end near 1), gamma 2.2: the last gleam
    # is as dim as it is.
    exposure = 1.0 / np.percentile(frames[0].max(axis=2), 99.0)
    figure, axes = plt.subplots(1, len(frames), figsize=(2.0 * len(frames), 2.6), constrained_layout=True)
    for ax, frame, (elevation, vfov) in zip(axes, frames, GREEN_FLASH_FRAMES):
        ax.imshow(np.clip(frame * exposure, 0.0, 1.0) ** (1 / 2.2))
        ax.set_title(f"sun {elevation:+.3f} deg\n{vfov * 60:.0f}' field", fontsize=8)
        ax.axis("off")
    figure.suptitle("Sunset over a warm sea (spectral): flattening, the mirage's cut, the green flash", fontsize=9)
    figure.savefig(out / "green_flash.png", dpi=110)
    plt.close(figure)
    print(f"wrote {out / 'green_flash.png'} ({len(frames)} frames {size}x{size}, spectral, {spp} spp: "
          f"{time.perf_counter() - start:.1f} s)", flush=True)


def _demo_shimmer(out: Path, size=(96, 32), noise_size=(320, 120)) -> None:
    """The hot road shimmering: out/shimmer.gif (physical turbulence in the hot layer, carried by
    the wind; `size` WxH) and out/shimmer_noise.gif (the geometric noise stand-in, not physical)."""
    import numpy as np

    import refracta
    from refracta import examples

    road = examples.hot_road(640, 240)
    start = time.perf_counter()
    # The mirage band, narrow and small: every ray there crosses ~300 m of turbulent layer, traced
    # in steps of a few 10 cm cells (refracta.Turbulence: 128^3 cells of 10 cm, a 12.8 m tile).
    camera = refracta.Camera(road.camera.position, road.camera.look_at, vfov=0.6, width=size[0], height=size[1])
    air = refracta.Turbulence(cells=128, spacing=0.1, depth=0.1, seed=1)
    refracta.animate(road.scene, camera, road.field, np.arange(6) * 0.15, out / "shimmer.gif", turbulence=air,
                     progress=False, max_length=road.max_length)
    print(f"wrote {out / 'shimmer.gif'} (6 frames {size[0]}x{size[1]} through refracta.Turbulence: "
          f"{time.perf_counter() - start:.1f} s)", flush=True)
    start = time.perf_counter()
    refracta.animate(road.scene, road.camera.resized(*noise_size), road.field, np.arange(12) * 0.08,
                     out / "shimmer_noise.gif", noise=dict(rms=4e-5, correlation_pixels=6.0, speed=(30.0, 0.0)),
                     progress=False, max_length=road.max_length)
    print(f"wrote {out / 'shimmer_noise.gif'} (12 frames {noise_size[0]}x{noise_size[1]}, geometric noise, "
          f"not physical: {time.perf_counter() - start:.1f} s)", flush=True)


def render_file(scene_path: Path, output: Path, method: str, size, spp: int, exposure=None,
                transport: str = "direct", max_depth=None, spectral: bool = False, tonemap=None,
                key=None, ev100=None) -> int:
    """Render a TOML scene file to an image (EXR stays linear; PNG/JPEG are tone mapped).

    exposure, ev100, key, tonemap: as refracta.io.write_image (None: its defaults, automatic
    exposure and the ACES curve).
    """
    import refracta

    scene, camera, field = refracta.load_scene(scene_path)
    if size is not None:
        camera = camera.resized(*size)
    start = time.perf_counter()
    image = refracta.render(scene, camera, field, method=method, transport=transport, spp=spp, max_depth=max_depth,
                            spectral=spectral, progress=True)
    refracta.io.write_image(output, image, exposure=exposure, tonemap=tonemap, key=key, ev100=ev100)
    print(f"wrote {output} ({camera.width}x{camera.height}, {method}, {transport}, {time.perf_counter() - start:.1f} s)")
    return 0


def edit_file(scene_path: Path, pairs_path: Path, output: Path, backend: str = None) -> int:
    """Solve the scene's atmosphere for the pairs file; write the scene with the solved atmosphere."""
    import refracta
    from refracta import edit
    from refracta.scene_file import with_atmosphere

    loaded = refracta.load_scene(scene_path)
    scene, camera, field = loaded
    if field is None:
        raise ValueError(f"{scene_path}: has no [atmosphere] table to edit")
    pairs, options = edit.load_pairs(pairs_path, scene, camera)
    if backend is not None:
        options["backend"] = backend
    result = edit.solve(field, camera, pairs, progress=True, **options)
    print(result.report())
    # The solved field carries the file's turbulence (if any): written with its settings again.
    output.write_text(with_atmosphere(Path(scene_path).read_text(), result.field, loaded.turbulence))
    print(f"wrote {output}")
    return 0 if result.success else 1


def main(argv=None) -> int:
    """Runs a command. A user error (a missing or malformed file, a bad value: ValueError, OSError
    and refracta.IoError, refracta.NumericalError) prints one line `refracta: error: ...` to stderr
    and returns 1; Ctrl-C returns 130; anything else is a bug and keeps its traceback."""
    import refracta

    try:
        return _run(argv)
    except (ValueError, OSError, refracta.NumericalError) as error:
        message = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
        print(f"refracta: error: {message}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("refracta: interrupted", file=sys.stderr)
        return 130


def _run(argv=None) -> int:
    parser = _Parser(prog="refracta", description="Physically based mirages.")
    commands = parser.add_subparsers(dest="command", required=True)
    demo_parser = commands.add_parser("demo", help="render the example mirages and ray fans")
    demo_parser.add_argument("--out", type=Path, default=Path("out"), help="output folder (default: out)")
    demo_parser.add_argument("--size", type=_size, default=(480, 160), help="image size WxH (default 480x160)")
    render_parser = commands.add_parser("render", help="render a TOML scene file")
    render_parser.add_argument("scene", type=Path, help="scene file (.toml)")
    render_parser.add_argument("-o", "--output", type=Path, default=Path("out.exr"), help="image file (default out.exr)")
    render_parser.add_argument("--method", choices=["curved", "straight", "raster_march"], default="curved")
    render_parser.add_argument("--size", type=_size, default=None, help="WxH (default: the file's camera size)")
    render_parser.add_argument("--spp", type=_count(1), default=1, help="samples per pixel")
    render_parser.add_argument("--exposure", type=float, default=None,
                               help="manual exposure: a scale of the radiance (default: automatic, the image's "
                                    "log-average luminance to --key)")
    render_parser.add_argument("--ev100", type=float, default=None,
                               help="manual exposure in EV100 (scale 1 / (1.2 2^EV100), Lagarde & de Rousiers 2014)")
    render_parser.add_argument("--transport", choices=["direct", "path"], default="direct", help="light transport")
    render_parser.add_argument("--max-depth", type=_count(0), default=None, help="scattering events per path")
    render_parser.add_argument("--spectral", action="store_true", help="hero-wavelength spectral rendering")
    render_parser.add_argument("--tonemap", choices=["aces", "reinhard", "linear", "film"], default=None,
                               help="display curve for PNG/JPEG output (default: aces, filmic)")
    render_parser.add_argument("--key", type=float, default=None,
                               help="automatic exposure's key: the log-average luminance shows as this grey "
                                    "(default 0.18; overrides --exposure/--ev100)")
    edit_parser = commands.add_parser("edit", help="solve a scene's atmosphere for point pairs (JSON)")
    edit_parser.add_argument("scene", type=Path, help="scene file (.toml) with an [atmosphere] table")
    edit_parser.add_argument("--pairs", type=Path, required=True, help="pairs file (.json), see refracta.edit.load_pairs")
    edit_parser.add_argument("-o", "--output", type=Path, required=True, help="scene file to write (.toml)")
    edit_parser.add_argument("--backend", default=None, help="ceres (default) or nlopt:<ALGORITHM>")
    args = parser.parse_args(argv)
    if args.command == "demo":
        return demo(args.out, args.size)
    if args.command == "render":
        return render_file(args.scene, args.output, args.method, args.size, args.spp, args.exposure, args.transport,
                           args.max_depth, args.spectral, args.tonemap, args.key, args.ev100)
    if args.command == "edit":
        return edit_file(args.scene, args.pairs, args.output, args.backend)
    parser.error(f"unknown command {args.command}")
    return 2


if __name__ == "__main__":
    sys.exit(main())
