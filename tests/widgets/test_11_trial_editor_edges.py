"""A technical artist's trial of the editor (7 December): a solve whose question changed while it
ran, a failed solve waited for, pairs loaded off the image, a pointer move without coordinates,
hot-spot toggles beside camera parameters, a refused camera, preview pixel bounds, a solve
superseded, a click in camera mode, a source dragged off the image, saving a Python-built scene."""

import threading

import pytest

from refracta import edit

from .conftest import CAR, HEIGHT, WIDTH, truth_source

WAIT = 120.0  # [s] bound on waiting for background work (a hang fails instead of blocking)


def held_solves(monkeypatch):
    """(started, release): edit.solve waits at its first progress report until release is set."""
    started, release = threading.Event(), threading.Event()
    real_solve = edit.solve

    def held_solve(*args, progress, **kwargs):
        def held(done, total):
            started.set()
            release.wait(WAIT)
            progress(done, total)

        return real_solve(*args, progress=held, **kwargs)

    monkeypatch.setattr(edit, "solve", held_solve)
    return started, release


def two_pairs(model, road):
    truth = road.field.with_params(surface_dt=16.0)
    for v in (61.9, 63.4):  # the mirage band below the horizon
        model.add_pair((160.0, v), truth_source(truth, road.camera, 160.0, v))


def test_a_solve_whose_pairs_were_undone_while_it_ran_is_dropped(make_model, road, monkeypatch):
    started, release = held_solves(monkeypatch)
    model = make_model()
    two_pairs(model, road)
    model.solve()
    assert started.wait(WAIT)
    model.undo()  # the second pair goes while the 2-pair solve runs
    release.set()
    assert model.wait(WAIT)
    assert model.field is road.field and model.result is None and len(model.pairs) == 1
    assert "changed while the solve ran" in model.message
    model.redo()  # the undone pair can still come back
    assert len(model.pairs) == 2


def test_solve_and_wait_returns_none_when_the_solve_fails(road):
    from refracta.widgets import MirageEditor

    editor = MirageEditor(road.scene, road.camera, road.field, free=["surface_dt"], stop_height=0.0)
    try:
        two_pairs(editor.model, road)
        first = editor.solve(wait=True)
        assert first is not None and first.success
        # A solve that raises in the worker (options changed behind the editor's checks): it fails,
        # and the result before it stays the editor's.
        editor.model.solve_options["max_iterations"] = 0
        assert editor.solve(wait=True) is None
        assert editor.model.result is first
    finally:
        editor.close()


def test_pairs_loaded_from_a_file_are_checked_on_the_image(make_model, tmp_path):
    model = make_model()
    path = tmp_path / "pairs.json"
    path.write_text('{"pairs": [{"destination": [89.0, 400.0], "source": [0.0, 1.0, -300.0]}]}')
    with pytest.raises(ValueError, match=rf"pair 0: pixel \(89.0, 400.0\) lies outside the {WIDTH} x {HEIGHT} image"):
        model.import_pairs(path)
    assert model.pairs == ()


def test_a_move_message_without_coordinates_is_ignored(road):
    from refracta.widgets import MirageEditor

    editor = MirageEditor(road.scene, road.camera, road.field)
    try:
        editor._pointer({"event": "down", "u": CAR[0], "v": CAR[1]})
        editor._pointer({"event": "move"})  # the browser's queued move after the button's release
        editor._pointer({"event": "up"})
        assert "Internal error" not in editor.model.message
    finally:
        editor.close()


def test_a_preview_cannot_take_the_full_images_pixel_bounds(make_model):
    with pytest.raises(ValueError, match="render_options: 'pixel_bounds' is the editor's to choose"):
        make_model(render_options={"pixel_bounds": (60, 20, 160, 60)})


def test_a_solve_superseded_by_another_does_not_say_cancelled(make_model, road, monkeypatch):
    started, release = held_solves(monkeypatch)
    model = make_model()
    two_pairs(model, road)
    said = []
    model.observe(lambda what: what == "message" and said.append(model.message))
    model.solve()
    assert started.wait(WAIT)
    model.solve()  # pressed again: supersedes the first
    release.set()
    assert model.wait(WAIT)
    assert not any("cancelled" in message for message in said)
    assert model.result is not None and model.result.success


def test_a_click_in_camera_mode_changes_nothing(make_model):
    model = make_model()
    model.set_mode("camera")
    camera = model.camera
    model.pointer_down(100.0, 50.0, 0, False, 1.0)
    model.pointer_up(100.0, 50.0)
    assert model.camera is camera and not model.can_undo


def test_a_dragged_source_stays_on_the_image(make_model, road):
    model = make_model()
    source = road.camera.pick(road.scene, *CAR)
    model.add_pair((CAR[0], 75.0), source)
    marker = next(m for m in model.markers() if m["kind"] == "source")
    model.pointer_down(marker["u"], marker["v"], 0, False, 1.0)
    model.pointer_move(marker["u"] - 400.0, marker["v"])  # far left of the image
    model.pointer_up()
    moved = next(m for m in model.markers() if m["kind"] == "source")
    assert 0.0 <= moved["u"] <= WIDTH  # the source is a point the image shows


def test_saving_a_python_built_scene_says_what_the_file_lacks(make_model, tmp_path):
    model = make_model()
    model.export_scene(tmp_path / "scene.toml")
    assert "built in Python" in model.message and model.message_kind == "error"
    model.import_scene(tmp_path / "scene.toml")  # render's hint, said in the editor (not on a worker's stderr)
    assert "the scene has no light and no sky" in model.message and model.message_kind == "error"
    assert model.wait(WAIT)
