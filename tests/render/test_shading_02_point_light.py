"""Lambert under a point light (shared/SHADING.md sections 5 and 9): a Diffuse(R) plane at depth h
below a point light of intensity I renders L = R/pi * I cos(theta)/r^2 at each pixel's hit point
(found here from Camera.ray and the plane, independently of Embree). 'direct' with one delta light
and spp 1 (pixel centres) is deterministic."""

import numpy as np
import pytest

import refracta
from refracta.shading import Diffuse

from .shading_scenes import floor_points, quad_mesh

# float32 film and Embree's float hit points (~1e-7 relative in r^2 and cos): 2e-6 relative.
DETERMINISTIC = 2e-6
R = (0.6, 0.3, 0.9)
INTENSITY = (5.0, 2.0, 7.0)  # I [W/sr] per channel
LIGHT = np.array([0.3, 1.2, -0.2])


@pytest.mark.parametrize("transport", ["direct", "path"])
def test_lambertian_plane_under_a_point_light(transport):
    scene = refracta.Scene()
    scene.add_mesh(*quad_mesh(5.0), material=Diffuse(R))
    scene.add_point_light(LIGHT, INTENSITY)
    camera = refracta.Camera([0.0, 0.8, 3.0], [0.0, 0.0, 0.0], vfov=50, width=24, height=16)
    image = refracta.render(scene, camera, None, transport=transport, spp=1, max_depth=1, progress=False)
    expected = np.zeros_like(image, dtype=float)
    for j in range(camera.height):
        for i in range(camera.width):
            origin, direction = camera.ray(i + 0.5, j + 0.5)
            points, hit = floor_points(np.asarray(origin), direction, 5.0)
            if hit[0]:
                r = LIGHT - points[0]
                r2 = r @ r
                expected[j, i] = np.array(R) / np.pi * np.array(INTENSITY) * (r[1] / np.sqrt(r2)) / r2
    # The light reaches a good part of the view: the comparison is not vacuous.
    assert (expected[..., 0] > 0).mean() > 0.4
    # DETERMINISTIC (derived above); 1e-9 absolute for the black pixels.
    np.testing.assert_allclose(image, expected, rtol=DETERMINISTIC, atol=1e-9)
