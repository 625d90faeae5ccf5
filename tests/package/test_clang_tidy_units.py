"""The unit splitting of .ci/clang_tidy.py (make lint's clang-tidy), on clang-tidy output given here.

Each layer's .cpp files are checked as one TU; when that TU does not compile (two files' helpers
of one name), the layer must be split and checked again, and a single file's compile error must be
reported as a finding, so that no file goes unchecked and no error is lost.
"""

import importlib.util
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]


def load_script():
    spec = importlib.util.spec_from_file_location("clang_tidy", ROOT / ".ci" / "clang_tidy.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def runner(files):
    script = load_script()
    return script, script.Runner({f: ["g++", "-c", str(f)] for f in files}, jobs=1)


FILES = [pathlib.Path(f"/src/cpp/refracta/render/{name}.cpp") for name in "abcdef"]


def test_a_clash_splits_the_unit_before_the_file_with_the_error():
    script, run = runner(FILES)
    text = f"{FILES[3]}:20:8: error: redefinition of 'sqr' [clang-diagnostic-error]\n"
    assert run.result(FILES, "render", text) == [(FILES[:3], "render.a"), (FILES[3:], "render.b")]
    assert not run.findings
    assert run.splits == [f"render: {text.strip()}"]


def test_an_error_elsewhere_halves_the_unit():
    script, run = runner(FILES)
    for where in ("/src/cpp/refracta/render/caster.h", str(FILES[0])):
        text = f"{where}:3:1: error: unknown type name 'Foo' [clang-diagnostic-error]\n"
        assert run.result(FILES, "render", text) == [(FILES[:3], "render.a"), (FILES[3:], "render.b")]


def test_a_single_files_error_and_findings_are_reported():
    script, run = runner(FILES)
    error = f"{FILES[2]}:3:1: error: unknown type name 'Foo' [clang-diagnostic-error]"
    finding = f"{FILES[4]}:17:10: error: 'v' used after it was moved [bugprone-use-after-move,-warnings-as-errors]"
    noise = "clang-tidy -p build/clang-tidy ...\n2 warnings generated."
    assert run.result(FILES[2:3], "render.a.b", f"{error}\n{noise}") == []
    assert run.result(FILES[3:], "render.b", f"{noise}\n{finding}\n") == []
    assert run.findings == {error, finding}
