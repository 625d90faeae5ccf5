"""Bools are not numbers anywhere in the module, nor numbers bools, and a scene file says what the Python calls say.

A new-user trial found pybind11 taking True as 1 in every bound number parameter (Camera(vfov=True)
drew a 1-degree view, HotSpot(True, ...) stood at x = 1); scene-file errors located twice or on the
table's first line instead of the key's; [sun] refusing limb_darkening that [[lights]] takes;
inputs taken and ignored (an explicit aerosol beside visibility, two_sided without emission,
texture_size without a texture).
"""

import re

import numpy as np
import pytest

import refracta

EYE, AHEAD = (0.0, 1.5, 0.0), (100.0, 1.0, 0.0)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: refracta.Camera(EYE, AHEAD, vfov=True), "Camera: vfov must be a number (got True)"),
        (lambda: refracta.Camera(EYE, AHEAD, width=True), "Camera: width must be a whole number or None (got True)"),
        # (numpy's repr of its bool: np.True_, or True under legacy print options another test may set)
        (lambda: refracta.Camera(EYE, AHEAD, vfov=np.bool_(True)), "Camera: vfov must be a number (got "),
        (
            lambda: refracta.Camera.photographic(EYE, AHEAD, True),
            "Camera.photographic: focal_length_mm must be a number (got True)",
        ),
        (lambda: refracta.HotSpot(True, 0.0, 10.0, 5.0), "HotSpot: x must be a number (got True)"),
        (
            lambda: refracta.Scene().add_sphere((0.0, 0.0, 0.0), False),
            "Scene.add_sphere: radius must be a number (got False)",
        ),
    ],
)
def test_a_bool_is_refused_where_a_number_is_expected(make, message):
    # Refused by the C++ conversion (strict_numbers.h), named by refracta/_arguments.py (pybind11
    # said "incompatible function arguments").
    with pytest.raises(refracta.ArgumentError, match=re.escape(message)):
        make()


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: refracta.shading.Water(body=0), "Water: body must be True or False (got 0)"),
        (lambda: refracta.shading.Water(body=1.0), "Water: body must be True or False (got 1.0)"),
        (
            lambda: refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0), multiple_scattering=1),
            "PhysicalSky: multiple_scattering must be True or False (got 1)",
        ),
        (
            lambda: refracta.Scene().set_aerial_perspective("yes"),
            "Scene.set_aerial_perspective: enabled must be True or False (got 'yes')",
        ),
        (
            lambda: refracta.Scene().set_physical_sky((0.0, 1.0, 0.0), aerial_perspective=None),
            "Scene.set_physical_sky: aerial_perspective must be True or False (got None)",
        ),
    ],
)
def test_a_number_or_string_is_refused_where_a_bool_is_expected(make, message):
    # pybind11 converts anything with __bool__: a flag given 0.5 or one argument slot off passed.
    with pytest.raises(TypeError, match=re.escape(message)):  # an ArgumentError is a TypeError
        make()


def test_python_and_numpy_bools_are_still_bools():
    assert refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0), multiple_scattering=np.bool_(False)) is not None
    refracta.Scene().set_aerial_perspective(np.bool_(False))
    refracta.shading.Water(body=False)


@pytest.mark.parametrize(
    ("options", "field", "value"),
    [
        (refracta.RenderOptions, "adaptive", 1),
        (refracta.RenderOptions, "spectral", 0.0),
        (refracta.RenderOptions, "differentials", None),
        (refracta.RasterRenderOptions, "use_sun", 1),
    ],
)
def test_an_options_flag_set_as_an_attribute_takes_a_bool_only(options, field, value):
    # As the constructor's keywords (options_binding.cpp set_field): pybind11's setter took a truth.
    target = options()
    with pytest.raises(ValueError, match=f"{options.__name__}: {field} must be True or False"):
        setattr(target, field, value)
    setattr(target, field, np.bool_(True))
    assert getattr(target, field) is True


def test_options_attributes_other_than_flags_set_as_before():
    options = refracta.RenderOptions()
    options.spp, options.seed = 8, 3
    assert (options.spp, options.seed) == (8, 3)
    options.spp = 12.0  # a whole float for an integer field, as the keywords take it
    assert options.spp == 12 and isinstance(options.spp, int)
    options.pixel_bounds = (0, 0, 4, 4)
    options.pixel_bounds = None  # an optional field takes None
    assert options.pixel_bounds is None


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("spp", True, "RenderOptions: spp must be a number (got True)"),
        ("spp", 2.5, "RenderOptions: spp must be a whole number (got 2.5)"),
        ("spp", None, "RenderOptions: spp cannot be None"),
        ("seed", 2**70, "RenderOptions: seed=1180591620717411303424 is out of the range of RenderOptions.seed"),
        ("max_length", "far", "RenderOptions: max_length must be a number (got 'far')"),
    ],
)
def test_an_options_attribute_refused_names_the_field(field, value, message):
    # The keywords' messages (options_binding.cpp set_refused); pybind11's setter raised a TypeError
    # listing its signature ("incompatible function arguments").
    options = refracta.RenderOptions()
    with pytest.raises(ValueError, match=re.escape(message)):
        setattr(options, field, value)
    unknown = "no_such_field"  # pybind11's classes take no new attributes; the strict setter keeps that
    with pytest.raises(AttributeError):
        setattr(options, unknown, 1)


def test_numpy_numbers_and_ints_for_floats_are_still_numbers():
    camera = refracta.Camera(EYE, AHEAD, vfov=np.float32(30.0), width=np.int64(32), height=16)
    assert (camera.vfov, camera.width) == (30.0, 32)
    assert refracta.HotSpot(np.float64(1.5), 0, 10, 5).x == 1.5


def test_integers_beyond_their_type_and_fractions_are_refused():
    with pytest.raises(TypeError):
        refracta.Camera(EYE, AHEAD, width=2**40)
    with pytest.raises(TypeError):
        refracta.Camera(EYE, AHEAD, width=32.5)


def test_an_options_field_names_a_bool_given_for_a_number():
    with pytest.raises(ValueError, match="spp must be a number"):
        refracta.RenderOptions(spp=True)


@pytest.mark.parametrize(
    "make",
    [
        lambda: refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0), aerosol=1.0, visibility=10.0),
        lambda: refracta.Scene().set_physical_sky((0.0, 1.0, 0.0), aerosol=1.0, visibility=10.0),
    ],
)
def test_an_explicit_default_aerosol_beside_visibility_is_refused(make):
    # aerosol=1.0 is the default's value: it was taken as "not given" and silently replaced.
    with pytest.raises(ValueError, match="give aerosol or visibility, not both"):
        make()


def test_visibility_alone_sets_the_aerosol_and_none_keeps_the_clear_sky():
    assert refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0), aerosol=None).aerosol == 1.0  # C++'s default
    # 10 km of visibility is far hazier than the clear sky (~100+ km): several times its aerosol.
    assert refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0), visibility=10.0).aerosol > 3.0


def test_two_sided_without_emission_and_texture_size_without_texture_are_refused():
    scene = refracta.Scene()
    triangle = dict(vertices=[(0, 0, 0), (1, 0, 0), (0, 1, 0)], triangles=[(0, 1, 2)])
    with pytest.raises(ValueError, match="two_sided makes an area light emit from both faces"):
        scene.add_mesh(**triangle, two_sided=True)
    scene.add_mesh(**triangle, emission=(1.0, 1.0, 1.0), two_sided=True)
    with pytest.raises(ValueError, match="texture_size applies to a texture"):
        scene.add_ground(texture_size=3.0)


def test_a_sphere_names_its_own_radius():
    with pytest.raises(ValueError, match=r"add_sphere: radius must be > 0 \(got -1"):
        refracta.Scene().add_sphere((0.0, 0.0, 0.0), -1.0)


CAMERA = "[camera]\nposition = [0, 1.5, 0]\nlook_at = [100, 1, 0]\nvfov = 10\nsize = [32, 16]\n"


def load(tmp_path, text):
    path = tmp_path / "scene.toml"
    path.write_text(CAMERA + text)
    return refracta.load_scene(path)


@pytest.mark.parametrize(
    "text, line, key, message",
    [
        # Located once, at the key (it was "scene.toml:6: [[objects]] #1: scene.toml:9: ...").
        ('[[objects]]\ntype = "sphere"\ncentre = [10, 0, 0]\nradius = "a"\n', 9, "radius", "must be a number"),
        # At the key the library's message names (was the table's first line, no key).
        ('[[objects]]\ntype = "sphere"\ncentre = [10, 0, 0]\nradius = -1\n', 9, "radius", "radius must be > 0"),
        ('[[objects]]\ntype = "box"\ncentre = [10, 0, 0]\nsize = [1, -1, 1]\n', 9, "size", "size must be > 0"),
        ('[[objects]]\ntype = "ground"\ntexture_size = 3.0\n', 8, "texture_size", "texture_size applies to a texture"),
        (
            '[[objects]]\ntype = "mesh"\nvertices = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\ntriangles = [[0, 1, 2]]\n'
            "two_sided = true\n",
            10,
            "two_sided",
            "give emission",
        ),
        # [sun] takes limb_darkening as [[lights]]' sun and Scene.set_sun do (it was an unknown key).
        ("[sun]\ndirection = [0, 1, 0]\nradiance = [1, 1, 1]\nlimb_darkening = 2\n", 9, "limb_darkening", r"\[0, 1\]"),
        (
            '[environment]\ntype = "physical_sky"\nsun_direction = [0, 1, 0]\naerosol = 1.0\nvisibility = 10\n',
            9,
            "aerosol",
            "not both",
        ),
        (
            '[[lights]]\ntype = "spot"\nposition = [0, 5, 0]\ndirection = [0, -1, 0]\nintensity = [1, 1, 1]\n'
            "inner_angle = 10\n",
            11,
            "inner_angle",
            "needs the cone's angle",
        ),
    ],
)
def test_scene_file_errors_name_the_line_and_key_once(tmp_path, text, line, key, message):
    with pytest.raises(ValueError, match=message) as error:
        load(tmp_path, text)
    text_of_error = str(error.value)
    assert text_of_error.count("scene.toml") == 1, text_of_error
    assert f"scene.toml:{line}:" in text_of_error
    if key is not None:
        assert f" {key}: " in text_of_error


def test_a_scene_files_sun_limb_darkening_reaches_the_sun(tmp_path):
    # The same sun through the file and through Scene.set_sun: equal renders, and unequal to the
    # undarkened disc (limb darkening dims the disc's edge, so the disc's mean radiance changes).
    sun = "[sun]\ndirection = [1, 0.0, 0]\nradiance = [100, 100, 100]\nangular_diameter = 2.0\n"
    camera = refracta.Camera(EYE, (100.0, 1.5, 0.0), vfov=4.0, width=24, height=24)

    def render(scene):
        return refracta.render(scene, camera, None, method="straight", spp=4, progress=False)

    darkened = load(tmp_path, sun + "limb_darkening = 0.8\n").scene
    direct = refracta.Scene()
    direct.set_sun((1.0, 0.0, 0.0), (100.0, 100.0, 100.0), 2.0, 0.8)
    plain = load(tmp_path, sun).scene
    np.testing.assert_array_equal(render(darkened), render(direct))  # same scene, same seed: bit-identical
    assert not np.array_equal(render(darkened), render(plain))


def test_ocean_waves_refuse_times_whose_phases_would_be_rounding_noise():
    # omega t at t = 1e20 s rounds to ~1e4 rad: a random sea, not this sea later.
    with pytest.raises(ValueError, match=r"time must be finite and within \+-1000000000 s"):
        refracta.OceanWaves(time=1e20, resolution=64)
    later = refracta.OceanWaves(time=3600.0, resolution=64)  # an hour on: the same sea, moved
    assert np.isfinite(later.heights()).all()


def test_review_findings_bools_and_planets():
    # Camera.ray took bools through its new array path (True, False was the ray through (1, 0)).
    camera = refracta.Camera(EYE, AHEAD, width=8, height=4)
    with pytest.raises(ValueError, match="Camera.ray: u must hold real numbers"):
        camera.ray(True, False)
    with pytest.raises(ValueError, match="Camera.ray: v must hold real numbers"):
        camera.ray(np.array([1.0, 2.0]), np.array([True, False]))
    # The Python layer names a non-bool flag before the strict binding's generic TypeError.
    with pytest.raises(ValueError, match="quantize: inverse must be True or False"):
        refracta.moments.quantize(np.full((1, 4), 0.5), inverse=1)
    # numpy's True and a string are no counts either (they were "must be a whole number").
    options = refracta.RenderOptions()
    for value in (np.True_, "x"):
        with pytest.raises(ValueError, match="RenderOptions: spp must be a number"):
            options.spp = value
    # A planet, not a pebble: the flat frame's n = e^(y/R) n(h) overflows 115 R up.
    with pytest.raises(ValueError, match="CurvedEarth: radius must be a planet's, at least 100000 m"):
        refracta.CurvedEarth(refracta.PhysicalAtmosphere(), 1.0)
    assert refracta.CurvedEarth(refracta.PhysicalAtmosphere(), 1e5).radius == 1e5  # the floor itself
