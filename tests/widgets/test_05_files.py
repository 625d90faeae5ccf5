"""The editor's files: pairs as `refracta edit --pairs` JSON, the scene as TOML with the editor's
camera and atmosphere; both read back by the library and the command line, and imported again."""

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

import refracta
from refracta import cli
from refracta.edit import load_pairs
from refracta.scene_file import with_atmosphere, with_camera
from refracta.widgets import EditorModel

from .conftest import truth_source

DATA = Path(__file__).resolve().parent.parent / "data"
WAIT = 120.0  # [s] bound on waiting for a background solve


@pytest.fixture
def scene_file(tmp_path):
    """tests/data/hot_road.toml (96 x 32) in tmp_path with its OBJ, the road 6 K warm instead of 10."""
    for name in ("tent.obj", "tent.mtl"):
        shutil.copy(DATA / name, tmp_path / name)
    _, _, truth = refracta.load_scene(DATA / "hot_road.toml")
    path = tmp_path / "start.toml"
    path.write_text(with_atmosphere((DATA / "hot_road.toml").read_text(), truth.with_params(surface_dt=6.0)))
    return path, truth


@pytest.fixture
def file_model(scene_file):
    path, _ = scene_file
    scene, camera, field = refracta.load_scene(path)
    model = EditorModel(
        scene, camera, field, ["surface_dt"], stop_height=0.0, scene_text=path.read_text(), autorender=False
    )
    yield model
    model.close()


def test_exported_pairs_read_back_with_weight_margin_and_options(file_model, tmp_path):
    model = file_model
    model.add_pair((48.0, 16.5), (350.0, 0.2, 0.0), weight=2.5, margin=0.75)
    model.add_pair((40.0, 17.0), (350.0, 0.1, 1.0))
    path = model.export_pairs(tmp_path / "pairs.json")
    pairs, options = load_pairs(path)
    assert pairs == list(model.pairs)
    assert options == {"free": ["surface_dt"], "stop_height": 0.0}
    assert json.loads(path.read_text())["pairs"][0]["margin"] == 0.75


def test_the_exported_scene_has_the_editor_camera_and_atmosphere_and_keeps_the_rest(file_model, tmp_path):
    model = file_model
    model.wheel(1.0)
    model.field = model.field.with_params(surface_dt=12.5)  # as a solve leaves it
    path = model.export_scene(tmp_path / "edited.toml")
    scene, camera, field = refracta.load_scene(path)
    assert field.params == model.field.params
    for name in ("position", "look_at", "up"):
        np.testing.assert_array_equal(getattr(camera, name), getattr(model.camera, name))
    assert (camera.vfov, camera.width, camera.height) == (model.camera.vfov, model.camera.width, model.camera.height)
    assert path.read_text().count("[[objects]]") == (DATA / "hot_road.toml").read_text().count("[[objects]]")


def test_the_command_line_solves_the_exported_files_as_the_editor_did(file_model, scene_file, tmp_path):
    model = file_model
    _, truth = scene_file
    for v in (16.5, 16.9, 17.2):  # the 10 K road's pixel rays in the mirage band
        model.add_pair((48.0, v), truth_source(truth, model.camera, 48.0, v))
    scene_path, pairs_path = model.export_scene(tmp_path / "scene.toml"), model.export_pairs(tmp_path / "pairs.json")
    model.solve()
    assert model.wait(WAIT) and model.result.success
    out = tmp_path / "solved.toml"
    assert cli.main(["edit", str(scene_path), "--pairs", str(pairs_path), "-o", str(out)]) == 0
    _, _, solved = refracta.load_scene(out)
    assert solved.params == model.field.params  # the same problem: the same bits


def test_imported_pairs_and_scene_replace_the_editor_state_undoably(file_model, tmp_path):
    model = file_model
    pairs_path = tmp_path / "pairs.json"
    pairs_path.write_text(
        json.dumps(
            {
                "pairs": [{"destination": [48, 16], "source": {"pixel": [60, 18]}, "weight": 3.0, "margin": 1.0}],
                "free": ["surface_depth"],
                "stop_height": 0.0,
            }
        )
    )
    model.import_pairs(pairs_path)
    (pair,) = model.pairs
    np.testing.assert_array_equal(pair.source, model.camera.pick(model.scene, 60, 18))
    assert (pair.weight, pair.margin, model.free) == (3.0, 1.0, ("surface_depth",))
    other = tmp_path / "other.toml"
    moved = refracta.Camera((0.0, 2.0, 0.0), (300.0, 0.62, 0.0), vfov=2.2, width=96, height=32)
    other.write_text(with_camera((tmp_path / "start.toml").read_text(), moved))
    model.import_scene(other)
    np.testing.assert_array_equal(model.camera.position, (0.0, 2.0, 0.0))
    assert model.scene_text == other.read_text()
    model.undo()
    assert model.camera.position[1] == 1.4
    model.undo()
    assert model.pairs == ()


def test_a_scene_given_as_objects_exports_its_camera_and_atmosphere(make_model, tmp_path):
    model = make_model()
    path = model.export_scene(tmp_path / "scene.toml")
    _, camera, field = refracta.load_scene(path)
    assert field.params == model.field.params and field.type_name == model.field.type_name
    np.testing.assert_array_equal(camera.position, model.camera.position)
    assert "from a Scene object" in path.read_text()


def test_file_errors_name_the_file(file_model, tmp_path):
    with pytest.raises(refracta.IoError, match="missing.json"):
        file_model.import_pairs(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"pairs": [{"destination": [1, 2], "source": [1, 2, 3], "margin": -1}]}))
    with pytest.raises(ValueError, match=r"bad.json: pairs\[0\].*margin"):
        file_model.import_pairs(bad)
    with pytest.raises(refracta.IoError, match="no_such_folder"):
        file_model.export_pairs(tmp_path / "no_such_folder" / "pairs.json")


def test_ground_is_the_deprecated_spelling_of_stop_height(make_model, tmp_path):
    """Issue 22 item 3: stop_height is the name; ground= and the pairs file's "ground" still work for
    one release, each with a DeprecationWarning naming the new name."""
    with pytest.warns(DeprecationWarning, match="ground= is deprecated; call it stop_height="):
        model = make_model(stop_height=None, ground=-1.0)
    assert model.stop_height == -1.0
    with pytest.raises(ValueError, match="pass stop_height= only"):
        make_model(ground=-1.0)  # make_model gives stop_height=0.0 as well
    pairs_path = tmp_path / "old.json"
    pairs_path.write_text(json.dumps({"pairs": [{"destination": [1, 2, 3], "source": [4, 5, 6]}], "ground": 0.5}))
    with pytest.warns(DeprecationWarning, match='"ground" is deprecated; call it "stop_height"'):
        _, options = load_pairs(pairs_path)
    assert options == {"stop_height": 0.5}
    pairs_path.write_text(json.dumps({"pairs": [], "ground": 0.5, "stop_height": 0.5}))
    with pytest.raises(ValueError, match='give "stop_height" only'):
        load_pairs(pairs_path)
