"""Defects a fourth new-user trial found in ray tracing, editing, scene files, animation, plots and
the command line: each is now refused by name or computed right."""

import subprocess
import sys

import numpy as np
import pytest

import refracta
from refracta import edit, plot
from refracta.edit import PointPair

ROAD = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
CAMERA = "[camera]\nposition = [0, 1, 0]\nlook_at = [10, 1, 0]\n"


@pytest.mark.parametrize("trace", ["rk45", "rk4", "stratified"])
def test_a_ray_launched_down_from_the_stop_height_stops_there(trace):
    path = refracta.trace_ray(ROAD, [0, 0, 0], [1, -0.01, 0], stop_height=0.0, max_length=100, trace=trace)
    assert path.stop == "stop_height"
    np.testing.assert_array_equal(path.points[-1], [0.0, 0.0, 0.0])  # where it started: not below the ground
    ends = refracta.trace_rays(ROAD, [0, 2, 0], [[1, -0.01, 0]], stop_height=2.0, max_length=500, trace=trace)
    assert ends.stops == ["stop_height"] and ends.end_points[0][1] == 2.0


def test_directions_of_any_finite_size_give_the_unit_directions_path():
    unit = refracta.trace_ray(ROAD, [0, 1.5, 0], [1, 1, 0], max_length=10)
    for scale in (1e200, 1e-300):  # |d|^2 overflows, or underflows to 0
        scaled = refracta.trace_ray(ROAD, [0, 1.5, 0], [scale, scale, 0], max_length=10)
        np.testing.assert_allclose(scaled.points[-1], unit.points[-1], rtol=1e-12)  # one normalisation's rounding
    with pytest.raises(ValueError, match=r"ray 1: direction must be finite and non-zero \(got \(0, 0, 0\)\)"):
        refracta.trace_rays(ROAD, [[0, 1.5, 0]] * 2, [[1, 0, 0], [0, 0, 0]], max_length=10)


def test_a_global_stage_cut_short_reports_a_cost_it_evaluated():
    air = refracta.PhysicalAtmosphere(surface_dt=5.0, surface_depth=0.1)
    pair = PointPair((300, 1.49, 0), (300, 0.5, 0))
    result = edit.solve(
        air, (0, 1.5, 0), [pair], free=["surface_dt", "surface_depth"], stop_height=0.0, max_evaluations=20
    )
    line = next(s for s in result.stages if s.startswith("global:"))
    lowest = float(line.split("lowest cost ")[1].split(" ")[0])
    # Unevaluated design points had cost 0 and were reported (and ranked) as the lowest.
    assert lowest > 0.0 and "stopped by the evaluation limit" in line


@pytest.mark.parametrize(
    "keywords, message",
    [
        (dict(free=5), r"free must be a parameter name or a list of names \(got 5\)"),
        (dict(bounds={"k_s": 5}), r"bounds\['k_s'\] must be a \(lower, upper\) pair of numbers"),
        (dict(bounds={"k_s": (0, 50, 7)}), r"bounds\['k_s'\] must be a \(lower, upper\) pair"),
        (dict(bounds=[("k_s", (0, 1))]), r"bounds must be a dict"),
    ],
)
def test_solve_names_a_malformed_free_or_bounds(keywords, message):
    pair = PointPair((1000, 1.2, 0), (1000, 3, 0))
    with pytest.raises(ValueError, match=message):
        edit.solve(refracta.LogisticProfile(), (0, 1.5, 0), [pair], **keywords)


def test_jacobian_refuses_an_empty_free_as_solve_does():
    with pytest.raises(ValueError, match="free is empty"):
        edit.jacobian(refracta.LogisticProfile(), (0, 1.5, 0), [PointPair((1000, 1.2, 0), (1000, 3, 0))], free=[])


def test_point_pairs_and_pair_files_name_what_is_malformed(tmp_path):
    with pytest.raises(ValueError, match=r"PointPair source must be 3 finite numbers \(got 'abc'\)"):
        PointPair((1, 2), "abc")
    with pytest.raises(ValueError, match="PointPair destination must be 2 or 3 finite numbers"):
        PointPair({"pixel": [1, 2]}, (1, 2, 3))
    path = tmp_path / "pairs.json"
    path.write_text('{"pairs": [{"destination": [10, 8], "source": {"pix": [10, 12]}}]}')
    scene = refracta.Scene()
    scene.add_box((20, 0, 0), (2, 2, 2))
    camera = refracta.Camera((0, 1, 0), (20, 1, 0), width=32, height=16)
    with pytest.raises(ValueError, match=r"pairs\[0\]: unknown key 'pix' in source"):
        edit.load_pairs(path, scene, camera)


def test_with_params_takes_names_and_hot_spots_stay_in_the_scenes_reach():
    with pytest.raises(ValueError, match=r"with_params takes the parameters by name"):
        ROAD.with_params({"surface_dt": 3.0})
    assert ROAD.with_params(surface_dt=3.0).params["surface_dt"] == 3.0
    with pytest.raises(ValueError, match=r"HotSpot: x must be within the scene's reach, 10000000 m \(got 1e\+200\)"):
        refracta.HotSpot(1e200, 0.0, 100.0, 10.0)
    with pytest.raises(ValueError, match="HotSpot: radius must be within the scene's reach"):
        refracta.HotSpot(0.0, 0.0, 1e200, 10.0)


def load(tmp_path, text):
    path = tmp_path / "scene.toml"
    path.write_text(text)
    return refracta.load_scene(path)


def test_scene_files_refuse_a_flat_zero_earth_and_a_second_sun(tmp_path):
    with pytest.raises(
        ValueError, match=r"scene.toml:\d+: .*curved_earth.*radius must be a planet's, at least 100000 m"
    ):
        load(tmp_path, CAMERA + "[atmosphere]\ncurved_earth = 0\n")
    sun = '[[lights]]\ntype = "sun"\ndirection = [0, 1, 1]\nradiance = [1, 1, 1]\n'
    with pytest.raises(ValueError, match=r"\[\[lights\]\] #2 type: a second sun"):
        load(tmp_path, CAMERA + sun + sun)


def test_a_scene_files_sun_takes_a_grey_radiance_as_a_lights_sun_does(tmp_path):
    grey = load(tmp_path, CAMERA + "[sun]\ndirection = [0, 1, 1]\nradiance = 1e4\n")
    rgb = load(tmp_path, CAMERA + "[sun]\ndirection = [0, 1, 1]\nradiance = [1e4, 1e4, 1e4]\n")
    assert str(grey.scene.lights[0]) == str(rgb.scene.lights[0])
    with pytest.raises(ValueError, match=r"scene.toml:6: \[sun\] radiance: ") as error:
        load(tmp_path, CAMERA + "[sun]\ndirection = [0, 1, 1]\nradiance = [1, 2]\n")
    assert str(error.value).count("scene.toml") == 1  # located once, not twice


def test_animate_refuses_file_settings_without_a_file():
    scene = refracta.Scene()
    scene.add_ground()
    camera = refracta.Camera((0, 1, 0), (10, 0.5, 0), width=8, height=4)
    for keywords in (dict(fps=10.0), dict(exposure=2.0)):
        with pytest.raises(ValueError, match="shapes? the file written to `path`, and no path is given"):
            refracta.animate(scene, camera, None, [0.0, 0.1], noise=dict(rms=1e-4, correlation_pixels=2), **keywords)


def test_plots_name_an_argument_of_the_wrong_kind():
    with pytest.raises(ValueError, match="ray_fan: field must be a refracta IndexField"):
        plot.ray_fan(None, 1.5, [-0.5], 100.0)
    with pytest.raises(ValueError, match="edit_report: result must be a refracta.edit.EditResult"):
        plot.edit_report(None)


def test_the_command_line_refuses_an_unwritable_output_before_rendering(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(CAMERA + "size = [8, 4]\n")
    for output, message in ((tmp_path / "missing" / "out.png", "does not exist"), (tmp_path, "is a folder")):
        run = subprocess.run(
            [sys.executable, "-m", "refracta", "render", str(scene), "-o", str(output)],
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert run.returncode == 1 and message in run.stderr and "wrote" not in run.stdout, run.stderr


def test_a_sounding_and_a_ground_name_the_value_out_of_range():
    with pytest.raises(
        ValueError,
        match=r"temperatures\[1\] \(t1\) must be in \[100, 10000\] K, in kelvin \(15 C is 288.15 K; got 1000000\)",
    ):
        refracta.TemperatureProfile([0, 1, 10], [300, 295, 290]).with_params(t1=1e6)
    scene = refracta.Scene()
    with pytest.raises(ValueError, match=r"ground: size must be > 0 and at most 20000000 m \(got inf\)"):
        scene.add_ground(size=float("inf"))
    with pytest.raises(ValueError, match=r"ground: size must be > 0 .* \(got 0\)"):
        scene.add_ground(size=0.0)


def test_aerial_perspective_refuses_a_bad_sun_and_stays_finite_deep_below():
    from refracta import spectrum

    air = spectrum.AerialPerspective(spectrum.PhysicalSky([0, 1, 0]))
    with pytest.raises(ValueError, match="height must be finite"):
        air.sun_transmittance(float("nan"), 10.0, 550.0)  # it crashed the process
    for elevation in (float("nan"), 280.0):
        with pytest.raises(ValueError, match=r"elevation must be in \[-90, 90\] deg"):
            air.sun_transmittance(0.0, elevation, 550.0)
    transmittance, light = air.along([0, -1e6, 0], [1000, -1e6, 0], 550.0)  # it gave NaN light
    assert np.isfinite(transmittance) and np.isfinite(light)


def test_a_low_suns_light_is_a_white_balance():
    from refracta import io, spectrum

    low = np.radians(0.5)
    sun = spectrum.PhysicalSky([np.cos(low), np.sin(low), 0]).sun_radiance_rgb().ravel()
    assert sun[2] < 0.0  # outside sRGB's gamut: a negative linear blue
    shown = io.to_display(np.ones((2, 2, 3), np.float32), white_balance=tuple(sun), exposure=0.2, tonemap="linear")
    assert np.all(np.isfinite(shown)) and shown[0, 0, 2] > shown[0, 0, 0]  # the orange light's white: grey shows blue


def test_write_layers_refuses_repeated_or_miscounted_channel_names(tmp_path):
    layer = np.ones((4, 6, 2))
    with pytest.raises(ValueError, match="channel names repeat: 'd.a'"):
        refracta.io.write_layers(tmp_path / "a.exr", np.zeros((4, 6, 3)), {"d": layer}, suffixes={"d": ("a", "a")})
    with pytest.raises(ValueError, match=r"suffixes\['d'\] gives 3 names for 2 channels"):
        refracta.io.write_layers(tmp_path / "a.exr", np.zeros((4, 6, 3)), {"d": layer}, suffixes={"d": ("a", "b", "c")})
