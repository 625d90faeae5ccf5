"""Malformed files against the loaders (issue 13): generated OBJ, MTL, TOML, EXR, PNG and PFM files
-- truncated, garbage numbers, out-of-range indices, huge counts, flipped bytes -- either load
(and then hold finite data) or raise refracta's named errors. The `fuzz` marker runs the larger
budget."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import refracta
from tests.hardening.properties import FAST, FUZZ, calls, finite, render_checking_scene_warnings

NUMBERS = st.one_of(
    st.floats(-10, 10).map(repr),
    st.sampled_from(
        ["nan", "inf", "-inf", "1e999", "abc", "", "0x1p3", "1e-400", "--1", "1.2.3", "+5", ".5", "1e", "9" * 400]
    ),
)
INDICES = st.one_of(
    st.integers(-6, 8).map(str),
    st.sampled_from(["0", "99999999999", "-99999999999", "a", "1//", "1/2/3/4", "1/a", "", "2147483648"]),
)


@st.composite
def obj_text(draw):
    lines = []
    for _ in range(draw(st.integers(0, 8))):
        kind = draw(st.sampled_from(["v", "vt", "vn", "f", "usemtl", "o", "mtllib", "#", "junk"]))
        if kind in ("v", "vn"):
            lines.append(" ".join([kind] + draw(st.lists(NUMBERS, min_size=0, max_size=5))))
        elif kind == "vt":
            lines.append(" ".join([kind] + draw(st.lists(NUMBERS, min_size=0, max_size=3))))
        elif kind == "f":
            corners = draw(
                st.lists(st.tuples(INDICES, st.sampled_from(["", "/1", "//1", "/1/1", "/9/9"])), min_size=0, max_size=5)
            )
            lines.append("f " + " ".join(i + rest for i, rest in corners))
        elif kind == "usemtl":
            lines.append("usemtl " + draw(st.sampled_from(["a", "missing", ""])))
        elif kind == "mtllib":
            lines.append("mtllib m.mtl")
        else:
            lines.append(draw(st.text(st.characters(codec="ascii", exclude_characters="\r\n\x00"), max_size=12)))
    text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n" * draw(st.booleans()) + "\n".join(lines) + "\n"
    cut = draw(st.integers(0, len(text)))
    return text[:cut] if draw(st.booleans()) else text


@st.composite
def mtl_text(draw):
    lines = ["newmtl a"] if draw(st.booleans()) else []
    for _ in range(draw(st.integers(0, 6))):
        key = draw(st.sampled_from(["Kd", "Ks", "Ke", "Ns", "Ni", "d", "illum", "Pr", "Pm", "map_Kd", "newmtl"]))
        if key == "map_Kd":
            lines.append("map_Kd " + draw(st.sampled_from(["missing.png", "", "m.mtl"])))
        elif key == "newmtl":
            lines.append("newmtl " + draw(st.sampled_from(["a", "b", ""])))
        else:
            lines.append(" ".join([key] + draw(st.lists(NUMBERS, min_size=0, max_size=4))))
    return "\n".join(lines) + "\n"


def check_obj(directory, obj, mtl):
    (directory / "m.obj").write_text(obj)
    (directory / "m.mtl").write_text(mtl)
    scene = refracta.Scene()
    ids = calls(scene.add_obj, str(directory / "m.obj"))
    if ids is not None:  # what loaded renders finite
        camera = refracta.Camera((0.3, 0.3, 3.0), (0.3, 0.3, 0.0), vfov=60, width=4, height=4)
        image = calls(refracta.render, scene, camera, None, method="straight", progress=False)
        assert image is None or finite(image)


@FAST
@given(obj_text(), mtl_text())
def test_malformed_obj_and_mtl_files_load_or_raise(tmp_path_factory, obj, mtl):
    check_obj(tmp_path_factory.mktemp("obj"), obj, mtl)


@pytest.mark.fuzz
@FUZZ
@given(obj_text(), mtl_text())
def test_malformed_obj_and_mtl_fuzz(tmp_path_factory, obj, mtl):
    check_obj(tmp_path_factory.mktemp("obj"), obj, mtl)


TOML_VALUES = st.sampled_from(
    [
        "1",
        "-1",
        "0",
        "1e400",
        "inf",
        "nan",
        '"x"',
        "true",
        "[]",
        "[1, 2]",
        "[1, 2, 3]",
        "[inf, 1, 2]",
        "[0, 0, 0]",
        "[1e308, -1e308, 0]",
        "[640.5, 2]",
        "[2, 2]",
        "{ a = 1 }",
        '"ground"',
        '"box"',
        '"sphere"',
        '"obj"',
        '"mesh"',
        '"PhysicalAtmosphere"',
    ]
)
TABLES = ["camera", "sun", "sky", "atmosphere", "environment", "[objects]", "[lights]", "[materials]", "bogus"]
KEYS = [
    "position",
    "look_at",
    "up",
    "vfov",
    "size",
    "direction",
    "radiance",
    "horizon",
    "zenith",
    "model",
    "type",
    "centre",
    "radius",
    "height",
    "file",
    "surface_dt",
    "name",
    "kd",
    "vertices",
    "triangles",
    "scale",
    "vfovv",
]


@st.composite
def toml_text(draw):
    lines = ["[camera]", "position = [0, 1, 0]", "look_at = [10, 1, 0]", "size = [4, 2]"] if draw(st.booleans()) else []
    for _ in range(draw(st.integers(0, 4))):
        table = draw(st.sampled_from(TABLES))
        lines.append(f"[{table}]")
        for _ in range(draw(st.integers(0, 4))):
            lines.append(f"{draw(st.sampled_from(KEYS))} = {draw(TOML_VALUES)}")
    return "\n".join(lines) + "\n"


def check_toml(directory, text):
    path = directory / "scene.toml"
    path.write_text(text)
    loaded = calls(refracta.load_scene, path)
    if loaded is not None:
        scene, camera, field = loaded
        if camera.width * camera.height <= 64:
            image = render_checking_scene_warnings(scene, camera, field, progress=False, max_length=100.0)
            assert image is None or finite(image)


@FAST
@given(toml_text())
def test_malformed_scene_files_load_or_raise(tmp_path_factory, text):
    check_toml(tmp_path_factory.mktemp("toml"), text)


@pytest.mark.fuzz
@FUZZ
@given(toml_text())
def test_malformed_scene_files_fuzz(tmp_path_factory, text):
    check_toml(tmp_path_factory.mktemp("toml"), text)


_VALID = {}


def valid_image_bytes(directory, suffix):
    """A small valid image file of each format (bytes), written by refracta itself."""
    if suffix not in _VALID:
        path = directory / f"valid{suffix}"
        pixels = np.linspace(0, 1, 4 * 3 * 3, dtype=np.float32).reshape(4, 3, 3)
        if suffix == ".pfm":
            path.write_bytes(b"PF\n3 4\n-1.0\n" + pixels.astype("<f4").tobytes())
        else:
            refracta.io.write_image(path, pixels)
        _VALID[suffix] = path.read_bytes()
    return _VALID[suffix]


@st.composite
def damaged(draw, data: bytes):
    data = bytearray(data)
    for _ in range(draw(st.integers(0, 4))):
        if not data:
            break
        where = draw(st.integers(0, len(data) - 1))
        data[where] = draw(st.integers(0, 255))
    if draw(st.booleans()):
        data = data[: draw(st.integers(0, len(data)))]
    if draw(st.booleans()):  # a header claiming a huge size
        data = data.replace(b"3 4", draw(st.sampled_from([b"99999999 99999999", b"-3 4", b"0 0", b"3 40000"])))
    return bytes(data)


def check_image(directory, suffix, data):
    path = directory / f"damaged{suffix}"
    path.write_bytes(data)
    image = calls(refracta.io.read_image, path)
    if image is not None:
        assert image.ndim == 3 and image.dtype == np.float32
    # As a texture: loads (finite texels) or raises.
    scene = refracta.Scene()
    calls(scene.add_ground, texture=str(path))


@FAST
@given(st.data(), st.sampled_from([".exr", ".png", ".pfm"]))
def test_damaged_images_load_or_raise(tmp_path_factory, data, suffix):
    directory = tmp_path_factory.mktemp("img")
    check_image(directory, suffix, data.draw(damaged(valid_image_bytes(directory, suffix))))


@pytest.mark.fuzz
@settings(FUZZ, max_examples=150)
@given(st.data(), st.sampled_from([".exr", ".png", ".pfm"]))
def test_damaged_images_fuzz(tmp_path_factory, data, suffix):
    directory = tmp_path_factory.mktemp("img")
    check_image(directory, suffix, data.draw(damaged(valid_image_bytes(directory, suffix))))
