"""The chain of issue 20's conventions end to end: a target placed by latitude, longitude and height
with LocalFrame, a camera by Camera.geographic, the air a CurvedEarth of the view's radius -- the
traced ray leaving the camera at refraction_coefficient's apparent elevation meets the target."""

import numpy as np
import pytest

import refracta
from refracta import geo


def test_a_ray_at_the_apparent_elevation_meets_the_target_placed_by_latitude_and_longitude():
    lat, lon, azimuth, distance = 46.2, 6.15, 62.0, 40000.0
    eye_height, target_height = 380.0, 1200.0
    radius = geo.radius_of_curvature(lat, azimuth)
    air = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius)
    frame = geo.LocalFrame(lat, lon, earth_radius=air)
    target_lat, target_lon, _ = geo.forward(lat, lon, azimuth, distance)
    target = frame.to_scene(target_lat, target_lon, target_height)

    result = refracta.refraction_coefficient(air, eye_height, distance, target_height=target_height)
    camera = refracta.Camera.geographic(
        lat, lon, eye_height, azimuth, result.apparent_elevation, vfov=1.0, image_width=8, image_height=8
    )
    origin, direction = camera.ray(4.0, 4.0)
    np.testing.assert_allclose(direction, frame.direction(azimuth, result.apparent_elevation), atol=1e-12)  # rounding
    path = refracta.trace_ray(air, origin, direction, max_length=2 * distance)
    _, miss, _ = path.closest_point(target)
    # The search stops within 1e-7 m of the target's height; rk45's tol is 1e-6 m over the path.
    assert miss == pytest.approx(0.0, abs=1e-5)  # 10x trace_ray's default tol (1e-6 m)
    # Launched at the true (straight-line) elevation the traced ray bends below the target: the air
    # lifts the target's image by apparent - true.
    straight = refracta.Camera.geographic(
        lat, lon, eye_height, azimuth, result.true_elevation, vfov=1.0, image_width=8, image_height=8
    )
    sight = refracta.trace_ray(air, *straight.ray(4.0, 4.0), max_length=2 * distance)
    below = sight.crossings((np.sin(np.radians(azimuth)), 0.0, -np.cos(np.radians(azimuth))), distance)[0][0]
    assert below[1] < target[1]
