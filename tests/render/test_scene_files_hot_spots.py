"""Scene files with areal hot spots ([[atmosphere.hot_spots]]) and turbulence
([atmosphere.turbulence]): written by atmosphere_table / with_atmosphere, read back by load_scene
as the same field (the same index at every point), mistakes named by file, line and key, and the
command line's edit moving a spot."""

import json
import pickle
import shutil
from pathlib import Path

import numpy as np
import pytest

import refracta
from refracta import cli
from refracta.scene_file import atmosphere_table, camera_table, with_atmosphere, with_camera

DATA = Path(__file__).resolve().parents[1] / "data"
ROAD = dict(surface_dt=10.0, surface_depth=0.1)
CELLS = 16  # a small grid: synthesised in ~20 ms (the default 256^3 takes ~2 s)
SPOT_REL = 1e-6  # a spot's centre solved from exact pairs: misses of < 1e-12 m pin it far tighter
CAMERA = "[camera]\nposition = [0, 1, 0]\nlook_at = [10, 1, 0]\nsize = [8, 4]\n"


@pytest.fixture
def road_text(tmp_path):
    """tests/data/hot_road.toml's text, its OBJ copied beside tmp_path's scene files."""
    for name in ("tent.obj", "tent.mtl"):
        shutil.copy(DATA / name, tmp_path / name)
    return (DATA / "hot_road.toml").read_text()


def points_near_the_road():
    """Points over the spots and the turbulence's layer: 0-300 m out, 0-1 m up, +-10 m across."""
    return np.random.default_rng(7).uniform([0.0, 0.0, -10.0], [300.0, 1.0, 10.0], (400, 3))


def read_back(tmp_path, text):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return refracta.load_scene(path)


@pytest.mark.parametrize(
    "field",
    [
        refracta.PhysicalAtmosphere(
            **ROAD,
            hot_spots=[
                refracta.HotSpot(120.0, -2.0, 6.0, 8.0, depth=0.25),
                refracta.HotSpot(200.0, 3.0, 4.0, -3.0, footprint="compact"),
            ],
        ),
        refracta.LogisticProfile(k_s=12.0, hot_spots=[refracta.HotSpot(40.0, 1.0, 3.0, 0.6, footprint="compact")]),
    ],
    ids=["physical-two-spots", "logistic-one-spot"],
)
def test_hot_spots_read_back_as_the_same_field(tmp_path, road_text, field):
    loaded = read_back(tmp_path, with_atmosphere(road_text, field)).field
    assert loaded.hot_spots == field.hot_spots  # centre, radius, dt, depth and footprint
    assert loaded.params == field.params
    points = points_near_the_road()
    np.testing.assert_array_equal(loaded.ior(points), field.ior(points))
    assert atmosphere_table(loaded) == atmosphere_table(field)


def test_spots_are_written_as_entries_with_their_current_values(road_text):
    field = refracta.PhysicalAtmosphere(**ROAD, hot_spots=[refracta.HotSpot(120.0, 0.0, 6.0, 8.0)])
    moved = field.with_params(hot_spot0_x=135.5)  # as a solve leaves it
    table = atmosphere_table(moved)
    assert "hot_spot0" not in table
    assert "[[atmosphere.hot_spots]]\nx = 135.5\nz = 0.0\nradius = 6.0\ndt = 8.0\ndepth = 0.1\n" in table


def test_turbulence_reads_back_as_the_same_pattern(tmp_path, road_text):
    air = refracta.Turbulence(1e-10, seed=5, cells=CELLS, wind=(0.5, 2.0), depth=0.2).at_time(0.7)
    field = refracta.PhysicalAtmosphere(
        **ROAD, hot_spots=[refracta.HotSpot(120.0, 0.0, 6.0, 8.0)], turbulence=air.layer
    )
    loaded = read_back(tmp_path, with_atmosphere(road_text, field, turbulence=air))
    # A new Turbulence, synthesised again from the settings: the same noise from the same seed.
    assert loaded.turbulence is not air
    settings = ("cn2", "outer_scale", "inner_scale", "seed", "wind", "spacing", "cells", "depth", "yaw", "time")
    assert [getattr(loaded.turbulence, s) for s in settings] == [getattr(air, s) for s in settings]
    assert loaded.field.turbulence is loaded.turbulence.layer
    points = points_near_the_road()
    assert np.ptp(field.ior(points) - field.height_only_part.ior(points)) > 0.0  # the spot and the turbulence show
    np.testing.assert_array_equal(loaded.field.ior(points), field.ior(points))
    assert atmosphere_table(loaded.field, loaded.turbulence) == atmosphere_table(field, air)


def test_uniform_turbulence_in_a_logistic_profile_reads_back(tmp_path, road_text):
    air = refracta.Turbulence(1e-9, seed=2, cells=CELLS, depth=None)  # no envelope: written as depth = inf
    field = refracta.LogisticProfile(turbulence=air.layer)
    loaded = read_back(tmp_path, with_atmosphere(road_text, field, air))
    assert loaded.turbulence.depth is None
    points = points_near_the_road()
    np.testing.assert_array_equal(loaded.field.ior(points), field.ior(points))


def test_a_field_with_turbulence_needs_the_turbulence_it_carries():
    air = refracta.Turbulence(1e-10, seed=5, cells=CELLS)
    field = refracta.PhysicalAtmosphere(**ROAD, turbulence=air.layer)
    with pytest.raises(ValueError, match="pass turbulence="):
        atmosphere_table(field)
    with pytest.raises(ValueError, match="not the refracta.Turbulence whose layer the field carries"):
        atmosphere_table(field, refracta.Turbulence(1e-10, seed=6, cells=CELLS))
    with pytest.raises(ValueError, match="not the refracta.Turbulence"):
        atmosphere_table(field, air.at_time(1.0))  # carried elsewhere by the wind
    with pytest.raises(ValueError, match="the field carries none"):
        atmosphere_table(refracta.PhysicalAtmosphere(**ROAD), air)
    # A pickled copy of the field (a dask worker's) still matches: same grid, same values.
    assert atmosphere_table(pickle.loads(pickle.dumps(field)), air) == atmosphere_table(field, air)


def test_turbulence_yaw_is_written_in_degrees_and_the_old_radians_key_still_reads(tmp_path):
    air = refracta.Turbulence(1e-10, seed=5, cells=CELLS, yaw_deg=20.0)
    table = atmosphere_table(refracta.PhysicalAtmosphere(**ROAD, turbulence=air.layer), air)
    assert "yaw_deg = 20.0" in table and "\nyaw =" not in table
    base = CAMERA + "[atmosphere]\n\n[atmosphere.turbulence]\ncells = 16\nseed = 5\n"
    with pytest.warns(DeprecationWarning, match="yaw_deg"):
        old = read_back(tmp_path, base + "yaw = 0.3\n").turbulence
    new = read_back(tmp_path, base + f"yaw_deg = {float(np.degrees(0.3))!r}\n").turbulence
    assert old.yaw_deg == new.yaw_deg and old.layer.yaw == new.layer.yaw
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match=r":10: .*yaw: give yaw_deg or"):
        read_back(tmp_path, base + "yaw = 0.3\nyaw_deg = 10.0\n")


def test_rewriting_replaces_every_sub_table_and_keeps_the_rest(tmp_path, road_text):
    air = refracta.Turbulence(1e-10, seed=5, cells=CELLS)
    spotted = refracta.PhysicalAtmosphere(
        **ROAD, hot_spots=[refracta.HotSpot(120.0, 0.0, 6.0, 8.0)] * 2, turbulence=air.layer
    )
    text = with_atmosphere(road_text, spotted, air)
    # TOML lets a sub-table stand away from its parent: the turbulence moved below [sky].
    turbulence = text[text.index("[atmosphere.turbulence]") : text.index("[sun]")]
    text = text.replace(turbulence, "").replace("[[objects]]", turbulence + "[[objects]]", 1)
    assert read_back(tmp_path, text).turbulence.seed == 5
    plain = refracta.PhysicalAtmosphere(surface_dt=4.0)
    rewritten = with_atmosphere(text, plain)
    assert "atmosphere." not in rewritten and rewritten.count("[atmosphere]") == 1
    assert rewritten.count("[[objects]]") == road_text.count("[[objects]]") and "[sky]" in rewritten
    loaded = read_back(tmp_path, rewritten)
    assert loaded.field.params == plain.params and loaded.turbulence is None


def test_with_camera_replaces_the_file_camera_or_puts_one_first(tmp_path, road_text):
    """The [camera] table goes through the same table surgery as [atmosphere]."""
    camera = refracta.Camera((0.0, 2.0, 0.0), (300.0, 0.6, 0.0), vfov=2.5, width=48, height=16)
    text = with_camera(road_text, camera)
    loaded = read_back(tmp_path, text).camera
    for name in ("position", "look_at", "up"):
        np.testing.assert_array_equal(getattr(loaded, name), getattr(camera, name))
    assert (loaded.vfov, loaded.width, loaded.height) == (2.5, 48, 16)
    assert text.startswith("# A small hot-road scene")  # the comment before it kept
    assert with_camera(text, camera) == text
    assert with_camera(text.replace(camera_table(camera), ""), camera).startswith("[camera]\n")


def test_a_scene_file_unpacks_as_three_and_pickles_with_its_turbulence(tmp_path, road_text):
    air = refracta.Turbulence(1e-10, seed=5, cells=CELLS)
    loaded = read_back(tmp_path, with_atmosphere(road_text, refracta.PhysicalAtmosphere(turbulence=air.layer), air))
    scene, camera, field = loaded
    assert (loaded.scene, loaded.camera, loaded.field) == (scene, camera, field)
    copy = pickle.loads(pickle.dumps(loaded))
    assert copy.turbulence.seed == 5 and len(copy) == 3
    points = points_near_the_road()
    np.testing.assert_array_equal(copy.field.ior(points), field.ior(points))


SPOT = "[atmosphere]\nsurface_dt = 5\n\n[[atmosphere.hot_spots]]\nx = 50\nz = 0\nradius = 3\ndt = 4\n"


@pytest.mark.parametrize(
    "text, message",
    [
        (CAMERA + SPOT.replace("radius = 3\n", ""), r":8: \[\[atmosphere.hot_spots\]\] #1 radius: missing"),
        (
            CAMERA + SPOT.replace("radius = 3", "radius = 0"),
            r":11: \[\[atmosphere.hot_spots\]\] #1 radius: HotSpot: radius must be >= 0.001 m \(got 0\)",
        ),
        (
            CAMERA + SPOT + "\n[[atmosphere.hot_spots]]\nx = 9\nz = 0\nradius = -2\ndt = 1\n",
            r":17: \[\[atmosphere.hot_spots\]\] #2 radius: HotSpot: radius must be >= 0.001 m",
        ),
        (
            CAMERA + SPOT + "footprint = 'square'\n",
            r":13: \[\[atmosphere.hot_spots\]\] #1 footprint: HotSpot: footprint must be 'gaussian' or 'compact'",
        ),
        (
            CAMERA + SPOT + "radious = 4\n",
            r":13: \[\[atmosphere.hot_spots\]\] #1 radious: unknown key for a hot spot \(did you mean radius\?",
        ),
        (CAMERA + SPOT.replace("x = 50", "x = '50'"), r":9: \[\[atmosphere.hot_spots\]\] #1 x: must be a number"),
        (
            CAMERA + SPOT.replace("surface_dt = 5", "model = 'LogisticProfile'") + "depth = 0.2\n",
            r":13: \[\[atmosphere.hot_spots\]\] #1 depth: LogisticProfile: hot_spots\[0\] has depth 0.2",
        ),
        (
            CAMERA + "[atmosphere]\nmodel = 'LinearSquaredProfile'\n\n[[atmosphere.hot_spots]]\nx = 1\n",
            r":8: \[\[atmosphere.hot_spots\]\] #1: LinearSquaredProfile takes no hot spots",
        ),
        (
            CAMERA + "[atmosphere]\nhot_spot0_x = 50\n",
            r":6: \[atmosphere\] hot_spot0_x: a hot spot is an \[\[atmosphere.hot_spots\]\] entry",
        ),
        (
            CAMERA + "[atmosphere]\nhot_spots = [{x = 1, z = 2, radius = 3, dt = 4, width = 1}]\n",
            r":6: \[\[atmosphere.hot_spots\]\] #1 width: unknown key for a hot spot",
        ),
        (
            CAMERA + "[atmosphere]\n\n[atmosphere.turbulence]\ncells = 16\nseeed = 3\n",
            r":9: \[atmosphere.turbulence\] seeed: unknown key for \[atmosphere.turbulence\] \(did you mean seed\?",
        ),
        (
            CAMERA + "[atmosphere]\n\n[atmosphere.turbulence]\ncells = 16\ncn2 = -1e-10\n",
            r":9: \[atmosphere.turbulence\] cn2: Turbulence: cn2 must be in \[0, 1\]",
        ),
        (
            CAMERA + "[atmosphere]\n\n[atmosphere.turbulence]\ncells = 16.5\n",
            r":8: \[atmosphere.turbulence\] cells: must be a whole number",
        ),
    ],
    ids=[
        "missing-radius",
        "zero-radius",
        "negative-radius-second-entry",
        "unknown-footprint",
        "unknown-key",
        "string-number",
        "logistic-depth",
        "model-without-spots",
        "parameter-name-as-key",
        "inline-unknown-key",
        "turbulence-unknown-key",
        "turbulence-bad-value",
        "turbulence-fractional-cells",
    ],
)
def test_malformed_spots_and_turbulence_name_file_line_and_key(tmp_path, text, message):
    with pytest.raises(ValueError, match=r"scene.toml" + message):
        read_back(tmp_path, text)


def test_the_command_line_edit_moves_a_hot_spot(tmp_path, road_text):
    """`refracta edit` with "free": ["hot_spot0_x"]: pairs made by a spot at x = 150 m move a
    spot written 10 m nearer back there, and the solved file keeps the spot's other numbers."""
    scene, camera, road = read_back(tmp_path, road_text)
    truth = refracta.PhysicalAtmosphere(**road.params, hot_spots=[refracta.HotSpot(150.0, 0.0, 8.0, 15.0)])
    entries = []
    for u, v in [(40.0, 18.0), (48.0, 18.3), (56.0, 18.0), (48.0, 17.6), (44.0, 18.6), (52.0, 18.6)]:
        origin, direction = camera.ray(u, v)  # pixel rays reaching the road 250-330 m out
        path = refracta.trace_ray(truth, origin, direction, tol=1e-10, max_length=400.0, stop_height=0.0)
        entries.append({"destination": [u, v], "source": [float(x) for x in path.point_at(200.0)[0]]})
    pairs_path = tmp_path / "pairs.json"
    pairs_path.write_text(json.dumps({"pairs": entries, "free": ["hot_spot0_x"], "stop_height": 0.0}))
    start_path = tmp_path / "start.toml"
    start_path.write_text(with_atmosphere(road_text, truth.with_params(hot_spot0_x=140.0)))
    out = tmp_path / "solved.toml"
    assert cli.main(["edit", str(start_path), "--pairs", str(pairs_path), "-o", str(out)]) == 0
    _, _, solved = refracta.load_scene(out)
    assert solved.params["hot_spot0_x"] == pytest.approx(150.0, rel=SPOT_REL)
    assert solved.with_params(hot_spot0_x=150.0).params == truth.params


def test_the_command_line_edit_keeps_the_file_turbulence(tmp_path, road_text):
    air = refracta.Turbulence(1e-12, seed=9, cells=CELLS, depth=0.01)  # a thin layer: cheap to trace
    start = refracta.PhysicalAtmosphere(**ROAD, turbulence=air.layer)
    start_path = tmp_path / "start.toml"
    start_path.write_text(with_atmosphere(road_text, start, air))
    _, camera, _ = refracta.load_scene(start_path)
    # A pair the start meets, 80 m out and still ~1 m up: its path stays above the turbulent layer,
    # through which rays step at most half a cell (2.5 cm; a path into it at 350 m: a 1.7 s solve).
    origin, direction = camera.ray(48.0, 18.0)
    source = refracta.trace_ray(start, origin, direction, tol=1e-10, max_length=100.0).point_at(80.0)[0]
    pairs_path = tmp_path / "pairs.json"
    pairs_path.write_text(
        json.dumps(
            {
                "pairs": [{"destination": [48.0, 18.0], "source": [float(x) for x in source]}],
                "free": ["surface_dt"],
                "stop_height": 0.0,
            }
        )
    )
    out = tmp_path / "solved.toml"
    assert cli.main(["edit", str(start_path), "--pairs", str(pairs_path), "-o", str(out)]) == 0
    solved = refracta.load_scene(out)
    assert "[atmosphere.turbulence]" in out.read_text() and solved.turbulence.seed == 9
