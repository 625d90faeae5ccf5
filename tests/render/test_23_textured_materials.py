"""Issue 23 item 11: a texture file as the colour of the shading materials (Diffuse's reflectance,
BlinnPhong's kd, Plastic's reflectance, Principled's base colour) -- one textured reflectance
(shading/material_util.h), registered in each scene the material is added to -- and `texture =`
in a scene file's [[materials]]."""

import pickle

import numpy as np
import pytest

import refracta
from refracta import shading

# A texel of a linear EXR whose channels half floats hold exactly (no sRGB decoding, no rounding).
TEXEL = (0.25, 0.5, 0.75)
# Textured and untextured renders take the same samples (the seeds, the cosine and light samples
# do not depend on the colour), so they differ by float32 rounding of the product alone.
RENDER_RTOL = 1e-5
SKY = (1.0, 1.0, 1.0)


def uniform_texture(path, texel=TEXEL):
    refracta.io.write_image(path, np.tile(np.asarray(texel, np.float32), (8, 8, 1)))
    return path


def two_colour_texture(path):
    """Left half red, right half blue (linear), as the OBJ test of test_textures.py."""
    image = np.zeros((8, 16, 3), np.float32)
    image[:, :8] = (1.0, 0.0, 0.0)
    image[:, 8:] = (0.0, 0.0, 1.0)
    refracta.io.write_image(path, image)
    return path


def quad_scene(material, sun=True):
    """A 4 m x 2 m quad 10 m ahead along +x, uvs over [0, 1]^2 (u along +z: the camera's right)."""
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    if sun:
        scene.set_sun((-1.0, 0.6, 0.3), (3.0, 3.0, 3.0))
    vertices = [(10, -1, -2), (10, -1, 2), (10, 1, 2), (10, 1, -2)]
    scene.add_mesh(vertices, [(0, 1, 2), (0, 2, 3)], material=material, uvs=[(0, 0), (1, 0), (1, 1), (0, 1)])
    return scene


CAMERA = refracta.Camera((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0, 1, 0), 10.0, 40, 20)


def render(scene, **options):
    return refracta.render(scene, CAMERA, None, method="straight", spp=4, progress=False, **options)


def scaled(colour, texel=TEXEL):
    return tuple(c * t for c, t in zip(colour, texel))


# (class, colour keyword, colour, other keywords): every material with a textured reflectance.
MATERIALS = [
    (shading.Diffuse, "reflectance", (0.8, 0.6, 0.4), {}),
    (shading.BlinnPhong, "kd", (0.8, 0.6, 0.4), {"ks": 0.2, "ns": 20.0}),
    (shading.Plastic, "reflectance", (0.8, 0.6, 0.4), {"alpha": 0.2}),
    (shading.Principled, "base_color", (0.8, 0.6, 0.4), {"roughness": 0.4, "sheen": 0.5}),
]


def test_the_issue_call_works_and_reads_back(tmp_path):
    """Diffuse(texture="albedo.png") raised pybind's "Unable to cast ... 'str'"; now the path is
    kept (absolute) and rebuilds the material."""
    path = uniform_texture(tmp_path / "albedo.exr")
    material = shading.Diffuse(0.5, texture=str(path))
    assert material.parameters["texture"] == str(path)
    assert "texture='" in repr(material)
    assert pickle.loads(pickle.dumps(material)).parameters == material.parameters
    assert shading.Diffuse(0.5, texture=path).parameters["texture"] == str(path)  # os.PathLike


def test_textured_diffuse_is_the_texture_times_the_untextured_render(tmp_path):
    """Sun and sky light a quad filling the view: with the uniform texture the image is TEXEL x
    the untextured image, pixel by pixel."""
    texture = str(uniform_texture(tmp_path / "albedo.exr"))
    plain = render(quad_scene(shading.Diffuse(0.8)))
    textured = render(quad_scene(shading.Diffuse(0.8, texture=texture)))
    assert plain.min() > 0.0  # the quad fills the view
    np.testing.assert_allclose(textured, plain * np.float32(TEXEL), rtol=RENDER_RTOL)


@pytest.mark.parametrize("cls, key, colour, extra", MATERIALS, ids=lambda v: getattr(v, "__name__", ""))
def test_each_textured_colour_is_the_colour_times_the_texel(tmp_path, cls, key, colour, extra):
    """For every material the texture multiplies its colour: the render with the texture equals
    the render of the same material whose colour is colour x texel."""
    texture = str(uniform_texture(tmp_path / "albedo.exr"))
    textured = render(quad_scene(cls(**{key: colour}, texture=texture, **extra)))
    reference = render(quad_scene(cls(**{key: scaled(colour)}, **extra)))
    # RENDER_RTOL; 1e-7 absolute for black pixels (float32).
    np.testing.assert_allclose(textured, reference, rtol=RENDER_RTOL, atol=1e-7)


@pytest.mark.parametrize("cls, key, colour, extra", MATERIALS, ids=lambda v: getattr(v, "__name__", ""))
def test_each_material_shows_the_texture_where_its_uvs_say(tmp_path, cls, key, colour, extra):
    """Red left half, blue right half of the texture land on the quad's left and right: there the
    image is that of the material coloured red, or blue, without texture."""
    texture = str(two_colour_texture(tmp_path / "sign.exr"))
    # 0.8: BlinnPhong's kd + ks must stay <= 1 (ks 0.2)
    image = render(quad_scene(cls(**{key: 0.8}, texture=texture, **extra), sun=False))
    red = render(quad_scene(cls(**{key: (0.8, 0.0, 0.0)}, **extra), sun=False))
    blue = render(quad_scene(cls(**{key: (0.0, 0.0, 0.8)}, **extra), sun=False))
    np.testing.assert_allclose(image[:, 12], red[:, 12], rtol=RENDER_RTOL, atol=1e-7)  # as above
    np.testing.assert_allclose(image[:, 28], blue[:, 28], rtol=RENDER_RTOL, atol=1e-7)  # as above


def test_one_material_serves_scenes_with_different_texture_tables(tmp_path):
    """The file is registered in each scene the material joins: in a scene whose table already
    holds another texture (a different id) it still shows its own file."""
    texture = str(uniform_texture(tmp_path / "albedo.exr"))
    other = str(uniform_texture(tmp_path / "other.exr", (1.0, 0.0, 0.0)))
    material = shading.Diffuse(0.8, texture=texture)
    first = quad_scene(material)
    second = refracta.Scene()
    second.add_billboard((-1e5, 0.0, 0.0), 1.0, 1.0, other)  # id 0 of this table, far behind the camera
    second.set_sky(SKY, SKY)
    second.set_sun((-1.0, 0.6, 0.3), (3.0, 3.0, 3.0))
    second.add_mesh(
        [(10, -1, -2), (10, -1, 2), (10, 1, 2), (10, 1, -2)],
        [(0, 1, 2), (0, 2, 3)],
        material=material,
        uvs=[(0, 0), (1, 0), (1, 1), (0, 1)],
    )
    np.testing.assert_array_equal(render(first), render(second))
    assert second.material(1).parameters["texture"] == texture


def test_a_scene_with_a_textured_material_pickles(tmp_path):
    scene = quad_scene(shading.Principled(0.9, texture=str(two_colour_texture(tmp_path / "sign.exr"))))
    np.testing.assert_array_equal(render(pickle.loads(pickle.dumps(scene))), render(scene))


def test_a_textured_ground_material_gets_texture_coordinates(tmp_path):
    """add_ground(material=<textured>) repeats the texture every texture_size, as texture= does."""
    texture = str(uniform_texture(tmp_path / "albedo.exr"))
    camera = refracta.Camera((0.0, 2.0, 0.0), (0.0, 0.0, 0.01), (1, 0, 0), 20.0, 8, 8)
    scenes = []
    cases = ((shading.Diffuse(0.8, texture=texture), {"texture_size": 3.0}), (shading.Diffuse(0.8), {}))
    for material, repeat in cases:
        scene = refracta.Scene()
        scene.set_sky(SKY, SKY)
        scene.add_ground(0.0, 100.0, material=material, **repeat)  # untextured: no texture_size (refused)
        scenes.append(refracta.render(scene, camera, None, method="straight", progress=False))
    np.testing.assert_allclose(scenes[0], scenes[1] * np.float32(TEXEL), rtol=RENDER_RTOL)


def test_bad_textures_are_refused_with_a_message_that_says_what_to_do(tmp_path):
    with pytest.raises(refracta.IoError, match="no such texture file"):
        shading.Diffuse(texture=str(tmp_path / "missing.png"))
    with pytest.raises(ValueError, match="texture must be an image file path"):
        shading.BlinnPhong(texture=1.5)
    textured = shading.Diffuse(texture=str(uniform_texture(tmp_path / "albedo.exr")))
    scene = refracta.Scene()
    with pytest.raises(ValueError, match="no texture coordinates.*uvs="):
        scene.add_box((0, 0, 0), (1, 1, 1), material=textured)
    with pytest.raises(ValueError, match="no texture coordinates"):
        scene.add_sphere((0, 0, 0), 1.0, material=textured)


def test_scene_files_take_texture_in_materials(tmp_path):
    """`texture =` in [[materials]] of type diffuse, blinn_phong and principled, relative to the
    file (it raised the pybind cast error)."""
    uniform_texture(tmp_path / "albedo.exr")
    (tmp_path / "scene.toml").write_text("""
[camera]
position = [0.0, 0.0, 0.0]
look_at = [10.0, 0.0, 0.0]
vfov = 10.0
size = [40, 20]

[sky]
horizon = [1.0, 1.0, 1.0]

[[materials]]
name = "a"
type = "diffuse"
reflectance = 0.8
texture = "albedo.exr"

[[materials]]
name = "b"
type = "blinn_phong"
kd = 0.8
texture = "albedo.exr"

[[materials]]
name = "c"
type = "principled"
base_color = 0.8
texture = "albedo.exr"

[[objects]]
type = "mesh"
material = "a"
vertices = [[10, -1, -2], [10, -1, 2], [10, 1, 2], [10, 1, -2]]
triangles = [[0, 1, 2], [0, 2, 3]]
uvs = [[0, 0], [1, 0], [1, 1], [0, 1]]
""")
    scene, camera, _ = refracta.load_scene(tmp_path / "scene.toml")
    assert scene.material(0).parameters["texture"] == str(tmp_path / "albedo.exr")
    image = refracta.render(scene, camera, None, method="straight", progress=False)
    plain = render(quad_scene(shading.Diffuse(0.8), sun=False))
    np.testing.assert_allclose(image[10, 20], plain[10, 20] * np.float32(TEXEL), rtol=RENDER_RTOL)
