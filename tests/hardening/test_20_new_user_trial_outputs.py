"""Bad input a third new-user trial (4 December: shading, cameras, output files, animation, denoising)
found accepted silently, failing late or naming the wrong argument: each now raises ValueError
naming the argument and its value, before any work, or warns as render does."""

import re
import warnings

import numpy as np
import pytest

import refracta
from refracta import shading


def sky_scene():
    scene = refracta.Scene()
    scene.set_sky((0.3, 0.4, 0.6))
    return scene


def small_camera():
    return refracta.Camera((0, 1.4, 0), (30, 0.9, 0), width=16, height=9)


NOISE = dict(rms=1e-3, correlation_pixels=2)


def test_animate_refuses_frames_that_would_not_fit_in_memory_before_rendering(monkeypatch):
    # A 16 GB machine, whatever this one has (a larger one would start rendering the million frames).
    monkeypatch.setattr(refracta._animate._core, "physical_memory_bytes", lambda: 16e9)
    camera = refracta.Camera((0, 1.4, 0), (30, 0.9, 0), width=160, height=90)
    # 1e6 frames of 160 x 90 float32 RGB: 172.8 GB.
    with pytest.raises(ValueError, match=r"animate: 1000000 times of 160 x 90 frames need 172\.8 GB .* 16\.0 GB"):
        refracta.animate(sky_scene(), camera, None, np.arange(10**6) * 0.1, noise=NOISE, progress=False)
    # Written to a GIF with automatic exposure: the frames stacked once more, and their 8-bit copies.
    with pytest.raises(ValueError, match=r"need 388\.8 GB for the frames and the file"):
        refracta.animate(sky_scene(), camera, None, np.arange(10**6) * 0.1, "a.gif", noise=NOISE, progress=False)


@pytest.mark.parametrize(
    "path, options, message",
    [
        ("frames/f{x}.png", {}, r"path's pattern must have one '\{\}' field .*KeyError"),
        ("frames/f{}{}.png", {}, r"path's pattern must have one '\{\}' field .*IndexError"),
        ("frames/f{{}}.png", {}, r"path's pattern must have one '\{\}' field .*names every frame alike"),
        ("frames/f{0[0]}.png", {}, r"path's pattern must have one '\{\}' field .*TypeError"),
        ("a.gif", {"exposure": 0}, r"exposure must be > 0 and finite \(got 0\)"),
        ("a.gif", {"tonemap": "filmic"}, r"tonemap must be .* \(got 'filmic'\)"),
    ],
)
def test_animate_checks_its_output_settings_before_rendering(tmp_path, monkeypatch, path, options, message):
    rendered = []
    monkeypatch.setattr(refracta._animate, "_render_frame", lambda *args: rendered.append(args))
    with pytest.raises(ValueError, match=message):
        refracta.animate(
            sky_scene(), small_camera(), None, [0.0, 0.1], str(tmp_path / path), noise=NOISE, progress=False, **options
        )
    assert rendered == []  # refused before the first frame


@pytest.mark.parametrize("noise", [{}, {"rms": 1e-3}])
def test_animate_names_what_noise_lacks(noise):
    with pytest.raises(ValueError, match=r"animate: noise needs .*correlation_pixels"):
        refracta.animate(sky_scene(), small_camera(), None, [0.0, 0.1], noise=noise, progress=False)


def test_denoise_refuses_values_beyond_float32():
    # Open Image Denoise works in float32: 1e39 came back as all zeros, one such pixel made every pixel inf.
    with pytest.raises(ValueError, match=r"denoise: image must lie in \[0, 3\.40282e\+38\]"):
        refracta.denoise(np.full((8, 8, 3), 1e39))


@pytest.mark.parametrize(
    "args, message",
    [
        # A negative horizon made no sky at all, and the render then warned that there was none.
        (((-1.0, 0.0, 0.0),), r"set_sky: horizon must be finite and >= 0 per channel \(got \(-1, 0, 0\)\)$"),
        (
            ((1.0, 1.0, 1.0), (-5.0, -5.0, -5.0)),
            r"set_sky: zenith must be finite and >= 0 per channel \(got \(-5, -5, -5\)\)$",
        ),
    ],
)
def test_set_sky_refuses_negative_radiance_naming_it(args, message):
    with pytest.raises(ValueError, match=message):
        refracta.Scene().set_sky(*args)


def test_set_sky_refuses_colours_beside_an_environment_map():
    with pytest.raises(ValueError, match="give horizon and zenith, or environment, not both"):
        refracta.Scene().set_sky((1.0, 1.0, 1.0), environment="sky.exr")


def test_set_environment_refuses_an_image_of_other_channels():
    for shape in ((4, 8, 2), (4, 8, 3, 1)):
        with pytest.raises(ValueError, match=re.escape(f"alpha ignored) (got shape {shape})")):
            refracta.Scene().set_environment(np.ones(shape))
    for shape in ((4, 8), (4, 8, 1), (4, 8, 3), (4, 8, 4)):  # grey, RGB and RGBA, as map files
        refracta.Scene().set_environment(np.ones(shape))


def test_a_texture_id_the_scene_does_not_hold_is_refused_when_the_material_is_added():
    # It failed at render time with IndexError: vector::_M_range_check.
    with pytest.raises(ValueError, match=r"texture id 5 is not one of this scene's textures \(it has 0\)"):
        refracta.Scene().add_ground(0, 100, material=shading.Diffuse(texture=5))


def test_bounds_of_a_scene_whose_geometry_was_all_removed():
    scene = refracta.Scene()
    scene.remove(scene.add_box((0, 0, 0), (1, 1, 1)))
    with pytest.raises(ValueError, match="the scene is empty"):
        _ = scene.bounds  # was (inf, -inf)
    # ... and render still works on it (its checks read the bounds).
    scene.set_sky((1.0, 1.0, 1.0))
    image = refracta.render(scene, small_camera(), None, progress=False)
    np.testing.assert_allclose(image, 1.0, rtol=1e-6)  # the constant sky, exactly up to float32 rounding


def test_eye_level_refuses_to_focus_nearer_than_the_focal_length():
    # It accepted a target 1e-9 m away and rendered wholly blurred; photographic refused the same.
    with pytest.raises(
        ValueError, match=r"eye_level: the target is 1e-09 m away, nearer than the focal length \(0\.05 m\)"
    ):
        refracta.Camera.eye_level((0, 0, 0), (1e-9, 0, 0), f_number=2)
    with pytest.raises(ValueError, match=r"photographic: the camera looks at a point 0\.01 m away"):
        refracta.Camera.photographic((0, 1, 0), (0.01, 1, 0), 50.0, f_number=2)


def test_framing_straight_down_names_direction_and_up():
    scene = refracta.Scene()
    scene.add_box((0, 0, 0), (1, 1, 1))
    with pytest.raises(ValueError, match=r"direction \(0, -1, 0\) must not be parallel to up \(0, 1, 0\)"):
        refracta.Camera.framing(scene, direction=(0, -1, 0))


def test_write_image_refuses_an_exposure_that_overflows_float32(tmp_path):
    with pytest.raises(ValueError, match=r"write_image: the image times the exposure \(1e\+10\) overflows float32"):
        refracta.io.write_image(tmp_path / "x.exr", np.full((4, 4, 3), 1e30, np.float32), exposure=1e10)


def test_write_layers_takes_a_dict(tmp_path):
    with pytest.raises(ValueError, match=r"layers must be a dict of name: array \(got list\)"):
        refracta.io.write_layers(tmp_path / "x.exr", np.ones((4, 4, 3)), [np.ones((4, 4))])


def test_render_raster_warns_like_render_when_nothing_lights_the_scene():
    scene = refracta.Scene()
    scene.add_box((0, 0.5, 0), (1, 1, 1))
    camera = refracta.Camera((3, 2, 3), (0, 0.5, 0), width=16, height=9)
    with pytest.warns(refracta.SceneWarning, match="render_raster: the scene has no light and no sky"):
        image = refracta.render_raster(scene, camera, progress=False)
    assert not image.any()  # black, as the warning says


@pytest.mark.parametrize(
    "call, message",
    [
        (
            lambda: refracta.render(sky_scene(), small_camera(), None, aovs=3),
            r"render: aovs must be a list of names, .*\(got 3\)",
        ),
        (
            lambda: refracta.render(sky_scene(), small_camera(), None, method="raster_march", denoise=True),
            r"denoise=True needs method 'straight' or 'curved'",
        ),
        (
            lambda: shading.thin_film_reflectance(1, 1, 1.33, 1.5, 0, thickness=-300, wavelength=550),
            r"thin_film_reflectance: thickness must be >= 0 and finite \(got -300\)$",
        ),
        (
            lambda: refracta.MboitSettings(z_near=-5, z_far=100).validate(),
            r"z_near must be > 0 with z_far > z_near \(got z_near -5, z_far 100\)",
        ),
        (lambda: refracta.Turbulence.memory_needed(0), r"cells must be >= 8 \(got 0\)"),
        (
            lambda: refracta.edit.solve(refracta.PhysicalAtmosphere(), small_camera(), None),
            r"pairs must be a PointPair",
        ),
    ],
)
def test_messages_name_the_argument_the_user_gave(call, message):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", refracta.SceneWarning)
        with pytest.raises(ValueError, match=message):
            call()


def test_scene_methods_take_pathlib_paths(tmp_path):
    # add_obj, add_ground(texture=), add_billboard, add_mesh(texture=) and set_sky(environment=) gave
    # pybind's signature dump for a pathlib.Path; set_environment said "radiance must hold real numbers".
    obj = tmp_path / "triangle.obj"
    obj.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    texture, environment = tmp_path / "grey.png", tmp_path / "sky.exr"
    refracta.io.write_image(texture, np.full((4, 4, 3), 0.5, np.float32))
    refracta.io.write_image(environment, np.ones((4, 8, 3), np.float32))
    scene = refracta.Scene()
    assert scene.add_obj(obj) == [0]
    assert scene.add_ground(0, 10, texture=texture) == 1
    assert scene.add_billboard((5, 1, 0), 2, 2, texture) == 2
    square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
    uvs = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    assert scene.add_mesh(square, [[0, 1, 2], [0, 2, 3]], uvs=uvs, texture=texture) == 3
    scene.set_sky(environment=environment)
    scene.set_environment(environment)
    assert len(scene.lights) == 1  # the environment replaced the sky


def small_turbulence():
    return refracta.Turbulence(1e-10, cells=16, spacing=0.1)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: small_turbulence().at_time("1"), r"at_time: t must be a finite number of seconds \(got '1'\)"),
        (lambda: small_turbulence().at_time(float("nan")), r"at_time: t must be a finite number"),
        (lambda: small_turbulence().structure_function([float("nan")]), r"r must be finite and >= 0 m"),
        (lambda: small_turbulence().structure_function([-1.0]), r"r must be finite and >= 0 m"),
        # A boolean is not a colour (Diffuse(True) was a white reflectance).
        (lambda: shading.Diffuse(True), r"must hold real numbers \(got dtype bool\)"),
        (
            lambda: refracta.Scene().set_sun((0, 1, 0), [1.0, 1.0], wavelengths=[-5.0, 500.0]),
            r"wavelengths must be finite, > 0 nm and increasing \(got -5 at 0\)",
        ),
    ],
)
def test_small_validation_gaps(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_out_of_range_mtl_values_are_clamped_with_a_warning(tmp_path):
    (tmp_path / "m.mtl").write_text("newmtl odd\nKd 5 -1 0.5\nKs 0.1 0.1 0.1\nNs -3\nd 7\n")
    (tmp_path / "m.obj").write_text("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl odd\nf 1 2 3\n")
    scene = refracta.Scene()
    moved = r"material 'odd' has Kd \(5, -1, 0\.5\), Ks .*, Ns -3, d 7 out of range; moved"
    with pytest.warns(UserWarning, match=moved):
        (part,) = scene.add_obj(tmp_path / "m.obj")
    # As renderers read MTL files: albedos and opacity in [0, 1], the exponent >= 0, and Kd + Ks
    # <= 1: Kd clamped to (1, 0, 0.5), then both scaled by 1 / 1.1 (Ks 0.1 was in range alone); in
    # double since tinyobjloader's double build (10 digits shown: 10/11, 5/11, 1/11).
    assert "kd=(0.9090909091, 0, 0.4545454545), ks=(0.09090909091" in repr(scene.material(part))
