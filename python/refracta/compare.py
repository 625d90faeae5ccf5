"""refracta.compare: shadow and transparency methods measured against their references.

compare.shadows(scene, camera, methods, kernels) renders the sun's shadow intensity per pixel
(render_raster(output='shadow')) with each method and kernel and compares it with the reference:
Embree shadow rays for unfiltered (1 x 1) lookups and for 'hard' / 'pcf', and PCF with the same
kernel for filtered moment methods (Peters & Klein 2015: filtered MSM approximates filtered PCF).
compare.transparency(scene, camera, methods) composites the same rasterized fragments with each
OIT method and compares with the exact (sorted) composite.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import Any

import numpy as np

from refracta import _core
from refracta._checks import is_seed
from refracta._raster_render import render_raster, shadow_fields_for

__all__ = ["format_table", "shadows", "transparency"]

#: A pixel leaks light (or is over-shadowed) when its intensity is this much below (above) the
#: reference: a quarter of a 8-bit display's 64 levels, visible as a seam.
LEAK_THRESHOLD = 0.05


def _refuse_own(options: dict, own, where: str, source: str) -> None:
    """ValueError for a render keyword the comparison sets per render (it would be given twice, or
    silently overwritten)."""
    for name in own:
        if name in options:
            raise ValueError(f"{where}: {name}= is set per render from {source}; give those")


def _reference_of(method: str, kernel: int) -> str:
    return "embree" if kernel == 1 or method in ("hard", "pcf", "embree") else "pcf"


def shadows(
    scene: _core.Scene,
    camera: _core.Camera,
    methods: Sequence[str] = ("hard", "pcf", "vsm", "msm_hamburger", "msm_hausdorff"),
    kernels: Sequence[int] = (1, 5, 9),
    figure: bool = True,
    **options,
):
    """Each (method, kernel) against its reference.

    options go to render_raster (resolution, depth_range, storage, bias, ...). Returns (rows,
    fig): rows, one dict per method and kernel with method, kernel, reference, pixels (how many
    were compared: lit in both; none gives NaN errors), mean_error, p99_error, light_leak
    (fraction of lit-side pixels at least LEAK_THRESHOLD below the reference), over_shadow (the
    same above), nan_count, bits_per_texel, seconds; fig (when
    `figure`) shows, for the largest kernel, each method's shadow image and its error map.
    """
    _refuse_own(options, ("kernel", "shadows", "output", "return_stats"), "compare.shadows", "methods and kernels")
    methods = _sequence(methods, "methods", "names")
    kernels = _sequence(kernels, "kernels", "odd whole numbers of texels")
    if not all(is_seed(k) and k % 2 == 1 for k in kernels):  # before any render
        raise ValueError(f"kernels must be odd whole numbers of texels (got {kernels!r})")
    kernels = [int(k) for k in kernels]
    if not methods or not kernels:
        raise ValueError("methods and kernels must not be empty")
    if "none" in methods:  # it was compared as a 1x1 kernel against pcf 3x3
        raise ValueError("methods: 'none' casts no shadow to compare (give shadow-map methods, e.g. 'pcf')")
    references: dict[tuple, np.ndarray] = {}

    def reference(name: str, kernel: int) -> np.ndarray:
        key = (name, kernel if name == "pcf" else 1)
        if key not in references:
            fields = shadow_fields_for(name, dict(options, kernel=key[1]))
            references[key] = render_raster(scene, camera, shadows=name, output="shadow", **fields)
        return references[key]

    rows: list[dict] = []
    images: dict[tuple[str, int], tuple[np.ndarray, np.ndarray, int | None]] = {}
    for kernel in kernels:
        for method in methods:
            fields = shadow_fields_for(method, dict(options, kernel=kernel))
            if "kernel" not in fields and kernel != kernels[0]:  # hard: one map, whatever the kernel
                images[(method, kernel)] = images[(method, kernels[0])]
                continue
            image, counts = render_raster(scene, camera, shadows=method, output="shadow", return_stats=True, **fields)
            ref_name = _reference_of(method, kernel)
            truth = reference(ref_name, kernel)
            valid = (image[..., 1] > 0) & (truth[..., 1] > 0)
            error = image[..., 0][valid] - truth[..., 0][valid]
            finite = error[np.isfinite(error)]
            # No pixel sees a surface the light reaches (a camera on the sky): NaN, not a perfect 0.
            nothing = finite.size == 0
            rows.append(
                {
                    "method": method,
                    "kernel": fields.get("kernel", 1),
                    "reference": ref_name if ref_name == "embree" else f"pcf {kernel}x{kernel}",
                    "pixels": int(finite.size),
                    "mean_error": math.nan if nothing else float(np.abs(finite).mean()),
                    "p99_error": math.nan if nothing else float(np.quantile(np.abs(finite), 0.99)),
                    "light_leak": math.nan if nothing else float(np.mean(finite < -LEAK_THRESHOLD)),
                    "over_shadow": math.nan if nothing else float(np.mean(finite > LEAK_THRESHOLD)),
                    "nan_count": int(np.count_nonzero(~np.isfinite(image[..., 0]))),
                    "bits_per_texel": 8 * counts.bytes_per_texel,
                    "seconds": counts.seconds,
                }
            )
            images[(method, kernel)] = (image, truth, fields.get("kernel"))
    fig = _figure(images, methods, max(kernels)) if figure else None
    return rows, fig


#: Transparency methods of compare.transparency: name -> render_raster keyword arguments.
TRANSPARENCY_METHODS: dict[str, dict[str, Any]] = {
    "peel 2": dict(transparency="peel", layers=2),
    "peel 4": dict(transparency="peel", layers=4),
    "wboit eq7": dict(transparency="wboit", weight="eq7"),
    "wboit eq9": dict(transparency="wboit", weight="eq9"),
    "mboit 4": dict(transparency="mboit", moments=4),
    "mboit 6": dict(transparency="mboit", moments=6),
    "mboit 8": dict(transparency="mboit", moments=8),
    "mboit trig 2": dict(transparency="mboit", moments=2, basis="trigonometric"),
    "mboit trig 3": dict(transparency="mboit", moments=3, basis="trigonometric"),
    "mboit trig 4": dict(transparency="mboit", moments=4, basis="trigonometric"),
    "mboit 4 unorm16": dict(transparency="mboit", moments=4, oit_storage="unorm16"),
    "mboit 6 unorm16": dict(transparency="mboit", moments=6, oit_storage="unorm16"),
    "mboit 8 unorm16": dict(transparency="mboit", moments=8, oit_storage="unorm16"),
    "mboit trig 3 unorm16": dict(transparency="mboit", moments=3, basis="trigonometric", oit_storage="unorm16"),
}


def transparency(
    scene: _core.Scene,
    camera: _core.Camera,
    methods: Sequence[str] = tuple(TRANSPARENCY_METHODS),
    figure: bool = True,
    **options,
):
    """Each transparency method against the exact (sorted) composite of the same fragments.

    methods: names of TRANSPARENCY_METHODS. options go to render_raster (shadows, ...). Returns
    (rows, fig): rows with method, pixels (those transparency changes; none: NaN errors),
    mean_error and p99_error (per pixel, the largest channel's error relative to the exact
    pixel's brightest channel, over pixels with fragments), nan_count,
    bytes_per_pixel, seconds; fig shows the exact image and each method's error map.
    """
    own = {"transparency", "return_stats"}.union(*(TRANSPARENCY_METHODS[m] for m in TRANSPARENCY_METHODS))
    _refuse_own(options, sorted(own), "compare.transparency", "methods")
    methods = _sequence(methods, "methods", "names")
    if not methods:  # the figure's grid had no axes to index
        raise ValueError("methods must not be empty")
    unknown = [m for m in methods if m not in TRANSPARENCY_METHODS]
    if unknown:
        raise ValueError(f"unknown transparency methods {unknown} (expected some of {list(TRANSPARENCY_METHODS)})")
    exact, counts = render_raster(scene, camera, transparency="exact", return_stats=True, **options)
    opaque = render_raster(scene, camera, transparency=None, **options)
    covered = np.abs(exact - opaque).max(axis=2) > 0  # pixels whose colour transparency changes
    scale = np.maximum(exact.max(axis=2), 1e-6)
    rows, images = [], {}
    for method in methods:
        image, stats = render_raster(scene, camera, return_stats=True, **TRANSPARENCY_METHODS[method], **options)
        error = (np.abs(image - exact).max(axis=2) / scale)[covered]
        finite = error[np.isfinite(error)]
        rows.append(
            {
                "method": method,
                "pixels": int(finite.size),  # none: no transparent surface in view, errors NaN
                "mean_error": float(finite.mean()) if finite.size else math.nan,
                "p99_error": float(np.quantile(finite, 0.99)) if finite.size else math.nan,
                "nan_count": int(np.count_nonzero(~np.isfinite(image))),
                "bytes_per_pixel": stats.oit_bytes_per_pixel,
                "seconds": stats.seconds,
            }
        )
        images[method] = image
    rows.insert(
        0,
        {
            "method": "exact",
            "pixels": int(np.count_nonzero(covered)),
            # The reference's own error: 0 over the pixels compared, NaN over none (as the others').
            "mean_error": 0.0 if covered.any() else math.nan,
            "p99_error": 0.0 if covered.any() else math.nan,
            "nan_count": 0,
            "bytes_per_pixel": counts.oit_bytes_per_pixel,
            "seconds": counts.seconds,
        },
    )
    fig = None
    if figure:
        import matplotlib.pyplot as plt

        from refracta.io import to_display

        fig, axes = plt.subplots(1, len(methods) + 1, figsize=(2.8 * (len(methods) + 1), 2.6), constrained_layout=True)
        axes[0].imshow(to_display(exact))
        axes[0].set_title("exact (sorted)", fontsize=9)
        for ax, method in zip(axes[1:], methods):
            ax.imshow(np.abs(images[method] - exact).max(axis=2) / scale, cmap="magma", vmin=0, vmax=0.3)
            ax.set_title(f"{method}: error", fontsize=9)
        for ax in axes:
            ax.axis("off")
    return rows, fig


def _sequence(value, what: str, kind: str) -> list:
    """A sequence (of `kind`) as a list; ValueError for one string (it would be read letter by
    letter), one number or anything else."""
    if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
        raise ValueError(f"{what} must be a sequence of {kind}, as ({value!r},) (got {value!r})")
    return list(value)


def _figure(images, methods, kernel):
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, len(methods), figsize=(3.2 * len(methods), 4.6), squeeze=False, constrained_layout=True)
    for column, method in enumerate(methods):
        image, truth, used = images[(method, kernel)]  # used: the kernel it took (None: it takes none)
        axes[0, column].imshow(image[..., 0], cmap="gray_r", vmin=0, vmax=1)
        axes[0, column].set_title(method if used is None else f"{method} {used}x{used}", fontsize=9)
        error = np.where(image[..., 1] > 0, image[..., 0] - truth[..., 0], 0.0)
        shown = axes[1, column].imshow(error, cmap="RdBu_r", vmin=-0.5, vmax=0.5)
        axes[1, column].set_title("error (red: too dark)", fontsize=8)
        for ax in axes[:, column]:
            ax.axis("off")
    fig.colorbar(shown, ax=axes[1, :].tolist(), shrink=0.8, label="shadow - reference")
    return fig


# The columns format_table prints of each kind of row.
_TRANSPARENCY_COLUMNS = ("method", "mean_error", "p99_error", "nan_count", "bytes_per_pixel", "seconds")
_SHADOW_COLUMNS = (
    "method",
    "kernel",
    "reference",
    "mean_error",
    "p99_error",
    "light_leak",
    "over_shadow",
    "nan_count",
    "bits_per_texel",
    "seconds",
)


def _pixels(row: dict) -> str:
    """A row's count of compared pixels in its column ("-" for a row made without one)."""
    return f"{row['pixels']:7d}" if isinstance(row.get("pixels"), int) else f"{'-':>7s}"


def format_table(rows: Sequence[dict]) -> str:
    """The rows of shadows() or transparency() as aligned text."""
    shadow_rows = bool(rows) and isinstance(rows[0], dict) and "kernel" in rows[0]
    needed = _SHADOW_COLUMNS if shadow_rows else _TRANSPARENCY_COLUMNS
    for i, r in enumerate(rows):
        missing = [key for key in needed if not isinstance(r, dict) or key not in r]
        if missing:
            raise ValueError(
                f"format_table: rows[{i}] lacks {', '.join(map(repr, missing))}: give the rows of "
                "compare.shadows() or compare.transparency(), one kind at a time"
            )
    name = max([14] + [len(r["method"]) for r in rows])  # the widest method's name sets the column
    if not shadow_rows:
        lines = [
            f"{'method':{name}s} {'pixels':>7s} {'mean':>8s} {'p99':>8s} {'NaN':>4s} {'bytes/px':>9s} {'time [s]':>8s}"
        ]
        for r in rows:
            lines.append(
                f"{r['method']:{name}s} {_pixels(r)} {r['mean_error']:8.4f} {r['p99_error']:8.4f} "
                f"{r['nan_count']:4d} {r['bytes_per_pixel']:9.1f} {r['seconds']:8.3f}"
            )
        return "\n".join(lines)
    header = (
        f"{'method':{name}s} {'kernel':>6s} {'reference':>10s} {'pixels':>7s} {'mean':>8s} {'p99':>8s} {'leak':>7s} "
        f"{'over':>7s} {'NaN':>4s} {'bits':>5s} {'time [s]':>8s}"
    )
    lines = [header]
    for r in rows:
        lines.append(
            f"{r['method']:{name}s} {r['kernel']:6d} {r['reference']:>10s} {_pixels(r)} {r['mean_error']:8.4f} "
            f"{r['p99_error']:8.4f} {r['light_leak']:7.4f} {r['over_shadow']:7.4f} {r['nan_count']:4d} "
            f"{r['bits_per_texel']:5d} {r['seconds']:8.3f}"
        )
    return "\n".join(lines)
