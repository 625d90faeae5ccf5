"""The API reference and the tutorials build with Sphinx without a single warning (as `make docs`,
with -W: a docstring docutils cannot parse fails the suite)."""

import pathlib
import subprocess
import sys

import pytest

DOCS = pathlib.Path(__file__).resolve().parents[2] / "python" / "docs"


@pytest.mark.slow
def test_sphinx_builds_the_docs_without_warnings(tmp_path):
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "sphinx",
            "-E",
            "-W",
            "--keep-going",
            "-q",
            "-b",
            "html",
            str(DOCS),
            str(tmp_path / "html"),
        ],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0, out.stderr
    index = (tmp_path / "html" / "index.html").read_text()
    assert "refracta" in index
    # The reference is built from the docstrings: the Scene and Camera APIs appear with theirs.
    scenes = (tmp_path / "html" / "api" / "scenes_and_rendering.html").read_text()
    assert "add_obj" in scenes and "texture_dirs" in scenes and "framing" in scenes
    edit = (tmp_path / "html" / "api" / "editing.html").read_text()
    assert "Solve for the parameters" in edit
    for notebook in ("01_rays_through_hot_air", "02_edit_a_mirage", "03_moment_shadows_and_oit"):
        assert (tmp_path / "html" / "notebooks" / f"{notebook}.html").exists(), notebook
