"""A mirror reproduces the environment (shared/SHADING.md section 9): a smooth Conductor() (F = 1)
plane renders, at each pixel, the environment's radiance along the camera ray reflected about the
plane's normal (and the environment itself where the ray misses the plane). The map is a smooth
function sampled on refracta's documented texel grid (column i at u = (i + 1/2)/W, row j at
v = j/(H - 1), Mitsuba's u = atan2(d.x, -d.z)/2 pi, v = acos(d.y)/pi), so its bilinear lookup
matches the function to the interpolation bound."""

import numpy as np

import refracta
from refracta.shading import Conductor

from .shading_scenes import quad_mesh

H, W = 96, 192
# Bilinear interpolation of f: |error| <= (du^2 f_uu + dv^2 f_vv) / 8 with du = 1/W, dv = 1/(H - 1):
# 0.4 (2 pi)^2 / W^2 / 8 + (0.4 + 0.3) pi^2 / (H - 1)^2 / 8 = 5.4e-5 + 9.6e-5; float32 film on top.
INTERPOLATION = 2e-4


def environment(u, v):
    return 1.0 + 0.4 * np.sin(2 * np.pi * u) * np.sin(np.pi * v) + 0.3 * np.cos(np.pi * v)


def uv(d):
    d = d / np.linalg.norm(d, axis=-1, keepdims=True)
    return (np.arctan2(d[..., 0], -d[..., 2]) / (2 * np.pi)) % 1.0, np.arccos(np.clip(d[..., 1], -1, 1)) / np.pi


def test_mirror_plane_reflects_the_environment():
    u = (np.arange(W) + 0.5) / W
    v = np.arange(H) / (H - 1)
    values = environment(u[None, :], v[:, None])
    image = np.repeat(values[:, :, None], 3, axis=2).astype(np.float32)
    scene = refracta.Scene()
    scene.add_mesh(*quad_mesh(50.0), material=Conductor())
    scene.set_environment(image)
    camera = refracta.Camera([0.0, 1.0, 0.0], [3.0, -0.4, 2.0], vfov=70, width=24, height=16)
    rendered = refracta.render(scene, camera, None, transport="direct", spp=1, max_depth=2, progress=False)
    expected = np.zeros((camera.height, camera.width))
    mirrored = 0
    for j in range(camera.height):
        for i in range(camera.width):
            origin, d = camera.ray(i + 0.5, j + 0.5)
            t = -origin[1] / d[1] if d[1] < 0 else np.inf
            p = origin + t * d if np.isfinite(t) else None
            if p is not None and abs(p[0]) < 50 and abs(p[2]) < 50:
                d = d * np.array([1.0, -1.0, 1.0])  # reflected about +y
                mirrored += 1
            expected[j, i] = environment(*uv(d))
    assert mirrored > 0.3 * camera.width * camera.height
    np.testing.assert_allclose(rendered[..., 0], expected, rtol=0, atol=INTERPOLATION)
