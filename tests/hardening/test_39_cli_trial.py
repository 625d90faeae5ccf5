"""A December 2026 trial of the command line and the scene files end to end: each test fails on
the code before the fix."""

import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
import tomllib

import refracta
from refracta import cli
from refracta.scene_file import relocate, with_atmosphere, with_camera

DATA = Path(__file__).resolve().parents[1] / "data"
SCENE = '''# top
[camera]
position = [0.0, 1.5, 0.0]
look_at = [10.0, 1.5, 0.0]
# about the air below

[atmosphere]   # mild road
surface_dt = 3.0 # K
# ---- Lighting section ----
# The sun is low.
[sun]
direction = [0.0, 1.0, 0.0]
radiance = 1.0
note = """
# not a comment
"""
'''


def test_editing_a_table_keeps_the_comments_of_the_next_one():
    out = with_atmosphere(SCENE, refracta.PhysicalAtmosphere(surface_dt=5.0))
    assert "# ---- Lighting section ----\n# The sun is low.\n[sun]" in out
    assert "# about the air below" in out and "# not a comment" in out
    assert tomllib.loads(out)["atmosphere"]["surface_dt"] == 5.0
    moved = with_camera(SCENE, refracta.Camera((0, 2, 0), (5, 2, 0), width=8, height=4))
    assert "# about the air below\n\n[atmosphere]" in moved
    assert tomllib.loads(moved)["camera"]["size"] == [8, 4]


def test_relocate_rewrites_a_quoted_file_key(tmp_path):
    # `"file" = "crate.obj"` made `refracta edit -o elsewhere/solved.toml` fail.
    text = '[[objects]]\ntype = "obj"\n"file" = "crate.obj"\n[[objects]]\ntype = "obj"\n\'file\' = "b.obj"\n'
    out = relocate(text, tmp_path / "scene", tmp_path / "solved")
    files = [entry["file"] for entry in tomllib.loads(out)["objects"]]
    assert files == ["../scene/crate.obj", "../scene/b.obj"]
    same = relocate('x = "file = \'a.obj\'"\n# file = "c.obj"\n', tmp_path / "scene", tmp_path / "solved")
    assert same == 'x = "file = \'a.obj\'"\n# file = "c.obj"\n'  # in a string and a comment: left alone


def test_unknown_keys_say_an_obj_and_list_model_and_curved_earth(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(
        '[camera]\nposition = [0, 1, 0]\nlook_at = [1, 1, 0]\n[[objects]]\ntype = "obj"\nfile = "a.obj"\nbogus = 1\n'
    )
    with pytest.raises(ValueError, match="unknown key for an obj object"):
        refracta.load_scene(path)
    path.write_text("[camera]\nposition = [0, 1, 0]\nlook_at = [1, 1, 0]\n[atmosphere]\nsurfce_dt = 1.0\n")
    with pytest.raises(ValueError, match=r"expected [^)]*\bcurved_earth\b[^)]*\bmodel\b"):
        refracta.load_scene(path)


def test_cli_threads_seed_denoise_and_version(tmp_path, capsys):
    with pytest.raises(SystemExit) as stop:
        cli.main(["--version"])
    assert stop.value.code == 0 and capsys.readouterr().out.strip() == f"refracta {refracta.__version__}"
    threads = refracta.get_threads()
    try:
        noisy, seeded, other = (tmp_path / f"{name}.exr" for name in ("noisy", "seeded", "other"))
        base = ["render", str(DATA / "hot_road.toml"), "--size", "24x9", "--spp", "2"]
        assert cli.main(["--threads", "1", *base, "-o", str(seeded), "--seed", "5"]) == 0
        assert refracta.get_threads() == 1
        assert cli.main([*base, "-o", str(other), "--seed", "6"]) == 0
        assert cli.main([*base, "-o", str(noisy), "--seed", "5", "--denoise"]) == 0
        # 0 is every core, as set_threads(0) is (the command line refused it: a trial).
        refracta.set_threads(0)
        every = refracta.get_threads()
        refracta.set_threads(1)
        assert cli.main(["--threads", "0", *base, "-o", str(tmp_path / "all.exr")]) == 0
        assert refracta.get_threads() == every
    finally:
        refracta.set_threads(threads)
    a, b, c = (refracta.io.read_image(path)[..., :3] for path in (seeded, other, noisy))
    assert not np.array_equal(a, b)  # another seed, other samples
    assert not np.array_equal(a, c)  # the same samples, denoised
    # Denoising keeps the picture: the mean within 5 % (OIDN preserves energy to ~1 % on smooth images).
    assert float(c.mean()) == pytest.approx(float(a.mean()), rel=0.05)


def test_a_low_spp_spectral_png_warns_and_an_exr_does_not(tmp_path):
    base = ["render", str(DATA / "hot_road.toml"), "--size", "16x6", "--spp", "1", "--spectral"]
    with pytest.warns(UserWarning, match="render: a spectral render at 1 spp is noisy in colour") as caught:
        assert cli.main([*base, "-o", str(tmp_path / "a.png")]) == 0
    assert "--denoise" in str(caught[0].message)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert cli.main([*base, "-o", str(tmp_path / "a.exr")]) == 0
        assert cli.main([*base, "--spp", "16", "-o", str(tmp_path / "b.png")]) == 0


def test_a_warning_reads_as_one_line_at_the_command_line(tmp_path):
    script = (
        "import warnings, refracta.cli as cli\n"
        "cli._run = lambda argv: warnings.warn('render: pass --max-length', UserWarning) or 0\n"
        "raise SystemExit(cli.main([]))\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0
    assert done.stderr == "refracta: UserWarning: render: pass --max-length\n"  # no Python file, line or source


def test_a_missing_file_a_scene_names_is_located_and_keeps_its_kind(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text(
        '[camera]\nposition = [0, 1, 0]\nlook_at = [1, 1, 0]\n\n[[objects]]\ntype = "obj"\nfile = "nothere.obj"\n'
    )
    with pytest.raises(refracta.IoError, match=r"scene.toml:7: \[\[objects\]\] #1 file: no such OBJ file"):
        refracta.load_scene(path)
    path.write_text(
        "[camera]\nposition = [0, 1, 0]\nlook_at = [1, 1, 0]\n\n" + '[environment]\ntype = "map"\nfile = "sky.exr"\n'
    )
    with pytest.raises(refracta.IoError, match=r"scene.toml:7: \[environment\] file: "):
        refracta.load_scene(path)


def test_demo_titles_fit_small_demos_and_keep_the_demo_s_own_size():
    title = "hot_spot: through the atmosphere, 60 m nearer"
    assert cli._title_points(title, 640, 9) == 9  # the committed demo images' titles unchanged
    small = cli._title_points(title, 160, 9)
    # At 100 dpi a character is ~0.6 em: the title's width in pixels at that size fits 160 px.
    assert small < 9 and len(title) * 0.6 * small * 100 / 72 <= 160 + 1e-9  # 1e-9: rounding of the product


def test_a_quoted_key_with_a_unicode_line_separator_is_one_line():
    # str.splitlines split ["x\u2028y"] in two (a review): TOML's lines end at line feeds only.
    camera = refracta.Camera((0, 1, 0), (1, 1, 0), width=8, height=4)
    out = with_camera('["x\u2028y"]\nk = 1\n[camera]\nvfov = 1\n', camera)
    assert tomllib.loads(out)["x\u2028y"] == {"k": 1} and tomllib.loads(out)["camera"]["size"] == [8, 4]


def test_cli_set_reaches_any_render_option_by_its_name(tmp_path, capsys):
    # Render options without a flag of their own (chord, tol, ...) had no way in from the command line.
    base = ["render", str(DATA / "hot_road.toml"), "--size", "16x6", "--spp", "1", "--max-length", "9e6"]
    assert cli.main([*base, "-o", str(tmp_path / "a.exr"), "--set", "chord=0.5"]) == 1
    assert "max_length 9000000 m with chord 0.5 m needs more than" in capsys.readouterr().err  # the value arrived
    assert cli.main([*base, "-o", str(tmp_path / "a.exr"), "--set", "chord=2000"]) == 0
    assert cli.main([*base[:-2], "-o", str(tmp_path / "b.exr"), "--set", "bogus=1"]) == 1
    assert "unknown option 'bogus'" in capsys.readouterr().err
    assert cli.main([*base[:-2], "-o", str(tmp_path / "b.exr"), "--set", "tol=1e-4", "--set", "tol=1e-5"]) == 1
    assert "--set tol is given twice" in capsys.readouterr().err
    with pytest.raises(SystemExit) as stop:
        cli.main([*base[:-2], "-o", str(tmp_path / "b.exr"), "--set", "chord"])
    assert stop.value.code == 2 and "must be NAME=VALUE" in capsys.readouterr().err
    assert cli._option('trace="rk45"') == ("trace", "rk45") == cli._option("trace=rk45")
    assert cli._option("pixel_bounds=[0, 0, 8, 4]") == ("pixel_bounds", [0, 0, 8, 4])


def test_a_max_length_beyond_the_scene_s_reach_is_refused_before_the_render(tmp_path, capsys):
    # A trial's --max-length 1e8 rendered for seconds, then failed: "ray origin ... beyond 1e7 m".
    road = refracta.examples.hot_road(16, 6)
    with pytest.raises(
        ValueError, match=r"render: max_length 100000000 m from a camera 1.5 m out .* at most 9999998.5 m"
    ):
        refracta.render(road.scene, road.camera, road.field, max_length=1e8, progress=False)
    args = ["render", str(DATA / "hot_road.toml"), "--size", "16x6", "--spp", "1", "-o", str(tmp_path / "a.exr")]
    assert cli.main([*args, "--max-length", "1e8"]) == 1
    err = capsys.readouterr().err
    assert "where scene coordinates end" in err and "rendering" not in err  # refused before any pixel
