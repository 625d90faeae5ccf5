"""Solving the camera and the air together (issue 20 section 4): a photograph taken by a camera
turned by a hidden yaw, pitch and roll, with a hidden field of view, through a hidden inversion.

The photograph's pairs are what it shows: each destination pixel's ray of the hidden camera,
traced through the hidden air (the integrator render uses), passes its source at the given range,
so the hidden camera and air meet every pair exactly. The hidden camera is built here from the
documented convention (yaw about up toward the right, then pitch about the new right upward, then
roll about the new forward turning up toward right), independently of C++'s CameraRig.
"""

import numpy as np
import pytest

import refracta
from refracta.edit import CAMERA_PARAMETERS, PointPair, jacobian, solve

W, H = 6000, 3000  # a photograph's pixels: a tenth of one is what a pair may miss by (no render is made)
EYE = np.array([0.0, 10.0, 0.0])
NOMINAL_VFOV = 8.0  # [deg] what the EXIF said
HIDDEN = {"camera_yaw": 0.3, "camera_pitch": -0.2, "camera_roll": 0.4, "camera_vfov": 8.1}  # [deg]
HIDDEN_INVERSION_DT = 6.0  # [K]
START_INVERSION_DT = 3.0  # [K]
FRACTIONS = [
    (0.07, 0.5),
    (0.94, 0.48),
    (0.5, 0.25),
    (0.5, 0.75),
    (0.25, 0.56),
    (0.75, 0.53),
    (0.12, 0.88),
    (0.88, 0.19),
]
PIXELS = [(u * W, v * H) for u, v in FRACTIONS]
RANGES = [3000.0, 8000.0, 15000.0, 2000.0, 25000.0, 5000.0, 1500.0, 12000.0]  # [m] where each source is
ORIENTATION_TOL = 0.01  # [deg] the bound on the solved orientation
VFOV_REL = 1e-3  # the bound on the solved field of view (0.1 %)
TRUTH_REL_TOL = 1e-13  # trace tolerance of the generating paths per metre: far below a pixel's footprint


def _nominal_camera():
    return refracta.Camera(EYE, EYE + np.array([0.0, 0.0, -1000.0]), (0.0, 1.0, 0.0), NOMINAL_VFOV, W, H)


def _turn(camera, yaw, pitch, roll):
    """The camera's local (x right, y up, z forward) vector turned by yaw, pitch, roll [deg], in the scene."""
    forward = np.asarray(camera.look_at) - np.asarray(camera.position)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, camera.up)
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    y_, p_, r_ = np.radians([yaw, pitch, roll])
    # Active rotations in the local frame: R = R_up(yaw) R_right(pitch) R_forward(roll).
    roll_m = np.array([[np.cos(r_), np.sin(r_), 0.0], [-np.sin(r_), np.cos(r_), 0.0], [0.0, 0.0, 1.0]])
    pitch_m = np.array([[1.0, 0.0, 0.0], [0.0, np.cos(p_), np.sin(p_)], [0.0, -np.sin(p_), np.cos(p_)]])
    yaw_m = np.array([[np.cos(y_), 0.0, np.sin(y_)], [0.0, 1.0, 0.0], [-np.sin(y_), 0.0, np.cos(y_)]])
    rotation = yaw_m @ pitch_m @ roll_m
    basis = np.column_stack([right, up, forward])
    return lambda local: basis @ (rotation @ np.asarray(local, dtype=float))


def _hidden_camera():
    turn = _turn(_nominal_camera(), HIDDEN["camera_yaw"], HIDDEN["camera_pitch"], HIDDEN["camera_roll"])
    return refracta.Camera(EYE, EYE + 1000.0 * turn((0, 0, 1)), turn((0, 1, 0)), HIDDEN["camera_vfov"], W, H)


def _air(inversion_dt):
    return refracta.CurvedEarth(
        refracta.PhysicalAtmosphere(
            t_ground=278.15, inversion_dt=inversion_dt, inversion_base=0.0, inversion_thickness=50.0
        )
    )


@pytest.fixture(scope="module")
def photograph_pairs():
    camera, air = _hidden_camera(), _air(HIDDEN_INVERSION_DT)
    pairs = []
    for (u, v), distance in zip(PIXELS, RANGES):
        origin, direction = camera.ray(u, v)
        path = refracta.trace_ray(air, origin, direction, tol=TRUTH_REL_TOL * distance, max_length=distance + 10.0)
        pairs.append(PointPair((u, v), path.point_at(distance)[0]))
    return pairs


def _angle_deg(a, b):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return np.degrees(np.arctan2(np.linalg.norm(np.cross(a, b)), np.dot(a, b)))


@pytest.mark.parametrize("backend", ["ceres", "nlopt:LD_LBFGS"])
def test_hidden_camera_and_inversion_are_recovered(photograph_pairs, backend):
    free = ["inversion_dt", *CAMERA_PARAMETERS]
    result = solve(_air(START_INVERSION_DT), _nominal_camera(), photograph_pairs, free=free, backend=backend)
    assert result.success, result.message
    for name, value in zip(CAMERA_PARAMETERS, result.camera_values):
        if name == "camera_vfov":
            assert value == pytest.approx(HIDDEN[name], rel=VFOV_REL)
        else:
            assert value == pytest.approx(HIDDEN[name], abs=ORIENTATION_TOL)
    # The solved camera itself: its rays through the centre and the corners within the orientation
    # bound of the hidden camera's.
    hidden, solved = _hidden_camera(), result.camera
    assert result.start_camera.vfov == NOMINAL_VFOV
    for u, v in [(W / 2, H / 2), (0, 0), (W, 0), (0, H), (W, H)]:
        assert _angle_deg(solved.ray(u, v)[1], hidden.ray(u, v)[1]) < ORIENTATION_TOL
    assert solved.vfov == pytest.approx(hidden.vfov, rel=VFOV_REL)

    # What the pairs allow of the inversion: every pair counts as met within its tolerance t_i (a
    # tenth of a pixel's footprint at its source). Linearised at the result, any parameters x
    # meeting them all have |J (x - x*)| <= sqrt(sum t_i^2), so |dx_p| <= |row p of pinv(J)| times
    # that: the bound below. The recovered value must lie inside it.
    _, jac, names = jacobian(result.field, result.camera, photograph_pairs, free=free)
    allowed = np.linalg.norm(np.linalg.pinv(jac)[names.index("inversion_dt")]) * np.linalg.norm(result.tolerances)
    assert 0.0 < allowed < 1.0  # [K] the pairs do pin the inversion (measured: 0.71 K)
    assert abs(result.field.params["inversion_dt"] - HIDDEN_INVERSION_DT) <= allowed
    assert "camera_roll" in result.report()


def test_camera_parameters_at_the_start_launch_the_camera_rays(photograph_pairs):
    """With the camera free but at its start, every pair's residual equals the fixed-direction one."""
    air, camera = _air(START_INVERSION_DT), _nominal_camera()
    fixed, _, _ = jacobian(air, camera, photograph_pairs, free=["inversion_dt"])
    free, _, names = jacobian(air, camera, photograph_pairs, free=["inversion_dt", *CAMERA_PARAMETERS])
    assert names == ["inversion_dt", *CAMERA_PARAMETERS]
    np.testing.assert_allclose(free, fixed, rtol=0.0, atol=1e-9)  # [m] the same rays: round-off of the turn only


def test_camera_derivatives_match_central_differences(photograph_pairs):
    air, camera = _air(START_INVERSION_DT), _nominal_camera()
    free = list(CAMERA_PARAMETERS)
    _, automatic, _ = jacobian(air, camera, photograph_pairs[:3], free=free, derivatives="automatic")
    _, numeric, _ = jacobian(air, camera, photograph_pairs[:3], free=free, derivatives="numeric")
    # Central differences step 1e-5 (pair_cost.cpp): the traces' 1e-9 m tolerance over that step is
    # ~1e-4 m/deg of noise, against entries of up to ~50 m/deg (a degree moves a 2-25 km miss by metres).
    derivative_noise = 1e-3  # [m/deg]
    assert np.abs(automatic).max() > 10.0  # [m/deg] the columns are not trivially small
    np.testing.assert_allclose(automatic, numeric, rtol=0.0, atol=derivative_noise)


def test_camera_parameters_need_a_camera_and_valid_names(photograph_pairs):
    air = _air(START_INVERSION_DT)
    with pytest.raises(ValueError, match="valid names: .*camera_yaw.*camera_vfov"):
        solve(air, _nominal_camera(), photograph_pairs, free=["camera_tilt"])
    three_d = [PointPair(EYE + np.array([0.0, 0.0, -1.0]), p.source) for p in photograph_pairs]
    with pytest.raises(ValueError, match="pass a Camera"):
        solve(air, EYE, three_d, free=["camera_yaw"])
    with pytest.raises(ValueError, match="camera_vfov' must lie within"):
        solve(air, _nominal_camera(), photograph_pairs, free=["camera_vfov"], bounds={"camera_vfov": (1.0, 200.0)})
    with pytest.raises(ValueError, match="start value of 'camera_yaw'"):
        solve(air, _nominal_camera(), photograph_pairs, free=["camera_yaw"], bounds={"camera_yaw": (1.0, 2.0)})
    jittered = _nominal_camera().jittered(np.zeros((H, W, 2), dtype=np.float32))
    with pytest.raises(ValueError, match="jittered camera"):
        solve(air, jittered, photograph_pairs, free=["camera_pitch"])


def test_the_solved_camera_and_air_render_the_photograph(photograph_pairs):
    """The photograph rendered (small: 120 x 60 of the same view) with the hidden camera and air, a
    box at each pair's source, is rendered again by the solved camera and air -- and not by the
    start's."""
    scene = refracta.Scene()
    scene.set_sky((0.3, 0.4, 0.6), (0.1, 0.2, 0.5))
    for pair in photograph_pairs:
        size = 0.004 * np.linalg.norm(np.asarray(pair.source) - EYE)  # [m] ~0.23 deg: two pixels across
        scene.add_box(tuple(pair.source), (size, size, size))

    def picture(camera, air):
        options = dict(spp=1, progress=False, max_length=30000.0)
        return refracta.render(scene, camera.resized(120, 60), air, **options)

    photograph = picture(_hidden_camera(), _air(HIDDEN_INVERSION_DT))
    start_camera, start_air = _nominal_camera(), _air(START_INVERSION_DT)
    result = solve(start_air, start_camera, photograph_pairs, free=["inversion_dt", *CAMERA_PARAMETERS])
    # The same samples through rays that differ by ~1e-12 deg: the same pixels, to float round-off.
    np.testing.assert_allclose(picture(result.camera, result.field), photograph, rtol=0.0, atol=1e-6)
    moved = np.abs(picture(start_camera, start_air) - photograph).max(axis=2) > 0.1  # a box against the sky
    assert moved.sum() >= 10  # the start shows the boxes elsewhere (measured: 58 pixels differ)
