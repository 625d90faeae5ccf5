"""Sunlight over a spherical Earth (CurvedEarth's flat frame): a surface X km from the scene's
origin has its local vertical turned by the central angle X / R, so a sun given in the origin's
frame stands higher over ground toward it and lower over ground away from it. Found by a new user
of terrain: beyond ~30 km, where X / R exceeds the sun's radius (0.265 deg), every shadow ray left
the air beside the disc and sunlit ground 100 km away rendered black."""

import math

import numpy as np
import pytest

import refracta
from refracta import shading

EARTH_RADIUS = 6371e3  # [m]
DISTANCE = 100e3  # [m] from the origin: a central angle of 0.90 deg, 3.4 sun radii
# The two sides' irradiance ratio against the closed form: both patches lose the same few per cent of
# their disc samples to the air's refraction (shadow rays over a spherical Earth are launched along
# the sun's direction in the point's frame, not pre-bent: direct_lighting.h), which cancels in the
# ratio up to the difference of refraction between local elevations 29.1 and 30.9 deg (~0.1 %) and
# the disc sampling's noise (measured 0.1 % at 30 deg and 2e-6 at 60 deg).
RATIO_TOLERANCE = 5e-3


def patch_radiance(x: float, sun_elevation: float) -> float:
    """Mean radiance of a white-ish diffuse patch on the ground at (x, 0, 0), seen from 20 m above."""
    scene = refracta.Scene()
    corners = np.array([[x - 50, 0, -50], [x + 50, 0, -50], [x - 50, 0, 50], [x + 50, 0, 50]], float)
    scene.add_mesh(corners, np.array([[0, 2, 1], [1, 2, 3]]), material=shading.Diffuse(0.5))
    e = math.radians(sun_elevation)
    scene.set_sun((math.cos(e), math.sin(e), 0.0), (1.0, 1.0, 1.0))  # toward +x, the patch at +x's side
    camera = refracta.Camera((x, 20.0, 0.0), (x, 0.0, 0.001), (1.0, 0.0, 0.0), 1.0, 8, 8)
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius=EARTH_RADIUS)
    return float(refracta.render(scene, camera, field, spp=16, progress=False)[..., 1].mean())


@pytest.mark.parametrize("sun_elevation", [30.0, 60.0])
def test_the_sun_stands_higher_over_ground_toward_it_by_the_central_angle(sun_elevation):
    toward, away = patch_radiance(DISTANCE, sun_elevation), patch_radiance(-DISTANCE, sun_elevation)
    assert away > 0.0  # lit at all (was black)
    phi, e = DISTANCE / EARTH_RADIUS, math.radians(sun_elevation)
    assert toward / away == pytest.approx(math.sin(e + phi) / math.sin(e - phi), rel=RATIO_TOLERANCE)


def test_eye_table_over_the_curved_earth_ends_paths_where_they_escape():
    # A setting sun (examples.green_flash's air and eye, 1500 km of path): the eye's table ends
    # each path where it leaves the air (Caster::plane_escape, as a traced camera ray does), so
    # paths longer than 150 km are served from it; the sun's rim, the sky and the warm sea's mirage
    # as the per-pixel traced render shows them.
    scene = refracta.Scene()
    scene.add_ground(0.0, 2.0e5, material=shading.Diffuse((0.1, 0.2, 0.3)))
    scene.set_environment((0.2, 0.3, 0.5))
    e = math.radians(-0.74)
    scene.set_sun((math.cos(e), math.sin(e), 0.0), (1000.0, 800.0, 600.0), angular_diameter=0.53)
    look = math.radians(-0.05)
    camera = refracta.Camera(
        (0.0, 4.0, 0.0), (1000 * math.cos(look), 4 + 1000 * math.sin(look), 0.0), vfov=0.7, width=12, height=12
    )
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(surface_dt=3.0, surface_depth=2.0))
    table = refracta.render(scene, camera, field, max_length=1.5e6, progress=False)
    traced = refracta.render(scene, camera, field, max_length=1.5e6, table=False, progress=False)
    assert np.sum(traced > 100.0) > 0  # the sun's disc is in the frame
    # Both end in the same escape integral; they differ by the table's interpolation of the path
    # below it (measured 0): a quarter pixel's shift would move the sun's rim by ~1e-1 of the maximum.
    np.testing.assert_allclose(table, traced, rtol=0.0, atol=1e-4 * float(np.max(traced)))
