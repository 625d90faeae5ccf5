"""Orbit, pan and dolly (refracta.widgets.camera_moves): what each gesture keeps and moves."""

import numpy as np
import pytest

import refracta
from refracta.widgets import camera_moves

GEOMETRY_TOL = 1e-9  # [m] relative to distances of ~300 m: round-off of a few rotations
PIXEL_TOL = 1e-6  # [pixels] projection round-off
ANGLE_TOL = 1e-9  # relative / [deg]: angles from arccos of rotated unit vectors, round-off


@pytest.fixture
def camera():
    return refracta.Camera((0.0, 1.4, 0.0), (300.0, 0.62, 0.0), vfov=2.2, width=320, height=120)


def distance(camera):
    return float(np.linalg.norm(np.asarray(camera.look_at) - np.asarray(camera.position)))


@pytest.mark.parametrize("du, dv", [(25.0, 0.0), (0.0, -40.0), (-13.0, 7.5)])
def test_orbit_keeps_the_look_at_point_its_distance_and_the_lens(camera, du, dv):
    moved = camera_moves.orbit(camera, du, dv)
    np.testing.assert_allclose(moved.look_at, camera.look_at, rtol=0, atol=GEOMETRY_TOL)
    assert distance(moved) == pytest.approx(distance(camera), rel=GEOMETRY_TOL)
    assert (moved.vfov, moved.width, moved.height) == (camera.vfov, camera.width, camera.height)
    assert not np.allclose(moved.position, camera.position)  # a move of metres: far beyond numpy's default 1e-5/1e-8


def test_dragging_right_carries_the_eye_left_and_dragging_down_lifts_it(camera):
    _, right, _ = camera_moves.frame(camera)
    sideways = camera_moves.orbit(camera, 30.0, 0.0)
    assert np.dot(sideways.position - camera.position, right) < 0.0
    assert sideways.position[1] == pytest.approx(camera.position[1], abs=GEOMETRY_TOL)  # yaw about the up vector
    lifted = camera_moves.orbit(camera, 0.0, 30.0)
    assert lifted.position[1] > camera.position[1]


def test_one_image_height_of_drag_turns_by_the_field_of_view(camera):
    offset = np.asarray(camera.position) - np.asarray(camera.look_at)
    moved = camera_moves.orbit(camera, camera.height, 0.0)
    new_offset = np.asarray(moved.position) - np.asarray(moved.look_at)
    flat = [np.array([o[0], o[2]]) for o in (offset, new_offset)]
    angle = np.degrees(np.arccos(np.dot(*flat) / (np.linalg.norm(flat[0]) * np.linalg.norm(flat[1]))))
    assert angle == pytest.approx(camera_moves.ORBIT_PER_HEIGHT * camera.vfov, rel=ANGLE_TOL)


def test_orbit_stops_short_of_looking_along_the_up_vector(camera):
    moved = camera_moves.orbit(camera, 0.0, 1e6)  # far past the pole
    offset = np.asarray(moved.position) - np.asarray(moved.look_at)
    polar = np.degrees(np.arccos(offset[1] / np.linalg.norm(offset)))
    assert polar == pytest.approx(camera_moves.POLE_MARGIN_DEG, abs=ANGLE_TOL)


@pytest.mark.parametrize("du, dv", [(10.0, 5.0), (-70.0, 0.0), (0.0, -33.3)])
def test_pan_keeps_a_point_at_the_look_at_distance_under_the_pointer(camera, du, dv):
    moved = camera_moves.pan(camera, du, dv)
    u, v, depth = moved.project(np.asarray([camera.look_at]))[0]
    assert (u, v) == pytest.approx((camera.width / 2 + du, camera.height / 2 + dv), abs=PIXEL_TOL)
    # the look-at point moved with the eye
    np.testing.assert_allclose(
        np.asarray(moved.look_at) - np.asarray(camera.look_at),
        np.asarray(moved.position) - np.asarray(camera.position),
        atol=GEOMETRY_TOL,
    )


def test_dolly_scales_the_distance_and_never_reaches_the_look_at_point(camera):
    # Default rel 1e-6: one multiplication of the distance.
    assert distance(camera_moves.dolly(camera, 1.0)) == pytest.approx(camera_moves.DOLLY_STEP * distance(camera))
    # Default rel 1e-6: two divisions of the distance.
    assert distance(camera_moves.dolly(camera, -2.0)) == pytest.approx(distance(camera) / camera_moves.DOLLY_STEP**2)
    close = camera_moves.dolly(camera, 1e6)
    assert distance(close) >= camera_moves.MIN_DISTANCE * (1 - ANGLE_TOL)
    forward, _, _ = camera_moves.frame(close)
    np.testing.assert_allclose(forward, camera_moves.frame(camera)[0], atol=ANGLE_TOL)  # same view direction


@pytest.mark.parametrize(
    "change, name",
    [
        (dict(position=(np.nan, 1.0, 0.0)), "position"),
        (dict(look_at=(0.0, 1.4, 0.0)), "look_at"),
        (dict(look_at=(0.0, 50.0, 0.0)), "up vector"),
        (dict(vfov=0.0), "vfov"),
        (dict(vfov=float("nan")), "vfov"),
    ],
)
def test_a_bad_pose_raises_value_error_naming_the_field(camera, change, name):
    with pytest.raises(ValueError, match=name):
        camera_moves.with_pose(camera, **change)
