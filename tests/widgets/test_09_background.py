"""A photograph as the editor's background (issue 20 section 4): the canvas shows it (with the
render's edges, blended, or alone) at the camera's pixels, and clicks on it place pairs there."""

import io

import numpy as np
import pytest

pytest.importorskip("anywidget", reason="the editor's view needs anywidget (pip install refracta[widgets])")

from PIL import Image

from refracta.widgets import MirageEditor

from .conftest import CAR, HEIGHT, WIDTH, truth_source

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
        stop_height=0.0,
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


HIDDEN_PITCH = 0.05  # [deg] how far the photograph's camera was tilted up from the editor's
PITCH_TOL = 1e-6  # [deg] exact pairs: the solve's misses of ~1e-7 m at 300 m are ~1e-8 deg


@pytest.mark.slow  # ~3.5 s: the solve, then the render of the solved view
def test_a_solve_with_the_camera_free_moves_the_editor_camera(make_model, road):
    """Pairs from a photograph whose camera was tilted: the editor solves the tilt with the air,
    adopts the solved camera, and undo brings the start camera back."""
    from ..edit.test_10_camera import _turn

    turn = _turn(road.camera, 0.0, HIDDEN_PITCH, 0.0)
    position = np.asarray(road.camera.position)
    hidden = type(road.camera)(
        position, position + 100.0 * turn((0, 0, 1)), turn((0, 1, 0)), road.camera.vfov, WIDTH, HEIGHT
    )
    truth = road.field.with_params(surface_dt=road.field.params["surface_dt"] + 2.0)
    model = make_model(free=["surface_dt", "camera_pitch"])
    for u, v, distance in ((160.0, 61.9, 350.0), (100.0, 63.4, 300.0), (220.0, 64.5, 250.0), (160.0, 50.0, 300.0)):
        model.add_pair((u, v), truth_source(truth, hidden, u, v, distance))
    model.solve()
    assert model.wait(WAIT)
    assert model.result.success, model.result.message
    assert model.camera is model.result.camera
    changes = {name: (start, solved, unit) for name, start, solved, unit in model.changed_parameters()}
    assert changes["camera_pitch"][0] == 0.0 and changes["camera_pitch"][2] == "deg"
    assert changes["camera_pitch"][1] == pytest.approx(HIDDEN_PITCH, abs=PITCH_TOL)
    model.undo()
    assert model.camera is road.camera
