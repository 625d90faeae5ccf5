"""A render is a pure function of scene, camera, field and options: the first render of a scene
(the one that commits its Embree BVH) equals every later one, bit for bit.

Embree's rtcCommitScene sets flush-to-zero and denormals-are-zero while it builds the BVH on the
TBB pool, and the workers kept that mode for the render's first tiles, so the first render of a
scene whose Water ground underflows to subnormals at grazing angles differed from the later ones
(refracta.core parallel.h: DefaultFloatingPointMode).
"""

import numpy as np
import pytest

import refracta
from refracta import shading


def _water_scene() -> refracta.Scene:
    scene = refracta.Scene()
    scene.add_ground(0.0, 2000.0, material=shading.Water())
    scene.set_sky((0.5, 0.6, 0.8))
    return scene


@pytest.mark.parametrize("spectral", [False, True])
def test_first_render_of_a_water_scene_equals_the_next(spectral: bool) -> None:
    camera = refracta.Camera((0, 2, 0), (10, 0, 0.5), vfov=40, width=32, height=32)
    scene = _water_scene()

    def render() -> np.ndarray:
        return refracta.render(scene, camera, None, progress=False, spp=8, max_length=1e4, spectral=spectral)

    first, second = render(), render()
    assert np.array_equal(first, second), f"{int((first != second).any(-1).sum())} pixels differ"
