"""A pipeline TD's trial of scene files and compare: text keys that take only text, mistakes named
by the key at fault, a key outside the tables said as such, and comparisons with nothing to
compare reported as NaN with their pixel count, not as a perfect score."""

import math

import numpy as np
import pytest

import refracta
from refracta import compare, shading

CAMERA = "[camera]\nposition = [0, 1, -4]\nlook_at = [0, 0, 0]\nsize = [8, 6]\n"


def load(tmp_path, text, top=""):
    path = tmp_path / "scene.toml"
    path.write_text(top + CAMERA + text)  # top: keys before any table header
    return refracta.load_scene(path)


@pytest.mark.parametrize("name", ["5", "1.5", "true"])
def test_a_name_must_be_text(tmp_path, name):
    # name = 5 loaded as "5", and material = 5 met it.
    text = f'[[materials]]\nname = {name}\ntype = "diffuse"\n'
    with pytest.raises(ValueError, match=rf":\d+: \[\[materials\]\] #1 name: must be a string \(got {name.title()}"):
        load(tmp_path, text)


def test_an_object_file_must_be_text(tmp_path):
    with pytest.raises(ValueError, match=r"\[\[objects\]\] #1 file: must be a string \(got True\)"):
        load(tmp_path, '[[objects]]\ntype = "obj"\nfile = true\n')


def test_a_box_given_a_textured_material_names_the_material(tmp_path):
    refracta.io.write_image(str(tmp_path / "t.png"), np.full((4, 4, 3), 0.5, np.float32))
    text = (
        '[[materials]]\nname = "t"\ntype = "diffuse"\ntexture = "t.png"\n'
        '[[objects]]\ntype = "box"\ncentre = [0, 0, 0]\nsize = [1, 1, 1]\nmaterial = "t"\n'
    )
    # It named size (inside texture_size in the message).
    with pytest.raises(ValueError, match=r"\[\[objects\]\] #1 material: .*no texture coordinates"):
        load(tmp_path, text)


def test_a_key_outside_the_tables_is_not_called_a_table(tmp_path):
    with pytest.raises(ValueError, match=r"\[version\]: unknown key outside the tables"):
        load(tmp_path, "", top="version = 2\n")
    with pytest.raises(ValueError, match=r"\[cameras\]: unknown table"):
        load(tmp_path, "[cameras]\nx = 1\n")


def test_a_bad_surface_depth_is_named_with_hot_spots(tmp_path):
    text = "[atmosphere]\nmodel = 'PhysicalAtmosphere'\nsurface_depth = -0.2\n"
    text += "[[atmosphere.hot_spots]]\nx = 10.0\nz = 0.0\nradius = 2.0\ndt = 5.0\n"
    # It said hot_spot0_depth, a name the file does not hold.
    with pytest.raises(ValueError, match=r"\[atmosphere\] surface_depth: .*surface_depth must be in"):
        load(tmp_path, text)


def sunlit_box():
    scene = refracta.Scene()
    scene.add_ground(0.0, 40.0, material=shading.Diffuse(0.5))
    scene.add_box((0.0, 1.0, 0.0), (1.0, 2.0, 1.0), material=shading.Diffuse(0.5))
    scene.set_sun((0.4, 1.0, 0.3), (5.0, 5.0, 5.0))
    return scene


def test_shadows_compared_over_no_pixel_are_nan_not_zero():
    sky = refracta.Camera((-10.0, 8.0, -10.0), (4.0, 80.0, 2.0), (0.0, 0.0, 1.0), vfov=20.0, width=32, height=24)
    rows, _ = compare.shadows(sunlit_box(), sky, ("pcf",), (3,), figure=False)
    assert rows[0]["pixels"] == 0
    assert all(math.isnan(rows[0][key]) for key in ("mean_error", "p99_error", "light_leak", "over_shadow"))
    ground = refracta.Camera((-6.0, 5.0, -6.0), (0.0, 0.0, 0.0), vfov=50.0, width=32, height=24)
    rows, _ = compare.shadows(sunlit_box(), ground, ("pcf",), (3,), figure=False)
    assert rows[0]["pixels"] > 0 and np.isfinite(rows[0]["mean_error"])


def test_no_shadow_is_not_a_method_to_compare():
    camera = refracta.Camera((-6.0, 5.0, -6.0), (0.0, 0.0, 0.0), vfov=50.0, width=16, height=12)
    with pytest.raises(ValueError, match="'none' casts no shadow to compare"):
        compare.shadows(sunlit_box(), camera, ("none",), (3,), figure=False)


def test_a_windows_file_keeps_its_line_ends_when_its_camera_is_replaced(tmp_path):
    from refracta.scene_file import with_camera

    text = (CAMERA + "\n[sky]\nzenith = [0.2, 0.3, 0.8]\nhorizon = [0.8, 0.8, 0.9]\n").replace("\n", "\r\n")
    edited = with_camera(text, refracta.Camera((0.0, 1.0, -5.0), (0.0, 0.0, 0.0), width=20, height=10))
    assert edited.count("\n") == edited.count("\r\n")  # the new [camera] wrote bare \n before
    path = tmp_path / "scene.toml"
    path.write_bytes(edited.encode())
    assert refracta.load_scene(path)[1].width == 20


def test_a_spot_light_radius_in_a_file_softens_the_reference_shadows(tmp_path):
    # [[lights]] radius was refused ("unknown key for a spot light"); Scene.add_spot_light takes it.
    scene_text = (
        '[[objects]]\ntype = "ground"\nheight = 0.0\nsize = 20.0\n'
        '[[objects]]\ntype = "box"\ncentre = [0, 0.5, 0]\nsize = [1, 1, 1]\n'
        '[[lights]]\ntype = "spot"\nposition = [0.5, 4, 0.3]\ndirection = [0, -1, 0]\nangle = 120.0\n'
        "intensity = [50, 50, 50]\n"
    )
    camera = "[camera]\nposition = [0, 6, -5]\nlook_at = [0, 0, 0]\nsize = [48, 36]\n"
    penumbra = []
    for radius in ("", "radius = 0.5\n"):
        path = tmp_path / "spot.toml"
        path.write_text(camera + scene_text + radius)
        scene, view, _ = refracta.load_scene(path)
        shadow = refracta.render_raster(scene, view, shadows="embree", output="shadow", shadow_light=0)
        lit = shadow[..., 1] > 0
        penumbra.append(int(np.count_nonzero((shadow[..., 0] > 0.0) & (shadow[..., 0] < 1.0) & lit)))
    assert penumbra[0] == 0 and penumbra[1] > 0  # a point light's shadow is hard, a disc's soft


def test_sky_and_lens_mistakes_name_their_keys(tmp_path):
    # Both were placed on the table's header line, naming no key.
    with pytest.raises(ValueError, match=r":\d+: \[sky\] horizon: .*must be finite"):
        load(tmp_path, "[sky]\nhorizon = [nan, 0.5, 0.5]\n")
    lens = "aperture_diameter = -0.01\nfocus_distance = 3.0\n"
    with pytest.raises(ValueError, match=r"\[camera\] aperture_diameter: Camera: aperture_diameter must be in"):
        refracta.load_scene(_write(tmp_path, CAMERA + lens))


def _write(tmp_path, text):
    path = tmp_path / "lens.toml"
    path.write_text(text)
    return path
