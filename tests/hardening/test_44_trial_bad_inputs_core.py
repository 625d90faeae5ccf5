"""An adversarial trial's findings whose fix lies in the C++ core: a path holding a NUL byte wrote
or read another file; EXR layer names cut to 255 bytes merged layers; a spot light listed twice
shone twice; settings that silently meant something else (an MBOIT range with z_far < z_near,
shadow biases that lit every receiver, a metres-wide lens blamed on max_length, Ceres' raw text for
a trust region outside its limits, an nlopt algorithm that cannot take the problem reported as a
verdict on the atmosphere); sea sizes reported as mesh vertices; booleans taken as coordinates.
Each raised nothing, or named the wrong thing, before."""

import numpy as np
import pytest

import refracta
from refracta import io
from refracta.edit import PointPair, solve


def test_a_path_holding_a_nul_byte_is_refused_not_cut(tmp_path):
    image = np.zeros((4, 4, 3), np.float32)
    stem = str(tmp_path / "a")
    for call in (
        lambda: io.write_image(stem + "\x00b.exr", image),
        lambda: io.write_layers(stem + "\x00b.exr", image, {"distance": np.zeros((4, 4), np.float32)}),
        lambda: io.read_image(stem + "\x00b.exr"),
        lambda: io.channel_names(stem + "\x00b.exr"),
    ):
        with pytest.raises(ValueError, match="holds a NUL byte"):
            call()
    assert not (tmp_path / "a").exists()  # 'a\0b.exr' wrote 'a'


def test_exr_layer_names_are_refused_where_exr_would_cut_them(tmp_path):
    image, layer = np.zeros((4, 4, 3), np.float32), np.zeros((4, 4), np.float32)
    with pytest.raises(ValueError, match="a channel name must hold 1 to 255 bytes"):
        io.write_layers(tmp_path / "l.exr", image, {"x" * 300: layer, "x" * 301: layer})  # one channel of two
    io.write_layers(tmp_path / "ok.exr", image, {"x" * 253: layer})  # with '.Y': 255 bytes, EXR's longest
    assert io.channel_names(tmp_path / "ok.exr")[-1] == "x" * 253 + ".Y"


def test_a_spot_light_listed_twice_is_refused():
    scene = refracta.Scene()
    scene.add_ground(0.0, 100.0)
    scene.add_spot_light((0.0, 5.0, 0.0), (0.0, -1.0, 0.0), angle=100.0, intensity=(200.0, 200.0, 200.0))
    camera = refracta.Camera((0.0, 12.0, -0.01), (0.0, 0.0, 0.0), (0, 0, 1), 60.0, 16, 16)
    refracta.render_raster(scene, camera, lights=[0])
    with pytest.raises(ValueError, match="spot light 0 is listed twice"):  # it shone exactly twice as bright
        refracta.render_raster(scene, camera, lights=[0, 0])


@pytest.mark.parametrize(
    ("build", "message"),
    [
        (
            lambda: refracta.MboitSettings(z_near=10.0, z_far=1.0),
            r"z_far must exceed z_near \(got z_near 10, z_far 1\)",
        ),
        (lambda: refracta.ShadowMapOptions(depth_bias=10.0), r"depth_bias must be in \[0, 1\)"),
        (lambda: refracta.ShadowMapOptions(normal_offset=1e30), "normal_offset must be >= 0 and at most the map's"),
        (
            lambda: refracta.MomentShadowSettings(bias_vector=(1e300, 0.0, 0.0, 0.0)),
            r"bias_vector must hold moments of depths in the unit range: b1..b4 each in \[0, 1\]",
        ),
        (
            lambda: refracta.MomentShadowSettings(depth_range="signed", bias_vector=(0.0, -0.5, 0.0, 0.5)),
            r"b2 and b4 in \[0, 1\]",
        ),
    ],
)
def test_raster_settings_that_silently_meant_something_else_are_refused(build, message):
    with pytest.raises(ValueError, match=message):
        build().validate()


def test_published_moment_bias_vectors_stay_valid():
    for depth_range in ("unit", "signed"):
        for storage in ("fp32", "unorm16"):
            settings = refracta.MomentShadowSettings(depth_range=depth_range, storage=storage)
            vector = refracta.MomentShadowSettings.published_bias_vector(depth_range, storage)
            refracta.MomentShadowSettings(depth_range=depth_range, storage=storage, bias_vector=vector).validate()
            settings.validate()


def test_a_lens_wider_than_a_kilometre_is_named_as_the_lens():
    camera = refracta.Camera((0.0, 1.5, 0.0), (1.0, 1.5, 0.0))
    for diameter in (1e8, 1e300):  # was reported as "max_length ... from a camera 100000001.5 m out"
        with pytest.raises(ValueError, match=r"aperture_diameter must be in \[0, 1000\] m"):
            camera.with_lens(diameter, 10.0)
    with pytest.raises(ValueError, match=r"focus_distance must be in \(0, 10000000\] m"):
        camera.with_lens(0.01, 1e300)


def test_solve_settings_outside_what_the_back_ends_take_are_named():
    field, eye = refracta.LinearSquaredProfile(), (0.0, 1.5, 0.0)
    pairs = [PointPair((1.0, 1.5, 0.0), (1000.0, 3.0, 0.0))]
    for value in (1e-300, 1e300):  # Ceres' own option name and limits came back
        with pytest.raises(ValueError, match=r"trust_region must be in \[1e-32, 1e\+16\]"):
            solve(field, eye, pairs, free="alpha", trust_region=value)
    with pytest.raises(ValueError, match=r"loss_scale must be in \[1e-06, 10000000\] m"):
        solve(field, eye, pairs, free="alpha", loss="cauchy", loss_scale=1e300)  # a NaN cost change
    # LN_NEWUOA needs two parameters: the failure was reported as the atmosphere's.
    with pytest.raises(ValueError, match=r"backend 'nlopt:LN_NEWUOA' cannot solve this problem \(1 free parameter\)"):
        solve(field, eye, pairs, free="alpha", backend="nlopt:LN_NEWUOA")
    assert solve(field, eye, pairs, free="alpha", backend="nlopt:LN_BOBYQA").success


def test_a_sea_beyond_the_scene_is_named_by_its_own_argument():
    scene = refracta.Scene()
    with pytest.raises(ValueError, match=r"add_sea: height must lie within 10000000 m of 0"):
        scene.add_sea(height=1e300)  # was "add_mesh: vertices[14740] must be finite and within 1e7 m"
    with pytest.raises(ValueError, match=r"add_sea: size must be > 0 and at most 20000000 m"):
        scene.add_sea(size=1e300)


def test_booleans_are_not_coordinates():
    field = refracta.LinearSquaredProfile()
    with pytest.raises(ValueError, match=r"points must hold real numbers \(got dtype bool\)"):
        field.ior(np.array([True, False, True]))
    with pytest.raises(ValueError, match=r"direction must hold real numbers \(got dtype bool\)"):
        refracta.trace_ray(field, (0.0, 1.0, 0.0), np.array([True, False, False]), max_length=10.0)
    with pytest.raises(ValueError, match="triangles must hold whole vertex indices"):
        refracta.Scene().add_mesh(np.eye(3), np.array([[True, False, True]]))


def test_a_hand_made_ray_path_state_must_be_a_trace():
    path = refracta.trace_ray(refracta.LinearSquaredProfile(), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0), max_length=10.0)
    nodes, stop, evaluations = path.__getstate__()
    copy = refracta.RayPath.__new__(refracta.RayPath)
    copy.__setstate__((nodes, stop, evaluations))
    assert copy.length == path.length
    bad_nodes = np.array(nodes, copy=True)
    bad_nodes[-1, 1] = np.nan  # was taken: length nan
    reversed_nodes = np.array(nodes[::-1], copy=True)
    for state, message in [
        ((bad_nodes, stop, evaluations), "nodes must be finite"),
        ((reversed_nodes, stop, evaluations), "arc lengths must not fall"),
        ((nodes, stop, -5), "evaluations -5"),
    ]:
        with pytest.raises(ValueError, match=message):
            refracta.RayPath.__new__(refracta.RayPath).__setstate__(state)


def test_project_over_a_sphere_refuses_a_radius_that_would_overflow():
    camera = refracta.Camera((0.0, 5.0, 0.0), (1000.0, 5.0, 0.0))
    for radius in (1e-300, 10.0, -1.0, float("nan")):  # 1e-300 gave NaN pixels, 10 a depth of -2.8e35
        with pytest.raises(ValueError, match=r"earth_radius must be at least 100000 m, or inf"):
            camera.project([100.0, 800.0, 0.0], earth_radius=radius)
    assert camera.project([100.0, 5.0, 0.0], earth_radius=float("inf"))[2] == pytest.approx(100.0)  # flat: exact


def test_a_lens_camera_aimed_at_a_far_point_focuses_within_the_scene():
    # A review: the default focus, the distance to look_at, was refused beyond 1e7 m by with_lens.
    camera = refracta.Camera.photographic((0.0, 2.0, 0.0), (5e7, 2.0, 0.0), 50.0, f_number=8.0)
    assert camera.focus_distance == 1e7
