"""Defects earlier new-user trials found and the last stop left open: each is now computed right or
refused by name."""

import numpy as np
import pytest

import refracta
from refracta import io, lights, shading, spectrum


def test_turbulence_at_any_finite_time_is_the_pattern_carried_by_the_wind():
    air = refracta.Turbulence(cells=16, spacing=0.05, depth=None)
    points = np.array([[1.0, 0.3, 2.0], [-7.5, 0.02, 40.0]])
    c, s = np.cos(air.yaw), np.sin(air.yaw)
    for t in (0.37, 1e6):
        shifted = points - np.array([air.wind[0] * t, 0.0, air.wind[1] * t])
        lattice = np.c_[c * shifted[:, 0] + s * shifted[:, 2], shifted[:, 1], -s * shifted[:, 0] + c * shifted[:, 2]]
        expected, _ = air.grid.evaluate(lattice)
        value, _ = air.at_time(t).layer.evaluate(points)
        # The layer reduces the wind's shift modulo the tile (exactly, by fmod) before adding it:
        # at t = 1e6 s the shift is 2e6 m, whose rotation rounds at ~1e-9 m, 2e-8 of a cell.
        np.testing.assert_allclose(value, np.sqrt(air.cn2) * expected, rtol=1e-6)
    value, gradient = air.at_time(1e18).layer.evaluate(points)  # a shift beyond a long's range of cells
    assert np.isfinite(value).all() and np.isfinite(gradient).all()
    assert np.abs(value).max() <= np.sqrt(air.cn2) * air.grid.bound  # the spline's bound: a value of the pattern


def test_a_jittered_camera_keeps_its_map_at_its_size_and_refuses_another():
    camera = refracta.Camera((0, 1, 0), (1, 1, 0), vfov=40, width=8, height=4)
    angles = np.full((4, 8, 2), 1e-3, dtype=np.float32)
    jittered = camera.jittered(angles)
    same = jittered.resized(8, 4)
    np.testing.assert_array_equal(same.jitter, angles)
    assert same.ray(3.5, 1.5)[1].tolist() == jittered.ray(3.5, 1.5)[1].tolist()
    with pytest.raises(ValueError, match=r"Camera.resized: this camera is jittered.*4 x 8 pixels"):
        jittered.resized(16, 8)
    assert camera.resized(16, 8).jitter is None


@pytest.mark.parametrize("distribution", [shading.Beckmann(0.3), shading.TrowbridgeReitz(0.3, 0.3)])
def test_microfacets_face_out_of_the_surface(distribution):
    up, down = [0.6, 0.0, 0.8], [0.6, 0.0, -0.8]
    d = distribution.D([up, down])
    assert d[0] > 0.0 and d[1] == 0.0  # D is a density over the upper hemisphere: int D cos = 1 there


def test_environment_uvs_and_light_pmfs_refuse_what_has_none():
    env = lights.EnvironmentLight(np.ones((8, 16, 3)))
    with pytest.raises(ValueError, match=r"direction_to_uv: dirs\[1\] must be a finite non-zero vector"):
        env.direction_to_uv([[1, 0, 0], [0, 0, 0]])
    np.testing.assert_array_equal(env.direction_to_uv([[1e200, 0, 0]]), env.direction_to_uv([[1, 0, 0]]))
    sampler = lights.LightSampler([env, lights.PointLight((0, 1, 0), 1.0)])
    assert sampler.pmf(0) + sampler.pmf(1) == pytest.approx(1.0, rel=1e-12)  # a distribution: sums to 1
    with pytest.raises(ValueError, match=r"LightSampler.pmf: index must be in \[0, 2\) \(got 2\)"):
        sampler.pmf(2)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: refracta.Camera((0, 1, 0), (1, 1, 0), vfov=40, width=8, height=4).ray("a", 1), r"Camera.ray: u"),
        (lambda: io.ev100("f/8", 1.0), r"ev100: f_number must be a number"),
        (lambda: io.ev100(8, 1.0, iso=[100]), r"ev100: iso must be a number"),
        (lambda: spectrum.blackbody("hot", 550.0), r"blackbody: temperature must be a number"),
        (lambda: spectrum.blackbody(5000.0, "green"), r"wavelengths must be a number or numbers \[nm\]"),
        (lambda: spectrum.xyz_to_linear_srgb("white"), r"xyz must be numbers, shape \(3,\) or \(N, 3\)"),
    ],
)
def test_helpers_of_one_number_name_what_is_not_one(call, message):
    with pytest.raises(ValueError, match=message):
        call()
