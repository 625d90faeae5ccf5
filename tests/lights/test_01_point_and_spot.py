"""Point and spot lights: the inverse-square law, the cone, the falloff and the power."""

import numpy as np
import pytest

from refracta.lights import PointLight, SpotLight

# Closed forms evaluated in double precision: only rounding separates them.
EXACT = 1e-12
# Power by a 20000-interval midpoint rule in cos(theta) over a smoothstep: error ~ 1e-9.
QUADRATURE = 1e-7


def test_point_light_irradiance_is_I_cos_over_r_squared(rng):
    intensity, position = 7.5, np.array([0.3, 4.0, -1.2])
    light = PointLight(position, intensity)
    points = rng.uniform(-3, 3, size=(50, 3)) * [1, 0, 1]
    normals = np.tile([0.0, 1.0, 0.0], (50, 1))
    wi, L, pdf, r = light.sample_li(points, normals, rng.random((50, 2)))
    d = position - points
    np.testing.assert_allclose(r, np.linalg.norm(d, axis=1), rtol=EXACT)
    np.testing.assert_allclose(wi, d / r[:, None], rtol=0, atol=EXACT)
    np.testing.assert_array_equal(pdf, 1.0)
    irradiance = L[:, 0] * np.sum(wi * normals, axis=1) / pdf
    cos = d[:, 1] / r
    np.testing.assert_allclose(irradiance, intensity * cos / r**2, rtol=EXACT)
    assert np.all(light.pdf_li(points, normals, wi) == 0.0)


def test_point_light_rgb_and_power():
    light = PointLight([0, 1, 0], [1.0, 2.0, 3.0])
    _, L, _, _ = light.sample_li(np.zeros((1, 3)), None, np.zeros((1, 2)))
    np.testing.assert_allclose(L[0], [1.0, 2.0, 3.0], rtol=EXACT)
    y = 0.2126 * 1 + 0.7152 * 2 + 0.0722 * 3  # luminance of the RGB intensity
    assert light.power == pytest.approx(4 * np.pi * y, rel=EXACT)
    assert PointLight([0, 0, 0], 2.0).power == pytest.approx(8 * np.pi, rel=EXACT)
    assert light.type == "delta_position" and light.is_delta


def test_point_light_at_the_point_gives_nothing_and_no_nan():
    light = PointLight([1.0, 2.0, 3.0], 1.0)
    wi, L, pdf, r = light.sample_li(np.array([[1.0, 2.0, 3.0]]), None, np.zeros((1, 2)))
    assert pdf[0] == 0 and np.all(np.isfinite(wi)) and np.all(L == 0)


def test_spot_hard_edge_full_inside_zero_outside():
    angle = 60.0
    light = SpotLight([0, 5, 0], [0, -1, 0], angle, 10.0)
    # Points on the ground at angles 29 and 31 degrees from the axis.
    inside = np.array([[5 * np.tan(np.radians(29.0)), 0, 0]])
    outside = np.array([[5 * np.tan(np.radians(31.0)), 0, 0]])
    _, L_in, pdf_in, r_in = light.sample_li(inside, None, np.zeros((1, 2)))
    _, L_out, pdf_out, _ = light.sample_li(outside, None, np.zeros((1, 2)))
    assert L_in[0, 0] == pytest.approx(10.0 / r_in[0] ** 2, rel=EXACT) and pdf_in[0] == 1
    assert pdf_out[0] == 0 and L_out[0, 0] == 0
    assert light.power == pytest.approx(2 * np.pi * 10.0 * (1 - np.cos(np.radians(30.0))), rel=EXACT)


def test_spot_smoothstep_falloff_and_its_power():
    angle, inner, intensity = 80.0, 40.0, 3.0
    light = SpotLight([0, 0, 0], [0, 0, 1], angle, intensity, inner_angle=inner)
    cos_o, cos_i = np.cos(np.radians(angle / 2)), np.cos(np.radians(inner / 2))
    theta = np.radians(np.array([5.0, 19.9, 25.0, 30.0, 35.0, 39.9, 45.0]))
    points = np.stack([np.sin(theta), np.zeros_like(theta), np.cos(theta)], axis=1) * 2.0
    _, L, _, _ = light.sample_li(points, None, np.zeros((len(theta), 2)))
    t = np.clip((np.cos(theta) - cos_o) / (cos_i - cos_o), 0, 1)
    expected = intensity * t * t * (3 - 2 * t) / 2.0**2  # pbrt-v4 SpotLight::I, r = 2
    np.testing.assert_allclose(L[:, 1], expected, rtol=EXACT, atol=EXACT)
    # Power by quadrature of the falloff over the sphere, independent of the closed form.
    edges = np.linspace(-1, 1, 20001)
    c = 0.5 * (edges[1:] + edges[:-1])
    tt = np.clip((c - cos_o) / (cos_i - cos_o), 0, 1)
    power = 2 * np.pi * intensity * np.sum(tt * tt * (3 - 2 * tt)) * (edges[1] - edges[0])
    assert light.power == pytest.approx(power, rel=QUADRATURE)


def test_scene_add_spot_light_takes_the_smooth_falloff_of_lights_spotlight():
    # A trial against Mitsuba 3: only lights.SpotLight took inner_angle, the scene's shorthand made
    # hard-edged spots alone. Now the same light either way: the same image to the bit.
    import refracta

    def floor_under(add):
        scene = refracta.Scene()
        scene.add_ground(0.0, 20.0, kd=0.5)
        add(scene)
        camera = refracta.Camera((0.0, 6.0, 0.01), (0.0, 0.0, 0.0), vfov=60.0, width=24, height=24)
        return refracta.render(scene, camera, None, spp=2, progress=False)

    args = ((0.0, 3.0, 0.0), (0.0, -1.0, 0.0), 60.0, (10.0, 10.0, 10.0))
    shorthand = floor_under(lambda s: s.add_spot_light(*args, inner_angle=30.0))
    assert np.array_equal(shorthand, floor_under(lambda s: s.add_light(SpotLight(*args, inner_angle=30.0))))
    assert not np.array_equal(shorthand, floor_under(lambda s: s.add_spot_light(*args)))  # the hard edge
    for bad in (-5.0, 0.0, 70.0, float("nan")):
        with pytest.raises(ValueError, match=r"add_spot_light: inner_angle must be in \(0, angle = 60\]"):
            refracta.Scene().add_spot_light(*args, inner_angle=bad)
