"""A December 2026 bad-input trial of the newest APIs, the Python package's side (the library's:
test_38): scene files read and rewritten, layered EXRs, orthophotos and photographs. Each test
fails on the code before the fix: a hang, a bare Python error, or a silently wrong result."""

import math
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest
from PIL import Image
from PIL.TiffImagePlugin import IFDRational

import refracta
from refracta import geo, photo
from refracta import scene_file as sf

from ..scene.test_terrain import write_geotiff

needs_fifo = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs a FIFO")


def returns_in_a_child(code: str) -> str:
    """Runs `code` in a fresh Python and returns what it printed; fails when it blocks (a FIFO
    read waiting for a writer: killed after 60 s, far above the child's ~1 s start-up)."""
    try:
        child = subprocess.run(
            [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL
        )
    except subprocess.TimeoutExpired:
        pytest.fail(f"blocked: {code}")
    assert child.returncode == 0, child.stderr[-1500:]
    return child.stdout


@pytest.fixture
def camera():
    return refracta.Camera((0.0, 1.0, 0.0), (0.0, 1.0, -10.0), vfov=30.0, width=64, height=32)


def new_camera_table(camera) -> dict:
    return sf.tomllib.loads(sf.camera_table(camera))["camera"]


# -- Reading scene files -------------------------------------------------------------------------


@needs_fifo
def test_read_scene_text_refuses_a_fifo_as_load_scene_does(tmp_path):
    # It blocked for ever, waiting for a writer; load_scene refused the FIFO.
    fifo = tmp_path / "scene.toml"
    os.mkfifo(fifo)
    code = (
        "import refracta\nfrom refracta.scene_file import read_scene_text\n"
        f"try:\n    read_scene_text({str(fifo)!r})\n"
        "except refracta.IoError as error:\n    print(error)\n"
    )
    assert "not a regular file" in returns_in_a_child(code)
    with pytest.raises(refracta.IoError, match="not a regular file"):
        sf.read_scene_text(tmp_path)  # a folder too
    (tmp_path / "ok.toml").write_text("[camera]\n")
    assert sf.read_scene_text(tmp_path / "ok.toml") == "[camera]\n"


def test_arrays_nested_thousands_deep_are_a_scene_file_error(tmp_path):
    # tomllib recurses once per level: a bare RecursionError came out of load_scene and relocate.
    text = "x = " + "[" * 5000 + "]" * 5000 + "\n"
    path = tmp_path / "deep.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match=r"deep\.toml: malformed TOML: arrays or inline tables nested too deeply"):
        refracta.load_scene(path)
    with pytest.raises(ValueError, match="relocate: the text is not TOML: arrays or inline tables nested too deeply"):
        sf.relocate(text, tmp_path, tmp_path / "other")


# -- with_camera and with_atmosphere -------------------------------------------------------------


def test_with_camera_finds_the_camera_header_only_in_code(camera):
    # A "[camera]" line inside a multi-line string was taken for the header: the new table went
    # into the string (unterminated TOML) and the real [camera] was lost.
    text = 'x = """\n[camera]\n"""\n[camera]\nvfov = 3.0\n'
    out = sf.with_camera(text, camera)
    data = sf.tomllib.loads(out)
    assert data["x"] == "[camera]\n"
    assert data["camera"] == new_camera_table(camera)
    assert out.count("[camera]") == 2  # the string's and the one table
    # An array of arrays of strings spanning lines is no header either.
    text = 'x = [\n["camera"],\n]\n[camera]\nvfov = 3.0\n'
    data = sf.tomllib.loads(sf.with_camera(text, camera))
    assert data["x"] == [["camera"]] and data["camera"] == new_camera_table(camera)


@pytest.mark.parametrize("header", ['["camera"]', "['camera']", '[ "camera" ]'])
def test_with_camera_replaces_a_quoted_camera_header(camera, header):
    # ["camera"] was not seen: a second [camera] was added ("Cannot declare ('camera',) twice").
    text = f"{header}\nvfov = 3.0\n\n[sun]\ndirection = [0.0, 1.0, 0.0]\nradiance = 1.0\n"
    data = sf.tomllib.loads(sf.with_camera(text, camera))
    assert data["camera"] == new_camera_table(camera)
    assert data["sun"] == {"direction": [0.0, 1.0, 0.0], "radiance": 1.0}


def test_with_atmosphere_finds_its_table_as_with_camera_does():
    air = refracta.PhysicalAtmosphere(surface_dt=4.0)
    text = 'x = """\n[atmosphere]\n"""\n["atmosphere"]\nmodel = "LogisticProfile"\n\n[camera]\nvfov = 3.0\n'
    data = sf.tomllib.loads(sf.with_atmosphere(text, air))
    assert data["x"] == "[atmosphere]\n" and data["camera"] == {"vfov": 3.0}
    assert data["atmosphere"] == sf.tomllib.loads(sf.atmosphere_table(air))["atmosphere"]
    removed = sf.tomllib.loads(sf.with_atmosphere(text, None))
    assert removed == {"x": "[atmosphere]\n", "camera": {"vfov": 3.0}}


def test_with_camera_and_with_atmosphere_refuse_text_that_is_not_toml(camera):
    # 'not toml [' came back with a camera table put before it, as if it were a scene file.
    with pytest.raises(ValueError, match=r"with_camera: the text is not TOML: Expected '='"):
        sf.with_camera("not toml [", camera)
    with pytest.raises(ValueError, match="with_atmosphere: the text is not TOML"):
        sf.with_atmosphere("[camera\n", refracta.PhysicalAtmosphere())
    with pytest.raises(ValueError, match="with_atmosphere: the text is not TOML"):
        sf.with_atmosphere("[camera\n", None)
    with pytest.raises(ValueError, match="with_camera: the text is not TOML: arrays or inline tables nested"):
        sf.with_camera("x = " + "[" * 5000 + "]" * 5000, camera)


def test_a_camera_put_first_does_not_take_the_keys_before_the_first_header(camera):
    # Put at the very top, [camera] took the root array of tables `objects = [...]` as its own key.
    text = 'objects = [{type = "ground"}]\n\n[sun]\ndirection = [0.0, 1.0, 0.0]\nradiance = 1.0\n'
    data = sf.tomllib.loads(sf.with_camera(text, camera))
    assert data["objects"] == [{"type": "ground"}]
    assert data["camera"] == new_camera_table(camera)
    assert sf.tomllib.loads(sf.with_camera('objects = [{type = "ground"}]', camera))["objects"] == [{"type": "ground"}]


def test_an_edit_that_would_break_the_text_raises_instead(camera, monkeypatch):
    # The safety net: whatever the splicing does, broken TOML or a lost table is never returned.
    monkeypatch.setattr(sf, "_with_table", lambda text, name, table, first: text + '\nx = """\n')
    with pytest.raises(ValueError, match=r"with_camera: cannot replace the \[camera\] table .*would not be TOML"):
        sf.with_camera("[camera]\nvfov = 3.0\n", camera)
    monkeypatch.setattr(sf, "_with_table", lambda text, name, table, first: text)
    with pytest.raises(ValueError, match=r"cannot replace the \[camera\] table of this text in place"):
        sf.with_camera("[camera]\nvfov = 3.0\n", camera)


# -- relocate ------------------------------------------------------------------------------------


def test_relocate_writes_a_file_name_with_an_escaped_newline_as_toml(tmp_path):
    # "a\nb.obj" was written back with a raw newline, and relocate failed on its own text.
    text = '[[objects]]\ntype = "obj"\nfile = "a\\nb.obj"\n'
    out = sf.relocate(text, tmp_path / "x", tmp_path / "y")
    assert sf.tomllib.loads(out)["objects"][0]["file"] == "../x/a\nb.obj"
    assert sf._toml_string("\x00\x1f\x7f\t") == '"\\u0000\\u001F\\u007F\\t"'


def test_relocate_reads_past_a_multiline_string_ending_in_an_escaped_backslash(tmp_path):
    # a = """x\\""" : the scanner took \" for an escaped quote, so the rest of the file was "in the
    # string" and file = "a.obj" was refused as "cannot rewrite the file name(s)".
    text = 'a = """x\\\\"""\nfile = "a.obj"\n'
    assert sf.tomllib.loads(text) == {"a": "x\\", "file": "a.obj"}
    out = sf.relocate(text, tmp_path / "x", tmp_path / "y")
    assert sf.tomllib.loads(out) == {"a": "x\\", "file": "../x/a.obj"}


def test_relocate_leaves_a_key_that_only_ends_in_file_alone(tmp_path):
    # my-file = "z.obj" was rewritten as if it named a file (found beside this trial's cases).
    text = '[a]\nmy-file = "z.obj"\nfile = "z.obj"\n'
    out = sf.tomllib.loads(sf.relocate(text, tmp_path / "x", tmp_path / "y"))
    assert out == {"a": {"my-file": "z.obj", "file": "../x/z.obj"}}


# -- Layered EXRs --------------------------------------------------------------------------------


def test_write_layers_refuses_what_write_image_refuses(tmp_path):
    path = tmp_path / "l.exr"
    image = np.ones((4, 6, 3), np.float32)
    # Complex: the imaginary part was dropped with numpy's warning.
    with pytest.raises(ValueError, match=r"layer 'c' must hold real numbers \(got dtype complex128\)"):
        refracta.io.write_layers(path, image, {"c": np.ones((4, 6)) * (1 + 2j)})
    with pytest.raises(ValueError, match="write_layers: image must hold real numbers"):
        refracta.io.write_layers(path, image.astype(np.complex64), {})
    with pytest.raises(ValueError, match=r"layer 's' must hold real numbers \(got dtype <U1\)"):
        refracta.io.write_layers(path, image, {"s": np.full((4, 6), "1")})
    # A float64 of 1e39 was written as inf.
    with pytest.raises(ValueError, match=r"write_layers: image values must fit float32 .*got 1e\+39"):
        refracta.io.write_layers(path, np.full((4, 6, 3), 1e39), {})
    with pytest.raises(ValueError, match=r"write_layers: layer 'depth' must fit float32 .*got 1e\+39"):
        refracta.io.write_layers(path, image, {"depth": np.full((4, 6), -1e39)})
    assert not path.exists()


@pytest.mark.parametrize(
    "name, problem",
    [
        (3, "layer name must be a string"),  # was written as channel '3.Y'
        ("", "must be a non-empty name"),  # '.Y'
        ("  ", "must be a non-empty name"),
        ("a\x00b", "without control characters"),  # OpenImageIO cut it to 'a'
        (".a", "dots only between non-empty parts"),
        ("a..b", "dots only between non-empty parts"),
    ],
)
def test_write_layers_refuses_names_that_are_not_channel_names(tmp_path, name, problem):
    with pytest.raises(ValueError, match=problem):
        refracta.io.write_layers(tmp_path / "l.exr", np.ones((4, 6, 3)), {name: np.ones((4, 6))})


def test_write_layers_refuses_channel_suffixes_that_are_not_names(tmp_path):
    # ("a", "b.c") wrote 'h.b.c': a layer 'h.b' whose channel is 'c'; 3 wrote 'h.3'.
    layer = {"h": np.ones((4, 6, 2))}
    cases = (((3, "b"), "must be a string"), (("a", "b.c"), "must hold no dot"), (("", "b"), "must be a non-empty"))
    for given, problem in cases:
        with pytest.raises(ValueError, match=rf"suffixes\['h'\] {problem}"):
            refracta.io.write_layers(tmp_path / "l.exr", np.ones((4, 6, 3)), layer, {"h": given})


def test_write_layers_names_its_channels_as_before(tmp_path):
    path = tmp_path / "l.exr"
    layers = {"hidden_height": np.ones((4, 6, 2)), "diffuse.direct": np.ones((4, 6), int)}
    layers["mask"] = np.ones((4, 6), bool)
    refracta.io.write_layers(path, np.ones((4, 6, 3)), layers, suffixes={"hidden_height": ("geometric", "refracted")})
    names = refracta.io.channel_names(path)
    assert set(names) == {"R", "G", "B", "hidden_height.geometric", "hidden_height.refracted"} | {
        "diffuse.direct.Y",
        "mask.Y",
    }


@needs_fifo
def test_channel_names_refuses_folders_and_fifos_before_opening_them(tmp_path):
    # A folder: "could not find a format reader"; a FIFO: a hang.
    with pytest.raises(refracta.IoError, match="not a regular file"):
        refracta.io.channel_names(tmp_path)
    fifo = tmp_path / "pipe.exr"
    os.mkfifo(fifo)
    code = (
        f"import refracta\ntry:\n    refracta.io.channel_names({str(fifo)!r})\n"
        "except refracta.IoError as error:\n    print(error)\n"
    )
    assert "not a regular file" in returns_in_a_child(code)


# -- Orthophotos and photographs -----------------------------------------------------------------


@pytest.mark.parametrize("scale", [(-0.002, 0.002), (0.0, 0.0), (0.002, math.inf)])
def test_an_orthophoto_with_a_bad_pixel_scale_is_refused_as_an_elevation_file_is(tmp_path, scale):
    # (-0.002, 0.002) was draped mirrored and misplaced without a word; (0, 0) a ZeroDivisionError.
    dem = write_geotiff(tmp_path / "dem.tif", np.full((8, 8), 100.0, np.float32), (7.0, 46.0), (0.002, 0.002))
    ortho = write_geotiff(tmp_path / "ortho.tif", np.zeros((4, 4, 3), np.uint8), (7.0, 46.0), scale)
    frame = geo.LocalFrame(45.995, 7.005, earth_radius=math.inf)
    message = r"add_terrain: orthophoto '.*ortho\.tif': pixel scale .* must be finite and > 0"
    with pytest.raises(ValueError, match=message):
        refracta.Scene().add_terrain(dem, frame=frame, orthophoto=ortho)


def write_jpeg(path, focal_mm=None, focal_35mm=None, plane_resolution=None):
    """A 32 x 16 JPEG whose EXIF gives a focal length, its 35 mm equivalent, and a focal-plane
    resolution (pixels per cm, unit 3) for its 32 x 16 pixels."""
    exif = Image.Exif()
    sub = exif.get_ifd(0x8769)
    if focal_mm is not None:
        sub[0x920A] = IFDRational(int(focal_mm), 1)
    if focal_35mm is not None:
        sub[0xA405] = focal_35mm
    if plane_resolution is not None:
        sub[0xA20E] = sub[0xA20F] = plane_resolution
        sub[0xA210] = 3
        sub[0xA002], sub[0xA003] = 32, 16
    Image.fromarray(np.zeros((16, 32, 3), np.uint8)).save(path, exif=exif, quality=100)
    return path


@pytest.mark.parametrize(
    "resolution, sensor",
    # 32 pixels at 1e-9 pixels per cm: a 3.2e11 mm sensor, vfov 179.99999993 deg; at 1e9: 1.8e-7 deg.
    [(IFDRational(1, 10**9), "3.2e\\+11 x 1.6e\\+11 mm"), (10**9, "3.2e-07 x 1.6e-07 mm")],
)
def test_an_impossible_exif_sensor_is_read_as_none_and_said(tmp_path, resolution, sensor):
    # The module's promise: EXIF tags that say nothing usable read as absent, and vfov falls back
    # to the 35 mm equivalent (or asks for sensor_mm). Said, as a UserWarning naming the tags.
    path = write_jpeg(tmp_path / "p.jpg", focal_mm=50, focal_35mm=50, plane_resolution=resolution)
    with pytest.warns(UserWarning, match=f"EXIF sensor size {sensor} .*FocalPlaneXResolution.*ignored"):
        picture = photo.load(path)
    assert picture.exif.sensor_mm is None and picture.exif.focal_length_mm == 50.0
    expected = photo.Photo(picture.image, False, photo.Exif(focal_length_35mm=50.0)).vfov()
    assert picture.vfov() == expected and 10.0 < expected < 60.0  # a normal lens's field of view
    alone = write_jpeg(tmp_path / "q.jpg", focal_mm=50, plane_resolution=resolution)
    with pytest.warns(UserWarning, match="ignored"):
        picture = photo.load(alone)
    with pytest.raises(ValueError, match="neither the sensor size nor a 35 mm equivalent: pass sensor_mm"):
        picture.vfov()
    # A real camera's (36 x 24 mm: 32 pixels at 8.89 pixels per cm) reads with no warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        real = photo.load(write_jpeg(tmp_path / "r.jpg", focal_mm=50, plane_resolution=IFDRational(80, 9)))
    assert real.exif.sensor_mm == pytest.approx((36.0, 18.0), rel=1e-12)  # a quotient of exact rationals


@pytest.mark.parametrize(
    "fields, named",
    [
        (dict(focal_length_35mm=-50.0), "focal_length_35mm"),  # vfov() was -34 deg
        (dict(focal_length_mm=0.0, sensor_mm=(36.0, 24.0)), "focal_length_mm"),
        (dict(focal_length_mm=math.nan), "focal_length_mm"),
        (dict(focal_length_35mm=math.inf), "focal_length_35mm"),
        (dict(focal_length_35mm="50"), "focal_length_35mm"),
        (dict(sensor_mm=(36.0, -24.0)), "sensor_mm"),
        (dict(orientation=9), "orientation"),
    ],
)
def test_an_exif_with_impossible_numbers_is_refused_naming_them(fields, named):
    with pytest.raises(ValueError, match=f"Exif: {named} must be"):
        photo.Exif(**fields)


def test_an_empty_photograph_has_no_field_of_view():
    # 0 x 0 pixels: ZeroDivisionError from vfov() and camera().
    empty = photo.Photo(np.zeros((0, 0, 3), np.float32), False, photo.Exif(focal_length_35mm=50.0))
    with pytest.raises(ValueError, match=r"the photograph's image is empty \(shape \(0, 0, 3\)\)"):
        empty.vfov()
    with pytest.raises(ValueError, match="the photograph's image is empty"):
        empty.camera((0.0, 1.0, 0.0), (0.0, 1.0, -1.0))


@pytest.mark.parametrize(
    "readouts, message",
    [
        # AttributeError: 'int' object has no attribute 'item', inside overlay's own error path.
        ({"object_id": np.zeros((8, 16), dtype=object)}, r"readout 'object_id' must hold numbers.*dtype object"),
        # numpy's "cannot reshape array of size 640 into shape (8,16)".
        ({"distance": np.zeros((8, 16, 5))}, r"readout 'distance' must be \(H, W\) or \(H, W, 1\).*\(8, 16, 5\)"),
        # "could not convert string to float".
        ({"distance": np.full((8, 16), "a")}, r"readout 'distance' must hold numbers.*dtype <U1"),
        ({"object_id": np.zeros((8, 16), bool)}, r"readout 'object_id' must hold numbers.*dtype bool"),
    ],
)
def test_overlay_checks_its_readouts_up_front(readouts, message):
    image = np.full((8, 16, 3), 0.5, np.float32)
    with pytest.raises(ValueError, match=message):
        photo.overlay(image, (image, readouts))


def test_overlay_draws_from_readouts_as_render_gives_them():
    image = np.full((8, 16, 3), 0.5, np.float32)
    ids = np.full((8, 16, 1), -1, np.int32)
    ids[5:] = 0
    distance = np.where(ids >= 0, 10.0, np.inf)
    for readouts in ({"object_id": ids}, {"distance": distance}, {"object_id": ids[..., 0].astype(float)}):
        assert photo.overlay(image, (image, readouts)).skyline.tolist() == [5] * 16


def test_write_layers_takes_suffixes_as_any_sequence_of_names(tmp_path):
    # A numpy array of names was refused as "must be a sequence of channel names" (a review).
    path = tmp_path / "l.exr"
    layers = {"hidden_height": np.ones((4, 6, 2))}
    refracta.io.write_layers(path, np.ones((4, 6, 3)), layers, {"hidden_height": np.array(["geometric", "refracted"])})
    assert "hidden_height.refracted" in refracta.io.channel_names(path)
    with pytest.raises(ValueError, match="must be a sequence of channel names"):
        refracta.io.write_layers(path, np.ones((4, 6, 3)), layers, {"hidden_height": "geometric"})


def test_an_error_in_a_quoted_table_names_its_line(tmp_path):
    # ["camera"] is [camera], "vfov" is vfov: the message gave line 0 for quoted spellings.
    path = tmp_path / "quoted.toml"
    path.write_text('["camera"]\nposition = [0, 1.5, 0]\nlook_at = [0, 1.5, -10]\n"vfov" = -5\nsize = [64, 32]\n')
    with pytest.raises(ValueError, match=r"quoted.toml:4: \[camera\] vfov: .*vfov must be in"):
        refracta.load_scene(path)
