"""Light leaking through a shading normal is refused on both sides of MIS: a direction the shading
frame reflects into but the geometry puts across the surface counts neither as a BSDF sample (the
path integrator's rule) nor as a light sample. Light samples alone took it, MIS-weighted, so part
of it counted: a quad with tilted vertex normals under a map bright below the horizon gave 0.78 in
render and 1.03 in render_raster where the integral over the allowed directions is 0.49 (a review)."""

import numpy as np
import pytest

import refracta

from ..environment_integrals import irradiance_under_map

TILT = (0.8, 1.0, 0.0)  # the vertex normals: 38.7 deg from the quad's geometric normal (+y)
KD = 0.5


def radiance_map():
    """16 x 32: 1 above, 10 from row 8 (v = 8/15, 6 deg below the horizon) down."""
    image = np.ones((16, 32))
    image[8:] = 10.0
    return image


def tilted_quad_scene():
    scene = refracta.Scene()
    scene.set_environment(np.repeat(radiance_map()[..., None], 3, axis=2).astype(np.float32))
    quad = np.array([[-2.0, 0.0, -2.0], [-2.0, 0.0, 2.0], [2.0, 0.0, 2.0], [2.0, 0.0, -2.0]])
    normals = np.tile(np.array(TILT) / np.linalg.norm(TILT), (4, 1))
    scene.add_mesh(quad, [[0, 1, 2], [0, 2, 3]], material=refracta.shading.Diffuse(KD), normals=normals)
    return scene


CAMERA = refracta.Camera((0.0, 1.0, 0.01), (0.0, 0.0, 0.0), vfov=4, width=4, height=4)


def expected_radiance():
    return KD / np.pi * irradiance_under_map(radiance_map(), TILT)


@pytest.mark.parametrize("transport", ["direct", "path"])
def test_the_ray_renderer_refuses_light_through_a_shading_normal(transport):
    image = refracta.render(tilted_quad_scene(), CAMERA, transport=transport, max_depth=1, spp=1024, progress=False)
    # 16 pixels x 1024 samples: within 0.4 % over seeds 0-3 (measured); 2 % leaves room for that,
    # far below the leak's +58 %.
    assert image[..., 0].mean() == pytest.approx(expected_radiance(), rel=0.02)


@pytest.mark.parametrize("strata", [8, 16])
def test_the_raster_refuses_light_through_a_shading_normal(strata):
    image = refracta.render_raster(tilted_quad_scene(), CAMERA, light_strata=strata)
    # Deterministic quadrature of n^2 light and BSDF samples: measured +2.0 % at 8, +0.2 % at 16;
    # 3 % is far below the leak's +108 %.
    assert image[..., 0].mean() == pytest.approx(expected_radiance(), rel=0.03)
