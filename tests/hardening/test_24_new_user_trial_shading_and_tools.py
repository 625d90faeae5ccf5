"""Defects a sixth new-user trial found in shading, spectra, waves, turbulence, the moment and OIT
helpers, geodesy, terrain and animation: each is now computed right or refused by name, before
any work."""

import math

import numpy as np
import pytest

import refracta
from refracta import examples_chroma, geo, lights, moments, oit, photo, shading, spectrum, turbulence

DEPTHS, ALPHAS, COLORS = [1.0, 2.0, 3.0], [0.5, 0.5, 0.5], [[1.0, 0.0, 0.0]] * 3


def test_the_spectrum_module_example_gives_back_its_reflectance():
    lam = np.arange(360.0, 831.0)
    s = spectrum.rgb_to_spectrum([0.8, 0.3, 0.1], lam)
    # The docstring's line: a reflectance seen under D65 (the fit reproduces its RGB to 1e-3).
    np.testing.assert_allclose(spectrum.spectrum_to_rgb(lam, s, kind="reflectance"), [0.8, 0.3, 0.1], atol=1e-3)
    assert 'kind="reflectance"' in spectrum.__doc__


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: turbulence.plane_wave_tilt_variance(1e-10, 100, -0.1), r"aperture must be > 0 m"),
        (lambda: turbulence.plane_wave_tilt_variance(-1e-10, -100, 0.1), r"cn2 must be >= 0.*path_length must be > 0"),
        (lambda: turbulence.plane_wave_tilt_variance(math.nan, 100, 0.1), r"cn2 must be >= 0"),
        (lambda: turbulence.plane_wave_tilt_variance(1e-10, 100, 0.0), r"aperture must be > 0 m"),
        (
            lambda: turbulence.tilt_variance("x", 100.0, 0.005),
            r"tilt_variance: cn2 must be >= 0 and finite \(got 'x'\)",
        ),
        (lambda: refracta.Turbulence(size=0.3, spacing=0.05), r"size / spacing must be at least 8 cells"),
        (lambda: refracta.OceanWaves(patch_size=1e-300, resolution=8), r"patch_size must be in \[0.01, 10000000\] m"),
        (lambda: refracta.OceanWaves().spectrum(math.nan, 0.0), r"OceanWaves.spectrum: k must be finite"),
        (lambda: shading.Ior("bk7").at(-5.0), r"Ior.at: wavelength must be in \[360, 830\] nm"),
        (lambda: shading.Ior("bk7").at(1e300), r"Ior.at: wavelength must be in \[360, 830\] nm"),
        (lambda: shading.Ior(sellmeier=[[1, 2, 3], [4, 5, 6]]), r"sellmeier must be six numbers"),
        (lambda: spectrum.blackbody(1e300, [500.0]), r"temperature must be in \(0, 1e\+?12\] K"),
        (lambda: spectrum.blackbody(True, [500.0]), r"blackbody: temperature must be a number"),
        (lambda: shading.TerrainShading().reflectance(math.nan, 5.0), r"height must be finite"),
        (lambda: shading.TerrainShading().reflectance(100.0, 200.0), r"slope must be in \[0, 90\] deg"),
        (lambda: shading.thin_film_reflectance(2.0, 1.0, 1.33, 1.5, 0.0, thickness=100.0, wavelength=550.0), r"cos_i"),
        (lambda: lights.SphereLight([0, 3, 0], 1e300, 1.0), r"SphereLight: radius must be <= 10000000 m"),
        (lambda: lights.SpotLight([0, 2, 0], [0, -1, 0], 60.0, 1.0, inner_angle="a"), r"inner_angle must be a number"),
        (
            lambda: lights.AreaLight(np.array([[0, 0, 0], [1e200, 0, 0], [0, 0, 1e200]]), np.array([[0, 2, 1]]), 1.0),
            r"positive, finite area \(got inf m\^2\)",
        ),
        (lambda: refracta._animate.geometric_noise_map(4, 4, 0.001, True), r"correlation_pixels must be in"),
    ],
)
def test_values_outside_what_the_physics_holds_are_refused(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_turbulence_points_beyond_the_scene_are_refused_not_nan():
    air = refracta.Turbulence(cells=16, spacing=0.05)
    values, _ = air.evaluate(np.array([[1e6, 0.05, 0.0]]))
    assert np.isfinite(values).all()
    with pytest.raises(ValueError, match=r"evaluate: points\[1\] must be finite and within 10000000 m"):
        air.evaluate(np.array([[1.0, 0.05, 0.0], [1e18, 0.05, 0.0]]))


def test_a_frame_pattern_of_an_unwritable_format_fails_before_any_frame(tmp_path):
    calls = []
    road = refracta.examples.hot_road()
    camera = road.camera.resized(8, 4)
    with pytest.raises(refracta.IoError, match=r"f0.txt"):
        refracta.animate(
            road.scene, camera, road.field, [0.0, 0.1], str(tmp_path / "f{}.txt"),
            noise=dict(rms=1e-4, correlation_pixels=2.0), progress=lambda done, total: calls.append(done),
        )  # fmt: skip
    assert calls == []  # refused before rendering
    frames = refracta.animate(
        road.scene, camera, road.field, [0.1, 0.0], str(tmp_path / "f{}.png"),
        noise=dict(rms=1e-4, correlation_pixels=2.0), progress=False, max_length=200.0,
    )  # fmt: skip
    assert frames.shape == (2, 4, 8, 3) and (tmp_path / "f1.png").is_file()  # any times: frame files have no rate
    with pytest.raises(ValueError, match=r"fps is a GIF's or an MP4's; frame files"):
        refracta.animate(
            road.scene, camera, road.field, [0.0, 0.1], str(tmp_path / "f{}.png"), fps=5,
            noise=dict(rms=1e-4, correlation_pixels=2.0),
        )  # fmt: skip


@pytest.mark.parametrize(
    ("method", "keywords", "message"),
    [
        ("exact", dict(layers=2), r"layers applies to method='peel', not with method='exact'"),
        ("exact", dict(beta=0.5), r"beta applies to method='mboit'"),
        ("wboit", dict(moments=6), r"moments applies to method='mboit', not with method='wboit'"),
        ("mboit", dict(z_range=5.0), r"z_range must be \(near, far\) with 0 < near < far \(got 5.0\)"),
    ],
)
def test_composite_refuses_what_its_method_does_not_use(method, keywords, message):
    with pytest.raises(ValueError, match=message):
        oit.composite(DEPTHS, ALPHAS, COLORS, method=method, **keywords)


def test_composite_still_takes_each_method_s_own_keywords():
    exact = oit.composite(DEPTHS, ALPHAS, COLORS, method="exact")
    # Three red layers of alpha 1/2 over black: 1/2 + 1/4 + 1/8 of red, exactly.
    np.testing.assert_allclose(exact, [0.875, 0.0, 0.0], atol=1e-15)
    peel = oit.composite(DEPTHS, ALPHAS, COLORS, method="peel", layers=3)
    np.testing.assert_allclose(peel, exact, atol=1e-15)  # every fragment peeled: the exact sum
    for weight in ("eq7", "eq9"):  # one colour: any weights average it to red, times 1 - 1/8 coverage
        np.testing.assert_allclose(
            oit.composite(DEPTHS, ALPHAS, COLORS, method="wboit", weight=weight), exact, atol=1e-12
        )
    mboit = oit.composite(DEPTHS, ALPHAS, COLORS, method="mboit", z_range=(0.5, 4.0))
    assert mboit[0] == pytest.approx(0.875, abs=0.05) and mboit[1] == mboit[2] == 0.0  # MBOIT's approximation: 5 %


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: moments.power_moments([0.5], count=0), r"count must be a whole number in \[1, 1024\]"),
        (lambda: moments.power_moments([]), r"depths must hold at least one depth"),
        (lambda: moments.power_moments([0.2, 0.4], [0.5, 0.6]), r"weights must be >= 0 and sum to 1"),
        (lambda: moments.power_moments([0.2, 0.4], [1.5, -0.5]), r"weights must be >= 0 and sum to 1"),
        (lambda: moments.power_moments([0.2, 0.4], [1.0]), r"weights must have depths' shape"),
        (lambda: moments.shadow_intensity(np.zeros(4), 0.5, bias_vector=0.5), r"bias_vector must be numbers of shape"),
        (lambda: moments.quantize(np.zeros(3)), r"quantize: moments must have shape \(\.\.\., 4\)"),
    ],
)
def test_moment_helpers_name_what_is_wrong(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_geodesy_and_cameras_refuse_meaningless_numbers():
    frame = geo.LocalFrame(46.5, 7.5)
    with pytest.raises(ValueError, match=r"image_width must be a whole number of pixels in \[1, \d+\] \(got 1.7\)"):
        frame.camera(1000.0, 45.0, 1.0, vfov=10.0, image_width=1.7)
    with pytest.raises(ValueError, match=r"image_height must be a whole number"):
        frame.camera(1000.0, 45.0, 1.0, vfov=10.0, image_height=True)
    with pytest.raises(ValueError, match=r"sensor_mm must be \(width, height\)"):
        frame.camera(1000.0, 45.0, 1.0, focal_length_mm=50.0, sensor_mm=(36,))
    assert frame.camera(1000.0, 45.0, 1.0, vfov=10.0, image_width=np.int64(64)).width == 64
    with pytest.raises(ValueError, match=r"lon1 must be finite in \[-360, 360\]"):
        geo.inverse(0, 1e300, 0, 0)
    with pytest.raises(ValueError, match=r"distance must be finite in \[0, 4.01e\+07\]"):
        geo.forward(0, 0, 90, 1e300)
    lat, lon, _ = geo.forward(0, 0, 90, 1000.0)  # a kilometre east along the equator
    assert lat == pytest.approx(0.0, abs=1e-12) and lon == pytest.approx(1000.0 / 111319.49, rel=1e-6)  # WGS84's a


def test_noise_maps_take_numpy_sizes():
    angles = refracta._animate.geometric_noise_map(np.int64(4), np.int64(6), 0.001, 2.0)
    assert angles.shape == (4, 6, 2)


def test_terrain_beyond_the_scene_s_reach_is_named_not_called_holes():
    scene = refracta.Scene()
    # Named as a file's sample is: no terrain lies 100 km from sea level (also far inside the reach).
    with pytest.raises(ValueError, match=r"add_terrain: heights\[0, 0\] is 1e\+40 m, beyond 100000 m of any terrain"):
        scene.add_terrain(np.full((3, 3), 1e40), origin=(0, 0), spacing=(1, 1))
    with pytest.raises(ValueError, match=r"origin and spacing \(x\) reach 1e\+300 m"):
        scene.add_terrain(np.zeros((3, 3)), origin=(1e300, 0), spacing=(1, 1))


def test_photographs_are_files(tmp_path):
    with pytest.raises(refracta.IoError, match=r"it is a folder, not a file"):
        photo.load(tmp_path)
    with pytest.raises(refracta.IoError, match=r"no such file"):
        photo.read_exif(tmp_path / "missing.jpg")


def test_a_depth_range_must_hold_the_fragments():
    # z_range (10, 20) around fragments at 1-3 m gave (0.29, 0.29, 0.29) for red, silently.
    with pytest.raises(ValueError, match=r"z_range \(10, 20\) must hold every fragment's depth \(got 1 to 3\)"):
        oit.composite(DEPTHS, ALPHAS, COLORS, method="mboit", z_range=(10, 20))


def test_spectral_estimates_and_gamut_mapping_refuse_impossible_input():
    radiance, lam = np.ones((1, 4)), np.full((1, 4), 550.0)
    with pytest.raises(ValueError, match=r"pdf must be finite and >= 0"):
        spectrum.to_linear_srgb(radiance, lam, np.full((1, 4), -0.01))
    with pytest.raises(ValueError, match=r"gamut_map: image must be finite"):
        examples_chroma.gamut_map(np.full((1, 1, 3), np.nan))
