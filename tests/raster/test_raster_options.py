"""The raster renderer's options as bound classes: fields by their C++ names, nested, pickled
through their fields, validated with every problem listed; render_raster's flat keywords land in
the nested fields and leave the caller's options object as it was."""

import pickle

import numpy as np
import pytest

import refracta
from refracta._raster_render import raster_render_options

CAMERA = refracta.Camera(position=(0, 6, 14), look_at=(0, 0, 0), vfov=40, width=48, height=32)


def lit_box():
    scene = refracta.Scene()
    scene.add_ground(size=40.0)
    scene.add_box((0, 1, 0), (2, 2, 2))
    scene.set_sun((-0.4, 0.8, 0.3), (3.0, 3.0, 3.0))
    return scene


def test_nested_fields_are_edited_in_place_and_pickled():
    options = refracta.RasterRenderOptions()
    options.shadow_map.resolution = 256
    options.shadow_map.moments.depth_range = "signed"
    options.shadow_map.moments.bias_vector = (0.1, 0.2, 0.3, 0.4)
    options.transparency = refracta.OitSettings(method="mboit")
    options.transparency.mboit.basis = "trigonometric"
    options.transparency.mboit.moments = 3
    copy = pickle.loads(pickle.dumps(options))
    assert copy.shadow_map.resolution == 256 and copy.shadow_map.moments.depth_range == "signed"
    assert copy.shadow_map.moments.bias_vector == (0.1, 0.2, 0.3, 0.4)
    assert copy.transparency.method == "mboit" and copy.transparency.mboit.basis == "trigonometric"
    assert copy.transparency.mboit.moments == 3 and repr(copy) == repr(options)


def test_validate_lists_every_problem_of_the_nested_options():
    options = refracta.RasterRenderOptions()  # the keyword constructor validates: set them after
    options.tile = 0
    options.shadow_map.kernel = 4
    options.shadow_map.moments.bias = 2.0
    options.transparency = refracta.OitSettings(method="mboit")
    options.transparency.mboit.beta = -1.0
    with pytest.raises(ValueError) as error:
        options.validate()
    for problem in (
        "tile must be in [1, 65536] pixels",
        "kernel must be an odd size",
        "bias must be in [0, 1)",
        "beta must be in [0, 1]",
    ):
        assert problem in str(error.value)


def test_unset_biases_are_the_published_ones():
    settings = refracta.MomentShadowSettings()
    assert settings.bias is None and settings.bias_vector is None
    assert refracta.MomentShadowSettings.published_bias("unit", "fp32") == 3e-6
    assert refracta.MomentShadowSettings.published_bias_vector("signed") == (0.0, 0.375, 0.0, 0.375)
    # JCGT 2017's 16-bit sparse quantisation pairs 6e-5 with its own vector (MOMENTS.md 2.2).
    assert refracta.MomentShadowSettings.published_bias_vector("signed", "unorm16") == (0.0, 0.628, 0.0, 0.628)
    assert refracta.MomentShadowSettings.published_bias_vector("unit", "unorm16") == (0.5, 0.5, 0.5, 0.5)
    assert refracta.MboitSettings.published_bias("power", 4, "unorm16") == 6e-5
    # fp64 (the method in double, no GPU's storage) takes fp32's published bias.
    assert refracta.MboitSettings(storage="fp64").storage == "fp64"
    assert refracta.MboitSettings.published_bias("power", 4, "fp64") == 5e-7
    with pytest.raises(ValueError, match=r"storage must be 'fp64', 'fp32' or 'unorm16' \(got 'fp16'\)"):
        refracta.MboitSettings(storage="fp16")


def test_flat_keywords_set_the_nested_fields_of_a_copy():
    given = refracta.RasterRenderOptions()
    options = raster_render_options(
        given,
        lights="sun",
        shadows="vsm",
        resolution=512,
        kernel=3,
        storage="unorm16",
        transparency="peel",
        layers=2,
        output="shadow",
    )
    assert (options.shadows, options.shadow_map.method, options.shadow_map.resolution) == ("map", "vsm", 512)
    assert options.shadow_map.kernel == 3 and options.shadow_map.moments.storage == "unorm16"
    assert options.transparency.method == "peel" and options.transparency.layers == 2
    assert options.output == "shadow" and options.use_sun and options.spots == []
    assert repr(given) == repr(refracta.RasterRenderOptions())  # the caller's object is untouched
    assert raster_render_options(shadows="embree").shadows == "embree"


def test_options_and_keywords_render_the_same_image():
    keywords = refracta.render_raster(lit_box(), CAMERA, shadows="vsm", resolution=256, kernel=3)
    options = refracta.RasterRenderOptions()
    options.shadow_map.method, options.shadow_map.resolution, options.shadow_map.kernel = "vsm", 256, 3
    image, stats = refracta.render_raster(lit_box(), CAMERA, options=options, return_stats=True)
    np.testing.assert_array_equal(image, keywords)  # the same options, the same deterministic render
    # VSM reads two fp32 moments (E[z], E[z^2]); it was reported as 4MSM's 16 (a trial)
    assert isinstance(stats, refracta.RasterRenderStats) and stats.bytes_per_texel == 8
    assert pickle.loads(pickle.dumps(stats)).bytes_per_texel == 8
    _, msm = refracta.render_raster(lit_box(), CAMERA, shadows="msm_hamburger", resolution=256, return_stats=True)
    assert msm.bytes_per_texel == 16  # four fp32 moments


@pytest.mark.parametrize(
    "keywords, message",
    [
        (dict(moments=6), "transparency is None"),
        (dict(resolution=512.5), "resolution"),
        (dict(options="pcf"), "options must be a refracta.RasterRenderOptions"),
        (dict(colour="red"), "unknown option 'colour'"),
    ],
)
def test_bad_keywords_name_themselves(keywords, message):
    with pytest.raises(ValueError, match=message):
        refracta.render_raster(lit_box(), CAMERA, **keywords)


def test_the_one_keyword_rule_follows_dotted_paths():
    build = refracta._core._build_options
    options = build(refracta.RasterRenderOptions, None, "here", {"shadow_map.moments.storage": "fp32", "tile": 8.0})
    assert options.shadow_map.moments.storage == "fp32" and options.tile == 8  # 8.0: a whole number
    with pytest.raises(ValueError, match="here: shadow_map.nope= names shadow_map.nope: no field nope"):
        build(refracta.RasterRenderOptions, None, "here", {"shadow_map.nope": 1})
    with pytest.raises(ValueError, match="here: layers= sets transparency.layers, but transparency is None"):
        build(refracta.RasterRenderOptions, None, "here", {"layers": 2}, {"layers": "transparency.layers"})
    with pytest.raises(ValueError, match=r"here: depth_range='half': depth_range must be"):
        build(
            refracta.RasterRenderOptions,
            None,
            "here",
            {"depth_range": "half"},
            {"depth_range": "shadow_map.moments.depth_range"},
        )


@pytest.mark.parametrize(
    "lights, message",
    [
        # Found as a new user: render_raster(scene, camera, field) as render(scene, camera, field)
        # raised TypeError "'PhysicalAtmosphere' object is not iterable", naming neither argument.
        (refracta.PhysicalAtmosphere(), r"lights must be None, 'sun', 'spots'.*render_raster takes no atmosphere"),
        (3, r"lights must be None, 'sun', 'spots' or a list of 'sun' and spot indices \(got 3\)"),
        (["sun", 1.5], "lights entries must be 'sun' or spot-light indices"),
    ],
)
def test_bad_lights_name_the_argument(lights, message):
    with pytest.raises(ValueError, match=message):
        refracta.render_raster(lit_box(), CAMERA, lights)
