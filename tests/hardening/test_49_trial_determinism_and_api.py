"""Defects found by a determinism trial of 7 December (threads, tiles, pixel_bounds, processes:
everything else bit-identical): animate(pixel_bounds=) stretched a 1-pixel window over whole frames
and refused any other window with numpy's broadcast error; the command line took no Python tuple
for --set pixel_bounds=(x0, y0, x1, y1)."""

import numpy as np
import pytest

import refracta
from refracta import cli, examples


def test_animate_with_pixel_bounds_gives_frames_of_the_window():
    road = examples.hot_road(48, 18)
    noise = dict(rms=1e-3, correlation_pixels=8.0, seed=3)  # frames that differ: a shaken camera
    common = dict(times=[0.0, 0.5], noise=noise, progress=False, max_length=road.max_length, spp=1)
    whole = refracta.animate(road.scene, road.camera, road.field, **common)
    for bounds in ((5, 3, 30, 11), (7, 5, 8, 6), (0, 5, 48, 6)):
        x0, y0, x1, y1 = bounds
        window = refracta.animate(road.scene, road.camera, road.field, pixel_bounds=bounds, **common)
        assert window.shape == (2, y1 - y0, x1 - x0, 3)
        # Each pixel exactly as in the whole frame (its seed is the whole image's).
        np.testing.assert_array_equal(window, whole[:, y0:y1, x0:x1])


def test_the_command_line_reads_a_python_tuple_as_an_array():
    assert cli._option("pixel_bounds=(10, 5, 50, 30)") == ("pixel_bounds", [10, 5, 50, 30])
    assert cli._option("pixel_bounds=[10, 5, 50, 30]") == ("pixel_bounds", [10, 5, 50, 30])
    assert cli._option("trace=rk45") == ("trace", "rk45")  # a bare word stays a string


def test_examples_set_physical_sky_names_the_sun_as_scene_set_physical_sky_does():
    # An API review: examples.set_physical_sky(direction=) against Scene.set_physical_sky(sun_direction=).
    scene = refracta.Scene()
    examples.set_physical_sky(scene, sun_direction=(0.0, 1.0, 0.0))
    with pytest.warns(DeprecationWarning, match="direction= is deprecated; call it sun_direction="):
        examples.set_physical_sky(scene, direction=(0.0, 1.0, 0.0))
    with pytest.raises(TypeError, match="give sun_direction"):
        examples.set_physical_sky(scene)
    with pytest.raises(TypeError, match="pass sun_direction only"):
        examples.set_physical_sky(scene, (0.0, 1.0, 0.0), direction=(0.0, 1.0, 0.0))
