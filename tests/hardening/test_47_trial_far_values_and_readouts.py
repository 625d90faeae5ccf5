"""A bad-input trial of the less-used public functions (6 December): a sweep grid too large to
build hung eating memory; points, angles and heights far beyond any scene were taken and
gave rounding noise (a closest point at the path's start, an azimuth of 1e300 deg taken for 0); a
black image's automatic exposure was 180 000; negative distances drew a skyline; a material's
unreadable texture was blamed on the object using it; and a few messages named the wrong thing."""

import warnings

import numpy as np
import pytest

import refracta
from refracta import examples, geo, io, photo, shading


def test_a_sweep_grid_too_large_to_build_is_refused_at_once():
    # Ten axes of ten values: 10^10 points, each a dict, were built before the first run.
    with pytest.raises(ValueError, match=r"the grid has 10,000,000,000 points \(a=10 x b=10 x .*more than 10,000,000"):
        refracta.sweep(lambda **k: 0, {c: list(range(10)) for c in "abcdefghij"}, progress=False)
    with pytest.raises(ValueError, match=r"grid\['a'\] must be a list of values"):
        refracta.sweep(lambda **k: 0, {"a": np.array(3)}, progress=False)
    assert list(refracta.sweep(lambda a: a, {"a": np.arange(3)}, progress=False)) == [0, 1, 2]


def test_a_closest_point_beyond_the_scenes_reach_is_refused():
    path = refracta.trace_ray(
        refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1), [0, 1, 0], [1, 0, 0], max_length=100.0
    )
    # 1e20 m away the path's points are all equally far in doubles: its start (s = 0) was returned.
    with pytest.raises(ValueError, match=r"closest_point: the point must be finite and within 10000000 m"):
        path.closest_point([1e20, 1.0, 0.0])
    point, distance, s = path.closest_point([1e6, 1.0, 0.0])
    assert s == pytest.approx(100.0, abs=1e-9)  # the path's end: float64 rounding of its length
    assert distance == pytest.approx(1e6 - 100.0, abs=1.0)  # the path bends by less than 1 m over 100 m


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: geo.forward(45.0, 7.0, 1e300, 1000.0), r"azimuth must be finite in \[-360, 360\]"),
        (lambda: geo.radius_of_curvature(45.0, 400.0), r"azimuth must be finite in \[-360, 360\]"),
        (lambda: geo.LocalFrame(45.0, 7.0, height=1e300), r"height must be finite in \[-1e\+07, 1e\+07\]"),
        (lambda: geo.LocalFrame(45.0, 7.0).to_scene(45.0, 7.0, 1e300), r"beyond the scene's reach"),
        (
            lambda: refracta.Camera.geographic(45, 7, 2, 0, 0, vfov=10, image_width=8, image_height=6, roll=1e300),
            r"roll must be finite in \[-360, 360\]",
        ),
        (
            lambda: refracta.lights.EnvironmentLight(np.ones((4, 8, 3))).uv_to_direction([[5.0, -3.0]]),
            r"uv must be in \[0, 1\] \(got row 0: \(5, -3\)\)",
        ),
        (lambda: shading.RoughConductor(alpha=1e300), r"alpha_u must be at most 100 \(got 1e\+300\)"),
        (
            lambda: geo.radius_of_curvature([0.0, 45.0], [0.0, 90.0, 180.0]),
            r"the arrays do not broadcast together: lat \(2,\), azimuth \(3,\)",
        ),
        (
            lambda: refracta.plot.ray_fan(refracta.PhysicalAtmosphere(), 1.5, [[0.0, 0.1]], 1000.0),
            r"ray_fan: elevations must be a non-empty list",
        ),
    ],
)
def test_values_beyond_meaning_are_refused_naming_them(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_values_within_reach_still_work():
    assert geo.forward(45.0, 7.0, -90.0, 1000.0)[1] < 7.0  # west
    direction = refracta.lights.EnvironmentLight(np.ones((4, 8, 3))).uv_to_direction([[0.0, 0.0], [1.0, 1.0]])
    assert np.allclose(np.abs(direction[:, 1]), 1.0)  # v = 0 and 1: the poles
    camera = examples.hot_road(8.0, 6.0).camera  # 8.0 is a whole number of pixels, as options take it
    assert (camera.width, camera.height) == (8, 6)
    with pytest.raises(ValueError, match="whole numbers of pixels"):
        examples.hot_road(8.5, 6)


def test_a_black_images_exposure_is_the_manual_one_with_a_warning():
    # 0.18 / delta: 180 000, which frames sharing it were blown out by.
    with pytest.warns(RuntimeWarning, match="the image has no light"):
        assert io.exposure_of(np.zeros((4, 4, 3))) == 1.0
    with pytest.warns(RuntimeWarning, match="the image has no light"):
        assert io.exposure_of(-np.ones((4, 4, 3)), ev100=5.0, key=0.18) == io.exposure_of(np.ones((4, 4, 3)), ev100=5.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert io.exposure_of(np.zeros((4, 4, 3)), exposure=2.0) == 2.0  # manual: nothing to meter
        assert io.to_display(np.zeros((2, 2, 3))).max() == 0.0  # black stays black, silently
        assert io.exposure_of(np.full((4, 4, 3), 0.5)) == pytest.approx(0.36, rel=1e-5)  # 0.18 / 0.5


def test_an_animation_of_black_frames_is_written_without_a_warning(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        io.write_animation(tmp_path / "black.gif", np.zeros((2, 4, 4, 3)), fps=10)
    assert (tmp_path / "black.gif").stat().st_size > 0


@pytest.mark.parametrize("bad", [-1.0, np.nan])
def test_an_overlays_distances_must_be_distances(bad):
    render = (np.ones((6, 8, 3)), {"distance": np.full((6, 8), bad)})
    with pytest.raises(ValueError, match=r"readout 'distance' must hold distances >= 0 \[m\], inf where nothing"):
        photo.overlay(np.zeros((6, 8, 3)), render)
    distances = np.full((6, 8), np.inf)
    distances[3:] = 100.0
    assert list(photo.overlay(np.zeros((6, 8, 3)), (np.ones((6, 8, 3)), {"distance": distances})).skyline) == [3] * 8


def test_a_photo_made_from_lists_is_an_array():
    picture = photo.Photo([[0.1, 0.2, 0.3], [0.4, 0.5, 0.6]], False)
    assert (picture.width, picture.height) == (3, 2) and picture.image.dtype == np.float32
    with pytest.raises(ValueError, match=r"Photo: image must be an array of numbers"):
        photo.Photo([[1, 2], [3]], False)


def test_a_materials_unreadable_texture_is_located_at_the_material(tmp_path):
    (tmp_path / "empty.tif").write_bytes(b"")
    (tmp_path / "scene.toml").write_text(
        "[camera]\nposition = [0, 1.6, 0]\nlook_at = [10, 1.5, 0]\nvfov = 30\nsize = [8, 6]\n\n"
        '[[materials]]\nname = "m"\ntype = "diffuse"\ntexture = "empty.tif"\n'
        '[[objects]]\ntype = "ground"\nmaterial = "m"\n'
    )
    # It said ":12: [[objects]] #1 file: cannot read texture", and the object has no file key.
    with pytest.raises(refracta.IoError, match=r"scene.toml:10: \[\[materials\]\] #1 texture: cannot read texture"):
        refracta.load_scene(tmp_path / "scene.toml")


def test_a_weight_too_small_for_the_cost_is_refused():
    # 1e-300 underflowed the cost: the solve stopped at once ("gradient max norm 0"), blaming the air.
    from refracta.edit import PointPair, solve

    pairs = [PointPair((1000.0, 1.2, 1.0), (1000.0, 30.0, 0.0), weight=1e-300)]
    with pytest.raises(ValueError, match=r"weight must be at least 1e-100 \(got 1e-300\)"):
        solve(refracta.LogisticProfile(), (0.0, 1.5, 0.0), pairs, free=["k_s"])
