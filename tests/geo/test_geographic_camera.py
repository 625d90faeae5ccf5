"""Camera.geographic and LocalFrame.camera (issue 20): where the camera stands and looks."""

import math
import pickle

import numpy as np
import pytest

import refracta
from refracta import geo


@pytest.mark.parametrize("azimuth, elevation", [(0.0, 0.0), (120.0, 0.0), (250.0, -3.5), (45.0, 30.0), (10.0, 90.0)])
def test_it_looks_along_the_stated_azimuth_and_elevation(azimuth, elevation):
    camera = refracta.Camera.geographic(
        46.5, 7.9, 1850.0, azimuth, elevation, vfov=10.0, image_width=64, image_height=48
    )
    # By default the camera's frame flattens the Earth with the radius of curvature along its view.
    frame = geo.LocalFrame(46.5, 7.9, earth_radius=geo.radius_of_curvature(46.5, azimuth))
    origin, forward = camera.ray(32.0, 24.0)  # the image centre: the view axis
    np.testing.assert_allclose(forward, frame.direction(azimuth, elevation), atol=1e-12)  # rounding of unit vectors
    np.testing.assert_allclose(origin, [0.0, frame.flat_height(1850.0), 0.0], atol=1e-9)  # rounding only
    assert (camera.width, camera.height, camera.vfov) == (64, 48, 10.0)


def test_vfov_from_the_focal_length_is_camera_photographics():
    camera = refracta.Camera.geographic(
        47.0, 8.0, 450.0, 120.0, 0.0, focal_length_mm=300.0, sensor_mm=(23.5, 15.6), image_width=960, image_height=640
    )
    reference = refracta.Camera.photographic((0, 0, 0), (1, 0, 0), 300.0, (23.5, 15.6), 960, 640)
    assert camera.vfov == reference.vfov
    assert camera.vfov == pytest.approx(2 * math.degrees(math.atan(15.6 / 600.0)), rel=1e-12)  # rounding only
    # Without a sensor: Camera.photographic's own default (full frame).
    default = refracta.Camera.geographic(47.0, 8.0, 450.0, 120.0, 0.0, focal_length_mm=300.0)
    assert default.vfov == refracta.Camera.photographic((0, 0, 0), (1, 0, 0), 300.0).vfov


def test_roll_dips_the_right_side():
    level = refracta.Camera.geographic(47.0, 8.0, 10.0, 200.0, 0.0, vfov=20.0, image_width=40, image_height=20)
    rolled = refracta.Camera.geographic(
        47.0, 8.0, 10.0, 200.0, 0.0, vfov=20.0, image_width=40, image_height=20, roll=5.0
    )
    # A level camera's middle row is horizontal; rolled clockwise (seen from behind), its right end
    # looks lower than its left, by the roll angle across the row's half-width.
    left, right = level.ray(0.0, 10.0)[1], level.ray(40.0, 10.0)[1]
    assert left[1] == pytest.approx(0.0, abs=1e-12) and right[1] == pytest.approx(0.0, abs=1e-12)  # rounding
    left, right = rolled.ray(0.0, 10.0)[1], rolled.ray(40.0, 10.0)[1]
    assert right[1] < 0.0 < left[1]
    half_width = math.atan(math.tan(math.radians(10.0)) * 2.0)  # the half-width's angle (40 / 20 of the half-height)
    assert math.degrees(math.asin(right[1])) == pytest.approx(
        -math.degrees(math.asin(math.sin(half_width) * math.sin(math.radians(5.0)))), rel=1e-9
    )  # rounding
    np.testing.assert_allclose(rolled.ray(20.0, 10.0)[1], level.ray(20.0, 10.0)[1], atol=1e-12)  # the axis stays


def test_frame_camera_elsewhere_in_the_frame_takes_the_local_compass_bearing():
    frame = geo.LocalFrame(47.0, 8.0, earth_radius=geo.radius_of_curvature(47.0, 90.0))
    # A camera 100 km east of the origin aimed by compass at a summit 20 km from it.
    here, summit = (47.0, 9.3), (47.1, 9.5)
    _, bearing, _ = geo.inverse(*here, *summit)
    camera = frame.camera(700.0, bearing, 0.0, vfov=5.0, position=here)
    np.testing.assert_allclose(camera.position, frame.to_scene(*here, 700.0), atol=1e-9)  # rounding only
    forward = camera.ray(320.0, 180.0)[1]
    towards = frame.to_scene(*summit, 700.0) - camera.position
    frame_bearing = math.degrees(math.atan2(towards[0], -towards[2]))
    # The local bearing is not the frame's: the meridians converge by about 1 deg here.
    assert abs(frame_bearing - bearing) > 0.5
    # Level, and along the projected geodesic: it bends off the straight line to the summit in the
    # frame by the projection's distortion, under 1e-4 rad over 20 km this close to the origin.
    assert forward[1] == pytest.approx(0.0, abs=1e-12)  # rounding of a level direction
    assert math.degrees(math.atan2(forward[0], -forward[2])) == pytest.approx(
        frame_bearing, abs=6e-3
    )  # 1e-4 rad: aeqd's distortion
    # At the origin the bearing is the frame's azimuth.
    at_origin = frame.camera(700.0, 270.0, -1.0, vfov=5.0)
    np.testing.assert_allclose(at_origin.ray(320.0, 180.0)[1], frame.direction(270.0, -1.0), atol=1e-12)  # rounding


def test_frames_pickle():
    frame = geo.LocalFrame(47.0, 8.0, 430.0, earth_radius=refracta.CurvedEarth(refracta.PhysicalAtmosphere(), 6.4e6))
    copy = pickle.loads(pickle.dumps(frame))
    assert repr(copy) == repr(frame)
    np.testing.assert_array_equal(copy.to_scene(47.3, 8.2, 1000.0), frame.to_scene(47.3, 8.2, 1000.0))


def test_bad_camera_arguments():
    with pytest.raises(ValueError, match="exactly one of vfov and focal_length_mm"):
        refracta.Camera.geographic(47.0, 8.0, 10.0, 0.0, 0.0)
    with pytest.raises(ValueError, match="exactly one of vfov and focal_length_mm"):
        refracta.Camera.geographic(47.0, 8.0, 10.0, 0.0, 0.0, vfov=5.0, focal_length_mm=50.0)
    with pytest.raises(ValueError, match="lat"):
        refracta.Camera.geographic(90.0, 8.0, 10.0, 0.0, 0.0, vfov=5.0)
    with pytest.raises(ValueError, match="elevation"):
        refracta.Camera.geographic(47.0, 8.0, 10.0, 0.0, 95.0, vfov=5.0)
    with pytest.raises(ValueError, match="roll"):
        refracta.Camera.geographic(47.0, 8.0, 10.0, 0.0, 0.0, vfov=5.0, roll=math.nan)


def test_a_camera_aimed_at_a_target_centres_it_with_no_air_and_refraction_lifts_it():
    # A 40 m sphere 60 km away at 780 m, seen from 20 m: aimed by target=, it sits at the image's
    # centre through air of almost no pressure, and the C++ readout's true elevation of its points
    # is LocalFrame.aim's elevation (two implementations of the straight line over the sphere).
    lat0, lon0, eye = 50.0, 1.0, 20.0
    lat, lon, _ = geo.forward(lat0, lon0, 30.0, 60000.0)
    target = (lat, lon, 780.0)
    camera = refracta.Camera.geographic(lat0, lon0, eye, target=target, vfov=0.5, image_width=48, image_height=48)
    radius = geo.radius_of_curvature(lat0, 30.0)
    frame = geo.LocalFrame(lat0, lon0, earth_radius=radius)
    azimuth, elevation = frame.aim(target, eye)
    assert azimuth == pytest.approx(30.0, abs=1e-9)  # the geodesic's own azimuth, rounding
    scene = refracta.Scene()
    scene.set_sky((0.5, 0.6, 0.8))  # only the readouts count: a sky keeps the image from being black
    scene.add_sphere(frame.to_scene(*target), 40.0)
    thin = refracta.CurvedEarth(refracta.PhysicalAtmosphere(lapse_rate=0.0, pressure=1e-3), radius)
    standard = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius)
    rows = {}
    for name, air in (("thin", thin), ("standard", standard)):
        _, aovs = refracta.render(
            scene, camera, air, aovs=["true_elevation", "object_id"], max_length=80000.0, progress=False
        )
        hit = aovs["object_id"] >= 0
        assert hit.sum() > 30  # the sphere spans ~7 pixels across
        ys, xs = np.nonzero(hit)
        assert xs.mean() == pytest.approx(23.5, abs=0.5)  # pixel centres: the image's centre column
        rows[name] = ys.mean()
        if name == "thin":
            # Its true elevation, averaged over its near face, is its centre's to its 0.04 deg radius / 10.
            assert np.mean(aovs["true_elevation"][hit]) == pytest.approx(elevation, abs=0.004)
    assert rows["thin"] == pytest.approx(23.5, abs=0.5)  # its pixel centres' mean: within half a pixel
    # Refraction lifts it by k d / 2R: k in [0.12, 0.22] around the standard 0.17, 96 pixels a degree.
    lift = (rows["thin"] - rows["standard"]) / 96.0
    assert 0.12 * 60000.0 / (2 * radius) < math.radians(lift) < 0.22 * 60000.0 / (2 * radius)


def test_aim_refuses_a_target_it_cannot_aim_at():
    frame = geo.LocalFrame(50.0, 1.0)
    for target, message in (
        ((50.0,), "target must be"),
        ("north", "target must be"),
        ((50.0, 1.0), "straight above or below"),
        ((95.0, 1.0), "target's lat"),
        ((50.1, 1.0, float("nan")), "target's height"),
    ):
        with pytest.raises(ValueError, match=message):
            frame.camera(20.0, target=target, vfov=1.0)
    with pytest.raises(ValueError, match="not both"):
        frame.camera(20.0, 30.0, 0.0, target=(50.1, 1.0), vfov=1.0)
    with pytest.raises(ValueError, match="or target"):
        frame.camera(20.0, vfov=1.0)
