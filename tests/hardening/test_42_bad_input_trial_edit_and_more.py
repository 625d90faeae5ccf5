"""A 6 December 2026 bad-input trial of editing, comparisons, spectra and the command line: each
test fails on the code before the fix."""

import numpy as np
import pytest

import refracta
from refracta import cli, compare, shading, spectrum
from refracta.edit import PointPair, load_pairs, solve

from .test_39_cli_trial import DATA

FIELD_ARGS = ((0.0, 1.5, 0.0), [PointPair((1000.0, 1.2, 1.0), (1000.0, 30.0, 0.0))])


def test_a_design_too_large_to_build_is_refused_at_once():
    # 10**8 points per parameter were built before the first evaluation: 23 GB, then killed.
    with pytest.raises(ValueError, match=r"design_per_param must be <= 100000 \(got 100000000\)"):
        solve(refracta.LogisticProfile(), *FIELD_ARGS, free=["k_s"], design_per_param=10**8)


def test_bounds_whose_width_overflows_are_refused():
    # (-1e308, 1e308): the unit box's width overflowed; the solve "failed in -2 iterations".
    with pytest.raises(ValueError, match="a finite width upper - lower"):
        solve(refracta.LogisticProfile(), *FIELD_ARGS, free=["k_s"], bounds={"k_s": (-1e308, 1e308)})


def test_a_weight_that_overflows_the_cost_is_refused():
    pairs = [PointPair((1000.0, 1.2, 1.0), (1000.0, 30.0, 0.0), weight=1e308)]
    with pytest.raises(ValueError, match=r"weight must be in \(0, 1e\+100\]"):
        solve(refracta.LogisticProfile(), (0.0, 1.5, 0.0), pairs, free=["k_s"])


def not_height_only():
    return refracta.CustomField(
        lambda p: 1.0003 + 1e-6 * p[:, 0], lambda p: np.tile([1e-6, 0.0, 0.0], (len(p), 1)), height_only=True
    )


def test_an_elevation_table_checks_a_custom_field_s_promise():
    # The table read the field through its vectorised calls, which skipped the first-use check.
    field = not_height_only()
    for _ in range(2):  # and a field refused once is refused again (the check was marked done)
        with pytest.raises(ValueError, match="height_only=True, but the field depends on x or z"):
            refracta.ElevationTable(field, 1.5, -1.0, 1.0)
    with pytest.raises(ValueError, match="height_only=True, but the field depends on x or z"):
        refracta.trace_rays(field, [0.0, 1.5, 0.0], [1.0, 0.0, 0.0])


def test_complex_and_overflowing_numbers_are_refused():
    with pytest.raises(ValueError, match="PointPair destination must be 2 or 3 finite numbers"):
        PointPair(np.array([1000 + 7j, 1.2, 0.0]), (1000.0, 3.0, 0.0))  # the imaginary part was dropped
    with pytest.raises(ValueError, match="PointPair destination must be 2 or 3 finite numbers"):
        PointPair((10**400, 1.0, 0.0), (1.0, 2.0, 3.0))  # an OverflowError escaped
    with pytest.raises(ValueError, match="directions must be numbers"):
        refracta.trace_rays(refracta.PhysicalAtmosphere(), [0.0, 1.5, 0.0], np.array([[1.0, 0.0, 0.0]]) + 1j)


def test_malformed_pairs_files_name_the_file(tmp_path):
    deep, binary = tmp_path / "deep.json", tmp_path / "binary.json"
    deep.write_text("[" * 100000 + "]" * 100000)
    binary.write_bytes(b"\xff\xfe not text")
    with pytest.raises(ValueError, match=r"deep.json: not a pairs file \(JSON nested too deeply\)"):
        load_pairs(deep)
    with pytest.raises(ValueError, match=r"binary.json: not a pairs file \(JSON is UTF-8 text"):
        load_pairs(binary)


def test_the_command_line_refuses_set_for_its_own_flags(tmp_path, capsys):
    base = ["render", str(DATA / "hot_road.toml"), "--size", "16x6", "-o", str(tmp_path / "a.png")]
    assert cli.main([*base, "--set", "spp=1"]) == 1  # was a TypeError traceback: spp given twice
    assert "--set spp: give it as --spp" in capsys.readouterr().err
    for name in ("progress", "scene", "return_stats"):  # render's own keywords: tracebacks or a late failure
        assert cli.main([*base, "--set", f"{name}=true"]) == 1
        assert f"--set {name}: not a refracta.RenderOptions field" in capsys.readouterr().err


def test_comparisons_refuse_keywords_they_set_per_render():
    scene = refracta.Scene()
    camera = refracta.Camera((0.0, 1.0, 5.0), (0.0, 0.0, 0.0), vfov=40.0, width=16, height=8)
    with pytest.raises(ValueError, match="compare.transparency: transparency= is set per render"):
        compare.transparency(scene, camera, methods=["peel 2"], transparency="exact")
    with pytest.raises(ValueError, match="compare.transparency: layers= is set per render"):
        compare.transparency(scene, camera, layers=3)
    with pytest.raises(ValueError, match="compare.shadows: output= is set per render"):
        compare.shadows(scene, camera, output="radiance")


def test_values_past_float64_are_refused_not_nan():
    wo, wi = np.array([[0.0, 0.0, 1.0]]), np.array([[0.0, 0.6, 0.8]])
    for material in (shading.Plastic(), shading.Water()):
        with pytest.raises(ValueError, match=r"eta_outside must be a refractive index in \[1e-50, 1e\+50\]"):
            material.f(wo, wi, eta_outside=1e200)
    with pytest.raises(ValueError, match=r"path_length must be in \(0, 1e\+07\] m"):
        refracta.Turbulence(cells=16).angle_of_arrival_variance(1e155)
    wavelengths = np.array([400.0, 500.0, 600.0, 700.0])
    # Refused before its integral overflows: a spectrum is at most 1e30, as a light's radiance.
    with pytest.raises(ValueError, match=r"values must be finite and in \[0, 1e\+30\] \(got 1e\+307"):
        spectrum.spectrum_to_rgb(wavelengths, np.full(4, 1e307))
    with pytest.raises(ValueError, match="wavelengths must be a number or numbers"):
        spectrum.blackbody(5800.0, "500")


@pytest.fixture(scope="module")
def hot_road():
    from refracta import examples

    return examples.hot_road(32, 12)


@pytest.mark.parametrize(
    "keywords, message",
    [
        (dict(render_options=dict(denoise="yes")), "render_options: denoise must be True or False"),
        (dict(render_options=dict(tiles=0)), "render_options: tiles must be a tile size >= 1"),
        (dict(render_options=dict(executor=5)), "render_options: executor must be None"),
        (dict(solve_options=dict(bounds=5)), "bounds must be a dict"),
        (dict(solve_options=dict(bounds={"zz": (0, 1)})), "bounds given for 'zz', which is not a parameter"),
        (dict(solve_options=dict(derivatives="zzz")), "derivatives must be 'auto', 'automatic' or 'numeric'"),
        (dict(turbulence=5), "turbulence must be a refracta.Turbulence or None"),
        (dict(render_options=dict(return_stats=True)), "render_options: 'return_stats' is the editor's to choose"),
        (dict(render_options=dict(aovs=["distance"])), "render_options: 'aovs' is the editor's to choose"),
        (dict(render_options=dict(tiles=(16, 1))), r"tiles \(nx, ny\) must be whole numbers in \[1, 8\]"),
        (dict(scene_text="[[[bad toml"), "scene_text is not a scene file's TOML text"),
    ],
)
def test_the_editor_refuses_bad_options_when_made(hot_road, keywords, message):
    # Each was stored and failed later, as a background job's message or at export.
    from refracta.widgets.model import EditorModel

    with pytest.raises(ValueError, match=message):
        EditorModel(hot_road.scene, hot_road.camera, hot_road.field, autorender=False, **keywords)


def test_importing_pairs_with_bad_options_changes_nothing(hot_road, tmp_path):
    import json

    from refracta.widgets.model import EditorModel

    model = EditorModel(hot_road.scene, hot_road.camera, hot_road.field, autorender=False)
    path = tmp_path / "bad.json"
    path.write_text(json.dumps({"free": ["surface_dt"], "max_iterations": -5, "pairs": []}))
    with pytest.raises(ValueError, match="max_iterations must be >= 1"):
        model.import_pairs(path)
    assert model.free is None and model.solve_options == {}  # free was set before the options failed
    # A good file's free, stop height and options come back with undo, as its pairs do.
    path.write_text(json.dumps({"free": ["surface_dt"], "stop_height": 0.5, "max_iterations": 7, "pairs": []}))
    model.import_pairs(path)
    assert (model.free, model.stop_height, model.solve_options) == (("surface_dt",), 0.5, {"max_iterations": 7})
    model.undo()
    assert (model.free, model.stop_height, model.solve_options) == (None, None, {})
    model.close()


def test_on_off_arguments_take_true_or_false_only():
    # bool('yes') is True: each was read so.
    with pytest.raises(ValueError, match="d65: normalised must be True or False"):
        spectrum.d65([500.0], normalised="yes")
    with pytest.raises(ValueError, match="sample_wavelengths: terminate_secondary must be True or False"):
        spectrum.sample_wavelengths(0.3, terminate_secondary="yes")
    camera = refracta.Camera((0.0, 1.0, 5.0), (0.0, 0.0, 0.0), vfov=40.0, width=8, height=4)
    with pytest.raises(ValueError, match="render_raster: return_stats must be True or False"):
        refracta.render_raster(refracta.Scene(), camera, return_stats="no")


def test_sizes_that_overflowed_later_are_named():
    for spacing in (1e-300, 1e300):  # were "TurbulenceGrid: coefficients must be finite"
        with pytest.raises(ValueError, match=r"spacing must be in \[1e-06, 10000\] m"):
            refracta.Turbulence(cells=16, spacing=spacing)
    with pytest.raises(ValueError, match="eye_height must be within the scene's reach"):
        refracta.ElevationTable(refracta.PhysicalAtmosphere(), 1e300, -1.0, 1.0)  # was TabulatedHeightField's


def test_the_editor_refuses_a_bad_display_scale(hot_road):
    from refracta.widgets.model import EditorModel

    model = EditorModel(hot_road.scene, hot_road.camera, hot_road.field, autorender=False)
    for scale in (0.0, -1.0, float("nan")):
        with pytest.raises(ValueError, match="scale"):
            model.pointer_down(10.0, 5.0, scale=scale)
    model.close()


def test_geometric_noise_at_a_huge_time_is_the_periodic_pattern_or_named():
    from refracta._animate import _fft_size, geometric_noise_map

    # The pattern repeats with its FFT grid (30 + 4 x 3 pixels wide: 45), so a shift of one period
    # is the same pattern exactly, and a shift of 1e300 pixels a finite one (it gave NaN angles).
    period = _fft_size(30 + 12) / 10.0
    start = geometric_noise_map(20, 30, 1e-3, 3.0, seed=1, time=0.0)
    np.testing.assert_array_equal(geometric_noise_map(20, 30, 1e-3, 3.0, seed=1, time=period), start)
    assert np.isfinite(geometric_noise_map(20, 30, 1e-3, 3.0, seed=1, time=1e299)).all()
    with pytest.raises(ValueError, match=r"speed x time must be a finite shift in pixels"):
        geometric_noise_map(20, 30, 1e-3, 3.0, seed=1, time=1e308)  # 10 pixels/s x 1e308 s overflows
