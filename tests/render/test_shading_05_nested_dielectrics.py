"""Nested dielectrics (Schmidt & Budge 2002, JGT 7(2); shared/SHADING.md section 4): glass (1.5,
priority 1) holding water (1.33, priority 2). Through planar layers the invariant n sin(theta)
fixes every layer's angle, so a camera looking at 45 degrees through the stack at a large emitter
below sees Le * prod_k (1 - F_k) with F_k the Fresnel reflectance at each true interface's
relative index (1.33/1.5 at glass-water, not 1.33/1 or 1.5/1), when max_depth equals the number of
true interfaces (a path that reflects anywhere needs more events to reach the emitter, and the
(eta_i/eta_t)^2 radiance scalings cancel from air to air). A false hit (a glass surface inside the
higher-priority water) is passed without an event but still updates the path's interior list: the
water's lower face then separates water from glass, not water from air (which would total-
internally reflect at 45 degrees)."""

import numpy as np

import refracta
from refracta.shading import Dielectric

from .shading_scenes import box_mesh, fresnel_dielectric

SPP = 256
NOISE_SIGMAS = 4.0  # the image mean (16 x 16 x 256 Bernoulli-like samples) within 4 standard errors
GLASS, WATER = 1.5, 1.33
INCIDENCE = 45.0
W = 50.0  # half width of the layers [m]


def transmission(layers):
    """prod (1 - F) over consecutive layer indices, air-to-air, at the incidence angle."""
    s = np.sin(np.radians(INCIDENCE))
    total = 1.0
    for n_i, n_t in zip(layers[:-1], layers[1:]):
        cos_i = np.sqrt(1.0 - (s / n_i) ** 2)
        total *= 1.0 - fresnel_dielectric(cos_i, n_t / n_i)
    return total


def render_stack(scene, interfaces):
    scene.add_mesh(
        np.array([[-200, -6, -200], [200, -6, -200], [200, -6, 200], [-200, -6, 200.0]]),
        np.array([[0, 2, 1], [0, 3, 2]]),
        emission=(1.0, 1.0, 1.0),
    )
    d = np.array([np.sin(np.radians(INCIDENCE)), -np.cos(np.radians(INCIDENCE)), 0.0])
    camera = refracta.Camera(-30.0 * d, [0.0, 0.0, 0.0], vfov=0.5, width=16, height=16)
    image = refracta.render(scene, camera, None, transport="direct", spp=SPP, max_depth=interfaces, progress=False)
    values = image[..., 0].ravel()
    return values.mean(), values.std(ddof=1) / np.sqrt(values.size)  # pixels are alike: all at 45 deg


def check(mean, stderr, layers):
    expected = transmission(layers)
    assert abs(mean - expected) <= NOISE_SIGMAS * stderr, (mean, expected, stderr)
    return expected


def test_water_inside_solid_glass():
    # Glass y in [-3, 3], water y in [-1, 1] inside it: four true interfaces.
    scene = refracta.Scene()
    scene.add_mesh(*box_mesh([-W, -3, -W], [W, 3, W]), material=Dielectric(GLASS, priority=1))
    scene.add_mesh(*box_mesh([-W, -1, -W], [W, 1, W]), material=Dielectric(WATER, priority=2))
    mean, stderr = render_stack(scene, 4)
    check(mean, stderr, [1.0, GLASS, WATER, GLASS, 1.0])
    # The wrong indices would be far outside the noise: water against air at both its faces.
    assert abs(transmission([1.0, GLASS, 1.0, WATER, 1.0, GLASS, 1.0]) - mean) > 10 * stderr


def test_half_filled_glass_with_water_overlapping_its_wall():
    # A hollow glass (outer y in [-3, 3], cavity y in [-1, 1], one mesh: one medium), water in
    # y in [-1.2, 0] overlapping the cavity's floor by 0.2 m (the usual way to model a filled
    # glass), air above it. Layers: air | glass | air | water | glass | air; the cavity's floor at
    # y = -1 lies inside the water: a false hit.
    outer_v, outer_t = box_mesh([-W, -3, -W], [W, 3, W])
    inner_v, inner_t = box_mesh([-W + 1, -1, -W + 1], [W - 1, 1, W - 1], inward=True)
    scene = refracta.Scene()
    scene.add_mesh(
        np.vstack([outer_v, inner_v]),
        np.vstack([outer_t, inner_t + len(outer_v)]),
        material=Dielectric(GLASS, priority=1),
    )
    scene.add_mesh(*box_mesh([-W + 1, -1.2, -W + 1], [W - 1, 0, W - 1]), material=Dielectric(WATER, priority=2))
    mean, stderr = render_stack(scene, 5)
    check(mean, stderr, [1.0, GLASS, 1.0, WATER, GLASS, 1.0])
