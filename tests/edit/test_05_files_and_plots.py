"""The edit's file formats, command line and report figure."""

import json

import numpy as np
import pytest

import refracta
from refracta import cli, plot
from refracta.edit import PointPair, load_pairs, solve
from refracta.scene_file import atmosphere_table, with_atmosphere

DATA = __import__("pathlib").Path(__file__).parent.parent / "data"


@pytest.fixture(autouse=True)
def _assets(tmp_path):
    """Scene files written to tmp_path find the OBJ that hot_road.toml names beside them."""
    import shutil

    for name in ("tent.obj", "tent.mtl"):
        shutil.copy(DATA / name, tmp_path / name)


@pytest.mark.parametrize(
    "field",
    [
        refracta.PhysicalAtmosphere(surface_dt=7.5, humidity=0.3),
        refracta.LogisticProfile(k_s=12.0),
        refracta.TemperatureProfile([0.0, 10.0, 50.0], [280.0, 284.0, 283.0]),
        refracta.CurvedEarth(refracta.PhysicalAtmosphere(inversion_dt=4.0), 6.4e6),
    ],
)
def test_a_written_atmosphere_reads_back_identically(tmp_path, field):
    path = tmp_path / "scene.toml"
    path.write_text(with_atmosphere((DATA / "hot_road.toml").read_text(), field))
    _, _, loaded = refracta.load_scene(path)
    assert loaded.type_name == field.type_name
    assert loaded.params == field.params
    assert atmosphere_table(loaded) == atmosphere_table(field)


def test_cli_edit_writes_the_solved_scene(tmp_path):
    scene, camera, truth = refracta.load_scene(DATA / "hot_road.toml")
    # Sources on the true field's pixel rays 0.18-0.23 deg below the horizon, in the mirage band.
    entries = []
    for v in (16.5, 16.9, 17.2):
        origin, direction = camera.ray(48.0, v)
        source, _ = refracta.trace_ray(truth, origin, direction, tol=1e-10, max_length=400.0, stop_height=0.0).point_at(
            350.0
        )
        entries.append({"destination": [48.0, v], "source": list(source)})
    pairs_path = tmp_path / "pairs.json"
    pairs_path.write_text(json.dumps({"pairs": entries, "free": ["surface_dt"], "stop_height": 0.0}))
    start_scene = tmp_path / "start.toml"
    start_scene.write_text(with_atmosphere((DATA / "hot_road.toml").read_text(), truth.with_params(surface_dt=6.0)))
    out = tmp_path / "solved.toml"
    assert cli.main(["edit", str(start_scene), "--pairs", str(pairs_path), "-o", str(out)]) == 0
    _, _, solved = refracta.load_scene(out)
    assert solved.params["surface_dt"] == pytest.approx(10.0, rel=1e-6)
    assert "[[objects]]" in out.read_text()  # the rest of the scene is kept


def test_pairs_file_errors_name_the_file_and_pair(tmp_path):
    path = tmp_path / "pairs.json"
    path.write_text(json.dumps({"pairs": [{"destination": [1, 2, 3], "source": [1, "x", 3]}]}))
    with pytest.raises(ValueError, match=r"pairs.json: pairs\[0\]"):
        load_pairs(path)
    path.write_text("{ not json")
    with pytest.raises(ValueError, match="pairs.json:1: not valid JSON"):
        load_pairs(path)
    with pytest.raises(refracta.IoError, match="missing.json"):
        load_pairs(tmp_path / "missing.json")


def test_a_pixel_source_is_picked_from_the_scene(tmp_path):
    scene, camera, _ = refracta.load_scene(DATA / "hot_road.toml")
    path = tmp_path / "pairs.json"
    path.write_text(json.dumps({"pairs": [{"destination": [48, 20], "source": {"pixel": [48, 20]}}]}))
    pairs, _ = load_pairs(path, scene, camera)
    np.testing.assert_allclose(pairs[0].source, camera.pick(scene, 48, 20))


def test_a_pixel_source_off_the_image_or_no_pairs_is_refused_naming_the_file(tmp_path, capsys):
    # A trial: a source pixel (1e6, 1e6) was picked along the extrapolated ray (a point on the ground
    # by the camera), and `refracta edit` with no pairs said "pairs is empty" without the file (the
    # editor saves and loads an empty list: load_pairs takes it).
    scene, camera, _ = refracta.load_scene(DATA / "hot_road.toml")
    path = tmp_path / "pairs.json"
    for pixel in ([1e6, 1e6], [48, camera.height + 1]):
        path.write_text(json.dumps({"pairs": [{"destination": [48, 20], "source": {"pixel": pixel}}]}))
        with pytest.raises(ValueError, match=r"pairs.json: pairs\[0\]: source pixel .* lies outside the camera's"):
            load_pairs(path, scene, camera)
    path.write_text(json.dumps({"pairs": []}))
    assert load_pairs(path, scene, camera) == ([], {})
    assert cli.main(["edit", str(DATA / "hot_road.toml"), "--pairs", str(path), "-o", str(tmp_path / "x.toml")]) != 0
    assert "pairs.json: 'pairs' is empty" in capsys.readouterr().err


def test_edit_report_draws_paths_and_history(road_pairs):
    truth, eye, pairs = road_pairs
    result = solve(truth.with_params(surface_dt=8.0), eye, pairs, free=["surface_dt"], stop_height=0.0)
    figure = plot.edit_report(result)
    paths_axis, cost_axis = figure.axes
    assert len(paths_axis.lines) == 2 * len(pairs) + len(pairs) + 1  # before, after, sources, eye
    assert len(cost_axis.lines[0].get_ydata()) == len(result.history)
    # Ceres' history starts at its iteration 0: the curve runs 0 .. iterations of the last local
    # solve (it ran 1 .. iterations + 1, past the result's marker), ending where the result is drawn.
    steps = cost_axis.lines[0].get_xdata()
    assert steps[0] == 0 and steps[-1] == len(result.history) - 1
    assert cost_axis.lines[2].get_xdata()[0] == steps[-1]


def test_edit_report_of_many_pairs_keeps_its_legend_short(road_pairs):
    """40 pairs' legend lines covered the plot and ran off the figure, and matplotlib's constrained
    layout warned that it could not be applied (a trial): beyond 10 pairs one line stands for all."""
    import warnings

    truth, eye, pairs = road_pairs
    many = [PointPair(p.destination, p.source) for p in pairs for _ in range(12 // len(pairs) + 1)][:12]
    result = solve(truth.with_params(surface_dt=8.0), eye, many, free=["surface_dt"], stop_height=0.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the layout's warning, if any, fails here
        figure = plot.edit_report(result)
        figure.canvas.draw()
    labels = [text.get_text() for text in figure.axes[0].get_legend().get_texts()]
    assert labels[0].startswith("12 sources: largest miss") and len(labels) == 2  # and the eye
