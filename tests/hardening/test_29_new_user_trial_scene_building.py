"""What a new user's trial of scene building found (5 December): grey textures rendered red, 8-bit
textures were never decoded from sRGB, texture alpha darkened the colour, Blinn-Phong and MTL
materials reflected more light than arrived, an area light added alone was invisible, and the CLI
rendered a whole image before refusing its file format."""

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image as PIL_Image

import refracta

DATA = Path(__file__).resolve().parents[1] / "data"
# The sRGB decoding of 8-bit 128 (IEC 61966-2-1): ((128/255 + 0.055) / 1.055)^2.4.
SRGB_128 = ((128 / 255 + 0.055) / 1.055) ** 2.4  # 0.2159
# The prepared texture is half-float: 0.2159 to ~1e-4; the render adds nothing (a constant sky, one
# diffuse bounce with kd = 1 seen head-on: radiance = albedo).
HALF_FLOAT = 2e-3


def _ground_albedo(texture) -> np.ndarray:
    scene = refracta.Scene()
    scene.add_ground(0.0, 100.0, kd=1.0, texture=str(texture))
    scene.set_environment(1.0)  # a white furnace: a diffuse surface shows its albedo
    camera = refracta.Camera((0.0, 0.5, 0.0), (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), 2.0, 8, 8)
    return refracta.render(scene, camera, None, progress=False).mean(axis=(0, 1))


@pytest.mark.parametrize(
    "name, pixels, mode",
    [
        ("grey.png", np.full((16, 32), 128, np.uint8), "L"),  # was (0.502, 0, 0): red, and not decoded
        ("rgb.png", np.full((16, 32, 3), 128, np.uint8), "RGB"),  # was 0.502: not decoded
        ("grey_alpha.png", np.dstack([np.full((16, 32), 128, np.uint8)] * 1 + [np.full((16, 32), 64, np.uint8)]), "LA"),
        ("rgba.png", np.dstack([np.full((16, 32, 3), 128, np.uint8), np.full((16, 32), 64, np.uint8)]), "RGBA"),
    ],
)
def test_8_bit_textures_are_decoded_from_srgb_in_every_channel_and_alpha_is_not_their_colour(
    tmp_path, name, pixels, mode
):
    PIL_Image.fromarray(pixels, mode).save(tmp_path / name)
    np.testing.assert_allclose(_ground_albedo(tmp_path / name), SRGB_128, atol=HALF_FLOAT)


def test_blinn_phong_refuses_more_reflectance_than_light():
    # kd = ks = 1 gave 2.09 in a white furnace.
    with pytest.raises(ValueError, match="kd \\+ ks must be <= 1 in every channel"):
        refracta.Scene().add_sphere((0.0, 0.0, 0.0), 1.0, kd=1.0, ks=1.0, ns=10)
    with pytest.raises(ValueError, match="kd \\+ ks must be <= 1"):
        refracta.shading.BlinnPhong(kd=(0.2, 0.9, 0.2), ks=0.2)


def test_an_mtl_material_brighter_than_its_light_is_scaled_with_a_warning(tmp_path):
    (tmp_path / "a.mtl").write_text("newmtl shiny\nKd 0.8 0.8 0.8\nKs 0.5 0.5 0.5\nNs 20\n")
    (tmp_path / "a.obj").write_text("mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nusemtl shiny\nf 1 2 3\n")
    scene = refracta.Scene()
    with pytest.warns(UserWarning, match="Kd \\+ Ks <= 1 \\(both scaled\\)"):
        scene.add_obj(str(tmp_path / "a.obj"))


def test_an_area_light_must_come_with_the_surface_that_emits_it():
    light = refracta.lights.AreaLight([(0, 2, 0), (1, 2, 0), (0, 2, 1)], [(0, 1, 2)], 10.0)
    with pytest.raises(ValueError, match="emission="):  # it lit the ground, but no ray saw it
        refracta.Scene().add_light(light)


def test_the_cli_refuses_an_image_format_before_rendering(tmp_path):
    result = subprocess.run(
        [sys.executable, "-m", "refracta", "render", str(DATA / "hot_road.toml"), "-o", str(tmp_path / "x.xyz")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 1 and "cannot write" in result.stderr
    assert "Traceback" not in result.stderr and "rendering" not in result.stdout.lower()


def test_mtl_emission_and_pbr_values_out_of_range_are_moved_with_the_warning(tmp_path):
    # A Ke of -5 was dropped without a word; a Pr of 5 was refused without the file's name.
    (tmp_path / "a.mtl").write_text("newmtl odd\nKd 0.5 0.5 0.5\nKe -5 0 0\nPr 5\n")
    (tmp_path / "a.obj").write_text("mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 0 1\nusemtl odd\nf 1 2 3\n")
    with pytest.warns(UserWarning, match="material 'odd' has Ke \\(-5, 0, 0\\), Pr 5 out of range"):
        refracta.Scene().add_obj(str(tmp_path / "a.obj"))


@pytest.mark.parametrize("which", ["scene", "camera", "field"])
def test_render_names_an_argument_of_the_wrong_kind(which):
    # pybind11 said "_render(): incompatible function arguments", naming a private function.
    arguments = {"scene": refracta.Scene(), "camera": refracta.Camera((0, 1, 0), (1, 1, 0), (0, 1, 0), 45, 8, 8)}
    arguments["field"] = None
    arguments[which] = "air"
    with pytest.raises(ValueError, match=f"render: {which} must be a refracta"):
        refracta.render(arguments["scene"], arguments["camera"], arguments["field"], progress=False)


def test_an_environment_light_given_a_path_says_how_to_read_it(tmp_path):
    # numpy read the path's characters: "image must hold real numbers (got dtype <U11)".
    for path in ("sky.png", tmp_path / "sky.png"):
        with pytest.raises(ValueError, match="read a file with refracta.io.read_image"):
            refracta.lights.EnvironmentLight(path)


def test_the_demo_refuses_a_file_as_its_folder(tmp_path):
    (tmp_path / "taken").write_text("")
    result = subprocess.run(
        [sys.executable, "-m", "refracta", "demo", "--out", str(tmp_path / "taken")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert result.returncode == 1 and "is a file: give a folder" in result.stderr  # was "[Errno 17] File exists"
