"""TOML scene files, OBJ meshes and the render command."""

from pathlib import Path

import numpy as np
import pytest

import refracta
from refracta import cli, lights

DATA = Path(__file__).resolve().parents[1] / "data"


def test_load_scene_builds_scene_camera_and_field():
    scene, camera, field = refracta.load_scene(DATA / "hot_road.toml")
    assert (camera.width, camera.height, camera.vfov) == (96, 32, 2.2)
    assert isinstance(field, refracta.PhysicalAtmosphere) and field.params["surface_dt"] == 10.0
    assert scene.geometry_count == 4  # ground, box, and the OBJ's two materials
    image = refracta.render(scene, camera, field, progress=False)
    assert image.shape == (32, 96, 3) and np.all(np.isfinite(image))


def test_obj_materials_come_from_the_mtl_file():
    scene = refracta.Scene()
    ids = scene.add_obj(str(DATA / "tent.obj"), offset=(10, 0, 0))
    assert len(ids) == 2
    # Facing the canvas side at z = +1 (triangle (10,0,1), (11.5,1,1), (10,2,1) after the offset).
    camera = refracta.Camera([10.5, 1, 5], [10.5, 1, 0], vfov=10, width=9, height=9)
    # Embree's float32 hit point at ~4 m: ~1e-6 relative.
    np.testing.assert_allclose(camera.pick(scene, 4.5, 4.5), [10.5, 1.0, 1.0], atol=1e-5)
    scene.set_sky((1, 1, 1))
    image = refracta.render(scene, camera, progress=False, spp=256)
    # Canvas Kd 0.8 0.6 0.2, Ks 0.1, Ns 20 under a uniform white sky, seen along its normal:
    # radiance = the Blinn-Phong directional albedo, estimated independently from the material's
    # own sample() weights. Eight seeds at 256 spp scatter by 0.005 (1 sigma): 0.02 is 4 sigma.
    canvas = refracta.shading.BlinnPhong(kd=(0.8, 0.6, 0.2), ks=(0.1, 0.1, 0.1), ns=20)
    rng = np.random.default_rng(1)
    samples = canvas.sample(np.tile([0.0, 0.0, 1.0], (200000, 1)), rng.random((200000, 3)))
    albedo = np.where(samples.valid[:, None], samples.weight, 0.0).mean(axis=0)
    assert albedo[0] > 0.8  # the specular lobe adds to Kd
    np.testing.assert_allclose(image[4, 4], albedo, atol=0.02)


def write(tmp_path, text, name="scene.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


CAMERA = "[camera]\nposition = [0, 1, 0]\nlook_at = [10, 1, 0]\nsize = [8, 4]\n"


@pytest.mark.parametrize(
    "text, message",
    [
        ("[camera\nposition = [0, 1, 0]\n", r"scene.toml: malformed TOML: .*line 1"),
        (CAMERA + "[atmosphere]\nmodel = 'Fog'\n", r"scene.toml:6: \[atmosphere\] model: unknown model 'Fog'"),
        (CAMERA + "[atmosphere]\nsurface_dt = 5\nsurface_depth = -1\n", r"scene.toml:7: \[atmosphere\] surface_depth"),
        (
            CAMERA + "[[objects]]\ntype = 'box'\ncentre = [1, 2]\nsize = [1, 1, 1]\n",
            r"scene.toml:7: \[\[objects\]\] #1 centre: must be a list of 3 numbers",
        ),
        (
            CAMERA + "[[objects]]\ntype = 'ground'\n[[objects]]\ntype = 'cone'\n",
            r"scene.toml:8: \[\[objects\]\] #2 type: unknown type 'cone'",
        ),
        (
            CAMERA + "[[objects]]\ntype = 'sphere'\ncentre = [1, 2, 3]\nradius = 1\ncolour = [1, 0, 0]\n",
            r"scene.toml:9: \[\[objects\]\] #1 colour: unknown key",
        ),
        (
            "[camera]\nposition = [0, 1, 0]\nlook_at = [0, 1, 0]\n",
            r"scene.toml:[23]: \[camera\] (position|look_at): .*look_at must differ",
        ),
        ("[camera]\nlook_at = [1, 1, 0]\n", r"scene.toml:1: \[camera\] position: missing"),
    ],
)
def test_scene_file_errors_name_file_line_and_key(tmp_path, text, message):
    with pytest.raises(ValueError, match=message):
        refracta.load_scene(write(tmp_path, text))


def test_missing_files_raise_io_errors(tmp_path):
    with pytest.raises(refracta.IoError, match="no such scene file"):
        refracta.load_scene(tmp_path / "nothing.toml")
    path = write(tmp_path, CAMERA + "[[objects]]\ntype = 'obj'\nfile = 'boat.obj'\n")
    with pytest.raises(refracta.IoError, match="boat.obj"):
        refracta.load_scene(path)
    (tmp_path / "broken.obj").write_text("v 0 0 0\nf 1 2 9\n")
    with pytest.raises(refracta.IoError, match="broken.obj"):
        refracta.Scene().add_obj(str(tmp_path / "broken.obj"))


def test_render_command_writes_the_image(tmp_path):
    output = tmp_path / "road.exr"
    assert cli.main(["render", str(DATA / "hot_road.toml"), "-o", str(output), "--size", "48x16"]) == 0
    image = refracta.io.read_image(output)
    assert image.shape == (16, 48, 3)


def test_render_command_exposes_pngs_as_write_image_does(tmp_path):
    # Automatic by default; --ev100 and --exposure are write_image's manual exposures (EXR: linear).
    linear = tmp_path / "road.exr"
    assert cli.main(["render", str(DATA / "hot_road.toml"), "-o", str(linear), "--size", "48x16"]) == 0
    image = refracta.io.read_image(linear)
    for extra, kwargs in (
        ([], {}),
        (["--ev100", "12"], dict(ev100=12.0)),
        (["--exposure", "0.5"], dict(exposure=0.5)),
        (["--key", "0.09", "--tonemap", "reinhard"], dict(key=0.09, tonemap="reinhard")),
    ):
        output = tmp_path / "road.png"
        assert cli.main(["render", str(DATA / "hot_road.toml"), "-o", str(output), "--size", "48x16", *extra]) == 0
        # 8-bit quantisation: half a level.
        np.testing.assert_allclose(
            refracta.io.read_image(output), refracta.io.to_display(image, **kwargs), atol=0.51 / 255
        )


def test_every_material_and_light_type_loads_and_renders_finite():
    scene, camera, field = refracta.load_scene(DATA / "materials_and_lights.toml")
    assert field is None
    # The physical sky (Scene.set_physical_sky through refracta.examples.set_physical_sky; scaled, so
    # a ScaledLight of it) and its sun, point, spot, the emissive panel (AreaLight) and sphere.
    kinds = sorted(
        type(light.light if isinstance(light, lights.ScaledLight) else light).__name__ for light in scene.lights
    )
    assert kinds == ["AreaLight", "PhysicalSky", "PointLight", "SphereLight", "SpotLight", "SunLight"]
    assert scene.geometry_count == 12  # ground, panel, 10 objects with the ten material types
    for transport in ("direct", "path"):
        image = refracta.render(scene, camera, field, transport=transport, spp=2, progress=False)
        assert image.shape == (16, 48, 3) and np.all(np.isfinite(image)) and image.min() >= 0.0
        assert image.mean() > 0.0


def test_materials_are_shared_by_name(tmp_path):
    """An object naming a material renders as the same material given in Python."""
    text = (
        CAMERA + "[environment]\ntype = 'constant'\nradiance = 1.0\n"
        "[[materials]]\nname = 'red'\ntype = 'diffuse'\nreflectance = [0.8, 0.1, 0.1]\n"
        "[[objects]]\ntype = 'sphere'\ncentre = [10, 1, 0]\nradius = 3\nmaterial = 'red'\n"
    )
    scene, camera, _ = refracta.load_scene(write(tmp_path, text))
    reference = refracta.Scene()
    reference.set_environment((1.0, 1.0, 1.0))
    reference.add_sphere([10, 1, 0], 3.0, material=refracta.shading.Diffuse((0.8, 0.1, 0.1)))
    options = dict(transport="path", spp=4, seed=2, progress=False)
    np.testing.assert_array_equal(
        refracta.render(scene, camera, **options), refracta.render(reference, camera, **options)
    )


LIGHT_CAMERA = CAMERA + "[environment]\ntype = 'constant'\nradiance = 0.1\n"


@pytest.mark.parametrize(
    "text, message",
    [
        (
            CAMERA + "[[materials]]\nname = 'x'\ntype = 'velvet'\n",
            r"scene.toml:7: \[\[materials\]\] #1 type: unknown material type 'velvet'",
        ),
        (
            CAMERA + "[[materials]]\nname = 'paint'\ntype = 'diffuse'\n[[objects]]\ntype = 'box'\n"
            "centre = [5, 1, 0]\nsize = [1, 1, 1]\nmaterial = 'pain'\n",
            r"scene.toml:12: \[\[objects\]\] #1 material: unknown material 'pain' \(materials: paint\)",
        ),
        (
            CAMERA + "[[materials]]\nname = 'metal'\ntype = 'rough_conductor'\n\nalpha = -0.1\n",
            r"scene.toml:9: \[\[materials\]\] #1 alpha: alpha_u must be finite and >= 0 \(got -0.1\)",
        ),
        (
            CAMERA + "[[materials]]\nname = 'paint'\ntype = 'principled'\nroughness = -0.2\n",
            r"scene.toml:8: \[\[materials\]\] #1 roughness: roughness must be in \[0, 1\]",
        ),
        (
            CAMERA + "[[materials]]\nname = 'glass'\ntype = 'dielectric'\niro = 1.5\n",
            r"scene.toml:8: \[\[materials\]\] #1 iro: unknown key for a dielectric material",
        ),
        (
            CAMERA + "[[materials]]\nname = 'a'\ntype = 'diffuse'\nreflectance = 'red'\n",
            r"scene.toml:8: \[\[materials\]\] #1 reflectance: must be a number or a list of numbers",
        ),
        (
            LIGHT_CAMERA + "[[lights]]\ntype = 'laser'\n",
            r"scene.toml:9: \[\[lights\]\] #1 type: unknown light type 'laser'",
        ),
        (
            LIGHT_CAMERA + "[[lights]]\ntype = 'point'\nposition = [0, 1, 0]\nintensity = -1\n",
            r"scene.toml:11: \[\[lights\]\] #1 intensity: intensity must be finite and >= 0",
        ),
        (
            LIGHT_CAMERA + "[[lights]]\ntype = 'spot'\nposition = [0, 1, 0]\ndirection = [1, 0, 0]\nintensity = 1\n"
            "cone = 30\n",
            r"scene.toml:13: \[\[lights\]\] #1 cone: unknown key for a spot light",
        ),
        (CAMERA + "[environment]\ntype = 'fog'\n", r"scene.toml:6: \[environment\] type: unknown environment type"),
        (
            CAMERA + "[environment]\ntype = 'physical_sky'\nsun_direction = [0, 0, 0]\n",
            r"scene.toml:7: \[environment\] sun_direction: must be a non-zero direction",
        ),
        (
            CAMERA + "[environment]\ntype = 'physical_sky'\nsun_direction = [0, 1, 0]\n[sun]\ndirection = [0, 1, 0]\n"
            "radiance = 1\n",
            r"scene.toml:8: \[sun\]: the physical sky sets its own sun",
        ),
        (
            CAMERA + "[[objects]]\ntype = 'ground'\nemission = [1, 1, 1]\n",
            r"scene.toml:7: \[\[objects\]\] #1 emission: unknown key for a ground",
        ),
    ],
)
def test_material_and_light_errors_name_file_line_and_key(tmp_path, text, message):
    with pytest.raises(ValueError, match=message):
        refracta.load_scene(write(tmp_path, text))


def test_a_photographic_camera_with_a_lens_loads_and_round_trips(tmp_path):
    text = (
        "[camera]\nposition = [0, 1.4, 0]\nlook_at = [200, 1.4, 0]\nsize = [96, 32]\nfocal_length_mm = 300.0\n"
        "sensor_mm = [36.0, 24.0]\nf_number = 4.0\n"
    )
    camera = refracta.load_scene(write(tmp_path, text)).camera
    same = refracta.Camera.photographic((0, 1.4, 0), (200, 1.4, 0), 300.0, width=96, height=32, f_number=4.0)
    assert camera.vfov == same.vfov
    assert camera.aperture_diameter == pytest.approx(0.075, rel=1e-15)  # f / N
    assert camera.focus_distance == pytest.approx(200.0, rel=1e-15)  # the look_at distance
    # camera_table writes the lens as aperture_diameter and focus_distance with the vfov.
    again = refracta.load_scene(write(tmp_path, refracta.scene_file.camera_table(camera), "again.toml")).camera
    assert (again.vfov, again.aperture_diameter, again.focus_distance) == (
        camera.vfov,
        camera.aperture_diameter,
        camera.focus_distance,
    )


@pytest.mark.parametrize(
    "extra, message",
    [
        ("vfov = 10.0\nfocal_length_mm = 50.0\n", r"\[camera\] focal_length_mm: give vfov or focal_length_mm"),
        ("f_number = 2.0\n", r"\[camera\] f_number: needs focal_length_mm"),
        (
            "focal_length_mm = 50.0\nf_number = 0.0\n",
            r"\[camera\] f_number: Camera.photographic: f_number must be in \[0.5, 10000\]",
        ),
        ("aperture_diameter = 0.01\n", r"\[camera\] aperture_diameter: needs focus_distance"),
        ("focus_distance = 5.0\n", r"\[camera\] focus_distance: needs f_number or aperture_diameter"),
    ],
)
def test_impossible_lenses_in_scene_files_are_refused_naming_the_key(tmp_path, extra, message):
    with pytest.raises(ValueError, match=message):
        refracta.load_scene(write(tmp_path, CAMERA + extra))


def test_a_byte_order_mark_is_read_past(tmp_path):
    # Windows editors save UTF-8 with a BOM; tomllib refused it as "Invalid statement (at line 1,
    # column 1)" (a trial). The file reads as it would without.
    text = (DATA / "hot_road.toml").read_text().replace('"tent.obj"', f'"{DATA / "tent.obj"}"')
    plain, marked = tmp_path / "plain.toml", tmp_path / "marked.toml"
    plain.write_text(text, encoding="utf-8")
    marked.write_text(text, encoding="utf-8-sig")
    assert marked.read_bytes().startswith(b"\xef\xbb\xbf")
    scene, camera, field = refracta.load_scene(marked)
    _, camera_plain, field_plain = refracta.load_scene(plain)
    assert field.params == field_plain.params and camera.position.tolist() == camera_plain.position.tolist()
