"""Fourth new-user trial (real places and the command line): each test failed before its fix.

(The orthophoto mirrored north-south is tests/scene/test_terrain.py's draping test.)
"""

import os

import pytest

from refracta import cli

SCENE = "[camera]\nposition = [0, 1.5, 0]\nlook_at = [100, 1, 0]\nvfov = 10\nsize = [16, 8]\n"


@pytest.fixture
def scene_file(tmp_path):
    path = tmp_path / "s.toml"
    path.write_text(SCENE)
    return path


def run(capsys, *argv):
    status = cli.main([str(a) for a in argv])
    return status, capsys.readouterr().err


def test_a_fifo_output_is_refused_before_the_render(tmp_path, scene_file, capsys):
    # Writing a FIFO waits for a reader that may never come: render finished, then hung.
    fifo = tmp_path / "fifo.jpg"
    os.mkfifo(fifo)
    status, err = run(capsys, "render", scene_file, "-o", fifo)
    assert status == 1 and "is not a regular file" in err


def test_render_refuses_a_scene_file_or_video_output_before_rendering(tmp_path, scene_file, capsys):
    # .toml and .mp4 were exempt from the format check for every command: the render ran, then
    # the write failed.
    for name in ("out.toml", "out.mp4"):
        status, err = run(capsys, "render", scene_file, "-o", tmp_path / name)
        assert status == 1 and "could not find a format writer" in err
        assert not (tmp_path / name).exists()


def test_edit_writes_only_a_scene_file(tmp_path, scene_file, capsys):
    # It wrote the solved scene's TOML text into solved.exr.
    pairs = tmp_path / "pairs.toml"
    pairs.write_text("pairs = []\n")
    status, err = run(capsys, "edit", scene_file, "--pairs", pairs, "-o", tmp_path / "solved.exr")
    assert status == 1 and "must be a scene file (.toml)" in err
    assert not (tmp_path / "solved.exr").exists()


def test_an_empty_readout_list_is_refused(tmp_path, scene_file, capsys):
    # --aovs ',,' rendered no readouts and exited 0.
    with pytest.raises(SystemExit):
        cli.main(["render", str(scene_file), "-o", str(tmp_path / "o.exr"), "--aovs", ",,"])
    assert "names no readout" in capsys.readouterr().err


def test_a_size_beyond_an_int_is_named_not_a_traceback(tmp_path, capsys):
    # 1e20 pixels reached Camera's int and escaped main as pybind11's TypeError.
    path = tmp_path / "big.toml"
    path.write_text(SCENE.replace("size = [16, 8]", "size = [99999999999999999999, 8]"))
    status, err = run(capsys, "render", path, "-o", tmp_path / "big.png")
    assert status == 1 and "[camera] size: must be two whole numbers of pixels in [1, 2147483647]" in err
