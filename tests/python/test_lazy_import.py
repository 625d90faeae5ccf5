"""`import refracta` is cheap and every submodule is reachable from it (PEP 562 __getattr__)."""

import json
import subprocess
import sys

SUBMODULES = [
    "cli",
    "compare",
    "edit",
    "examples",
    "geo",
    "io",
    "lights",
    "moments",
    "oit",
    "plot",
    "raster",
    "scene_file",
    "shading",
    "spectrum",
    "testing",
]


def run_python(code: str) -> dict:
    """Runs `code` in a fresh interpreter (nothing imported yet) and returns the JSON it prints."""
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def test_import_refracta_does_not_import_matplotlib_pyproj_or_the_heavy_submodules():
    result = run_python(
        "import json, sys, refracta\n"
        "print(json.dumps(sorted(m for m in sys.modules if m in ('matplotlib', 'pyproj') or m.startswith(("
        "'matplotlib.', 'pyproj.', 'refracta.edit', 'refracta.plot', 'refracta.compare', 'refracta.examples', "
        "'refracta.cli', 'refracta.geo')))))"
    )
    assert result == []


def test_every_submodule_is_an_attribute_after_import_refracta():
    result = run_python(
        "import json, types, refracta\n"
        f"names = {SUBMODULES!r}\n"
        "listed = set(dir(refracta))\n"
        "print(json.dumps({n: [isinstance(getattr(refracta, n), types.ModuleType),"
        " getattr(refracta, n).__name__, n in listed] for n in names}))"
    )
    for name in SUBMODULES:
        assert result[name] == [True, f"refracta.{name}", True], name


def test_unknown_attribute_raises_attribute_error():
    result = run_python(
        "import json, refracta\n"
        "try:\n"
        "    refracta.no_such_module\n"
        "    print(json.dumps('no error'))\n"
        "except AttributeError as error:\n"
        "    print(json.dumps(str(error)))"
    )
    assert "no_such_module" in result
