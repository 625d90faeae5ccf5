"""Defects an eighth new-user trial found following the README's real-place and editing workflows
as a photographer would: each is now computed right or refused by name."""

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


def test_objects_beyond_the_rays_reach_are_named_though_a_sea_surrounds_the_camera():
    # The sea around the camera made the scene's box reach it: no warning, and a coast 20 km away
    # rendered as sky with the default max_length (5 km). The objects' box leaves flat surfaces out.
    scene = refracta.Scene()
    scene.add_ground(0.0, 100000.0)
    scene.add_box((20000.0, 50.0, 0.0), (100.0, 100.0, 100.0))
    scene.set_sky((1, 1, 1))
    camera = refracta.Camera((0, 10, 0), (20000, 50, 0), vfov=1.0, width=8, height=4)
    lower, _ = scene.object_bounds
    assert lower[0] == pytest.approx(19950.0)  # the box's near face: the ground left out
    with pytest.warns(
        refracta.SceneWarning,
        match=r"nearest of the scene.s objects is 19950 m from the camera, beyond the rays. reach max_length = 5000 m",
    ):
        refracta.render(scene, camera, AIR, progress=False)


def test_the_command_line_sets_how_far_rays_reach():
    from refracta import cli

    assert cli._metres("120000") == 120000.0
    for text in ("-5", "0", "inf", "far"):
        with pytest.raises(Exception, match=r"must be"):
            cli._metres(text)
