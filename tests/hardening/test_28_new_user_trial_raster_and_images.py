"""What a new user's trial of the raster pipeline, images and exposure found (5 December): PNG
colours divided by their alpha, alpha scaled by the exposure, aerial perspective left out of
render_raster, shadow and light keywords taken and ignored, lens and exposure values no camera
has. (Spheres in render_raster: tests/raster/test_rasterizer.py.)"""

import numpy as np
import pytest
from PIL import Image as PIL_Image

import refracta
from refracta import compare, examples, io

# 8-bit quantisation of a display value, and float32 of a linear one.
ONE_LEVEL = 1.0  # of 255
RASTER_AIR = 0.02  # box 10 km off: raster against the ray tracer at 64 spp agreed to 0.07 % (pixel centre both)


def test_a_png_with_alpha_stores_and_reads_back_the_display_colours(tmp_path):
    # OIIO took the colours as premultiplied: a 0.5-alpha pixel's (231, 149, 63) was stored as
    # (255, 255, 125) and read back halved again.
    image = np.zeros((2, 2, 4), np.float32)
    image[..., :3], image[..., 3] = (0.8, 0.3, 0.05), 0.5
    shown = io.to_display(image, exposure=1.0, tonemap="linear")[0, 0] * 255
    path = str(tmp_path / "alpha.png")
    io.write_image(path, image, exposure=1.0, tonemap="linear")
    stored = np.asarray(PIL_Image.open(path), dtype=float)[0, 0]  # an independent reader
    np.testing.assert_allclose(stored, np.round(shown), atol=ONE_LEVEL)
    np.testing.assert_allclose(io.read_image(path)[0, 0] * 255, stored, atol=1e-3)  # float32 of n / 255, times 255


def test_a_float_file_scales_the_colours_by_the_exposure_not_the_alpha(tmp_path):
    image = np.zeros((2, 2, 4), np.float32)
    image[..., :3], image[..., 3] = (0.8, 0.3, 0.05), 0.25
    io.write_image(tmp_path / "a.exr", image, exposure=3.0)
    expected = (2.4, 0.9, 0.15, 0.25)
    np.testing.assert_allclose(io.read_image(tmp_path / "a.exr")[0, 0], expected, rtol=1e-6)  # float32 rounding


def test_render_raster_sees_distant_boxes_through_the_same_haze_as_the_ray_tracer():
    def scene(**air):
        made = refracta.Scene()
        made.add_ground(0.0, 30000.0, kd=(0.1, 0.1, 0.1))
        made.add_box((10000, 150, 0), (200, 300, 3000), kd=(0.05, 0.05, 0.05))
        made.set_physical_sky((0.3, 0.3, 0.5), scale=examples.RADIANCE_SCALE, **air)
        return made

    camera = refracta.Camera((0, 10, 0), (10000, 150, 0), (0, 1, 0), 4, 32, 16)
    hazy, clear = scene(visibility=20.0), scene(aerial_perspective=False)
    traced = refracta.render(hazy, camera, None, method="straight", spp=64, progress=False, max_length=50000)[8, 16]
    raster = refracta.render_raster(hazy, camera)[8, 16]
    assert raster.mean() > 10 * refracta.render_raster(clear, camera)[8, 16].mean()  # it was the same
    np.testing.assert_allclose(raster, traced, rtol=RASTER_AIR)


def _boxes():
    scene = refracta.Scene()
    scene.set_sun((-0.5, 0.6, 0.3), (2e4, 2e4, 2e4))
    scene.add_ground(0.0, 100.0)
    scene.add_box((4.0, 1.0, 0.0), (1.0, 2.0, 1.0))
    scene.add_spot_light((0.0, 6.0, 0.0), (0.0, -1.0, 0.0), angle=60.0, intensity=(50.0, 50.0, 50.0))
    return scene


CAMERA = refracta.Camera((-6, 6, -8), (4, 0, 0), (0, 1, 0), 50, 32, 20)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(shadows="hard", kernel=9), "kernel applies to shadows='pcf' or 'vsm'"),
        (dict(shadows="pcf", storage="fp32"), "storage applies to shadows='vsm'"),
        (dict(shadows="msm_hamburger", depth_bias=1e-3), "depth_bias applies to shadows='hard' or 'pcf'"),
        (dict(shadows="embree", resolution=512), "resolution applies to shadows='hard'"),
        (dict(shadows="pcf", bleeding_reduction=0.2), "bleeding_reduction applies to shadows='vsm'"),
        (dict(lights=["sun"], spots=[0]), "give lights= or spots=, not both"),  # spot 0 shone anyway
        (dict(lights="spots", use_sun=True), "give lights= or use_sun=, not both"),
        (dict(shadow_light=0), "shadow_light applies to output='shadow'"),
        (
            dict(lights="sun", output="shadow", shadow_light=0),
            "shadow_light 0 must index the spot lights shaded",  # said the scene had none
        ),
    ],
)
def test_render_raster_refuses_keywords_that_would_change_nothing(kwargs, match):
    with pytest.raises(ValueError, match=match):
        refracta.render_raster(_boxes(), CAMERA, **kwargs)


def test_render_raster_refuses_an_mboit_range_that_misses_its_fragments():
    scene = _boxes()
    scene.add_box((2.0, 1.0, 0.0), (0.2, 2.0, 2.0), kd=(0.8, 0.1, 0.1), alpha=0.5)
    far = refracta.OitSettings(method="mboit", mboit=refracta.MboitSettings(z_near=100.0, z_far=200.0))
    with pytest.raises(ValueError, match="must hold every transparent fragment's depth"):
        refracta.render_raster(scene, CAMERA, options=refracta.RasterRenderOptions(transparency=far))


def test_compare_transparency_refuses_no_methods():
    with pytest.raises(ValueError, match="methods must not be empty"):  # was an Axes TypeError
        compare.transparency(_boxes(), CAMERA, methods=())


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(f_number=2.0, focus_distance=1e300), r"focus_distance must be in \(0, 10000000\] m"),  # NaN lens rays
        (dict(f_number=1e-6), r"f_number must be in \[0.5, 10000\]"),  # a 50 km aperture
        (dict(focal_length_mm=1e300), r"focal_length_mm must be in \[0.1, 100000\]"),
        (dict(focal_length_mm=1e-300), r"focal_length_mm must be in \[0.1, 100000\]"),  # blamed vfov
    ],
)
def test_lenses_no_camera_has_are_refused_by_name(kwargs, match):
    kwargs.setdefault("focal_length_mm", 50.0)
    with pytest.raises(ValueError, match=match):
        refracta.Camera.photographic((0, 1.5, 0), (30, 1, 0), width=32, height=16, **kwargs)


def test_denoise_keeps_an_image_near_float32s_limit():
    # Open Image Denoise's exposure estimate overflowed: 1e38 came back as zeros.
    out = refracta.denoise(np.full((8, 8, 3), 1e38, np.float32))
    np.testing.assert_allclose(out, 1e38, rtol=0.01)  # a flat image stays flat (within 0.5 %: _denoise)


def test_exposures_no_camera_meets_are_refused_and_a_keyword_replaces_the_displays():
    image = np.full((4, 4, 3), 0.3, np.float32)
    with pytest.raises(ValueError, match="give EV100 inf, beyond"):
        io.ev100(1e300, 1e-300)  # was inf
    with pytest.raises(ValueError, match=r"ev100 must be in \[-50, 50\]"):
        io.to_display(image, ev100=1e300)  # was a black image
    with pytest.raises(ValueError, match="f_number 1e\\+300, shutter 0.01 s"):
        io.to_display(image, f_number=1e300, shutter=0.01)  # blamed ev100, not given
    # The keyword's exposure replaces the display's ev100 (it was "give one manual exposure").
    replaced = io.to_display(image, display=refracta.DisplaySettings(ev100=10.0), exposure=2.0)
    np.testing.assert_array_equal(replaced, io.to_display(image, exposure=2.0))
