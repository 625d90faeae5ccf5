"""Loaders refuse what they cannot read instead of spinning, blocking or reading 0 (issue 13):
read_image on a FIFO or /dev/zero spun in OIIO's readers, add_obj on a FIFO blocked, and
tinyobjloader read `v nan 0 0` and `Kd abc` as 0."""

import os

import numpy as np
import pytest

import refracta


@pytest.fixture
def fifo(tmp_path):
    path = tmp_path / "pipe"
    os.mkfifo(path)
    return path


def test_read_image_refuses_fifos_and_devices(fifo):
    for path in (fifo, "/dev/zero"):
        with pytest.raises(refracta.IoError, match="not a regular file"):
            refracta.io.read_image(path)


def test_add_obj_refuses_a_fifo(fifo, tmp_path):
    with pytest.raises(refracta.IoError, match="not a regular file"):
        refracta.Scene().add_obj(str(fifo))
    # An MTL library that is a FIFO blocked tinyobjloader too.
    os.mkfifo(tmp_path / "lib.mtl")
    (tmp_path / "a.obj").write_text("mtllib lib.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(refracta.IoError, match="MTL .* not a regular file"):
        refracta.Scene().add_obj(str(tmp_path / "a.obj"))


@pytest.mark.parametrize(
    "line, token",
    [("v nan 0 0", "nan"), ("v 1e999 0 0", "1e999"), ("v 0 0x 0", "0x"), ("vn 0 abc 1", "abc"), ("vt 0.5 --1", "--1")],
)
def test_unparsable_obj_numbers_name_file_line_and_token(tmp_path, line, token):
    path = tmp_path / "bad.obj"
    path.write_text(f"# triangle\nv 0 0 0\n{line}\nv 1 0 0\nv 0 1 0\nf 1 3 4\n")
    with pytest.raises(refracta.IoError, match=rf"bad.obj' line 3: .* '{token}', which is not a finite number"):
        refracta.Scene().add_obj(str(path))


def test_unparsable_mtl_numbers_name_file_line_and_token(tmp_path):
    (tmp_path / "m.mtl").write_text("newmtl a\nKd abc 1 1\n")
    (tmp_path / "m.obj").write_text("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n")
    with pytest.raises(refracta.IoError, match=r"MTL .*m.mtl' line 2: 'Kd' has 'abc'"):
        refracta.Scene().add_obj(str(tmp_path / "m.obj"))


def test_legal_mtl_forms_still_load(tmp_path):
    # Comments, "d -halo", "Kd xyz", "Kd spectral" are MTL syntax, not bad numbers.
    (tmp_path / "m.mtl").write_text(
        "newmtl a\nKd 0.8 0.1 0.1\nd -halo 1.0\nKs xyz 0.1 0.1 0.1\nKa spectral ident.rfl 1.0\nNs 10\nillum 2\n"
    )
    (tmp_path / "m.obj").write_text("mtllib m.mtl\nv 0 0 0\nv 1 0 0 # x\nv 0 1 0\nusemtl a\nf 1 2 3\n")
    scene = refracta.Scene()
    (geometry,) = scene.add_obj(str(tmp_path / "m.obj"))
    # Default rtol 1e-7: the MTL's Kd parsed to double, rounding only.
    np.testing.assert_allclose(scene.material(geometry).parameters["kd"], [0.8, 0.1, 0.1])


def test_an_image_header_claiming_more_than_memory_is_refused_before_allocating(tmp_path):
    # A PFM header of 10^6 x 10^6 pixels (12 TB of float RGB) and no data.
    path = tmp_path / "huge.pfm"
    path.write_bytes(b"PF\n1000000 1000000\n-1.0\n" + bytes(12))
    with pytest.raises(refracta.IoError, match=r"needs at least 12000000000000 bytes"):
        refracta.io.read_image(path)


def test_elevation_files_refuse_fifos_and_name_missing_files_as_every_loader_does(tmp_path):
    # Found trying the README's terrain as a new user: a FIFO named like a GeoTIFF blocked
    # add_terrain forever (tifffile waited for a writer), a folder named like an SRTM tile was
    # "not SRTM elevation data: 4096 bytes", and a missing tile raised a bare FileNotFoundError
    # where every other loader raises refracta.IoError (README, "Errors").
    from refracta import geo

    frame = geo.LocalFrame(46.0, 7.0)
    os.mkfifo(tmp_path / "N46E007.hgt")
    os.mkfifo(tmp_path / "relief.tif")
    (tmp_path / "folder").mkdir()
    (tmp_path / "folder" / "N45E007.hgt").mkdir()
    for path in (tmp_path / "N46E007.hgt", tmp_path / "relief.tif", tmp_path / "folder" / "N45E007.hgt"):
        with pytest.raises(refracta.IoError, match="not a regular file"):
            refracta.Scene().add_terrain(path, frame=frame)
    with pytest.raises(refracta.IoError, match="no such elevation file") as error:
        refracta.terrain.read_elevation(tmp_path / "N44E007.hgt")
    assert isinstance(error.value, FileNotFoundError)  # the built-in a user would catch, kept
