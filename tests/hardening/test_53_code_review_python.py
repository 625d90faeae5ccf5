"""Defects found by a read-through of the Python package on 7 December: process-pool workers
exited on their first task where there is no /proc (macOS); threads building an example's texture
together raced on one temporary file; scene files were written in the locale's encoding but read
as UTF-8 (a solve under LC_ALL=C was lost to a "°C" in a comment); terrain reads in threads left
tifffile's logging silenced."""

import json
import logging
import os
import subprocess
import sys
import threading
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from multiprocessing import get_context
from pathlib import Path

import numpy as np

import refracta
from refracta import _sweep, examples, terrain
from refracta.scene_file import with_atmosphere

DATA = Path(__file__).resolve().parent.parent / "data"


def square(x):
    return x * x


def test_a_process_pool_sweep_runs_where_there_is_no_proc(monkeypatch):
    # The workers fork from here and inherit the flag: the parent-watch takes the signal-0 probe.
    monkeypatch.setattr(_sweep, "_HAS_PROC", False)
    assert _sweep._alive(os.getpid())
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()
    assert not _sweep._alive(child.pid)  # reaped: gone
    with ProcessPoolExecutor(1, mp_context=get_context("fork")) as pool:
        result = refracta.sweep(square, {"x": [1, 2, 3]}, executor=pool, progress=False)
    assert list(result) == [1, 4, 9] and not result.failures


def test_threads_build_an_example_texture_together(tmp_path, monkeypatch):
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path))  # a cold cache of its own
    colours = np.random.default_rng(1).random((4, 8, 3)).astype(np.float32)
    with ThreadPoolExecutor(4) as pool:
        paths = list(pool.map(lambda _: examples._coast_texture("race", colours), range(16)))
    assert len(set(paths)) == 1 and Path(paths[0]).exists()
    assert sorted(p.name for p in (tmp_path / "refracta_examples").iterdir()) == [Path(paths[0]).name]  # no leftovers


def test_a_solved_scene_file_is_written_in_utf8_whatever_the_locale(tmp_path):
    scene, camera, truth = refracta.load_scene(DATA / "hot_road.toml")
    entries = []
    for v in (16.5, 16.9, 17.2):  # the mirage band, as tests/edit/test_05_files_and_plots.py
        origin, direction = camera.ray(48.0, v)
        path = refracta.trace_ray(truth, origin, direction, tol=1e-10, max_length=400.0, stop_height=0.0)
        entries.append({"destination": [48.0, v], "source": list(path.point_at(350.0)[0])})
    pairs = tmp_path / "pairs.json"
    pairs.write_text(json.dumps({"pairs": entries, "free": ["surface_dt"], "stop_height": 0.0}))
    text = "# the road at 35 °C\n" + with_atmosphere(
        (DATA / "hot_road.toml").read_text(encoding="utf-8"), truth.with_params(surface_dt=6.0)
    )
    for name in ("tent.obj", "tent.mtl"):  # the scene's objects, beside it
        (tmp_path / name).write_bytes((DATA / name).read_bytes())
    start = tmp_path / "start.toml"
    start.write_text(text, encoding="utf-8")
    out = tmp_path / "solved.toml"
    env = dict(os.environ, LC_ALL="C", LANG="C", PYTHONUTF8="0", PYTHONCOERCECLOCALE="0")
    code = "import sys; from refracta import cli; sys.exit(cli.main(sys.argv[1:]))"
    done = subprocess.run(
        [sys.executable, "-c", code, "edit", str(start), "--pairs", str(pairs), "-o", str(out)],
        capture_output=True,
        text=True,
        encoding="utf-8",
        errors="replace",
        env=env,
        timeout=300,
    )
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    assert "# the road at 35 °C" in out.read_text(encoding="utf-8")


def test_terrain_reads_in_threads_leave_tifffile_logging_as_it_was():
    logger = logging.getLogger("tifffile")
    before = logger.level
    gate = threading.Barrier(4)

    def read(_):
        gate.wait()
        with terrain._quiet_tifffile():
            gate.wait()  # all four inside together
        return logger.level

    for _ in range(5):
        with ThreadPoolExecutor(4) as pool:
            list(pool.map(read, range(4)))
        assert logger.level == before
    with terrain._quiet_tifffile():
        assert logger.level > logging.CRITICAL
    assert logger.level == before
