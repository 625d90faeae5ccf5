"""The editor's image canvas: an anywidget whose front end (canvas.js beside this file) draws the
rendered PNG, the hot spots' outlines and the pairs' markers, and sends pointer events back in
image pixels."""

from __future__ import annotations

import io
from pathlib import Path
from typing import Callable

import anywidget
import numpy as np
import traitlets

__all__ = ["ImageCanvas", "png_bytes"]


def png_bytes(pixels: np.ndarray) -> bytes:
    """uint8 (H, W, 3) sRGB pixels as PNG bytes (fast compression: the browser is local)."""
    from PIL import Image

    buffer = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(pixels), "RGB").save(buffer, format="PNG", compress_level=1)
    return buffer.getvalue()


class ImageCanvas(anywidget.AnyWidget):
    """A rendered image with markers; pointer events go to on_pointer(message).

    Traits (synced with the browser): image (PNG bytes), width, height (the camera's image size:
    the coordinate space of markers and events), scale (display pixels per image pixel), markers
    (see EditorModel.markers), spots (hot-spot outlines drawn under the markers, see
    EditorModel.spot_outlines), interactive (False: no events), cursor (CSS), level ('preview' or
    'full') and generation (increases with each image; both mirrored into the canvas element's
    data-level and data-generation attributes).
    """

    _esm = (Path(__file__).with_name("canvas.js")).read_text(encoding="utf-8")
    _css = ".refracta-canvas { display: block; outline: none; touch-action: none; user-select: none; }"

    image = traitlets.Bytes(b"").tag(sync=True)
    width = traitlets.Int(1).tag(sync=True)
    height = traitlets.Int(1).tag(sync=True)
    scale = traitlets.Float(1.0).tag(sync=True)
    markers: traitlets.List[dict] = traitlets.List().tag(sync=True)
    spots: traitlets.List[dict] = traitlets.List().tag(sync=True)
    interactive = traitlets.Bool(True).tag(sync=True)
    cursor = traitlets.Unicode("crosshair").tag(sync=True)
    level = traitlets.Unicode("").tag(sync=True)
    generation = traitlets.Int(0).tag(sync=True)

    def __init__(self, on_pointer: Callable[[dict], None] | None = None, **kwargs):
        super().__init__(**kwargs)
        self._on_pointer = on_pointer
        self.on_msg(self._handle_message)

    def show(self, pixels: np.ndarray, level: str) -> None:
        """Show uint8 (H, W, 3) pixels (any size: the browser scales them to width x height)."""
        data = png_bytes(pixels)
        with self.hold_sync():
            self.image = data
            self.level = level
            self.generation = self.generation + 1

    def _handle_message(self, _widget, content, _buffers) -> None:
        if self._on_pointer is not None and isinstance(content, dict) and "event" in content:
            self._on_pointer(content)
