"""refracta.geo.LocalFrame: the scene frame around an observer (issue 20's conventions): azimuthal
equidistant on WGS84 horizontally, CurvedEarth's flat heights vertically."""

import math

import numpy as np
import pytest

import refracta
from refracta import geo

# Origins: the Alps, the antimeridian (Fiji), the far south.
ORIGINS = [(47.0, 8.0), (-17.0, 179.8), (-75.0, -60.0)]


def points_around(lat0, lon0):
    """Points at 1 m, 30 km, 150 km and 900 km in several directions, heights from sea level to 4 km."""
    distances = np.array([1.0, 3e4, 1.5e5, 9e5, 3e4, 1.5e5])
    azimuths = np.array([10.0, 95.0, 181.0, 260.0, 300.0, 45.0])
    heights = np.array([0.0, 12.5, 4000.0, 300.0, 1.6, 2500.0])
    lat, lon, _ = geo.forward(lat0, lon0, azimuths, distances)
    return lat, lon, heights, distances, azimuths


@pytest.mark.parametrize("lat0, lon0", ORIGINS)
def test_horizontal_placement_is_geodesic_distance_and_azimuth(lat0, lon0):
    frame = geo.LocalFrame(lat0, lon0)
    lat, lon, heights, distances, azimuths = points_around(lat0, lon0)
    p = frame.to_scene(lat, lon, heights)
    assert p.shape == (6, 3) and p.dtype == np.float64
    # The azimuthal equidistant projection keeps geodesic distance and azimuth from its centre
    # (PROJ's ellipsoidal aeqd solves the geodesic): x = d sin a, z = -d cos a.
    # 1 mm over 1000 km; 10 nm absolute: rounding of the degrees (an ulp of 47 deg is 1 nm)
    np.testing.assert_allclose(np.hypot(p[:, 0], p[:, 2]), distances, rtol=1e-9, atol=1e-8)
    scene_azimuth = np.degrees(np.arctan2(p[:, 0], -p[:, 2]))
    np.testing.assert_allclose(
        np.remainder(scene_azimuth - azimuths + 180.0, 360.0) - 180.0, 0.0, atol=1e-7
    )  # 1e-7 deg: 1.6 mm at 900 km
    # ... and the same as geo.inverse from the origin.
    d, a, _ = geo.inverse(lat0, lon0, lat, lon)
    # as above: 1 mm over 1000 km, rounding of the degrees
    np.testing.assert_allclose(np.hypot(p[:, 0], p[:, 2]), d, rtol=1e-9, atol=1e-8)


@pytest.mark.parametrize("lat0, lon0", ORIGINS)
def test_round_trip_is_below_a_millimetre(lat0, lon0):
    frame = geo.LocalFrame(lat0, lon0, earth_radius=geo.radius_of_curvature(lat0, 30.0))
    lat, lon, heights, _, _ = points_around(lat0, lon0)
    p = frame.to_scene(lat, lon, heights)
    lat2, lon2, h2 = frame.to_geographic(p)
    d, _, _ = geo.inverse(lat, lon, lat2, lon2)
    assert np.max(d) < 1e-3  # the round-trip bound [m]
    np.testing.assert_allclose(h2, heights, atol=1e-6)  # 1 um: log1p / expm1 round trip at 4 km
    again = frame.to_scene(lat2, lon2, h2)
    np.testing.assert_allclose(again, p, atol=1e-3)  # the round-trip bound [m]
    # Arrays of any shape broadcast: a (2, 3) grid of points against one height.
    grid = frame.to_scene(lat.reshape(2, 3), lon.reshape(2, 3), 10.0)
    assert grid.shape == (2, 3, 3)


def test_heights_are_curved_earths_flat_heights():
    radius = geo.radius_of_curvature(47.0, 120.0)
    earth = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius)
    heights = np.array([0.0, 2.0, 100.0, 4478.0])
    by_radius = geo.LocalFrame(47.0, 8.0, earth_radius=radius).to_scene(47.0, 8.0, heights)
    by_field = geo.LocalFrame(47.0, 8.0, earth_radius=earth).to_scene(47.0, 8.0, heights)
    np.testing.assert_array_equal(by_radius[:, 1], earth.flat_height(heights))
    np.testing.assert_array_equal(by_field[:, 1], earth.flat_height(heights))
    # y' = R ln(1 + h / R) is h - h^2 / (2R) to first order: 1.57 m lower at 4478 m.
    assert heights[-1] - by_radius[-1, 1] == pytest.approx(
        heights[-1] ** 2 / (2 * radius), rel=1e-3
    )  # the h^3/(3R^2) term
    # Over a flat Earth (no CurvedEarth) the height is the scene's y.
    flat = geo.LocalFrame(47.0, 8.0, earth_radius=math.inf)
    np.testing.assert_array_equal(flat.to_scene(47.0, 8.0, heights)[:, 1], heights)
    np.testing.assert_array_equal(flat.to_geographic(flat.to_scene(47.0, 8.0, heights))[2], heights)


def test_default_earth_radius_is_the_gaussian_mean_of_eulers():
    frame = geo.LocalFrame(47.0, 8.0, height=430.0)
    m, n = geo.principal_radii(47.0)
    assert frame.earth_radius == pytest.approx(math.sqrt(m * n), rel=1e-15)  # rounding only
    # sqrt(M N) is the mean over azimuths of Euler's radius.
    mean = np.mean(geo.radius_of_curvature(47.0, np.arange(0.0, 360.0, 1.0)))
    assert frame.earth_radius == pytest.approx(mean, rel=1e-12)  # a 360-point mean of a smooth periodic function
    np.testing.assert_allclose(frame.origin_ground(), [0.0, frame.flat_height(430.0), 0.0], rtol=0, atol=0)


def test_directions_follow_the_azimuth_convention():
    d = geo.LocalFrame.direction([0.0, 90.0, 180.0, 270.0, 30.0], [0.0, 0.0, 0.0, 0.0, 90.0])
    np.testing.assert_allclose(d[:4], [[0, 0, -1], [1, 0, 0], [0, 0, 1], [-1, 0, 0]], atol=1e-15)  # cos(90 deg) ~ 6e-17
    np.testing.assert_allclose(d[4], [0, 1, 0], atol=1e-15)  # cos(90 deg) ~ 6e-17
    np.testing.assert_allclose(np.linalg.norm(geo.LocalFrame.direction(123.0, -4.0)), 1.0, rtol=1e-15)  # rounding


def test_bad_points_are_value_errors():
    frame = geo.LocalFrame(47.0, 8.0)
    with pytest.raises(ValueError, match="lat"):
        frame.to_scene(95.0, 8.0, 0.0)
    with pytest.raises(ValueError, match="height"):
        frame.to_scene(47.0, 8.0, math.nan)
    with pytest.raises(ValueError, match="points"):
        frame.to_geographic([1.0, 2.0])
    with pytest.raises(ValueError, match="earth_radius"):
        geo.LocalFrame(47.0, 8.0, earth_radius=-1.0)
    with pytest.raises(ValueError, match="height"):  # below the Earth's centre: no flat height
        frame.to_scene(47.0, 8.0, -2e7)
    # A string, a bool or an array for one number (the trial's: "46.5" and True were taken as numbers).
    with pytest.raises(ValueError, match="lat must be a number or an array of numbers \\(got '46.5'\\)"):
        geo.LocalFrame("46.5", 8.0)
    with pytest.raises(ValueError, match="lon must be a number or an array of numbers \\(got True\\)"):
        geo.LocalFrame(47.0, True)
    with pytest.raises(ValueError, match="lat must be one number \\(got an array of shape \\(2,\\)\\)"):
        geo.LocalFrame([46.0, 47.0], 8.0)
    # 1e9 m east gave a point past the antipode; scene coordinates end at 1e7 m (single precision).
    with pytest.raises(ValueError, match=r"points: 1e\+09 m from the frame's origin, beyond the scene's reach"):
        frame.to_geographic([1e9, 0.0, 0.0])
    # to_scene refuses such points as to_geographic does (the antipode came back as z = -2e7 m).
    with pytest.raises(ValueError, match=r"to_scene: the points: 2e\+07 m from the frame's origin"):
        frame.to_scene(-47.0, -172.0, 0.0)
    # The antipode: the eye was put 2e7 m away, where rays are refused only when rendering.
    with pytest.raises(ValueError, match="position: 2e\\+07 m from the frame's origin"):
        frame.camera(2.0, 0.0, 0.0, vfov=10.0, position=(-47.0, -172.0))


def test_bearing_turns_a_frame_azimuth_into_the_compass_bearing_camera_takes():
    # A trial's camera 20 km west-north of the origin at bearing 270: its view's frame azimuth is
    # 270.177 (the meridians' convergence), which bearing() takes back to 270.
    frame = geo.LocalFrame(45.0, 10.0)
    for compass in (0.0, 90.0, 270.0, 359.5):
        camera = frame.camera(100.0, compass, 0.0, vfov=1.0, image_width=41, image_height=11, position=(45.05, 9.75))
        forward = camera.ray(20.5, 5.5)[1]
        frame_azimuth = np.degrees(np.arctan2(forward[0], -forward[2])) % 360.0
        assert abs(frame_azimuth - compass) > 0.1 or compass == 0.0  # the turn is real here (0.18 deg)
        turn = (frame.bearing(frame_azimuth, camera.position) - compass + 180.0) % 360.0 - 180.0
        assert abs(turn) < 1e-6  # the round trip of two 1 m geodesic steps in double: ~1e-9 deg
    # At the origin the frame's north is the compass's; arrays map element by element.
    at_origin = frame.bearing(np.array([[10.0, 200.0]]), (0.0, 1.0, 0.0))
    assert at_origin.shape == (1, 2)
    np.testing.assert_allclose(at_origin, [[10.0, 200.0]], atol=1e-6)  # the same 1 m round trip
    with pytest.raises(ValueError, match="position must be one scene point"):
        frame.bearing(10.0, (0.0, 1.0))


def test_a_camera_away_from_the_origin_centres_its_target_and_warns_of_the_frames_distortion():
    # A trial's camera 150 km north-east of the origin aimed at a summit 100 km away at bearing 300:
    # aimed by the geodesic's bearing it showed the summit 0.0067 deg (13 px) to the side, the
    # azimuthal equidistant plane's distortion away from its origin (about D s / 3R^2). Aimed along
    # the frame's straight line to the summit it is centred; the distance readout stays long by the
    # same distortion (8.5 m in 100 km), which the warning names.
    frame = geo.LocalFrame(45.0, 7.0)
    lat_b, lon_b, _ = geo.forward(45.0, 7.0, 45.0, 150e3)
    lat_c, lon_c, _ = geo.forward(lat_b, lon_b, 300.0, 100e3)
    summit = frame.to_scene(lat_c, lon_c, 0.0)
    scene = refracta.Scene()
    scene.add_box((summit[0], 1000.0, summit[2]), (3.0, 2000.0, 3.0))
    scene.set_environment((1.0, 1.0, 1.0))
    with pytest.warns(UserWarning, match=r"150 km from the frame's origin: .* about 21 pixels to the side"):
        camera = frame.camera(
            30.0, target=(lat_c, lon_c, 1000.0), position=(lat_b, lon_b), vfov=0.0305, image_width=61, image_height=61
        )
    air = refracta.CurvedEarth(refracta.LinearSquaredProfile(1.0, 0.0), frame.earth_radius)
    _, aovs = refracta.render(
        scene, camera, air, method="straight", progress=False, max_length=150e3, aovs=["object_id"]
    )
    columns = np.nonzero((aovs["object_id"] == 0).any(axis=0))[0]
    # The 3 m box is 3.4 px wide at 100 km: its columns' middle within half a pixel of the centre's.
    assert abs(0.5 * (columns.min() + columns.max()) - 30.0) <= 0.5
    # Near the origin the distortion is far below a pixel: no warning (pytest turns one into an error).
    frame.camera(100.0, target=(45.3, 7.2), position=(45.05, 7.1), vfov=1.0, image_width=41, image_height=11)
