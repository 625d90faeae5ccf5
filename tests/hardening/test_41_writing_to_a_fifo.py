"""Writing an image, its layers or an animation to a FIFO waited forever for a reader (found in
the December 2026 bad-input trial): writers now refuse a path that exists and is not a regular
file, as the readers do, before opening it. The writes run in a subprocess with a timeout, so a
regression fails instead of hanging the suite."""

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import refracta
from refracta import io

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs (POSIX)")

WRITES = textwrap.dedent(
    """
    import os, sys
    import numpy as np
    import refracta
    from refracta import io

    folder = sys.argv[1]
    image = np.ones((4, 4, 3), np.float32)
    writes = {
        "a.png": lambda path: io.write_image(path, image),
        "a.exr": lambda path: io.write_image(path, image),
        "layers.exr": lambda path: io.write_layers(path, image, {"distance": np.ones((4, 4), np.float32)}),
        "a.gif": lambda path: io.write_animation(path, np.ones((3, 4, 4, 3), np.float32), fps=10),
    }
    for name, write in writes.items():
        path = os.path.join(folder, name)
        os.mkfifo(path)
        try:
            write(path)
            print(name, "written")
        except refracta.IoError as error:
            print(name, error)
    """
)


def test_writers_refuse_a_fifo(tmp_path):
    done = subprocess.run([sys.executable, "-c", WRITES, str(tmp_path)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    lines = done.stdout.splitlines()
    assert len(lines) == 4
    assert all("not a regular file" in line for line in lines), lines


def test_a_name_the_system_refuses_is_an_io_error(tmp_path):
    # std::filesystem's own error (here ENAMETOOLONG) surfaced as a RuntimeError.
    with pytest.raises(refracta.IoError, match="cannot write .*File name too long"):
        io.write_image(str(tmp_path / ("a" * 300 + ".png")), np.ones((4, 4, 3), np.float32))


def test_a_regular_file_is_still_overwritten(tmp_path):
    path = tmp_path / "a.png"
    path.write_bytes(b"old")
    io.write_image(str(path), np.ones((4, 4, 3), np.float32))
    assert io.read_image(str(path)).shape == (4, 4, 3)
