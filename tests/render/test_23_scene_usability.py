"""Issue 23 item 15: Scene.set_material and Scene.remove (an imported model's parts changed or
dropped without editing its files), refracta.SceneWarning for a scene without light and for a
ground away from the field's height 0, and the index models' real __init__ signatures."""

import pickle
import pydoc
import warnings

import numpy as np
import pytest

import refracta
from refracta import shading

SKY = (1.0, 1.0, 1.0)
CAMERA = refracta.Camera((0.0, 1.0, 0.0), (10.0, 1.0, 0.0), (0, 1, 0), 30.0, 24, 16)


def render(scene, field=None, **options):
    return refracta.render(scene, CAMERA, field, method="straight", spp=2, progress=False, **options)


def two_boxes(front=(0.8, 0.2, 0.2)):
    """A red box in front of a grey one, on a ground at y = 0, under a white sky."""
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_ground(0.0, 200.0)
    back = scene.add_box((20.0, 1.5, 0.0), (1.0, 3.0, 6.0), material=shading.Diffuse(0.5))
    front_id = scene.add_box((10.0, 1.0, 0.0), (1.0, 2.0, 2.0), material=shading.Diffuse(front))
    return scene, back, front_id


def test_set_material_changes_the_render_as_building_it_so_would():
    scene, _, front = two_boxes()
    before = render(scene)
    scene.set_material(front, shading.Diffuse((0.2, 0.2, 0.8)))
    after = render(scene)
    rebuilt, _, _ = two_boxes(front=(0.2, 0.2, 0.8))
    np.testing.assert_array_equal(after, render(rebuilt))
    # The front box's face (rows 6-10, columns 10-14: it spans 2 m = 6 pixels about the centre),
    # red, then blue: over its 25 pixels, not one (at 2 spp a pixel's two sky-lighting samples can
    # both be shadowed: 0 in every channel).
    face_before, face_after = before[6:11, 10:15].mean(axis=(0, 1)), after[6:11, 10:15].mean(axis=(0, 1))
    assert face_before[0] > face_before[2] and face_after[2] > face_after[0]
    assert scene.material(front).parameters["reflectance"] == (0.2, 0.2, 0.8)


def test_remove_drops_a_geometry_and_keeps_the_other_ids():
    """Removing the front box shows the grey box behind it, exactly as a scene built without it
    (Embree's structure is committed again); ids stay, a removed id is refused and not reused."""
    scene, back, front = two_boxes()
    count = scene.geometry_count
    scene.remove(front)
    without = refracta.Scene()
    without.set_sky(SKY, SKY)
    without.add_ground(0.0, 200.0)
    without.add_box((20.0, 1.5, 0.0), (1.0, 3.0, 6.0), material=shading.Diffuse(0.5))
    np.testing.assert_array_equal(render(scene), render(without))
    assert scene.geometry_count == count
    assert scene.material(back).parameters["reflectance"] == (0.5, 0.5, 0.5)
    for call in (
        lambda: scene.remove(front),
        lambda: scene.material(front),
        lambda: scene.set_material(front, shading.Diffuse()),
    ):
        with pytest.raises(ValueError, match=f"geometry {front} was removed"):
            call()
    with pytest.raises(ValueError, match="no geometry 99"):
        scene.remove(99)
    assert scene.add_sphere((5.0, 1.0, 3.0), 0.5) == count  # a new id, not the removed one
    assert scene.intersect((0.0, 1.0, 0.0), (1.0, 0.0, 0.0))[2] == back


def test_removing_an_emitter_removes_its_light_and_the_bounds_shrink():
    scene = refracta.Scene()
    scene.add_ground(0.0, 10.0)
    lamp = scene.add_sphere((0.0, 50.0, 0.0), 1.0, emission=(5.0, 5.0, 5.0))
    # Default rel 1e-6: the sphere's top, 50 + 1 m, from float bounds.
    assert len(scene.lights) == 1 and scene.bounds[1][1] == pytest.approx(51.0)
    scene.remove(lamp)
    # Default abs 1e-12 at 0: the ground's top, exactly 0.
    assert len(scene.lights) == 0 and scene.bounds[1][1] == pytest.approx(0.0)


def test_a_scene_with_removed_geometry_pickles_with_its_ids():
    scene, back, front = two_boxes()
    scene.remove(back)
    copy = pickle.loads(pickle.dumps(scene))
    np.testing.assert_array_equal(render(copy), render(scene))
    assert copy.material(front).parameters == scene.material(front).parameters
    with pytest.raises(ValueError, match="was removed"):
        copy.material(back)


def test_set_material_refuses_a_texture_on_geometry_without_uvs(tmp_path):
    refracta.io.write_image(tmp_path / "t.exr", np.ones((4, 4, 3), np.float32))
    scene, _, front = two_boxes()
    with pytest.raises(ValueError, match="no texture coordinates"):
        scene.set_material(front, shading.Diffuse(texture=str(tmp_path / "t.exr")))
    with pytest.raises(ValueError, match="refracta.shading material"):
        scene.set_material(front, "red")


def render_quietly(scene, field, method="curved"):
    """Renders with every warning an error; returns the SceneWarnings raised (none expected)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        refracta.render(scene, CAMERA.resized(4, 3), field, method=method, progress=False, max_length=100.0)
    return [w for w in caught if issubclass(w.category, refracta.SceneWarning)]


def test_a_scene_without_light_warns_that_it_renders_black():
    scene = refracta.Scene()
    scene.add_ground(0.0, 100.0)
    with pytest.warns(refracta.SceneWarning, match="no light and no sky.*set_sky"):
        image = render(scene)
    assert not image.any()
    scene.set_sky(SKY, SKY)
    assert render_quietly(scene, None) == []
    emitter_only = refracta.Scene()
    emitter_only.add_sphere((10.0, 1.0, 0.0), 1.0, emission=(1.0, 1.0, 1.0))
    assert render_quietly(emitter_only, None) == []


def test_animate_warns_once_for_all_its_frames():
    scene = refracta.Scene()
    scene.add_ground(0.0, 100.0)
    with pytest.warns(refracta.SceneWarning, match="no light") as record:
        refracta.animate(
            scene,
            CAMERA.resized(4, 3),
            None,
            [0.0, 0.1, 0.2],
            noise={"rms": 1e-4, "correlation_pixels": 2.0},
            progress=False,
        )
    assert len([w for w in record if issubclass(w.category, refracta.SceneWarning)]) == 1


HOT_ROAD = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)


@pytest.mark.parametrize("height", [0.5, -1.5])
def test_a_ground_away_from_the_fields_height_0_warns(height):
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_ground(height, 100.0)
    with pytest.warns(refracta.SceneWarning, match=f"ground is at y = {height:g} m"):
        refracta.render(scene, CAMERA.resized(4, 3), HOT_ROAD, progress=False, max_length=100.0)


def test_a_wave_sea_is_placed_by_its_mean_level_not_its_troughs():
    # A trial: a 10 m/s sea at mean level 0 under layered air was told to move 1.84 m up (its troughs).
    calm_at_zero, lowered = refracta.Scene(), refracta.Scene()
    for scene, level in ((calm_at_zero, 0.0), (lowered, -2.0)):
        scene.set_sky(SKY, SKY)
        scene.add_sea(refracta.OceanWaves(wind_speed=10.0, resolution=32), height=level, detail_radius=50.0)
    assert float(calm_at_zero.bounds[0][1]) < -1.0  # the troughs reach well below the mean level
    assert render_quietly(calm_at_zero, HOT_ROAD) == []
    with pytest.warns(refracta.SceneWarning, match="ground is at y = -2 m"):
        refracta.render(lowered, CAMERA.resized(4, 3), HOT_ROAD, progress=False, max_length=100.0)


def test_no_ground_warning_where_it_does_not_apply():
    """Ground at 0 (within GROUND_TOLERANCE), no field, straight rays, or air without a ground
    layer (the standard atmosphere looks the same 1.5 m lower): no warning."""
    at_zero = refracta.Scene()
    at_zero.set_sky(SKY, SKY)
    at_zero.add_ground(0.05, 100.0)
    assert render_quietly(at_zero, HOT_ROAD) == []
    low = refracta.Scene()
    low.set_sky(SKY, SKY)
    low.add_ground(-1.5, 100.0)
    assert render_quietly(low, None) == []
    assert render_quietly(low, HOT_ROAD, method="straight") == []
    assert render_quietly(low, refracta.PhysicalAtmosphere()) == []


@pytest.mark.parametrize(
    "model, parameter",
    [
        (refracta.PhysicalAtmosphere, "surface_dt: float = 0.0"),
        (refracta.LogisticProfile, "a_hot: float"),
        (refracta.LinearSquaredProfile, "alpha: float"),
    ],
)
def test_the_index_models_show_their_parameters_in_help(model, parameter):
    text = pydoc.render_doc(model.__init__, renderer=pydoc.plaintext)
    assert parameter in text and "*args" not in text
    assert ("hot_spots" in text) == (model is not refracta.LinearSquaredProfile)


def test_geometry_beyond_the_rays_reach_warns_and_a_longer_reach_sees_it():
    """A box 300 m away with max_length 100 m: curved rays stop in the air and the image is sky, so
    render() says so; with max_length 400 m the same render sees the box and does not warn."""
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_box((300.0, 10.0, 0.0), (20.0, 20.0, 20.0), kd=(0.8, 0.2, 0.1))  # resting on y = 0
    camera = refracta.Camera((0.0, 1.0, 0.0), (300.0, 1.0, 0.0), (0.0, 1.0, 0.0), 5.0, 4, 3)
    with pytest.warns(
        refracta.SceneWarning,
        match="290 m from the camera, beyond the rays' reach max_length = 100 m, so the image shows none of them",
    ):
        short = refracta.render(scene, camera, HOT_ROAD, progress=False, max_length=100.0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        long = refracta.render(scene, camera, HOT_ROAD, progress=False, max_length=400.0)
    assert not [w for w in caught if issubclass(w.category, refracta.SceneWarning)]
    sky, box = short[1, 2], long[1, 2]
    assert box[0] > box[2] and not sky[0] > sky[2]  # the box's red (kd 0.8, 0.2, 0.1) only when reached
    assert render_quietly(scene, HOT_ROAD, method="straight") == []  # straight rays have no reach


@pytest.mark.parametrize("eye_y", [0.0, -10.0])
def test_a_camera_at_or_below_the_scenes_ground_warns(eye_y):
    """A trial's eye at sea level (Camera.geographic height 0) saw sky where the sea under it lies,
    and at -10 m the sea's underside, silently; an eye above the ground renders without the hint."""
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_ground(0.0, 100.0, kd=(0.5, 0.5, 0.5))
    camera = refracta.Camera((0.0, eye_y, 0.0), (100.0, eye_y - 1.0, 0.0), (0.0, 1.0, 0.0), 5.0, 4, 3)
    for field in (HOT_ROAD, None):
        with pytest.warns(
            refracta.SceneWarning, match=f"the camera is at y = {eye_y:g} m, at or below the scene's ground"
        ):
            refracta.render(scene, camera, field, progress=False, max_length=200.0)
    above = refracta.Camera((0.0, 1.5, 0.0), (100.0, 0.5, 0.0), (0.0, 1.0, 0.0), 5.0, 4, 3)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        refracta.render(scene, above, HOT_ROAD, progress=False, max_length=200.0)
    assert not [w for w in caught if issubclass(w.category, refracta.SceneWarning)]


def test_a_camera_above_a_ground_below_height_zero_has_no_hint():
    # The review's Dead Sea: a shore 430 m below the ellipsoid, the eye 2 m above it; the hint
    # compared the eye with height 0, not with the scene's ground.
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_ground(-430.0, 200.0, kd=(0.5, 0.5, 0.5))
    camera = refracta.Camera((0.0, -428.0, 0.0), (100.0, -428.5, 0.0), (0.0, 1.0, 0.0), 5.0, 4, 3)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        refracta.render(scene, camera, refracta.PhysicalAtmosphere(), progress=False, max_length=300.0)
    assert not [w for w in caught if "the camera is at y" in str(w.message)]


def test_a_camera_below_a_target_without_a_ground_has_no_hint():
    # A scene of a target alone (the geographic readout's tests: an eye 5 m up, a box whose bottom
    # lies at 19 m in the flat frame) has no ground to be below.
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_box((100.0, 20.0, 0.0), (2.0, 2.0, 2.0), kd=(0.5, 0.5, 0.5))
    camera = refracta.Camera((0.0, 5.0, 0.0), (100.0, 20.0, 0.0), (0.0, 1.0, 0.0), 5.0, 4, 3)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        refracta.render(scene, camera, refracta.PhysicalAtmosphere(), progress=False, max_length=300.0)
    assert not [w for w in caught if "the camera is at y" in str(w.message)]


def test_a_light_panel_overhead_is_no_ground():
    # A lone emitting quad 3 m up (an area light over the camera) was taken for the scene's ground,
    # and render() said the camera stood under it; the same quad as a plain surface is a ground.
    quad = {"vertices": [(-1, 3, -1), (1, 3, -1), (1, 3, 1), (-1, 3, 1)], "triangles": [(0, 2, 1), (0, 3, 2)]}
    camera = refracta.Camera((0.0, 1.5, 0.0), (0.0, 3.0, 0.1), (0.0, 1.0, 0.0), 60.0, 4, 3)
    panel = refracta.Scene()
    panel.add_mesh(**quad, emission=(1.0, 1.0, 1.0), two_sided=True)
    assert panel.ground_bounds is None
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        refracta.render(panel, camera, None, progress=False)
    assert not [w for w in caught if "the camera is at y" in str(w.message)]
    surface = refracta.Scene()
    surface.set_sky(SKY, SKY)
    surface.add_mesh(**quad, kd=(0.5, 0.5, 0.5))
    lower, upper = surface.ground_bounds
    assert lower[1] == upper[1] == 3.0 and lower[0] == -1.0 and upper[2] == 1.0
    with pytest.warns(refracta.SceneWarning, match="the camera is at y = 1.5 m, at or below the scene's ground"):
        refracta.render(surface, camera, None, progress=False)


def test_a_floor_inside_walls_is_the_rooms_not_a_ground():
    # A floor quad within a box's footprint and height (a room's) is no ground: the eye may stand on
    # either side of it; a sea reaching beyond the objects is one.
    scene = refracta.Scene()
    scene.add_box((0.0, 2.0, 0.0), (10.0, 4.0, 10.0), kd=(0.5, 0.5, 0.5))
    scene.add_mesh(vertices=[(-4, 1, -4), (4, 1, -4), (4, 1, 4), (-4, 1, 4)], triangles=[(0, 2, 1), (0, 3, 2)])
    assert scene.ground_bounds is None
    scene.add_ground(0.0, 100.0)
    lower, upper = scene.ground_bounds
    assert lower[1] == 0.0 and upper[1] == 1.0 and upper[0] == 50.0  # both flat surfaces: the sea's box
