"""The command line reports user errors in one line on stderr, without a traceback, and exits
non-zero (issue 13: every user error printed a traceback)."""

import subprocess
import sys
from pathlib import Path

import pytest

DATA = Path(__file__).resolve().parents[1] / "data"


def refracta_cli(*args, cwd):
    return subprocess.run(
        [sys.executable, "-m", "refracta", *args], capture_output=True, text=True, cwd=cwd, timeout=120
    )


@pytest.mark.parametrize(
    "args, message, code",
    [
        (["render", "missing.toml"], "refracta: error: no such scene file: 'missing.toml'", 1),
        (
            ["render", str(DATA / "hot_road.toml"), "--spp", "0"],
            "refracta render: error: argument --spp: must be >= 1",
            2,
        ),
        (["render", str(DATA / "hot_road.toml"), "--size", "0x4"], "refracta render: error: argument --size", 2),
        (["render", "bad.toml"], "refracta: error: ", 1),
        (["edit", str(DATA / "hot_road.toml"), "--pairs", "nopairs.json", "-o", "x.toml"], "refracta: error: ", 1),
        ([], "refracta: error: the following arguments are required: command", 2),
    ],
)
def test_user_errors_print_one_line_and_exit_non_zero(tmp_path, args, message, code):
    (tmp_path / "bad.toml").write_text("[camera]\nposition = [0, 1, 0]\nlook_at = [1, 1, 0]\nvfovv = 3\n")
    result = refracta_cli(*args, cwd=tmp_path)
    assert result.returncode == code
    assert "Traceback" not in result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith(message), result.stderr


@pytest.mark.parametrize(
    "option, message",
    [
        (["--white-balance", "Daylight"], "white_balance must be 'auto', 'none', 'daylight'"),
        (["--white-balance", "500"], "white_balance must be a colour temperature in [1000, 40000] K"),
        (["--key", "nan"], "key must be > 0 and finite"),
    ],
)
def test_a_bad_display_option_is_refused_before_rendering(tmp_path, option, message):
    # Found as a new user: `refracta render scene.toml -o x.png --white-balance Daylight` rendered
    # the whole scene (its progress bar on stderr), then refused the white balance and wrote nothing:
    # minutes lost on a large render. The display settings are checked before the render starts.
    result = refracta_cli(
        "render", str(DATA / "hot_road.toml"), "-o", "x.png", "--size", "32x12", *option, cwd=tmp_path
    )
    assert result.returncode == 1
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("refracta: error: "), result.stderr  # no progress bar
    assert message in lines[0]
    assert not (tmp_path / "x.png").exists()
