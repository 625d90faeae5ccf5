"""A glass slab displaces a ray by t sin(theta - theta_t) / cos(theta_t) (shared/SHADING.md
section 9; Snell's law at two parallel faces: the ray leaves parallel to itself, shifted
perpendicular to it).

Scene: an emissive half-plane x < 0 (its edge along y) on the plane z = -Z_EMITTER, facing +z,
nothing else lit; a Dielectric(1.5) slab of thickness t, large sideways, tilted by theta about
y (normal (sin theta, 0, cos theta)); a camera DISTANCE metres away on +z with a field of view
a few centimetres wide, so its rays are parallel to -z to 4e-4 rad. 'direct' transport with
max_depth 2 keeps exactly the refract-refract chain (internal reflections, which would add
ghost edges of relative weight F^2 ~ 2e-3, end unlit).

The edge is located sub-pixel from the image: on each row, the pixels' radiance over the
plateau value (the emitter fully seen) is the covered fraction of each pixel (box filter, the
jitter is uniform over each stratum), so the covered width in pixels is sum(value / plateau);
the edge's world x on the emitter plane follows from Camera.ray through that pixel coordinate.
The shift between the renders with and without the slab is compared with the formula: a ray
refracted toward the slab's inner normal leaves shifted to -x, so the edge appears at +d.
"""

import numpy as np
import pytest

import refracta
from refracta.shading import Dielectric

from .shading_scenes import box_mesh, fresnel_dielectric

ETA = 1.5
DISTANCE = 50.0  # camera distance [m]
VIEW = 0.04  # field of view width at the slab [m]
SIZE = 64  # pixels per side: pixel = VIEW / SIZE = 0.625 mm
SPP = 64  # an 8 x 8 stratified grid per pixel (a perfect square: see test_shading_07)
Z_EMITTER = 0.8  # the emitter plane behind the slab's centre [m]
LE = 1.0
PIXEL = VIEW / SIZE
# Sub-pixel edge from area fractions averaged over SIZE rows: each edge pixel's fraction has the
# binomial noise of the Fresnel choice, sqrt(p (1 - p) / SPP) / p ~ 0.04 per pixel, ~0.005 pixel
# over 64 rows; Embree's float32 hit distance at 50 m is ~3e-6 m = 0.005 pixel; each refracted
# ray starts 1e-5 m off its face (SurfaceInteraction::offset_toward), moving the exit ray sideways
# by up to 1e-5 (sin theta_t + sin theta) m ~ 0.02 pixel (measured +0.007 to +0.016 pixel).
# 0.03 pixel (19 um, 0.3% of the ~5.5 mm shifts) bounds the three.
EDGE_PIXELS = 0.03
# The plateau (fully covered pixels) is the emitter's radiance times the chance of refracting at
# both faces, (1 - F)^2; its estimate over ~2000 pixels x 64 samples has a relative error ~1e-3.
PLATEAU = 5e-3


def slab_mesh(thickness, theta_deg, half=0.3):
    """A box thickness [m] deep along its normal, 2 half wide, rotated by theta about +y."""
    v, tri = box_mesh([-half, -half, -thickness / 2], [half, half, thickness / 2])
    a = np.radians(theta_deg)
    rot = np.array([[np.cos(a), 0.0, np.sin(a)], [0.0, 1.0, 0.0], [-np.sin(a), 0.0, np.cos(a)]])
    return v @ rot.T, tri


def scene(thickness=None, theta_deg=0.0):
    s = refracta.Scene()
    v = np.array([[-1.0, -1.0, -Z_EMITTER], [0.0, -1.0, -Z_EMITTER], [0.0, 1.0, -Z_EMITTER], [-1.0, 1.0, -Z_EMITTER]])
    s.add_mesh(v, np.array([[0, 1, 2], [0, 2, 3]]), emission=(LE, LE, LE))  # counter-clockwise seen from +z
    if thickness is not None:
        s.add_mesh(*slab_mesh(thickness, theta_deg), material=Dielectric(ETA))
    return s


def camera(centre_x):
    vfov = np.degrees(2.0 * np.arctan(VIEW / 2.0 / DISTANCE))
    return refracta.Camera([centre_x, 0.0, DISTANCE], [centre_x, 0.0, 0.0], (0, 1, 0), vfov, SIZE, SIZE)


def edge_x(image, cam):
    """(world x of the edge on the emitter plane, plateau radiance): covered width per row from
    area fractions, averaged over rows, then mapped through Camera.ray."""
    grey = np.asarray(image, float).mean(-1)
    columns = grey.mean(0)
    covered = columns > 0.5 * columns.max()
    first_dark = int(np.argmin(covered))
    assert covered[:first_dark].all() and not covered[first_dark:].any(), columns  # one edge
    assert 4 <= first_dark <= SIZE - 4, first_dark  # inside the view, with a plateau to its left
    plateau = grey[:, : first_dark - 2].mean()
    u = float((grey / plateau).sum(1).mean())  # covered width [pixels] from the left border
    origin, direction = cam.ray(u, SIZE / 2)
    t = (-Z_EMITTER - origin[2]) / direction[2]
    return origin[0] + t * direction[0], plateau


def displacement(thickness, theta_deg):
    theta = np.radians(theta_deg)
    theta_t = np.arcsin(np.sin(theta) / ETA)
    return thickness * np.sin(theta - theta_t) / np.cos(theta_t)


def render(s, cam):
    return refracta.render(s, cam, None, transport="direct", spp=SPP, max_depth=2, progress=False)


def test_edge_without_slab_is_at_zero():
    cam = camera(0.3 * VIEW)
    x, plateau = edge_x(render(scene(), cam), cam)
    assert abs(x) < EDGE_PIXELS * PIXEL, x / PIXEL
    assert plateau == pytest.approx(LE, rel=1e-6)  # the plateau's emission through float32 pixels


@pytest.mark.parametrize("thickness,theta_deg", [(0.04, 20.0), (0.02, 40.0), (0.01, 60.0), (0.03, 30.0)])
def test_slab_displacement(thickness, theta_deg):
    expected = displacement(thickness, theta_deg)
    cam = camera(expected + 0.2 * VIEW)  # the shifted edge 30% right of the view's left border
    x, plateau = edge_x(render(scene(thickness, theta_deg), cam), cam)
    base, _ = edge_x(render(scene(), camera(0.2 * VIEW)), camera(0.2 * VIEW))
    shift = x - base
    print(
        f"t {thickness} m theta {theta_deg}: shift {shift * 1e3:.4f} mm, formula {expected * 1e3:.4f} mm, "
        f"difference {(shift - expected) / PIXEL:+.4f} pixel"
    )
    assert abs(shift - expected) < EDGE_PIXELS * PIXEL, (shift - expected) / PIXEL
    # sanity: the edge moved by several pixels, so the test would see a missing refraction
    assert expected > 5 * PIXEL
    transmit = (1.0 - fresnel_dielectric(np.cos(np.radians(theta_deg)), ETA)) ** 2
    assert plateau == pytest.approx(LE * transmit, rel=PLATEAU)


def test_glass_seen_from_afar_transmits():
    """The plateau through a 2 cm slab at normal incidence, camera 500 m away, is (1 - F(0))^2."""
    cam = refracta.Camera(
        [-0.2 * VIEW, 0.0, 500.0],
        [-0.2 * VIEW, 0.0, 0.0],
        (0, 1, 0),
        np.degrees(2.0 * np.arctan(VIEW / 2.0 / 500.0)),
        SIZE,
        SIZE,
    )
    image = np.asarray(render(scene(0.02, 0.0), cam), float).mean(-1)
    transmit = (1.0 - fresnel_dielectric(1.0, ETA)) ** 2
    assert image[:, :10].mean() == pytest.approx(LE * transmit, rel=0.02)  # binomial noise ~0.3%
