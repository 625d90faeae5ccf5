"""The editor model's background work: progressive renders that newer requests supersede, solves
that change the atmosphere (undoably), report unreachable destinations per pair and stop on cancel."""

import threading

import numpy as np
import pytest

import refracta
from refracta import edit

from .conftest import CAR, truth_source

WAIT = 120.0  # [s] bound on waiting for background work (a hang fails instead of blocking)
TRUTH_SURFACE_DT = 16.0  # [K] the atmosphere that meets the generated pairs exactly
RECOVERY_TOL = 1e-6  # [K] surface_dt recovered from exact pairs: the solve's misses are ~1e-7 m
IMAGE_CHANGE = 1e-3  # mean |difference| of display values in [0, 1] that counts as a new image
# (the hotter road moves the mirage band by pixels: measured ~1e-2)


def record_images(model):
    """A list that collects (level, shape) of each image the model shows."""
    shown = []
    model.observe(
        lambda what: (
            what == "image" and shown.append((model.images["curved"].level, model.images["curved"].pixels.shape))
        )
    )
    return shown


def test_the_quarter_resolution_preview_comes_before_the_full_image(make_model, road):
    model = make_model(autorender=True)
    shown = record_images(model)
    assert model.wait(WAIT)
    assert shown[-2:] == [
        ("preview", (road.camera.height // 4, road.camera.width // 4, 3)),
        ("full", (road.camera.height, road.camera.width, 3)),
    ]
    expected = refracta.render(road.scene, road.camera, road.field, max_length=road.max_length, progress=False)
    np.testing.assert_array_equal(model.images["curved"].linear, expected)  # the same render, same bits


def test_a_camera_move_supersedes_the_render_still_running(make_model, road):
    model = make_model()
    shown = record_images(model)
    model.render()
    model.wheel(1.0)  # a new view before the first full image can be done (~0.2 s)
    assert model.wait(WAIT)
    assert [level for level, _ in shown].count("full") == 1  # only the newest request finished
    expected = refracta.render(road.scene, model.camera, road.field, max_length=road.max_length, progress=False)
    np.testing.assert_array_equal(model.images["curved"].linear, expected)


def test_the_straight_view_renders_without_atmosphere_on_demand(make_model, road):
    model = make_model()
    model.set_show_straight(True)
    assert model.wait(WAIT)
    expected = refracta.render(
        road.scene, road.camera, None, method="straight", max_length=road.max_length, progress=False
    )
    np.testing.assert_array_equal(model.images["straight"].linear, expected)


@pytest.fixture
def reachable(make_model, road):
    """A model with three pairs that the hot road at TRUTH_SURFACE_DT meets exactly."""
    truth = road.field.with_params(surface_dt=TRUTH_SURFACE_DT)
    model = make_model()
    for v in (61.9, 63.4, 64.5):  # pixels of the mirage band below the horizon
        model.add_pair((160.0, v), truth_source(truth, road.camera, 160.0, v))
    return model


def test_a_solve_meets_reachable_pairs_and_shows_the_new_image(reachable, road):
    model = reachable
    model.render()
    assert model.wait(WAIT)
    before = model.images["curved"].pixels
    model.solve()
    assert model.wait(WAIT)
    result = model.result
    assert result.success and list(result.met) == [True, True, True]
    assert model.field is result.field
    assert model.field.params["surface_dt"] == pytest.approx(TRUTH_SURFACE_DT, abs=RECOVERY_TOL)
    assert model.changed_parameters()[0][:2] == ("surface_dt", road.field.params["surface_dt"])
    assert model.images["curved"].level == "full"
    assert np.abs(model.images["curved"].pixels / 255.0 - before / 255.0).mean() > IMAGE_CHANGE
    assert model.fan_png[:8] == b"\x89PNG\r\n\x1a\n"  # edit_report's figure: paths before and after
    assert model.message_kind == "success"
    assert all(marker["met"] for marker in model.markers())


def test_undo_of_a_solve_restores_the_start_atmosphere(reachable, road):
    model = reachable
    model.solve()
    assert model.wait(WAIT)
    solved = model.field
    model.undo()
    assert model.field is road.field and model.result is None
    model.redo()
    assert model.field is solved
    assert model.wait(WAIT)


def test_a_destination_no_atmosphere_can_reach_is_reported_per_pair(reachable, road):
    model = reachable
    model.add_pair((CAR[0], 5.0), road.camera.pick(road.scene, *CAR))  # the car's bottom up in the sky
    model.solve()
    assert model.wait(WAIT)
    result = model.result
    assert not result.success and not result.met[3]
    assert model.message_kind == "error" and "pair(s) 3" in model.message
    assert [m["met"] for m in model.markers() if m["pair"] == 3] == [False, False]


def test_cancel_stops_the_solve_and_changes_nothing(reachable, road, monkeypatch):
    started, release = threading.Event(), threading.Event()
    real_solve = edit.solve

    def held_solve(*args, progress, **kwargs):
        def held(done, total):  # the first report waits until the test has pressed cancel
            started.set()
            release.wait(WAIT)
            progress(done, total)

        return real_solve(*args, progress=held, **kwargs)

    monkeypatch.setattr(edit, "solve", held_solve)
    model = reachable
    model.solve()
    assert started.wait(WAIT)
    model.cancel()
    release.set()
    assert model.wait(WAIT)
    assert model.field is road.field and model.result is None
    assert "cancelled" in model.message


def test_a_solve_without_pairs_says_so(make_model):
    model = make_model()
    assert model.solve() is None
    assert model.message_kind == "error" and "Add at least one pair" in model.message


def test_a_solved_edit_that_one_pair_cannot_fix_says_it_is_not_unique(make_model, road):
    # One pair, two free parameters: the solve's summary said the solution is not unique (Jacobian
    # rank 1), the editor only "Solved: every pair met" -- and notebook 04 read its answer as the one.
    truth = road.field.with_params(surface_dt=TRUTH_SURFACE_DT)
    model = make_model(free=["surface_dt", "surface_depth"])
    model.add_pair((160.0, 63.4), truth_source(truth, road.camera, 160.0, 63.4))
    model.solve()
    assert model.wait(WAIT)
    assert model.result.success and "The solution is not unique" in model.result.message
    assert model.message_kind == "success"
    assert model.message.startswith("Solved: every pair met")
    assert "The solution is not unique: the pairs fix 1 of the 2" in model.message
    assert model.message.endswith("meet them as well.")
