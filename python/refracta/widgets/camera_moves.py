"""Orbit, pan and dolly for the mirage editor: a new refracta.Camera from a mouse gesture.

Cameras are immutable, so every move returns a new Camera with the same up vector, vertical field
of view and image size. Gestures are measured in image pixels of that camera (u right, v down, as
Camera.ray and Camera.project use them):

- orbit(camera, du, dv): the eye circles the look-at point; dragging right carries the eye to
  the left around it (the scene turns with the pointer), dragging down lifts the eye. One image
  height of drag turns by ORBIT_PER_HEIGHT times the vertical field of view, so the look-at
  point's surroundings move at about the pointer's speed whatever the zoom.
- pan(camera, du, dv): eye and look-at point move together across the view so that a point at
  the look-at distance stays under the pointer.
- dolly(camera, steps): the eye moves toward the look-at point (steps > 0, a mouse wheel turned
  away from the user) or away from it, by DOLLY_STEP per step of its distance; it never reaches
  the point.
"""

from __future__ import annotations

import math

import numpy as np

from refracta import _core
from refracta._checks import number, real_array

__all__ = ["DOLLY_STEP", "ORBIT_PER_HEIGHT", "POLE_MARGIN_DEG", "dolly", "frame", "orbit", "pan", "with_pose"]

ORBIT_PER_HEIGHT = 1.0  # turn per image height dragged, in vertical fields of view: the point moves
# with the pointer near the middle of the image
DOLLY_STEP = 0.9  # distance kept per wheel step: ten steps bring the eye about 3x closer
POLE_MARGIN_DEG = 1.0  # orbits stop this far from looking straight along the up vector, where
# the view's right vector is undefined
MIN_DISTANCE = 1e-6  # [m] the eye stays at least this far from the look-at point (Camera needs
# a view direction)


def frame(camera: _core.Camera):
    """(forward, right, true_up) unit vectors of `camera`: forward toward the look-at point, right
    along +u, true_up along -v."""
    forward = np.asarray(camera.look_at, dtype=float) - np.asarray(camera.position, dtype=float)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, np.asarray(camera.up, dtype=float))
    right /= np.linalg.norm(right)
    return forward, right, np.cross(right, forward)


def with_pose(camera: _core.Camera, position=None, look_at=None, vfov=None, size=None) -> _core.Camera:
    """`camera` with some of position, look_at [m], vfov [deg] and size (width, height) replaced.

    Raises ValueError naming the field: non-finite numbers, the eye at the look-at point, a view
    direction along the up vector, vfov outside (0, 180)."""
    position = real_array(camera.position if position is None else position, "camera position")
    look_at = real_array(camera.look_at if look_at is None else look_at, "camera look_at")
    vfov = number(camera.vfov if vfov is None else vfov, "camera vfov")  # True was a 1-degree view
    width, height = (camera.width, camera.height) if size is None else (int(size[0]), int(size[1]))
    for name, value in (("position", position), ("look_at", look_at)):
        if value.shape != (3,) or not np.all(np.isfinite(value)):
            raise ValueError(f"camera {name} must be 3 finite numbers [m] (got {value.tolist()})")
    if not (0.0 < vfov < 180.0):
        raise ValueError(f"camera vfov must be in (0, 180) degrees (got {vfov!r})")
    direction = look_at - position
    distance = float(np.linalg.norm(direction))
    if not distance > 0.0:
        raise ValueError("camera look_at must differ from its position")
    up = np.asarray(camera.up, dtype=float)
    if np.linalg.norm(np.cross(direction / distance, up / np.linalg.norm(up))) < 1e-9:
        raise ValueError(f"camera look_at must not lie straight along the up vector {up.tolist()} from the position")
    return _core.Camera(position, look_at, up, vfov, width, height)


def _rotate(vector: np.ndarray, axis: np.ndarray, angle: float) -> np.ndarray:
    """Rodrigues' rotation of `vector` by `angle` [rad] about the unit `axis` (right-handed)."""
    c, s = np.cos(angle), np.sin(angle)
    return vector * c + np.cross(axis, vector) * s + axis * np.dot(axis, vector) * (1.0 - c)


def orbit(camera: _core.Camera, du: float, dv: float) -> _core.Camera:
    """The eye moved around the look-at point by a drag of (du, dv) pixels (see the module doc)."""
    radians_per_pixel = ORBIT_PER_HEIGHT * np.radians(camera.vfov) / camera.height
    target = np.asarray(camera.look_at, dtype=float)
    offset = np.asarray(camera.position, dtype=float) - target
    up = np.asarray(camera.up, dtype=float)
    up /= np.linalg.norm(up)
    # Yaw about the up vector through the look-at point: dragging right swings the eye to the left.
    offset = _rotate(offset, up, -du * radians_per_pixel)
    # Pitch about the view's right vector, kept POLE_MARGIN_DEG away from the up vector's poles.
    polar = np.arccos(np.clip(np.dot(offset, up) / np.linalg.norm(offset), -1.0, 1.0))
    margin = np.radians(POLE_MARGIN_DEG)
    new_polar = np.clip(polar - dv * radians_per_pixel, margin, np.pi - margin)
    right = np.cross(-offset, up)
    right /= np.linalg.norm(right)
    offset = _rotate(offset, right, new_polar - polar)
    return with_pose(camera, position=target + offset)


def pan(camera: _core.Camera, du: float, dv: float) -> _core.Camera:
    """Eye and look-at point moved across the view by a drag of (du, dv) pixels (see the module doc)."""
    _, right, true_up = frame(camera)
    distance = float(np.linalg.norm(np.asarray(camera.look_at) - np.asarray(camera.position)))
    metres_per_pixel = 2.0 * distance * np.tan(np.radians(camera.vfov) / 2.0) / camera.height
    shift = metres_per_pixel * (-du * right + dv * true_up)
    return with_pose(camera, position=np.asarray(camera.position) + shift, look_at=np.asarray(camera.look_at) + shift)


def dolly(camera: _core.Camera, steps: float) -> _core.Camera:
    """The eye moved along the view toward (steps > 0) or away from the look-at point (see the module doc)."""
    target = np.asarray(camera.look_at, dtype=float)
    offset = np.asarray(camera.position, dtype=float) - target
    distance = float(np.linalg.norm(offset))
    # In logarithms, the far end held inside the scene's reach as the near one above MIN_DISTANCE:
    # 0.9 ** -1e4 overflowed (a trial).
    reach = _core._SCENE_REACH - float(np.abs(target).max())
    log_distance = math.log(distance) + float(steps) * math.log(DOLLY_STEP)
    new_distance = math.exp(min(max(log_distance, math.log(MIN_DISTANCE)), math.log(max(reach, distance))))
    return with_pose(camera, position=target + offset * (new_distance / distance))
