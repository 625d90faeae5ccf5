"""Defects an eighth new-user trial found following the README's real-place and editing workflows
as a photographer would: each is now computed right or refused by name."""

import numpy as np
import pytest

import refracta
from refracta.edit import PointPair, solve

EYE = (0.0, 1.5, 0.0)
AIR = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)


def test_a_source_behind_the_eye_is_missed_by_its_distance():
    # The miss was the offset's part across the path at the closest approach; at the path's start
    # the offset runs along the path, so a source 40 km behind the eye cost 6e-24 m^2 and its
    # stage said "1 of 1 pairs met" while the pair table said 40 km, not met.
    camera = refracta.Camera(EYE, (100.0, 1.5, 0.0), vfov=5.0, width=32, height=16)
    result = solve(AIR, camera, [PointPair((16.0, 8.0), (-1000.0, 1.5, 0.0))], free=["camera_yaw", "camera_pitch"])
    assert not result.success
    assert result.cost == pytest.approx(0.5 * 1000.0**2, rel=1e-6)  # 1/2 |eye - source|^2: nothing turns it
    assert not any("1 of 1 pairs met" in stage for stage in result.stages), result.stages

