"""A real-time graphics researcher's trial of the moment shadow maps and MBOIT: what it found."""

import numpy as np
import pytest

import refracta
from refracta import moments

LIT = 0.0625  # the floor's mean radiance with the quad away (measured): the scale of a lost shadow


@pytest.mark.parametrize("gap", [0.008, 0.003])
def test_an_occluder_a_few_millimetres_from_a_spot_light_still_casts_its_shadow(gap):
    # The spot map's near plane was 1 cm: a lamp shade's quad 8 mm or 3 mm below the light was clipped
    # and every shadow it cast was lost (the map lit, Embree dark).
    scene = refracta.Scene()
    scene.add_ground(0.0, 40.0)
    scene.set_environment((0.0, 0.0, 0.0))
    quad = np.array([[-0.5, 1, -0.5], [0.5, 1, -0.5], [0.5, 1, 0.5], [-0.5, 1, 0.5]], float)
    scene.add_mesh(quad, np.array([[0, 2, 1], [0, 3, 2]]))
    scene.add_spot_light((0.0, 1.0 + gap, 0.0), (0.0, -1.0, 0.0), 90.0, (100.0,) * 3)
    camera = refracta.Camera((0, 8, 6), (0, 0, 0), (0, 1, 0), 60, 60, 45)
    exact = refracta.render_raster(scene, camera, shadows="embree", light_strata=1).mean()
    for shadows in ("hard", "msm_hamburger"):
        mapped = refracta.render_raster(scene, camera, shadows=shadows, light_strata=1).mean()
        # The quad hides the whole cone: Embree 0; a map within 1e-4 of the lit mean (MSM's leak
        # through its bias is ~1e-6 of it, measured 8e-8).
        assert abs(mapped - exact) < 1e-4 * LIT, (shadows, mapped, exact)


@pytest.mark.parametrize("vector", [(1.0, 0.0, 1.0, 0.0), (0.5, 0.1, 0.5, 0.1)])
def test_a_bias_vector_that_is_no_distribution_s_moments_is_refused(vector):
    # In the box, but the Hankel matrix is indefinite: (1, 0, 1, 0) made a shadow of 1.0 where PCF is 0.65.
    b = [0.22386402, 0.05016604, 0.01125341, 0.00252705]
    with pytest.raises(ValueError, match="positive semi-definite"):
        moments.shadow_intensity(b, 0.2288538780037529, bias=1e-3, bias_vector=vector)
    with pytest.raises(ValueError, match="positive semi-definite"):
        refracta.MomentShadowSettings(bias_vector=vector).validate()


def test_the_published_bias_vectors_are_accepted():
    b = [0.22386402, 0.05016604, 0.01125341, 0.00252705]
    for vector, depth_range in [((0.5, 0.5, 0.5, 0.5), "unit"), ((0.0, 0.375, 0.0, 0.375), "signed")]:
        # (0.5, ...) is the two-point distribution on {0, 1}: its Hankel matrix is singular (eigenvalue 0).
        settings = refracta.MomentShadowSettings(bias_vector=vector, depth_range=depth_range)
        settings.validate()
    assert 0.0 <= moments.shadow_intensity(b, 0.2288538780037529, bias=1e-3, bias_vector=(0.5,) * 4) <= 1.0


def test_a_huge_moment_count_is_refused_not_a_hang():
    with pytest.raises(ValueError, match=r"count must be a whole number in \[1, 1024\]"):
        moments.power_moments([0.5], count=10**9)
    assert moments.power_moments([0.5], count=1024).shape == (1024,)
