"""The type stubs shipped with the package describe the compiled module as built."""

import os
import pathlib
import subprocess
import sys

import pytest

import refracta

pytest.importorskip("pybind11_stubgen")


def test_core_stubs_match_the_built_module(tmp_path):
    subprocess.run(
        [sys.executable, "-m", "pybind11_stubgen", "refracta._core", "-o", str(tmp_path)],
        check=True,
        capture_output=True,
        env={**os.environ, "REFRACTA_UNWRAPPED_CORE": "1"},  # the compiled module itself (refracta/_arguments.py)
    )
    generated = (tmp_path / "refracta" / "_core.pyi").read_text()
    shipped = (pathlib.Path(refracta.__file__).parent / "_core.pyi").read_text()
    assert generated == shipped, "python/refracta/_core.pyi is stale: run `make stubs`"
