"""A downloaded model's textures: Scene.add_obj(texture_dirs=..., missing_textures=...) finds the
images its MTL names in the MTL's folder, then in the given folders (the original mirage editor's
Portland scene keeps them in a sibling textures/ folder); Scene.bounds and Camera.framing show the
model in two lines."""

import itertools
import math
import pickle

import numpy as np
import pytest
from PIL import Image

import refracta

FRAMING_TOL = 1e-9  # [m]: the framing distance is a closed form; round-off only


def write_model(folder, map_kd="facade.png", kd="1 1 1"):
    """A 2 m x 1 m quad in the plane z = 0 (front +z, uvs over [0, 1]^2) with one material whose
    map_Kd is `map_Kd`; returns the OBJ's path."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "model.mtl").write_text(f"newmtl facade\nKd {kd}\nmap_Kd {map_kd}\n")
    (folder / "model.obj").write_text(
        "mtllib model.mtl\n"
        "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "usemtl facade\n"
        "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
    )
    return folder / "model.obj"


def write_texture(path, rgb):
    path.parent.mkdir(parents=True, exist_ok=True)
    Image.new("RGB", (4, 4), rgb).save(path)


def centre_colour(scene):
    """Radiance at the image centre of the quad seen head-on under a white constant sky."""
    scene.set_sky((1.0, 1.0, 1.0))
    camera = refracta.Camera((1.0, 0.5, 4.0), (1.0, 0.5, 0.0), vfov=10, width=8, height=6)
    image = refracta.render(scene, camera, progress=False)
    return image[3, 4]


@pytest.fixture
def city(tmp_path):
    """model/model.obj + model.mtl naming facade.png, which lives in model/textures/ (red)."""
    obj = write_model(tmp_path / "model")
    write_texture(tmp_path / "model" / "textures" / "facade.png", (255, 0, 0))
    return obj


def test_a_texture_in_no_searched_folder_raises_file_not_found_naming_it_and_the_folders(city):
    with pytest.raises(refracta.TextureNotFoundError) as error:
        refracta.Scene().add_obj(str(city))
    # Both what every missing file raises and the built-in a user would catch.
    assert isinstance(error.value, refracta.IoError) and isinstance(error.value, FileNotFoundError)
    assert "'facade.png'" in str(error.value)
    assert str(city.parent) in str(error.value)


def test_texture_dirs_find_the_sibling_textures_folder(city):
    scene = refracta.Scene()
    scene.add_obj(str(city), texture_dirs=[city.parent / "textures"])
    r, g, b = centre_colour(scene)
    assert r > 0.1 and g == 0.0 and b == 0.0  # Kd 1 times the red texture


def test_missing_texture_with_warn_uses_kd_and_warns_once(city):
    scene = refracta.Scene()
    with pytest.warns(UserWarning, match="texture 'facade.png' of material 'facade' not found") as record:
        scene.add_obj(str(city), missing_textures="warn")
    assert len(record) == 1
    r, g, b = centre_colour(scene)
    assert r > 0.1 and r == g == b  # Kd = 1 1 1: grey, no texture


def test_folders_are_searched_in_order_and_by_file_name(tmp_path):
    obj = write_model(tmp_path / "model", map_kd=r"C:\Users\author\maps\facade.png")  # the author's path
    write_texture(tmp_path / "first" / "facade.png", (0, 255, 0))
    write_texture(tmp_path / "second" / "facade.png", (0, 0, 255))
    scene = refracta.Scene()
    scene.add_obj(str(obj), texture_dirs=[str(tmp_path / "missing"), tmp_path / "first", tmp_path / "second"])
    r, g, b = centre_colour(scene)
    assert g > 0.1 and r == 0.0 and b == 0.0  # green: the first folder holding it


def test_the_mtl_folder_comes_before_texture_dirs(tmp_path):
    obj = write_model(tmp_path / "model")
    write_texture(tmp_path / "model" / "facade.png", (0, 0, 255))
    write_texture(tmp_path / "elsewhere" / "facade.png", (255, 0, 0))
    scene = refracta.Scene()
    scene.add_obj(str(obj), texture_dirs=[tmp_path / "elsewhere"])
    r, g, b = centre_colour(scene)
    assert b > 0.1 and r == 0.0 and g == 0.0  # the blue texture was found (any clear blue); red and green exactly 0


def test_bad_missing_textures_and_texture_dirs_raise_value_error(city):
    with pytest.raises(ValueError, match="missing_textures must be 'error' or 'warn'"):
        refracta.Scene().add_obj(str(city), missing_textures="ignore")
    with pytest.raises(ValueError, match="texture_dirs must be a folder or a sequence of folders"):
        refracta.Scene().add_obj(str(city), texture_dirs=[3])


def test_a_single_folder_is_accepted_as_texture_dirs(city):
    scene = refracta.Scene()
    scene.add_obj(str(city), texture_dirs=city.parent / "textures")
    assert centre_colour(scene)[0] > 0.1  # the red texture was found: any clear red (not the untextured black)


def test_scene_bounds_are_the_box_around_every_geometry():
    scene = refracta.Scene()
    with pytest.raises(ValueError, match="empty"):
        _ = scene.bounds
    scene.add_box((1.0, 2.0, 3.0), (2.0, 4.0, 6.0))
    scene.add_sphere((10.0, 0.0, 0.0), 1.0)  # exact: centre +- radius
    lower, upper = scene.bounds
    assert lower.tolist() == [0.0, -1.0, -1.0]
    assert upper.tolist() == [11.0, 4.0, 6.0]


def test_framing_shows_the_whole_box_from_the_bounding_sphere_distance(city):
    scene = refracta.Scene()
    scene.add_obj(str(city), texture_dirs=[city.parent / "textures"])
    lower, upper = scene.bounds
    assert lower.tolist() == [0.0, 0.0, 0.0] and upper.tolist() == [2.0, 1.0, 0.0]
    for width, height, vfov in [(320, 180, 45.0), (100, 300, 30.0)]:
        camera = refracta.Camera.framing(scene, direction=(-1.0, -0.5, -1.0), vfov=vfov, width=width, height=height)
        centre, radius = 0.5 * (lower + upper), 0.5 * np.linalg.norm(upper - lower)
        half_v = math.radians(vfov) / 2
        half = min(half_v, math.atan(math.tan(half_v) * width / height))
        assert np.allclose(camera.look_at, centre, rtol=0, atol=FRAMING_TOL)
        offset = camera.position - centre
        assert math.isclose(np.linalg.norm(offset), radius / math.sin(half), rel_tol=0, abs_tol=FRAMING_TOL)
        # A unit vector from the framing formula in double: rounding.
        assert np.allclose(offset / np.linalg.norm(offset), np.array([1.0, 0.5, 1.0]) / 1.5, rtol=0, atol=1e-12)
        corners = np.array(list(itertools.product(*zip(lower, upper))))
        u, v, depth = camera.project(corners).T
        assert (depth > 0).all() and (u >= 0).all() and (u <= width).all() and (v >= 0).all() and (v <= height).all()
        assert camera.pick(scene, width / 2, height / 2) is not None  # the model is at the centre


def test_framing_accepts_bounds_and_rejects_empty_or_degenerate_boxes():
    camera = refracta.Camera.framing(((0, 0, 0), (1, 1, 1)), width=64, height=64)
    assert np.allclose(camera.look_at, [0.5, 0.5, 0.5])  # numpy's default 1e-5/1e-8: the box's centre in double
    with pytest.raises(ValueError, match="single point"):
        refracta.Camera.framing(((1, 1, 1), (1, 1, 1)))
    with pytest.raises(ValueError, match="lower <= upper"):
        refracta.Camera.framing(((1, 0, 0), (0, 1, 1)))
    with pytest.raises(ValueError, match="empty"):
        refracta.Camera.framing(refracta.Scene())


def test_obj_options_as_an_object_or_by_keyword(tmp_path):
    """refracta.ObjOptions: add_obj's settings as one bound class (fields, pickling, validate()
    listing every problem), taken as options= or as its fields by keyword."""
    path = write_model(tmp_path / "model", map_kd="elsewhere.png")
    write_texture(tmp_path / "textures" / "elsewhere.png", (255, 0, 0))
    options = refracta.ObjOptions(offset=(1, 2, 3), scale=2.0, texture_dirs=tmp_path / "textures")
    assert pickle.loads(pickle.dumps(options)).texture_dirs == [str(tmp_path / "textures")]
    by_object, by_keywords = refracta.Scene(), refracta.Scene()
    by_object.add_obj(str(path), options=options, progress=False)
    by_keywords.add_obj(str(path), (1, 2, 3), 2.0, texture_dirs=tmp_path / "textures", progress=False)
    for a, b in zip(by_object.bounds, by_keywords.bounds):
        np.testing.assert_array_equal(a, b)  # the same settings, the same vertices
    np.testing.assert_array_equal(by_object.bounds[1], (5, 4, 3))  # (2, 1, 0) * 2 + offset
    bad = refracta.ObjOptions()  # the keyword constructor validates: set them after
    bad.scale = -1.0
    bad.missing_textures = "warn"
    assert bad.missing_textures == "warn"
    bad.offset = (0, 0, 0)
    with pytest.raises(ValueError, match="scale must be > 0"):
        bad.validate()
    with pytest.raises(ValueError, match="missing_textures must be 'error' or 'warn'"):
        refracta.ObjOptions(missing_textures="ignore")
    with pytest.raises(ValueError, match="add_obj: options must be a refracta.ObjOptions or None"):
        refracta.Scene().add_obj(str(path), options={"scale": 2.0}, progress=False)
