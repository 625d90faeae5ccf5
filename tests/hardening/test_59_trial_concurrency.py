"""What a service developer's trial (threads, callbacks, leaks, pickling) found: messages quoting
a file's bytes that are not UTF-8 lost their exception; file names that are not UTF-8, and bytes
paths, were refused or misread."""

import os

import numpy as np
import pytest

import refracta


def test_a_damaged_png_whose_chunk_name_is_not_utf8_raises_ioerror(tmp_path):
    # The diagnostic quotes the chunk's name as the file stores it (bytes 0xdd...): pybind11 decoded
    # it as UTF-8 and raised UnicodeDecodeError in place of the IoError naming the file.
    bad = tmp_path / "bad.png"
    bad.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00\x00\x0dIHDR" + bytes(range(200, 256)) * 4)
    with pytest.raises(refracta.IoError, match=r"bad\.png.*\\xdd\\xde\\xdf\\xe0 chunk"):
        refracta.io.read_image(str(bad))


def test_a_latin1_material_library_name_is_escaped_in_its_message(tmp_path):
    obj = tmp_path / "m.obj"
    obj.write_bytes(b"mtllib caf\xe9.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(refracta.MissingFileError, match=r"caf\\xe9\.mtl"):
        refracta.Scene().add_obj(str(obj))


def test_image_files_whose_names_are_not_utf8_are_written_and_read(tmp_path):
    # os.fsdecode keeps such a name's bytes as surrogates; a std::string parameter refused it with
    # pybind11's bare "incompatible function arguments".
    path = tmp_path / os.fsdecode(b"n\xe9.exr")
    image = np.arange(12, dtype=np.float32).reshape(2, 2, 3)
    refracta.io.write_image(path, image)
    np.testing.assert_array_equal(refracta.io.read_image(path), image)


def test_set_environment_takes_a_bytes_path_as_a_path(tmp_path):
    # It was read as an array ("radiance must hold real numbers (got dtype |S36)").
    path = tmp_path / "sky.exr"
    refracta.io.write_image(path, np.full((8, 16, 3), 0.5, np.float32))
    by_name, by_bytes = refracta.Scene(), refracta.Scene()
    by_name.set_environment(str(path))
    by_bytes.set_environment(os.fsencode(str(path)))
    assert repr(by_bytes.lights) == repr(by_name.lights)
