"""Spot lights: the inverse-square law and the cone in shading, perspective shadow maps against
Embree shadow rays, and sampled area lights as the soft reference."""

import numpy as np
import pytest

import refracta

KD = 0.5
HEIGHT = 5.0


def lamp_scene(radius=0.0, occluder=True):
    scene = refracta.Scene()
    scene.set_sky((0.0, 0.0, 0.0))  # no sky light, no sun: the lamp alone
    scene.set_sun((0, 1, 0), (0.0, 0.0, 0.0))
    scene.add_ground(0.0, 100.0, kd=(KD, KD, KD))
    if occluder:  # lit from the side, its shadow falls beside it where the camera sees it
        scene.add_spot_light(
            (3.0, HEIGHT, 0.0), (-3.0, -HEIGHT, 0.0), angle=100.0, intensity=(200.0, 200.0, 200.0), radius=radius
        )
        scene.add_box((1.5, 1.5, 0.0), (1.0, 0.4, 1.0))
    else:
        scene.add_spot_light((0.0, HEIGHT, 0.0), (0.0, -1.0, 0.0), angle=100.0, intensity=(200.0, 200.0, 200.0))
    return scene


CAMERA = refracta.Camera((0.0, 12.0, -0.01), (0.0, 0.0, 0.0), (0, 0, 1), 60.0, 96, 96)


def test_ground_radiance_follows_the_inverse_square_law():
    """Lambertian ground: L = (kd / pi) I cos(theta) / d^2 (Blinn-Phong's diffuse term)."""
    scene = lamp_scene(occluder=False)
    image = refracta.render(scene, CAMERA, None, method="straight", progress=False)
    for x, z in [(0.3, 0.2), (2.0, 1.0), (3.5, -1.5)]:
        u, v, _ = CAMERA.project([x, 0.0, z])
        origin, direction = CAMERA.ray(int(u) + 0.5, int(v) + 0.5)
        point = origin + direction * (-origin[1] / direction[1])  # the pixel centre's ground point
        d2 = point[0] ** 2 + HEIGHT**2 + point[2] ** 2
        expected = KD / np.pi * 200.0 * (HEIGHT / np.sqrt(d2)) / d2
        # Float32 film and Embree's float hit point: ~1e-7 relative each, 1e-5 with margin.
        assert image[int(v), int(u), 0] == pytest.approx(expected, rel=1e-5)


def test_nothing_is_lit_outside_the_cone():
    scene = lamp_scene(occluder=False)
    image = refracta.render(scene, CAMERA, None, method="straight", progress=False)
    u, v, _ = CAMERA.project([6.5, 0.0, 0.0])  # 52 deg off the axis, the cone's half angle is 50
    assert image[int(v), int(u)].max() == 0.0


def test_a_spot_shadow_map_matches_shadow_rays():
    scene = lamp_scene()
    truth = refracta.render_raster(scene, CAMERA, shadows="embree", output="shadow", shadow_light=0)
    mapped = refracta.render_raster(scene, CAMERA, shadows="hard", output="shadow", shadow_light=0, resolution=1024)
    valid = (truth[..., 1] > 0) & (mapped[..., 1] > 0)
    in_shadow, lit = valid & (truth[..., 0] == 1), valid & (truth[..., 0] == 0)
    assert in_shadow.sum() > 50  # the box's shadow beside it
    assert np.mean(mapped[..., 0][in_shadow] == 1) > 0.9
    # Lit pixels stay lit but within a texel of an edge (as test_shadow_maps).
    assert np.mean(mapped[..., 0][lit] == 0) > 0.99


def test_an_area_light_casts_a_penumbra_that_filtered_moments_follow():
    """A 0.5 m disc: Embree's 64 samples give an umbra (1) and a penumbra (0 < s < 1); filtered
    MSM from the spot's perspective map approximates it better than a hard map."""
    scene = lamp_scene(radius=0.5)
    soft = refracta.render_raster(scene, CAMERA, shadows="embree", output="shadow", shadow_light=0)
    shadow = soft[..., 0][soft[..., 1] > 0]
    assert np.any(shadow == 1.0) and np.any((shadow > 0.05) & (shadow < 0.95))
    errors = {}
    for method, filtering in (("hard", {}), ("msm_hamburger", {"kernel": 15})):
        image = refracta.render_raster(
            scene, CAMERA, shadows=method, output="shadow", shadow_light=0, resolution=512, **filtering
        )
        valid = (soft[..., 1] > 0) & (image[..., 1] > 0)
        errors[method] = np.abs(image[..., 0] - soft[..., 0])[valid].mean()
    assert errors["msm_hamburger"] < errors["hard"]


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(angle=0.0), "angle"),
        (dict(angle=400.0), "angle"),
        (dict(radius=-1.0), "radius"),
        (dict(direction=(0, 0, 0)), "direction"),
        (dict(intensity=(1, -1, 1)), "intensity"),
    ],
)
def test_bad_spot_lights_raise_value_error(kwargs, match):
    args = dict(position=(0, 5, 0), direction=(0, -1, 0))
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        refracta.Scene().add_spot_light(**args)


def test_a_missing_spot_light_index_raises_value_error():
    with pytest.raises(ValueError, match="shadow_light"):
        refracta.render_raster(lamp_scene(), CAMERA, shadows="hard", output="shadow", shadow_light=3)


def test_lights_select_the_scene_lights():
    scene = lamp_scene(occluder=False)
    scene.set_sun((0.2, 1.0, 0.1), (1e3, 1e3, 1e3))
    both = refracta.render_raster(scene, CAMERA, shadows="embree")
    sun = refracta.render_raster(scene, CAMERA, "sun", shadows="embree")
    spot = refracta.render_raster(scene, CAMERA, [0], shadows="embree")
    np.testing.assert_allclose(both, sun + spot, rtol=1e-5, atol=1e-6)  # light adds up
    assert spot.max() > 0 and sun.max() > 0
    with pytest.raises(ValueError, match="spot light 2"):
        refracta.render_raster(scene, CAMERA, [2], shadows="embree")
    with pytest.raises(ValueError, match="lights"):
        refracta.render_raster(scene, CAMERA, "moon", shadows="embree")
