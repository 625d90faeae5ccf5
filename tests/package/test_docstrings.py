"""The bindings' docstrings written once, in the C++ headers' comments: cpp/generated/docstrings.h
is what `make docstrings` (.ci/docstrings.py, pybind11_mkdoc) makes of them, and the module shows
them."""

import importlib.util
import pathlib

import pytest

import refracta.lights

pytest.importorskip("pybind11_mkdoc")

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.mark.slow  # libclang parses the listed headers (Eigen included): 1.5-6 s with the machine's load
def test_generated_docstrings_are_up_to_date():
    spec = importlib.util.spec_from_file_location("docstrings", ROOT / ".ci" / "docstrings.py")
    assert spec is not None and spec.loader is not None
    docstrings = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(docstrings)
    shipped = (ROOT / "cpp" / "generated" / "docstrings.h").read_text()
    assert docstrings.generate() == shipped, "cpp/generated/docstrings.h is stale: run `make docstrings`"


def test_a_class_shows_its_header_comment():
    header = (ROOT / "cpp" / "refracta" / "shading" / "sun_light.h").read_text()
    assert "// The sun: a disc at infinity toward direction, mean radiance" in header
    assert refracta.lights.SunLight.__doc__.startswith("The sun: a disc at infinity toward direction, mean radiance")
