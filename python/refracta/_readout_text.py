"""The text of render's per-pixel readouts at one pixel (refracta.widgets.show_readouts shows it
under the pointer, refracta.plot.readouts_figure in matplotlib's status bar)."""

from __future__ import annotations

import numpy as np

# How each readout is shown: its channels' labels, unit and decimals (names as render's aovs); a
# readout whose channels differ gives a unit and decimals per channel, each shown after its value.
_FORMATS: dict[str, tuple[tuple[str, ...], str | tuple[str, ...], int | tuple[int, ...]]] = {
    "distance": (("",), "m", 2),
    "position": (("x", "y", "z"), "m", 2),
    "object_id": (("",), "", 0),
    "geographic": (("lat", "lon", "height"), ("deg", "deg", "m"), (6, 6, 2)),  # 1e-6 deg: ~0.1 m
    "apparent_elevation": (("",), "deg", 5),
    "apparent_azimuth": (("",), "deg", 5),
    "true_elevation": (("",), "deg", 5),
    "hidden_height": (("geometric", "refracted"), "m", 3),
    "images": (("",), "", 0),
    "albedo": (("r", "g", "b"), "", 3),
    "normal": (("x", "y", "z"), "", 3),
}


def _format(name: str, channels: int) -> tuple[tuple[str, ...], str, tuple[str, ...], tuple[int, ...]]:
    """(labels, the unit after all values, the unit after each value, decimals per value)."""
    labels, unit, digits = _FORMATS.get(name, (tuple(str(c) for c in range(channels)), "", 4))
    if len(labels) != channels:
        labels, unit, digits = tuple(str(c) for c in range(channels)), "", 4
    each = unit if isinstance(unit, tuple) else ("",) * channels
    decimals = digits if isinstance(digits, tuple) else (digits,) * channels
    return labels, "" if isinstance(unit, tuple) else unit, each, decimals


def _planes(aovs: dict) -> list[tuple[str, np.ndarray]]:
    planes = []
    for name, values in aovs.items():
        array = np.asarray(values, dtype=np.float64)
        planes.append((name, array[..., None] if array.ndim == 2 else array))
    return planes


def checked_planes(aovs: dict, image, who: str) -> tuple[np.ndarray, list[tuple[str, np.ndarray]]]:
    """The image (H, W, >= 3) and its readouts' planes (name, (H, W, C)), each the image's size,
    else ValueError naming `who` and the readout: a hover would show another pixel's values."""
    pixels = np.asarray(image)
    if pixels.ndim != 3 or pixels.shape[2] < 3:
        raise ValueError(f"{who}: image must be (H, W, 3) (got shape {pixels.shape})")
    planes = _planes(aovs)
    for name, array in planes:
        if array.shape[:2] != pixels.shape[:2]:
            raise ValueError(f"{who}: aovs[{name!r}] is {array.shape[:2]}, the image {pixels.shape[:2]}")
    return pixels, planes


def readout_text(aovs: dict, u: float, v: float) -> str:
    """The readouts at image point (u, v) (pixels: u right, v down; pixel (i, j) covers
    [i, i + 1) x [j, j + 1)) as lines 'name: value unit': 'none' where a readout has no value (NaN:
    a sky pixel's position, elevations), 'inf' for a sky pixel's distance (its ray ran off). A point
    outside the image reads the nearest edge pixel (a pointer just past the edge), the line
    'pixel (i, j)' saying which."""
    if not (np.isfinite(u) and np.isfinite(v)):  # NaN said "cannot convert float NaN to integer"
        raise ValueError(f"readout_text: the image point must be finite (got u={u!r}, v={v!r})")
    planes = _planes(aovs)
    height, width = planes[0][1].shape[:2] if planes else (1, 1)
    i, j = min(max(int(np.floor(u)), 0), width - 1), min(max(int(np.floor(v)), 0), height - 1)
    lines = [f"pixel ({i}, {j})"]
    for name, array in planes:
        labels, unit, units, decimals = _format(name, array.shape[2])
        parts = []
        for label, value, own, digits in zip(labels, array[j, i], units, decimals):
            text = (
                "none"
                if np.isnan(value)
                else ("inf" if value > 0 else "-inf")
                if np.isinf(value)
                else f"{value:.{digits}f}" + (f" {own}" if own else "")
            )
            parts.append(f"{label} {text}" if label else text)
        met = not np.all(np.isnan(array[j, i]))  # "none", not "none deg"
        lines.append(f"{name}: {', '.join(parts)}" + (f" {unit}" if unit and met else ""))
    return "\n".join(lines)
