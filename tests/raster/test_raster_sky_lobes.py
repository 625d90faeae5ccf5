"""render_raster lights a surface under a sky by light_strata^2 BSDF samples whose lobe choice is
shuffled against their directions (raster_renderer.cpp): a lobe of small probability -- a rough
dielectric's reflection, F ~ 0.03 at the view's ~70 deg from the normal -- is sampled across the
directions (the R2 sequence's order of the strata), not in one row or on a few lines of them."""

import pytest

import refracta
from refracta import shading

CAMERA = refracta.Camera((0.0, 3.0, 0.0), (0.0, 0.0, 3.0), vfov=20, width=20, height=20)


def rough_water_under_a_sky(material):
    scene = refracta.Scene()
    scene.add_ground(-1.0, 100.0, material=shading.Diffuse(0.0))  # black below: the reflection alone
    scene.add_ground(0.0, 100.0, material=material)
    scene.set_sky(1.0)
    return scene


@pytest.mark.parametrize("material", [shading.Water(body=False), shading.RoughDielectric(0.17, ior=1.33)])
def test_a_rough_dielectric_under_a_sky_reflects_it_as_the_ray_renderer_does(material):
    scene = rough_water_under_a_sky(material)
    reference = refracta.render(scene, CAMERA, None, transport="direct", spp=64, progress=False).mean()
    # The reflection lobe takes ~F n^2 of the n^2 samples (F ~ 0.03): 2 at n = 8, 123 at 64, so the
    # quadrature's error falls from tens of % to a few. Measured (raster / direct): Water 0.68, 0.90,
    # 0.94, 0.99 and RoughDielectric 0.72, 1.03, 1.02, 0.98 at n = 8, 16, 32, 64; before the lobe
    # ranks, Water was 0.13-0.15 at every n (7-10x too dark).
    for strata, tolerance in ((8, 0.4), (16, 0.12), (32, 0.12), (64, 0.05)):
        raster = refracta.render_raster(scene, CAMERA, light_strata=strata).mean()
        assert raster == pytest.approx(reference, rel=tolerance), (strata, raster, reference)
