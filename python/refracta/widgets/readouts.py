"""Hovering over a rendered image in Jupyter shows its per-pixel readouts (render(aovs=[...])):
``show_readouts(image, aovs)`` returns a small anywidget -- the image, and under the pointer the
values at that pixel, read in the browser from the readouts sent once (readouts.js beside this
file) -- and ``readout_text(aovs, u, v)`` is the same text in Python (for a script, a test, or
matplotlib's status bar: refracta.plot.readouts_figure)."""

from __future__ import annotations

from pathlib import Path

import anywidget
import numpy as np
import traitlets

from refracta import io
from refracta._readout_text import _format, checked_planes, readout_text
from refracta.widgets.canvas import png_bytes

__all__ = ["ReadoutViewer", "readout_text", "show_readouts"]


class ReadoutViewer(anywidget.AnyWidget):
    """The image and, under the pointer, its readouts (see the module). Traits: image (PNG bytes),
    width, height, scale (display pixels per image pixel), values (float32 bytes of the readouts,
    H x W x channels), layout (each readout's offset, labels, unit, decimals) and text (the last
    readout shown)."""

    _esm = (Path(__file__).with_name("readouts.js")).read_text(encoding="utf-8")

    image = traitlets.Bytes(b"").tag(sync=True)
    width = traitlets.Int(1).tag(sync=True)
    height = traitlets.Int(1).tag(sync=True)
    scale = traitlets.Float(1.0).tag(sync=True)
    values = traitlets.Bytes(b"").tag(sync=True)
    layout: traitlets.List[dict] = traitlets.List().tag(sync=True)
    text = traitlets.Unicode("").tag(sync=True)


def show_readouts(
    image: np.ndarray, aovs: dict, scale: float | None = None, exposure: float | None = None
) -> ReadoutViewer:
    """A ReadoutViewer of a render's image (linear HDR, shown through refracta.io.to_display with
    `exposure`, None: automatic) and its readouts (render's second result). scale: display pixels
    per image pixel (None: the image about 640 pixels wide)."""
    pixels, planes = checked_planes(aovs, image, "show_readouts")
    height, width = pixels.shape[:2]
    layout, offset = [], 0
    for name, array in planes:
        labels, unit, units, digits = _format(name, array.shape[2])
        layout.append(
            {
                "name": name,
                "offset": offset,
                "labels": list(labels),
                "unit": unit,
                "units": list(units),
                "digits": list(digits),
            }
        )
        offset += array.shape[2]
    stacked = np.concatenate([a for _, a in planes], axis=2) if planes else np.zeros((height, width, 0))
    display = np.clip(io.to_display(pixels[..., :3], exposure=exposure) * 255.0 + 0.5, 0, 255).astype(np.uint8)
    return ReadoutViewer(
        image=png_bytes(display),
        width=width,
        height=height,
        scale=scale if scale is not None else max(1.0, 640.0 / width),
        values=np.ascontiguousarray(stacked, dtype="<f4").tobytes(),
        layout=layout,
        text=readout_text(aovs, 0.5 * width, 0.5 * height),
    )
