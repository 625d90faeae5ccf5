"""refracta as a user installs it: `python -m build` makes an sdist, the wheel is built from that
sdist (so the sdist is complete), installed into a fresh virtual environment (numpy and matplotlib
from PyPI, the C++ libraries the system's Debian packages) and used from outside the source tree.

The wheel is compiled once per session into build/package-test/<hash of the sdist's content>/ and
reused while the sources are unchanged (a clean C++ build takes minutes on 2 cores). The build
holds /tmp/refracta-build.lock (the lock every build in this checkout takes), unless the test runs
under `flock` on that lock already (then it is ours).

`pip install .` runs the same build_wheel hook of scikit-build-core on the source tree that this
test runs on the unpacked sdist; a user's wheel builds in a temporary folder without -Werror
(pyproject.toml's override for the "wheel" state), never in the editable install's build/<wheel_tag>;
this test builds in the unpacked sdist's own build/<wheel_tag> (see WHEEL_FROM_CACHE).
"""

import contextlib
import fcntl
import hashlib
import json
import os
import pathlib
import re
import subprocess
import sys
import tarfile
import textwrap
import zipfile

import pytest

import refracta

ROOT = pathlib.Path(__file__).resolve().parents[2]
DIST = ROOT / "build" / "package-test"
LOCK = "/tmp/refracta-build.lock"
BUILD_TIMEOUT = 3600  # [s]: a clean build is ~5 min on 2 cores; generous for a loaded machine
# The wheel compiles as the editable install did -- in build/<wheel_tag> under its source folder,
# with warnings as errors, against the installed build requirements (no isolation; the sdist step
# above still builds in an isolated environment) -- so ccache (CMakeLists.txt) serves every object
# `make install` compiled (measured: 99 of 99 hits, ~1.5 min instead of ~5 on 2 cores, the rest
# being CMake's configure and the extension's LTO link).
WHEEL_FROM_CACHE = ("--no-isolation", "-C", "build-dir=build/{wheel_tag}", "-C", "cmake.define.REFRACTA_WERROR=ON")


def run(command, **kwargs):
    out = subprocess.run([str(c) for c in command], capture_output=True, text=True, **kwargs)
    assert out.returncode == 0, f"{' '.join(map(str, command))}\n{out.stdout[-3000:]}\n{out.stderr[-6000:]}"
    return out


def lock_held_by_an_ancestor() -> bool:
    """Whether a process above this one is `flock LOCK ...` (taking the lock again would wait
    for ourselves)."""
    pid = os.getppid()
    while pid > 1:
        try:
            argv = pathlib.Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")
            stat = pathlib.Path(f"/proc/{pid}/stat").read_text()
        except OSError:
            return False
        if argv and argv[0].endswith(b"flock") and LOCK.encode() in argv:
            return True
        pid = int(stat.rsplit(")", 1)[1].split()[1])  # the parent's pid follows the state
    return False


@contextlib.contextmanager
def build_lock():
    if lock_held_by_an_ancestor():
        yield
        return
    with open(LOCK, "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # one build at a time on this machine
        yield


def content_hash(sdist: pathlib.Path) -> str:
    """Hash of the sdist's member names and contents (not its timestamps)."""
    digest = hashlib.sha256()
    with tarfile.open(sdist) as archive:
        for member in sorted(archive.getmembers(), key=lambda m: m.name):
            digest.update(member.name.encode())
            if member.isfile():
                digest.update(archive.extractfile(member).read())
    return digest.hexdigest()[:16]


@pytest.fixture(scope="session")
def dist(tmp_path_factory):
    """(sdist, wheel) of the current sources."""
    staging = tmp_path_factory.mktemp("sdist")
    run([sys.executable, "-m", "build", "--sdist", "--outdir", staging, ROOT], timeout=BUILD_TIMEOUT)
    (sdist,) = staging.glob("refracta-*.tar.gz")
    folder = DIST / content_hash(sdist)
    with build_lock():
        if not list(folder.glob("refracta-*.whl")):
            for stale in DIST.glob("*/refracta-*.whl"):  # wheels of earlier sources
                stale.unlink()
            unpacked = tmp_path_factory.mktemp("unpacked")
            with tarfile.open(sdist) as archive:
                archive.extractall(unpacked, filter="data")
            (source,) = unpacked.iterdir()
            run(
                [sys.executable, "-m", "build", "--wheel", *WHEEL_FROM_CACHE, "--outdir", folder, source],
                timeout=BUILD_TIMEOUT,
            )
    (wheel,) = folder.glob("refracta-*.whl")
    return sdist, wheel


@pytest.fixture(scope="session")
def venv(dist, tmp_path_factory):
    """A fresh virtual environment (no system site-packages) with the wheel installed."""
    folder = tmp_path_factory.mktemp("venv")
    run([sys.executable, "-m", "venv", folder])
    python = folder / "bin" / "python"
    run([python, "-m", "pip", "install", "--quiet", dist[1]], timeout=BUILD_TIMEOUT)
    return python


def test_sdist_holds_the_sources_and_no_build_products(dist):
    with tarfile.open(dist[0]) as archive:
        names = {name.split("/", 1)[1] for name in archive.getnames() if "/" in name}
    for needed in (
        "pyproject.toml",
        "CMakeLists.txt",
        "LICENSE",
        "README.md",
        "cpp/refracta/bindings/module.cpp",
        "python/refracta/__init__.py",
        "python/refracta/_core.pyi",
    ):
        assert needed in names, needed
    assert not [n for n in names if n.startswith(("build/", "out/")) or n.endswith(".so")]


def test_wheel_holds_the_extension_stubs_and_metadata_of_the_version(dist):
    with zipfile.ZipFile(dist[1]) as wheel:
        names = wheel.namelist()
        (metadata,) = [n for n in names if n.endswith(".dist-info/METADATA")]
        version = re.search(r"^Version: (.+)$", wheel.read(metadata).decode(), re.M).group(1)
        entry_points = wheel.read(metadata.replace("METADATA", "entry_points.txt")).decode()
    assert version == refracta.__version__
    assert dist[1].name.startswith(f"refracta-{refracta.__version__}-")
    assert [n for n in names if re.fullmatch(r"refracta/_core\..*\.so", n)]
    assert {"refracta/_core.pyi", "refracta/py.typed", "refracta/__init__.py"} <= set(names)
    assert "refracta = refracta.cli:main" in entry_points


@pytest.mark.slow
def test_installed_wheel_renders_a_tiny_scene_from_outside_the_source_tree(venv, tmp_path):
    code = textwrap.dedent("""
        import importlib.metadata, json, sys
        import numpy as np
        import refracta
        scene = refracta.Scene()
        scene.add_ground(0.0, 200.0)
        scene.add_box((30.0, 1.0, 0.0), (2.0, 2.0, 2.0), kd=(0.8, 0.2, 0.1))
        scene.set_sky((0.6, 0.7, 0.9))
        camera = refracta.Camera.framing(((29, 0, -1), (31, 2, 1)), direction=(1, -0.1, 0), width=24, height=16)
        field = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
        image = refracta.render(scene, camera, field, max_length=500.0, progress=False)
        print(json.dumps({"file": refracta.__file__, "version": refracta.__version__,
                          "metadata": importlib.metadata.version("refracta"), "shape": list(image.shape),
                          "finite": bool(np.isfinite(image).all()), "box": image[8, 12].tolist(),
                          "sky": image[0, 12].tolist(), "lazy": refracta.edit.__name__,
                          "matplotlib_loaded": "matplotlib" in sys.modules}))
    """)
    out = run([venv, "-c", code], cwd=tmp_path, timeout=600)
    result = json.loads(out.stdout)
    assert result["file"].startswith(str(venv.parent.parent)), result["file"]  # the venv's copy
    assert result["version"] == result["metadata"] == refracta.__version__
    assert result["shape"] == [16, 24, 3] and result["finite"]
    red, green, blue = result["box"]
    assert red > green > 0.0  # the box's kd (0.8, 0.2, 0.1) under a bluish sky
    assert result["sky"][2] > result["sky"][0] > 0.0
    assert result["lazy"] == "refracta.edit" and not result["matplotlib_loaded"]
    cli = run([venv.parent / "refracta", "--help"], cwd=tmp_path)
    assert "usage" in cli.stdout.lower()
