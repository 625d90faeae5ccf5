"""The editor shows hot spots (issue 10): each spot's footprint drawn where the camera sees its
circle on the ground, the spots listed with their numbers, their parameters free in a solve like
any other -- and a solve that moves a spot moves its outline."""

import numpy as np
import pytest

import refracta
from refracta.widgets import EditorModel
from refracta.widgets.model import SPOT_SEGMENTS, ground_circle

WAIT = 120.0  # [s] bound on waiting for a background solve
GROUND_TOL = 1e-9  # [m] a drawn point's pixel ray meets the ground on the circle: project and ray are
# inverse to round-off (measured 5e-14 m at 150 m, where rays graze the road at 0.5 deg)
SPOT_REL = 1e-6  # a spot's centre solved from exact pairs (misses < 1e-12 m pin it far tighter)
TRUTH_X, START_X = 150.0, 140.0  # [m] the spot that makes the pairs, and where the editor's starts
SMALL = (160, 60)  # the solve's camera: the road's at half the resolution (a quarter of the pixels to render)
PAIR_PIXELS = [(70.0, 33.0), (80.0, 33.5), (90.0, 33.0), (75.0, 34.0), (85.0, 34.5), (80.0, 35.0)]
# rays over the spot that reach the road 250-330 m out


def spotted(road, x=TRUTH_X, cold=True):
    """The road's atmosphere with a hot gaussian spot at (x, 0) and (cold) a cold compact one nearer
    (which the renderer crosses with rk45 in most of the lower image: 3 s at 320 x 120 on 2 cores,
    against 0.5 s without it)."""
    spots = [refracta.HotSpot(x, 0.0, 8.0, 15.0)]
    if cold:
        spots.append(refracta.HotSpot(60.0, -3.0, 2.0, -4.0, footprint="compact"))
    return refracta.PhysicalAtmosphere(**road.field.params, hot_spots=spots)


def ground_point(camera, u, v):
    """Where the camera's (straight) ray through pixel (u, v) meets the ground plane y = 0."""
    origin, direction = camera.ray(u, v)
    return origin - origin[1] / direction[1] * direction


@pytest.fixture
def make_spot_model(road):
    """make_spot_model(field) -> an EditorModel of the road through `field` (no render until asked);
    closed after the test."""
    made = []

    def make(field, camera=road.camera):
        made.append(
            EditorModel(road.scene, camera, field, stop_height=0.0, max_length=road.max_length, autorender=False)
        )
        return made[-1]

    yield make
    for model in made:
        model.close()


@pytest.fixture
def spot_model(make_spot_model, road):
    return make_spot_model(spotted(road, START_X))


def test_each_outline_is_the_spot_circle_on_the_ground_as_the_camera_sees_it(spot_model, road):
    outlines = spot_model.spot_outlines()
    assert [(o["spot"], o["footprint"], o["hot"]) for o in outlines] == [(0, "gaussian", True), (1, "compact", False)]
    for outline, spot in zip(outlines, spot_model.hot_spots):
        # gaussian: 1 sigma and where it fades below 1e-6; compact: its support only
        expected = [("radius", spot.radius)] + ([("reach", spot.reach)] if spot.footprint == "gaussian" else [])
        assert [(ring["kind"], ring["radius"]) for ring in outline["rings"]] == expected
        np.testing.assert_allclose(
            ground_point(road.camera, *outline["centre"]), [spot.x, 0.0, spot.z], atol=GROUND_TOL
        )
        for ring in outline["rings"]:
            points = ring["points"]
            assert len(points) == SPOT_SEGMENTS + 1 and points[-1] == points[0]  # closed
            ground = np.array([ground_point(road.camera, u, v) for u, v in points])
            np.testing.assert_allclose(
                np.hypot(ground[:, 0] - spot.x, ground[:, 2] - spot.z), ring["radius"], atol=GROUND_TOL
            )


def test_the_part_of_a_circle_behind_the_camera_is_left_out(road):
    points = ground_circle(road.camera, 0.0, 0.0, 5.0)  # around the eye's feet: half behind it
    behind = [p is None for p in points]
    assert 0 < sum(behind) < len(points)
    ground = np.array([ground_point(road.camera, *p) for p in points if p is not None])
    forward = road.camera.look_at - road.camera.position
    assert np.all((ground - road.camera.position) @ forward > 0.0)  # only what is in front of the eye
    np.testing.assert_allclose(np.hypot(ground[:, 0], ground[:, 2]), 5.0, atol=GROUND_TOL)


def test_an_atmosphere_without_spots_draws_none(make_model):
    model = make_model()
    assert model.hot_spots == [] and model.spot_outlines() == []


def test_a_solve_with_a_free_spot_centre_moves_it_and_its_outline(make_spot_model, road):
    camera = road.camera.resized(*SMALL)
    model = make_spot_model(spotted(road, START_X, cold=False), camera)
    truth = spotted(road, cold=False)
    for u, v in PAIR_PIXELS:
        origin, direction = camera.ray(u, v)
        path = refracta.trace_ray(truth, origin, direction, tol=1e-10, max_length=400.0, stop_height=0.0)
        model.add_pair((u, v), path.point_at(200.0)[0])
    model.set_free(["hot_spot0_x"])  # a spot's parameters are free parameters like any other
    before = model.spot_outlines()[0]
    model.solve()
    assert model.wait(WAIT)
    assert model.result.success, model.result.message
    assert model.field.params["hot_spot0_x"] == pytest.approx(TRUTH_X, rel=SPOT_REL)
    after = model.spot_outlines()[0]
    centre = ground_point(camera, *after["centre"])
    assert centre[0] == pytest.approx(TRUTH_X, rel=SPOT_REL)
    assert ground_point(camera, *before["centre"])[0] == pytest.approx(START_X, rel=SPOT_REL)
    assert after["centre"][1] < before["centre"][1]  # 10 m farther: nearer the horizon in the image
    model.undo()
    assert model.spot_outlines()[0] == before


def test_the_exported_scene_keeps_the_spots_and_the_turbulence(road, tmp_path):
    air = refracta.Turbulence(1e-10, seed=4, cells=16, depth=0.01)  # a thin layer: the render on import is cheap
    field = refracta.PhysicalAtmosphere(
        **road.field.params, hot_spots=[refracta.HotSpot(150.0, 0.0, 8.0, 15.0)], turbulence=air.layer
    )
    model = EditorModel(road.scene, road.camera, field, turbulence=air, autorender=False)
    try:
        loaded = refracta.load_scene(model.export_scene(tmp_path / "scene.toml"))
        assert loaded.field.hot_spots == field.hot_spots and loaded.turbulence.seed == 4
        points = np.random.default_rng(3).uniform([0.0, 0.0, -10.0], [300.0, 1.0, 10.0], (200, 3))
        np.testing.assert_array_equal(loaded.field.ior(points), field.ior(points))
        model.field = refracta.PhysicalAtmosphere()  # another atmosphere: then loading the file again
        model.import_scene(tmp_path / "scene.toml")
        assert model.turbulence.seed == 4 and model.hot_spots == field.hot_spots
    finally:
        model.close()


def test_the_view_lists_the_spots_and_their_toggles_free_their_parameters(road):
    pytest.importorskip("anywidget", reason="the editor's view needs anywidget (pip install refracta[widgets])")
    from refracta.widgets import MirageEditor

    editor = MirageEditor(
        road.scene, road.camera, spotted(road), free=["surface_dt"], stop_height=0.0, max_length=road.max_length
    )
    try:
        assert editor._canvas.spots == editor.model.spot_outlines()
        assert editor._straight.spots == editor._canvas.spots
        assert "hot_spot1_radius" in editor._free.options  # the free list offers them like any other
        rows = editor._spot_rows.children
        assert len(rows) == 2 and "#0" in rows[0].children[0].value and "compact" in rows[1].children[0].value
        editor._spot_toggles["hot_spot0_x"].value = True
        assert editor.model.free == ("surface_dt", "hot_spot0_x")
        assert editor._free.value == ("surface_dt", "hot_spot0_x")
        editor._free.value = ("hot_spot1_dt",)  # the free list drives the toggles too
        assert [n for n, t in editor._spot_toggles.items() if t.value] == ["hot_spot1_dt"]
        # A toggle keeps free camera parameters (a trial's lost them).
        editor.model.set_free(["surface_dt", "camera_pitch"])
        editor._spot_toggles["hot_spot0_x"].value = True
        assert editor.model.free == ("surface_dt", "hot_spot0_x", "camera_pitch")
        editor.model.wheel(1.0)  # a camera move redraws the outlines
        assert editor._canvas.spots == editor.model.spot_outlines()
    finally:
        editor.close()
