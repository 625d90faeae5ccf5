"""The checks and state the scene, light, camera, ocean and terrain bindings now leave to the library
(render/scene_building, shading/light_batch, scene/camera, scene/ocean_waves, scene/terrain): each
reached through Python once, so a binding that stops forwarding to them fails here."""

import pickle

import numpy as np
import pytest

import refracta
from refracta import lights, shading

NAN = float("nan")
TRIANGLE = [[0, 0, 0], [1, 0, 0], [0, 0, 1]]


def test_scene_building_refuses_bad_input_naming_it():
    scene = refracta.Scene()
    with pytest.raises(ValueError, match=r"angle must be in \(0, 360\]"):
        scene.add_spot_light([0, 5, 0], [0, -1, 0], angle=400.0)
    for radius in (-1.0, 1e300, float("nan")):  # 1e300 turned shadow rays to NaN in render_raster (a trial)
        with pytest.raises(ValueError, match=r"spot light radius must be in \[0, 1000\] m"):
            scene.add_spot_light([0, 5, 0], [0, -1, 0], radius=radius)
    with pytest.raises(ValueError, match="normals must have one entry per vertex"):
        scene.add_mesh(TRIANGLE, [[0, 1, 2]], normals=[[0, 1, 0]])
    with pytest.raises(ValueError, match="normals must be non-zero"):
        scene.add_mesh(TRIANGLE, [[0, 1, 2]], normals=[[0, 1, 0], [0, 0, 0], [0, 1, 0]])
    with pytest.raises(ValueError, match="geometry must be an id returned by add_"):
        scene.remove(-1)
    with pytest.raises(ValueError, match="direction must be non-zero"):
        scene.intersect([0, 1, 0], [0, 0, 0])
    with pytest.raises(ValueError, match="sun_direction must be non-zero"):
        scene.set_physical_sky([0, 0, 0])
    positions = np.zeros((2, 2, 3), np.float32)
    with pytest.raises(ValueError, match=r"positions must be a \(rows, cols, 3\) array"):
        scene._add_terrain_grid(np.zeros((2, 2), np.float32), shading.Diffuse(0.5), np.zeros((2, 3)))
    with pytest.raises(ValueError, match=r"uv_from_index must be a \(2, 3\) array"):
        scene._add_terrain_grid(positions, shading.Diffuse(0.5), np.zeros((3, 2)))
    with pytest.raises(ValueError, match="add_terrain: material must be a refracta.shading material"):
        scene._add_terrain_grid(positions, None, np.zeros((2, 3)))


def test_spot_light_index_and_shadow_radius_through_the_library():
    scene = refracta.Scene()
    scene.add_point_light([0, 5, 0], 10.0)
    assert scene.add_spot_light([0, 5, 0], [0, -1, 0], radius=0.5) == 0
    assert scene.add_spot_light([1, 5, 0], [0, -1, 0]) == 1
    assert len(scene.lights) == 3


def test_sea_refuses_a_water_of_another_wind():
    waves = refracta.OceanWaves(wind_speed=5.0, resolution=16)
    with pytest.raises(ValueError, match="wind_speed of the waves"):
        refracta.Scene().add_sea(waves, material=shading.Water(wind_speed=8.0))
    with pytest.raises(ValueError, match="resolved_slope_variance must be 0"):
        refracta.Scene().add_sea(waves, material=shading.Water(wind_speed=5.0, resolved_slope_variance=1e-4))
    ids = refracta.Scene().add_sea(waves, detail_radius=2.0 * waves.spacing)  # at least one spacing
    assert ids == sorted(ids) and len(ids) >= 2  # bands, then the flat plane


def test_ocean_waves_arrays_repr_and_pickle():
    waves = refracta.OceanWaves(wind_speed=6.0, wind_direction=(0.0, 2.0), resolution=8, seed=3, time=1.5)
    assert waves.heights().shape == (8, 8) and waves.slopes().shape == (8, 8, 2)
    assert repr(waves).startswith("OceanWaves(wind_speed=6, wind_direction=(0, 2), patch_size=100, resolution=8")
    copy = pickle.loads(pickle.dumps(waves))
    np.testing.assert_array_equal(copy.heights(), waves.heights())  # the same seed: the same sea
    with pytest.raises(ValueError, match="seed must be >= 0"):
        refracta.OceanWaves(seed=-1)


def test_camera_state_restores_jitter_and_lens_and_repr_names_the_lens():
    camera = refracta.Camera([0, 1, 0], [0, 1, -10], width=4, height=3).with_lens(0.01, 5.0)
    camera = camera.jittered(np.full((3, 4, 2), 1e-3, np.float32))
    copy = pickle.loads(pickle.dumps(camera))
    assert copy.jitter is not None and copy.aperture_diameter == 0.01 and copy.focus_distance == 5.0
    assert repr(copy) == repr(camera) and "aperture_diameter=0.01, focus_distance=5" in repr(camera)
    with pytest.raises(ValueError, match="Camera.ray: u must be finite"):
        camera.ray(NAN, 1.0)


def test_light_batches_refuse_mismatched_rows():
    light = lights.PointLight([0, 1, 0], 1.0)
    with pytest.raises(ValueError, match="p_light must have shape"):
        light.pdf_li(np.zeros((2, 3)), None, np.tile([0.0, 1.0, 0.0], (2, 1)), p_light=np.zeros((1, 3)))
    with pytest.raises(ValueError, match="normals must have shape"):
        light.L(np.zeros((2, 3)), np.zeros((1, 3)), np.tile([0.0, 1.0, 0.0], (2, 1)))
    environment = lights.EnvironmentLight(np.ones((4, 8, 3)))
    with pytest.raises(ValueError, match="uv must be finite"):
        environment.uv_to_direction(np.array([[0.5, NAN]]))
    with pytest.raises(ValueError, match="no lights to sample"):
        lights.LightSampler([]).sample(np.array([0.5]))
    assert light.type == "delta_position" and environment.type == "infinite"


def test_area_normal_empty_bounds_and_an_array_map_through_pickle():
    area = lights.AreaLight(TRIANGLE, [[0, 2, 1]], 1.0)
    np.testing.assert_array_equal(area.normal(0), [0.0, 1.0, 0.0])  # (v1 - v0) x (v2 - v0) of vertices 0, 2, 1: up
    with pytest.raises(ValueError, match=r"triangle must be < 1 \(got 1\)"):
        area.normal(1)
    with pytest.raises(ValueError, match="Scene.bounds: the scene is empty"):
        _ = refracta.Scene().bounds
    texels = np.random.default_rng(1).uniform(0.0, 2.0, (4, 8, 3)).astype(np.float32)
    environment = pickle.loads(pickle.dumps(lights.EnvironmentLight(texels, scale=2.0)))
    uv = np.array([[0.3, 0.4], [0.8, 0.9]])
    np.testing.assert_array_equal(  # the float texels travel exactly
        environment.Le(environment.uv_to_direction(uv)),
        lights.EnvironmentLight(texels, scale=2.0).Le(environment.uv_to_direction(uv)),
    )
    camera = refracta.Camera([0, 1, 0], [0, 1, -10])
    assert camera.project(np.array([[0.0, 1.0, -5.0], [0.0, 1.0, 5.0]])).shape == (2, 3)
    # On the view axis: the image centre at depth 5 m, to the rounding of a few double operations.
    np.testing.assert_allclose(camera.project([0.0, 1.0, -5.0]), [320.0, 180.0, 5.0], rtol=1e-12)
