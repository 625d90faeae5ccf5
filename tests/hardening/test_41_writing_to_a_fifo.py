"""Writing an image, its layers or an animation to a FIFO waited forever for a reader (found in
the December 2026 bad-input trial): writers now refuse a path that exists and is not a regular
file, as the readers do, before opening it."""

import os

import numpy as np
import pytest

import refracta
from refracta import io


@pytest.fixture
def fifo(tmp_path):
    def make(name):
        path = tmp_path / name
        os.mkfifo(path)
        return str(path)

    return make


def test_image_writers_refuse_a_fifo(fifo):
    image = np.ones((4, 4, 3), np.float32)
    for path in (fifo("a.png"), fifo("a.exr")):
        with pytest.raises(refracta.IoError, match="not a regular file"):
            io.write_image(path, image)
    with pytest.raises(refracta.IoError, match="not a regular file"):
        io.write_layers(fifo("layers.exr"), image, {"distance": np.ones((4, 4), np.float32)})


def test_an_animation_refuses_a_fifo(fifo):
    frames = np.ones((3, 4, 4, 3), np.float32)
    with pytest.raises(refracta.IoError, match="not a regular file"):
        io.write_animation(fifo("a.gif"), frames, fps=10)


def test_a_regular_file_is_still_overwritten(tmp_path):
    path = tmp_path / "a.png"
    path.write_bytes(b"old")
    io.write_image(str(path), np.ones((4, 4, 3), np.float32))
    assert io.read_image(str(path)).shape == (4, 4, 3)
