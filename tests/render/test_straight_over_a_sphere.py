"""method='straight' and Camera.pick over a spherical Earth: straight lines of the true geometry,
not of the CurvedEarth's flat frame (where they would cross a flat Earth), as a new user placing a
camera by latitude and longitude found (a pixel 0.045 deg below the horizontal from 15 m showed
sea 19 km out, where the real Earth shows sky: its geometric dip is 0.124 deg)."""

import math

import numpy as np
import pytest

import refracta

R = 6371000.0
EYE = 15.0


def sea_and_camera():
    scene = refracta.Scene()
    scene.add_ground(0.0, 2e5)
    scene.set_sky((0.7, 0.8, 0.9), (0.3, 0.4, 0.8))
    # 40 rows over 0.4 deg around -0.1 deg: row r looks at -0.1 + (20 - (r + 0.5)) * 0.01 deg.
    look_at = (1000.0, EYE - 1000.0 * math.tan(math.radians(0.1)), 0.0)
    camera = refracta.Camera((0.0, EYE, 0.0), look_at, vfov=0.4, width=4, height=40)
    return scene, camera


def elevation_of_row(camera, row):
    _, direction = camera.ray(2.5, row + 0.5)
    return math.asin(direction[1])


def sphere_distance(elevation):
    """Where the straight line from EYE above a sphere of radius R, `elevation` [rad] above the
    horizontal, meets the sphere (inf where it passes above it)."""
    b = (R + EYE) * math.sin(-elevation)
    disc = b * b - (2.0 * R * EYE + EYE * EYE)
    return b - math.sqrt(disc) if disc >= 0.0 and b > 0.0 else math.inf


def test_straight_rays_over_a_curved_earth_meet_the_sphere_where_geometry_says():
    scene, camera = sea_and_camera()
    air = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), R)
    options = dict(max_length=2e5, spp=1, aovs=["distance"], progress=False)
    _, straight = refracta.render(scene, camera, air, method="straight", **options)
    _, reference = refracta.render(scene, camera, refracta.without_refraction(air), **options)
    np.testing.assert_array_equal(straight["distance"], reference["distance"])  # one idea, one path
    dip = math.acos(R / (R + EYE))
    assert math.degrees(dip) == pytest.approx(0.1243, abs=1e-4)  # the trial's figure, given to 4 decimals
    for row in (14, 24, 30, 39):
        elevation = elevation_of_row(camera, row)
        exact = sphere_distance(elevation)
        seen = float(straight["distance"][row, 2])
        if math.isinf(exact):
            assert elevation > -dip and math.isinf(seen)  # above the geometric horizon: sky
            assert camera.pick(scene, 2.5, row + 0.5, refracta.without_refraction(air)) is None
        else:
            # The flat frame keeps lengths to ~h/R (2e-6 here) and the trace is held to 1 mm: 1e-5 relative
            # covers both and float32 readouts (6e-8).
            assert seen == pytest.approx(exact, rel=1e-5)
            point = camera.pick(scene, 2.5, row + 0.5, refracta.without_refraction(air))
            assert float(np.linalg.norm(point - camera.position)) == pytest.approx(exact, rel=1e-5)  # as above
    # The scene's own straight ray is the flat frame's: a flat Earth, sea where the sphere shows sky.
    flat = camera.pick(scene, 2.5, 14.5)
    # Embree's single-precision hit distance: a few float32 roundings (1.2e-7 each) of 19 km.
    assert float(np.linalg.norm(flat - camera.position)) == pytest.approx(
        EYE / math.tan(-elevation_of_row(camera, 14)), rel=1e-6
    )


def test_pick_through_the_air_sees_what_the_render_sees():
    """pick(..., field) follows the render's own curved path: the refracted point is nearer than the
    geometric one (standard air bends rays down toward the sea) and matches the render's distance."""
    scene, camera = sea_and_camera()
    air = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), R)
    _, seen = refracta.render(scene, camera, air, max_length=2e5, spp=1, aovs=["distance"], progress=False)
    row = 30
    point = camera.pick(scene, 2.5, row + 0.5, air)
    geometric = sphere_distance(elevation_of_row(camera, row))
    distance = float(np.linalg.norm(point - camera.position))
    assert distance < geometric
    # At 1 spp the render samples the pixel's centre, (2.5, 30.5): the same ray, traced to 1 mm, its
    # distance read as float32 (6e-8): 1e-5 relative. (Half a pixel off would be ~1.5 % here.)
    assert distance == pytest.approx(float(seen["distance"][row, 2]), rel=1e-5)


def test_pick_refuses_a_reach_beyond_the_scene():
    scene, camera = sea_and_camera()
    with pytest.raises(ValueError, match="max_length must be > 0"):
        camera.pick(scene, 2.5, 30.5, max_length=0.0)
    with pytest.raises(ValueError, match="where scene coordinates end"):
        camera.pick(scene, 2.5, 30.5, max_length=2e7)
