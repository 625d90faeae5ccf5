"""The Jupyter view (MirageEditor) driven as the browser drives it: canvas messages, button clicks and
typed values reach the model; user mistakes become a message in the editor, never an exception."""

import numpy as np
import pytest

pytest.importorskip("anywidget", reason="the editor's view needs anywidget (pip install refracta[widgets])")

from refracta.widgets import MirageEditor

from .conftest import CAR, SKY, truth_source

WAIT = 120.0  # [s] bound on waiting for background work


@pytest.fixture
def editor(road):
    editor = MirageEditor(
        road.scene, road.camera, road.field, free=["surface_dt"], stop_height=0.0, max_length=road.max_length
    )
    yield editor
    editor.close()


def canvas_event(editor, event, **fields):
    """A message as canvas.js sends it."""
    editor._canvas._handle_message(editor._canvas, dict(event=event, **fields), [])


def click(editor, u, v, **fields):
    canvas_event(editor, "down", u=u, v=v, button=0, shift=False, scale=editor._canvas.scale, **fields)
    canvas_event(editor, "up", u=u, v=v)


def test_the_first_image_reaches_the_canvas_as_a_full_resolution_png(editor, road):
    assert editor.wait(WAIT)
    canvas = editor._canvas
    assert canvas.image[:8] == b"\x89PNG\r\n\x1a\n" and canvas.level == "full"
    assert (canvas.width, canvas.height) == (road.camera.width, road.camera.height)
    assert canvas.generation >= 2  # the preview, then the full image
    assert "full (320×120)" in editor._render_status.value


def test_two_clicks_on_the_canvas_add_a_pair_with_its_markers(editor):
    click(editor, *CAR)
    click(editor, 180.4, 66.0)
    assert "<b>1</b> pair" in editor._pair_count.value
    assert [m["kind"] for m in editor._canvas.markers] == ["source", "destination"]
    assert "Pair 0 added" in editor._message.value


def test_a_click_on_the_sky_shows_a_message_instead_of_raising(editor):
    click(editor, *SKY)
    assert "Nothing at pixel" in editor._message.value and "<b>0</b> pairs" in editor._pair_count.value


def pair_fields(editor, index=0):
    row = editor._pair_rows.children[index]
    return row.children[1], row.children[2]  # weight, margin (Text)


@pytest.mark.parametrize(
    "which, text, name", [(0, "nan", "pair 0 weight"), (1, "-1", "pair 0 margin"), (0, "heavy", "pair 0 weight")]
)
def test_a_bad_weight_or_margin_typed_in_the_list_is_named_and_undone(editor, which, text, name):
    editor.add_pair((180.4, 66.0), (258.0, 0.4, 1.7))
    field = pair_fields(editor)[which]
    field.value = text
    assert name in editor._message.value
    assert (editor.pairs[0].weight, editor.pairs[0].margin) == (1.0, 0.0)
    assert pair_fields(editor)[which].value in ("1", "0")  # the list shows the kept value again


def test_typed_weight_and_margin_change_the_pair(editor):
    editor.add_pair((180.4, 66.0), (258.0, 0.4, 1.7))
    weight, _ = pair_fields(editor)
    weight.value = "2.5"
    _, margin = pair_fields(editor)
    margin.value = "0.5"
    assert (editor.pairs[0].weight, editor.pairs[0].margin) == (2.5, 0.5)


def test_the_delete_button_and_undo(editor):
    editor.add_pair((180.4, 66.0), (258.0, 0.4, 1.7))
    delete = editor._pair_rows.children[0].children[4]
    delete.click()
    assert editor.pairs == []
    editor._undo.click()
    assert len(editor.pairs) == 1


def test_the_solve_button_shows_the_new_image_misses_parameters_and_ray_fan(editor, road):
    truth = road.field.with_params(surface_dt=16.0)
    for v in (61.9, 63.4):
        editor.add_pair((160.0, v), truth_source(truth, road.camera, 160.0, v))
    assert editor.wait(WAIT)
    generation = editor._canvas.generation
    editor._solve.click()
    assert editor.wait(WAIT)
    assert editor.result.success
    assert editor._canvas.generation >= generation + 2 and editor._canvas.level == "full"
    assert "surface_dt" in editor._result.value and "16" in editor._result.value
    assert editor._fan.value[:8] == b"\x89PNG\r\n\x1a\n"
    assert "met" in editor._pair_rows.children[0].children[-1].value
    assert editor._solve_progress.value == 1.0


def test_camera_mode_drag_and_numeric_fields_move_the_camera(editor, road):
    editor._mode.value = "camera"
    canvas_event(editor, "down", u=100.0, v=60.0, button=0, shift=False, scale=1.0)
    canvas_event(editor, "move", u=120.0, v=60.0)
    canvas_event(editor, "up", u=120.0, v=60.0)
    # Default rel 1e-6: the field shows the camera's coordinate (a float widget).
    assert editor._position[2].value == pytest.approx(float(editor.camera.position[2]))
    assert editor.camera.position[2] != road.camera.position[2]
    editor._position[1].value = 3.0
    assert editor.camera.position[1] == 3.0
    editor._vfov.value = -1.0
    assert "vfov" in editor._message.value and editor.camera.vfov == road.camera.vfov
    canvas_event(editor, "wheel", steps=1.0)
    # Hot_road's look-at is 300 m away: one wheel step brings the camera closer.
    assert np.linalg.norm(editor.camera.look_at - editor.camera.position) < 300.0


def test_the_straight_view_is_shown_on_demand(editor):
    assert editor._straight_box.layout.display == "none"
    editor._straight_toggle.value = True
    assert editor.wait(WAIT)
    assert editor._straight_box.layout.display == "flex"
    assert editor._straight.image[:8] == b"\x89PNG\r\n\x1a\n"


def test_file_buttons_save_and_load_and_report_a_missing_file(editor, tmp_path):
    editor._pairs_path.value = str(tmp_path / "missing.json")
    load = editor._tabs.children[3].children[1].children[2]
    load.click()
    assert "missing.json" in editor._message.value
    editor.add_pair((180.4, 66.0), (258.0, 0.4, 1.7))
    editor._pairs_path.value = str(tmp_path / "pairs.json")
    save = editor._tabs.children[3].children[1].children[1]
    save.click()
    assert (tmp_path / "pairs.json").exists() and "Wrote" in editor._message.value
    editor._free.value = ("surface_depth",)
    assert editor.model.free == ("surface_depth",)
    load.click()  # the file's free parameters come back with its pairs
    assert editor._free.value == ("surface_dt",) and "Loaded 1 pair" in editor._message.value


def test_an_editor_from_a_scene_file_exports_the_whole_file(tmp_path):
    import shutil
    from pathlib import Path

    import refracta

    data = Path(__file__).resolve().parent.parent / "data"
    for name in ("hot_road.toml", "tent.obj", "tent.mtl"):
        shutil.copy(data / name, tmp_path / name)
    editor = MirageEditor.from_file(tmp_path / "hot_road.toml", free=["surface_dt"], stop_height=0.0)
    try:
        editor.model.wheel(1.0)
        path = editor.export_scene(tmp_path / "edited.toml")
        scene, camera, field = refracta.load_scene(path)
        assert path.read_text().count("[[objects]]") == (data / "hot_road.toml").read_text().count("[[objects]]")
        np.testing.assert_array_equal(camera.position, editor.camera.position)
        assert field.params == editor.field.params
    finally:
        editor.close()
    no_air = tmp_path / "no_air.toml"
    no_air.write_text("[camera]\nposition = [0.0, 1.4, 0.0]\nlook_at = [300.0, 0.62, 0.0]\nsize = [96, 32]\n")
    with pytest.raises(ValueError, match="no \\[atmosphere\\]"):
        MirageEditor.from_file(no_air)


def test_camera_parameters_can_be_free_in_the_editor(road):
    """free=["surface_dt", "camera_pitch"] raised traitlets' "Invalid selection" (the list offered the
    field's parameters alone), and set_free with one left the widget and the model apart (a trial)."""
    editor = MirageEditor(
        road.scene, road.camera, road.field, free=["surface_dt", "camera_pitch"], stop_height=0.0,
        max_length=road.max_length,
    )  # fmt: skip
    try:
        assert editor._free.value == ("surface_dt", "camera_pitch")
        editor.model.set_free(["surface_depth", "camera_yaw"])
        assert editor._free.value == ("surface_depth", "camera_yaw") == tuple(editor.model.free)
    finally:
        editor.close()


def test_an_accepted_edit_clears_the_last_mistakes_message(editor):
    # A trial: after "weight must be > 0" and then an accepted weight, the red message stayed.
    editor.add_pair((180.4, 66.0), (258.0, 0.4, 1.7))
    pair_fields(editor)[0].value = "0"
    assert "pair 0 weight" in editor._message.value
    pair_fields(editor)[0].value = "2"
    assert editor.pairs[0].weight == 2.0 and "weight" not in editor._message.value


def test_a_refused_camera_value_shows_the_kept_camera_again(editor):
    # A trial: a NaN eye x stayed in its box, and every later camera edit was refused for it.
    x = editor._position[0]
    kept = x.value
    x.value = float("nan")
    assert "position" in editor._message.value
    assert x.value == kept
    editor._vfov.value = 30.0
    assert editor.model.camera.vfov == 30.0


def test_pickling_the_editor_is_refused_by_name(editor):
    # A live widget with a worker thread: the pickler's own error named a lambda inside it.
    import pickle

    with pytest.raises(TypeError, match=r"MirageEditor cannot be pickled .* editor.export_scene"):
        pickle.dumps(editor)
