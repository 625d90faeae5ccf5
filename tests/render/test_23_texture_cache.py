"""Issue 23 item 12: the texture cache (scene/textures.cpp). Prepared files are written under a
name of their own process and renamed, so two sessions preparing the same texture at once both
get it right (they shared one partial name: "... is not an OpenEXR file"); a TMPDIR naming a
missing folder falls back to /tmp (it was "filesystem error: temp_directory_path");
REFRACTA_TEXTURE_CACHE chooses the folder; add_obj reports its textures' progress."""

import json
import os
import subprocess
import sys
import time

import numpy as np
import pytest

import refracta

# The texture filtered over one pixel straight below a camera looking down is the texel's own
# value up to the half-float storage of the prepared file (11-bit mantissa: 2^-11 relative).
TEXEL_RTOL = 1e-3

# A process rendering a textured ground: prints the image's mean colour as JSON. Both copies wait
# for the same start time so that they prepare the texture at once.
CHILD = r"""
import json, sys, time
import numpy as np
import refracta
path, start = sys.argv[1], float(sys.argv[2])
time.sleep(max(0.0, start - time.time()))
scene = refracta.Scene()
scene.set_sky((1.0, 1.0, 1.0), (1.0, 1.0, 1.0))
scene.add_ground(0.0, 100.0, kd=(1.0, 1.0, 1.0), texture=path, texture_size=1e-3)
camera = refracta.Camera((0.0, 1.0, 0.0), (0.0, 0.0, 0.001), (1, 0, 0), 1.0, 4, 4)
image = refracta.render(scene, camera, None, method="straight", progress=False)
print(json.dumps(image.reshape(-1, 3).mean(axis=0).tolist()))
"""


def large_texture(path, rng, size=1024):
    """A texture whose preparing takes ~1.5 s (measured: 0.4 s per 512 x 512), so the two
    processes started together overlap throughout. Its mean is what CHILD's ground shows: a
    repeat every millimetre, several per pixel, filtered to the coarse MIP levels."""
    image = rng.uniform(0.2, 0.8, (size, size, 3)).astype(np.float32)
    refracta.io.write_image(path, image)
    return image


def uniform_texture(path, texel=(0.25, 0.5, 0.75)):
    refracta.io.write_image(path, np.tile(np.asarray(texel, np.float32), (8, 8, 1)))
    return str(path)


def textured_render(path):
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0), (1.0, 1.0, 1.0))
    scene.add_ground(0.0, 100.0, kd=(1.0, 1.0, 1.0), texture=str(path), texture_size=10.0)
    camera = refracta.Camera((0.0, 1.0, 0.0), (0.0, 0.0, 0.001), (1, 0, 0), 1.0, 4, 4)
    return refracta.render(scene, camera, None, method="straight", progress=False)


@pytest.mark.slow
def test_two_processes_preparing_the_same_texture_both_succeed(tmp_path, rng):
    texture = tmp_path / "big.exr"
    image = large_texture(texture, rng)
    cache = tmp_path / "cache"
    env = dict(os.environ, REFRACTA_TEXTURE_CACHE=str(cache))
    start = time.time() + 3.0  # both are importing refracta by then
    children = [
        subprocess.Popen(
            [sys.executable, "-c", CHILD, str(texture), str(start)],
            env=env,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
        )
        for _ in range(2)
    ]
    outputs = [child.communicate(timeout=300) for child in children]
    for child, (out, err) in zip(children, outputs):
        assert child.returncode == 0, err
        # The far ground's colour: the texture's mean (its coarsest MIP level).
        np.testing.assert_allclose(json.loads(out), image.reshape(-1, 3).mean(axis=0), rtol=TEXEL_RTOL)
    assert [p.name for p in cache.iterdir() if p.suffix == ".exr" and ".part" not in p.name]
    assert not list(cache.glob("*.part.exr"))  # no partial file left behind


def test_a_missing_tmpdir_falls_back(tmp_path, monkeypatch):
    """TMPDIR names a folder that does not exist: renders use /tmp/refracta-textures."""
    monkeypatch.delenv("REFRACTA_TEXTURE_CACHE", raising=False)
    monkeypatch.setenv("TMPDIR", str(tmp_path / "missing"))
    path = uniform_texture(tmp_path / f"albedo-{time.time_ns()}.exr")  # a new file: prepared now
    image = textured_render(path)
    np.testing.assert_allclose(image[0, 0], (0.25, 0.5, 0.75), rtol=TEXEL_RTOL)
    assert not (tmp_path / "missing").exists()


def test_refracta_texture_cache_chooses_the_folder(tmp_path, monkeypatch):
    cache = tmp_path / "made" / "on" / "demand"
    monkeypatch.setenv("REFRACTA_TEXTURE_CACHE", str(cache))
    image = textured_render(uniform_texture(tmp_path / "albedo.exr"))
    np.testing.assert_allclose(image[0, 0], (0.25, 0.5, 0.75), rtol=TEXEL_RTOL)
    assert len(list(cache.glob("*.exr"))) == 1


def test_an_unusable_cache_folder_is_named(tmp_path, monkeypatch):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("REFRACTA_TEXTURE_CACHE", str(blocker))
    with pytest.raises(refracta.IoError, match="REFRACTA_TEXTURE_CACHE=.*cannot be made or written"):
        textured_render(uniform_texture(tmp_path / "albedo.exr"))


def write_model(folder, textures):
    """An OBJ of `textures` quads, each with its own map_Kd (one texture shared by two quads)."""
    mtl, obj = [], ["mtllib model.mtl"]
    for i in range(textures):
        uniform_texture(folder / f"t{i}.exr", (0.1 * (i + 1), 0.5, 0.5))
        mtl += [f"newmtl m{i}", "Kd 1 1 1", f"map_Kd t{i}.exr"]
    mtl += ["newmtl again", "Kd 1 1 1", "map_Kd t0.exr"]
    for i, name in enumerate([f"m{i}" for i in range(textures)] + ["again"]):
        obj += [
            f"v {i} 0 0",
            f"v {i} 0 1",
            f"v {i} 1 1",
            "vt 0 0",
            "vt 1 0",
            "vt 1 1",
            f"usemtl {name}",
            f"f {3 * i + 1}/{3 * i + 1} {3 * i + 2}/{3 * i + 2} {3 * i + 3}/{3 * i + 3}",
        ]
    (folder / "model.mtl").write_text("\n".join(mtl) + "\n")
    (folder / "model.obj").write_text("\n".join(obj) + "\n")
    return folder / "model.obj"


def test_add_obj_reports_its_textures_progress(tmp_path, capsys):
    """A callable gets (done, total) distinct texture files; the default bar stays quiet for a
    model prepared in well under a second."""
    model = write_model(tmp_path, 3)
    calls = []
    refracta.Scene().add_obj(str(model), progress=lambda done, total: calls.append((done, total)))
    assert calls == [(1, 3), (2, 3), (3, 3)]
    refracta.Scene().add_obj(str(model))
    assert capsys.readouterr().err == ""
    with pytest.raises(ValueError, match="progress must be"):
        refracta.Scene().add_obj(str(model), progress="yes")


def test_the_default_bar_waits_a_quiet_second_then_draws(tmp_path, monkeypatch):
    """add_obj's default progress is the 'preparing textures' bar with a quiet second: a model whose
    textures are prepared sooner leaves no trace, a longer one draws it to n/n (timing-free: the
    bar is recorded, and its quiet period is checked on its own below)."""
    from refracta import _progress

    made = []

    class Recording(_progress.ProgressBar):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            self.calls = []
            made.append(self)

        def __call__(self, done, total):
            self.calls.append((done, total))
            super().__call__(done, total)

    monkeypatch.setattr(_progress, "ProgressBar", Recording)
    refracta.Scene().add_obj(str(write_model(tmp_path, 3)))
    assert [(bar.label, bar.quiet_seconds) for bar in made] == [("preparing textures", 1.0)]
    assert made[0].calls == [(1, 3), (2, 3), (3, 3)]


def test_a_progress_bar_is_silent_within_its_quiet_period_and_draws_after():
    import io

    from refracta._progress import ProgressBar

    quiet, loud = io.StringIO(), io.StringIO()
    silent = ProgressBar("preparing textures", stream=quiet, quiet_seconds=1e9)
    drawing = ProgressBar("preparing textures", stream=loud, quiet_seconds=0.0)
    for done in (1, 2, 3):
        silent(done, 3)
        drawing(done, 3)
    assert quiet.getvalue() == ""
    assert "preparing textures" in loud.getvalue() and "100%" in loud.getvalue() and loud.getvalue().endswith("\n")
