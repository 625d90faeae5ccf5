"""Wavefront MTL records become refracta.shading materials: Kd/Ks/Ns -> BlinnPhong, Pr/Pm (the PBR
extension) -> Principled, glass (illum 4/6/7 with d < 1 and Ni > 1) -> Dielectric(Ni), Ke -> an area
light that renders its radiance."""

import numpy as np
import pytest

import refracta

OBJ = """mtllib parts.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vn 0 0 1
usemtl paint
f 1//1 2//1 3//1
usemtl metal
f 1//1 3//1 4//1
o second
v 0 0 -1
v 1 0 -1
v 1 1 -1
usemtl glass
f 5 6 7
v 0 0 -2
v 1 0 -2
v 1 1 -2
usemtl lamp
f 8 9 10
"""

MTL = """newmtl paint
Kd 0.8 0.1 0.1
Ks 0.2 0.2 0.2
Ns 50
newmtl metal
Kd 0.9 0.9 0.9
Pr 0.3
Pm 1.0
newmtl glass
Kd 1 1 1
d 0.1
Ni 1.5
illum 7
newmtl lamp
Kd 0 0 0
Ke 2 3 4
"""


MTL_FLOAT = 1e-7  # tinyobjloader reads MTL numbers as float32 (6e-8 relative)


def load(tmp_path):
    (tmp_path / "parts.obj").write_text(OBJ)
    (tmp_path / "parts.mtl").write_text(MTL)
    scene = refracta.Scene()
    ids = scene.add_obj(str(tmp_path / "parts.obj"))
    return scene, {name: i for i, name in zip(ids, ("paint", "metal", "glass", "lamp"))}


def test_each_mtl_model_becomes_its_material(tmp_path):
    scene, part = load(tmp_path)  # one geometry per material, in the file's order
    kinds = {name: repr(scene.material(i)).split("(")[0] for name, i in part.items()}
    assert kinds == {"paint": "BlinnPhong", "metal": "Principled", "glass": "Dielectric", "lamp": "BlinnPhong"}
    # The Blinn-Phong part evaluates as the MTL's Kd/pi + Ks (Ns + 8)/(8 pi) (n.h)^Ns at normal incidence.
    f = scene.material(part["paint"]).f([0, 0, 1.0], [0, 0, 1.0])[0]
    np.testing.assert_allclose(f, np.array([0.8, 0.1, 0.1]) / np.pi + 0.2 * 58 / (8 * np.pi), rtol=MTL_FLOAT)
    # Glass: the MTL's Ni, a delta lobe (f = 0 everywhere, pdf 0).
    glass = scene.material(part["glass"])
    assert "1.5" in repr(glass)
    assert np.all(glass.f([0, 0, 1.0], [0.0, 0.6, 0.8]) == 0.0)


def test_ke_makes_an_area_light_of_that_radiance(tmp_path):
    scene, _ = load(tmp_path)
    # The lamp triangle (z = -2, counter-clockwise toward +z) seen from the front, emitters only.
    camera = refracta.Camera([0.7, 0.3, 5.0], [0.7, 0.3, -2.0], vfov=0.5, width=3, height=3)
    scene_lamp_only = refracta.Scene()
    (tmp_path / "lamp.obj").write_text("mtllib parts.mtl\nv 0 0 -2\nv 1 0 -2\nv 1 1 -2\nusemtl lamp\nf 1 2 3\n")
    scene_lamp_only.add_obj(str(tmp_path / "lamp.obj"))
    image = refracta.render(scene_lamp_only, camera, progress=False, max_depth=0)
    # The emission seen directly through float32 pixels.
    np.testing.assert_allclose(image[1, 1], (2.0, 3.0, 4.0), rtol=1e-6)
    assert len(scene.lights) == 1


def test_a_colour_of_one_value_is_a_grey(tmp_path):
    # The MTL specification: "g and b are optional; if only r is specified, g and b are assumed equal
    # to r". tinyobjloader read (r, 0, 0): a grey paint came out red, a white lamp red (a trial).
    (tmp_path / "one.obj").write_text("mtllib one.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n")
    (tmp_path / "one.mtl").write_text("newmtl grey\nKd 0.3\nKs 0.2\nNs 10\nKe 2\n")
    scene = refracta.Scene()
    ids = scene.add_obj(str(tmp_path / "one.obj"))
    material = scene.material(ids[0])
    np.testing.assert_allclose(material.parameters["kd"], (0.3, 0.3, 0.3), rtol=1e-7)  # float32 in the reader
    np.testing.assert_allclose(material.parameters["ks"], (0.2, 0.2, 0.2), rtol=1e-7)
    scene.set_sky((0.0, 0.0, 0.0))
    camera = refracta.Camera((0.3, 0.3, 2.0), (0.3, 0.3, 0.0), width=4, height=4)
    np.testing.assert_array_equal(refracta.render(scene, camera, None, progress=False)[2, 1], (2.0, 2.0, 2.0))
    (tmp_path / "two.obj").write_text("mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n")
    (tmp_path / "two.mtl").write_text("newmtl grey\nKd 0.3 0.4\n")  # b was read as 0
    with pytest.raises(refracta.IoError, match=r"line 2: 'Kd' has 2 values; a colour is r g b, or one grey value"):
        refracta.Scene().add_obj(str(tmp_path / "two.obj"))


def test_an_index_of_refraction_at_or_below_zero_is_noted(tmp_path):
    (tmp_path / "ni.obj").write_text("mtllib ni.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl glass\nf 1 2 3\n")
    (tmp_path / "ni.mtl").write_text("newmtl glass\nillum 7\nd 0.1\nNi -1.5\n")
    with pytest.warns(UserWarning, match="material 'glass' has Ni -1.5 out of range"):
        refracta.Scene().add_obj(str(tmp_path / "ni.obj"))


def test_a_missing_material_library_is_named(tmp_path):
    # tinyobjloader's words were passed on: "Material file [ missing.mtl ] not found in a path : ...".
    (tmp_path / "m.obj").write_text("mtllib missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n")
    with pytest.raises(refracta.IoError, match=r"m\.obj': its material library 'missing\.mtl' \(mtllib\) is not in"):
        refracta.Scene().add_obj(str(tmp_path / "m.obj"))
