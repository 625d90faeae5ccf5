"""A Diffuse(R) floor under a square emissive quad: pixel radiance R/pi * E, E from Lambert's
polygon formula E = L/2 sum_i gamma_i n . (r_i x r_{i+1}) / |r_i x r_{i+1}| (the edge
integral of a uniform Lambertian polygon; Arvo 1995, eq. 2), through 'direct' and 'path'
(max_depth 1), both with next-event estimation and BSDF sampling joined by MIS.

The two strategies cannot be switched off from Python, so the test covers both regimes of the
power heuristic: a large quad close to the floor (BSDF sampling carries much of the weight) and a
small, far one (light sampling carries almost all). Both must match the closed form: MIS weights
that did not sum to one, or a strategy that lost samples, shows as a bias in one regime.
"""

import numpy as np
import pytest

import refracta
from refracta.shading import Diffuse

from .shading_scenes import check_against, floor_points, pixel_grid_mean, quad_mesh

SEEDS = 16  # independent 16-spp renders: their spread gives each pixel's standard error; the
# bound is Student's t (15 dof) at a Bonferroni-corrected 1e-3 false alarm (~4.9 sigma)
SUBPIXELS = 6  # closed form averaged over a 6 x 6 grid per pixel (the render jitters over
# the pixel); the grid's quadrature error is below 1e-3 relative here
QUADRATURE = 2e-3  # relative allowance for that pixel quadrature
MEAN_SIGMAS = 4.0  # the whole image's relative error, in its standard errors (from the seeds' sums)
R = 0.6
LE = 3.0


def polygon_irradiance(points, normal, verts, radiance):
    """Lambert's formula: irradiance [W/m^2] at points (N, 3) with unit normal from a uniform
    Lambertian polygon verts (K, 3) of radiance L (all of it above the points' horizon)."""
    E = np.zeros(len(points))
    r = verts[None, :, :] - points[:, None, :]
    r /= np.linalg.norm(r, axis=2, keepdims=True)
    for i in range(len(verts)):
        a, b = r[:, i], r[:, (i + 1) % len(verts)]
        c = np.cross(a, b)
        gamma = np.arccos(np.clip(np.sum(a * b, axis=1), -1.0, 1.0))
        E += gamma * (c @ normal) / np.linalg.norm(c, axis=1)
    return np.abs(E) * radiance / 2.0


def scene_and_camera(half, height):
    quad = np.array([[-half, height, -half], [half, height, -half], [half, height, half], [-half, height, half]])
    scene = refracta.Scene()
    scene.add_mesh(*quad_mesh(6.0), material=Diffuse(R))
    v, t = quad, np.array([[0, 1, 2], [0, 2, 3]])  # front (counter-clockwise) facing -y: down
    scene.add_mesh(v, t, emission=(LE, LE, LE))
    camera = refracta.Camera([0.0, 0.6 * height, 1.8], [0.0, 0.0, -0.3], vfov=55, width=16, height=12)
    return scene, camera, quad


def expected_image(camera, quad):
    def radiance(points):
        return R / np.pi * polygon_irradiance(points, np.array([0.0, 1.0, 0.0]), quad, LE)

    return pixel_grid_mean(camera, SUBPIXELS, lambda o, d: floor_points(o, d, 6.0), radiance)


@pytest.mark.parametrize("half,height", [(0.8, 0.6), (0.1, 2.0)], ids=["large_near", "small_far"])
@pytest.mark.parametrize("transport", ["direct", "path"])
def test_floor_under_a_quad_light_matches_the_polygon_formula(transport, half, height):
    scene, camera, quad = scene_and_camera(half, height)
    expected, on_floor = expected_image(camera, quad)
    renders = np.array(
        [
            refracta.render(scene, camera, None, transport=transport, spp=16, max_depth=1, seed=seed, progress=False)[
                ..., 0
            ]
            for seed in range(SEEDS)
        ]
    )
    mask = on_floor & (expected > 1e-3 * expected.max())
    worst, bound, relative, relative_stderr = check_against(renders, expected, mask, QUADRATURE * expected)
    assert worst <= bound, (worst, bound)
    assert relative <= MEAN_SIGMAS * relative_stderr + QUADRATURE, (relative, relative_stderr)
