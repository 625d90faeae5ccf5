"""A photograph as the editor's background (issue 20 section 4): the canvas shows it (with the
render's edges, blended, or alone) at the camera's pixels, and clicks on it place pairs there."""

import io

import numpy as np
import pytest

pytest.importorskip("anywidget", reason="the editor's view needs anywidget (pip install refracta[widgets])")

from PIL import Image

from refracta.widgets import MirageEditor

from .conftest import CAR, HEIGHT, WIDTH

WAIT = 120.0  # [s] bound on waiting for background work
QUANTUM = 1  # [8-bit levels] the canvas PNG holds display values rounded to 8 bits


def _photograph():
    """A synthetic 'photograph' at twice the camera's size: a horizontal ramp, its top half darker."""
    ramp = np.linspace(0.1, 0.9, 2 * WIDTH, dtype=np.float32)
    image = np.repeat(np.repeat(ramp[None, :, None], 2 * HEIGHT, axis=0), 3, axis=2)
    image[:HEIGHT] *= 0.5
    return image


def _canvas_pixels(editor):
    return np.asarray(Image.open(io.BytesIO(editor._canvas.image)).convert("RGB"), dtype=np.int64)


@pytest.mark.slow  # ~3 s: the editor renders the road at full resolution
def test_the_photograph_is_the_image_to_click_on(road):
    photograph = _photograph()
    editor = MirageEditor(
        road.scene,
        road.camera,
        road.field,
        free=["surface_dt"],
        ground=0.0,
        max_length=road.max_length,
        background=photograph,
    )
    try:
        assert editor.wait(WAIT)
        # 'edges': the photograph (resampled to the camera's pixels) wherever the render has no edge.
        shown = _canvas_pixels(editor)
        expected = np.round(photograph[1::2, 1::2] * 255.0).astype(np.int64)  # nearest of 2x2: the lower right
        red = (shown[..., 0] == 255) & (shown[..., 1] == 0) & (shown[..., 2] == 0)
        assert 0 < red.sum() < red.size // 4  # some edges are drawn, most of the image is the photograph
        plain = ~red
        assert np.abs(shown[plain] - expected[plain]).max() <= QUANTUM
        editor.set_background(photograph, mode="photo")
        assert np.abs(_canvas_pixels(editor) - expected).max() <= QUANTUM
        # A click on the photograph: source on the car, destination at the clicked pixel.
        for u, v in (CAR, (180.4, 66.0)):
            editor._canvas._handle_message(
                editor._canvas, dict(event="down", u=u, v=v, button=0, shift=False, scale=editor._canvas.scale), []
            )
            editor._canvas._handle_message(editor._canvas, dict(event="up", u=u, v=v), [])
        assert editor.model.pairs[0].destination == (180.4, 66.0)
        with pytest.raises(ValueError, match="not the camera's aspect"):
            editor.set_background(photograph[:, :WIDTH])
        with pytest.raises(ValueError, match="mode must be"):
            editor.set_background(photograph, mode="sum")
        editor.set_background(None)  # the render alone again
        np.testing.assert_array_equal(_canvas_pixels(editor), editor.model.images["curved"].pixels)
    finally:
        editor.close()
