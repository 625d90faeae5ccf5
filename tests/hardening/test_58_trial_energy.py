"""What a rendering researcher's energy audit of the path tracer found (white furnaces, BSDF
consistency, Mitsuba 3): a bounce limit that wrapped round, and a coat index that divided by 0."""

import numpy as np
import pytest

import refracta
from refracta import shading


def furnace(max_depth, transport):
    scene = refracta.Scene()
    scene.add_sphere((0.0, 0.0, 0.0), 1.0, material=shading.Diffuse(1.0))
    scene.set_environment((1.0, 1.0, 1.0))
    camera = refracta.Camera((0.0, 0.0, 4.0), (0.0, 0.0, 0.0), vfov=30, width=8, height=8)
    return refracta.render(scene, camera, None, transport=transport, spp=16, max_depth=max_depth, progress=False)


@pytest.mark.parametrize("transport", ["direct", "path"])
def test_a_bounce_limit_near_two_to_the_thirtieth_is_a_limit_not_a_wrap(transport):
    # 4 max_depth + 64 passes, counted in int, wrapped negative for max_depth >= 536 870 896 and
    # a white sphere in a white furnace rendered 0.635 where it renders 1. A convex sphere's paths
    # leave it after one bounce: every bounce limit from 1 on draws the same samples.
    np.testing.assert_array_equal(furnace(10**9, transport), furnace(5, transport))


def test_a_plastic_coat_index_beyond_100_is_refused():
    # ior 5e6 and up: the coat's internal diffuse reflectance rounded to 1, a white base's
    # 1 / (1 - R Fdr) was infinite and every sample invalid (a black sphere, no message).
    with pytest.raises(ValueError, match="ior must be at most 100"):
        shading.Plastic(1.0, ior=1e9, alpha=0.3)
    f = shading.Plastic(1.0, ior=100.0, alpha=0.3).f(np.array([0.6, 0.0, 0.8]), np.array([0.0, 0.0, 1.0]))
    assert np.all(np.isfinite(f)) and np.all(f > 0.0)
