"""render_raster lights area lights through the ray renderers' light evaluation (DirectLighting,
its shadow rays aimed at the sampled light point): a sphere lamp over a Lambertian ground against
the closed form, with Embree shadow rays and without shadows alike."""

import numpy as np
import pytest

import refracta

KD, L, R, D = 0.5, 10.0, 0.5, 3.0  # albedo, the lamp's radiance, radius [m] and height [m]


def sphere_lamp_scene():
    scene = refracta.Scene()
    scene.set_sky((0.0, 0.0, 0.0))  # no sky, no sun: the lamp alone
    scene.set_sun((0, 1, 0), (0.0, 0.0, 0.0))
    scene.add_ground(0.0, 100.0, kd=(KD, KD, KD))
    scene.add_sphere((0.0, D, 0.0), R, emission=(L, L, L))
    return scene


CAMERA = refracta.Camera((0.0, 8.0, -6.0), (0.0, 0.0, 0.0), (0, 1, 0), 40.0, 64, 64)


@pytest.mark.parametrize("shadows", ["embree", "none"])
def test_a_sphere_lamp_lights_the_ground_as_the_closed_form(shadows):
    """A sphere of radiance L wholly above a surface gives it irradiance pi L (R / d)^2 cos theta
    (d, theta: distance and angle to its centre), so a Lambertian ground reflects kd L (R/d)^2 cos."""
    image = refracta.render_raster(sphere_lamp_scene(), CAMERA, shadows=shadows)
    for x, z in [(0.0, 0.0), (1.5, 0.5), (-2.0, 1.0)]:
        u, v, _ = CAMERA.project([x, 0.0, z])
        origin, direction = CAMERA.ray(int(u) + 0.5, int(v) + 0.5)
        point = origin + direction * (-origin[1] / direction[1])  # the pixel centre's ground point
        d = np.linalg.norm(np.array([0.0, D, 0.0]) - point)
        expected = KD * L * (R / d) ** 2 * (D / d)
        # light_strata 8: 64 stratified samples of the lamp's cone (measured within 1.2e-6 of the
        # closed form); 1e-4 leaves room for the sampling, well below the 26 % the lamp lost when
        # its shadow rays met its own surface.
        assert image[int(v), int(u), 0] == pytest.approx(expected, rel=1e-4)
