"""A trial of refracta in a long-running service: native memory and file handles released with
the Scene that held them, trace_rays refusing a batch larger than memory before any work, and the
refusal of a scene changed from its own render's progress callback said as it is."""

import ctypes
import os

import numpy as np
import pytest

import refracta
from refracta import io

mallinfo2 = getattr(ctypes.CDLL("libc.so.6"), "mallinfo2", None)  # glibc >= 2.33 (Debian 12: 2.36)


class MallInfo2(ctypes.Structure):
    _fields_ = [
        (name, ctypes.c_size_t)
        for name in ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks", "fsmblks", "uordblks", "fordblks")
        + ("keepcost",)
    ]


def malloc_in_use():
    mallinfo2.restype = MallInfo2
    return mallinfo2().uordblks


@pytest.mark.skipif(mallinfo2 is None, reason="needs glibc's mallinfo2")
def test_a_scene_returns_its_native_memory():
    # Each Scene kept its texture system's private image cache: 24.7 kB of malloc in use for ever.
    # Now a Scene makes one with its first texture (OIIO 2.4 cannot free a private cache safely:
    # textures.cpp), and these, without textures, keep nothing.
    for _ in range(200):  # the allocator's own first arenas and Python's caches, before counting
        refracta.Scene()
    before = malloc_in_use()
    for _ in range(2000):
        refracta.Scene()
    # Python's objects live in its own arenas, not malloc's: what is left is noise of a few bytes
    # per Scene (0.0 kB measured), against the 24.7 kB of the leak.
    assert (malloc_in_use() - before) / 2000 < 2000


def test_a_textured_scene_closes_its_files(tmp_path):
    texture = tmp_path / "texture.png"
    io.write_image(str(texture), np.random.default_rng(1).random((32, 32, 3)).astype(np.float32))
    camera = refracta.Camera((0.3, 0.3, 3.0), (0.3, 0.3, 0.0), vfov=30.0, width=8, height=8)

    def render_once():
        scene = refracta.Scene()
        triangle = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        scene.add_mesh(triangle, [[0, 1, 2]], uvs=[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], texture=str(texture))
        scene.set_sky((0.5, 0.5, 0.5))
        refracta.render(scene, camera, None, spp=1, progress=False)

    render_once()  # the prepared texture's cache file, made once
    handles = len(os.listdir("/proc/self/fd"))
    for _ in range(30):
        render_once()
    # Each Scene left its prepared texture open (30 more handles); now none stays.
    assert len(os.listdir("/proc/self/fd")) <= handles


def test_trace_rays_refuses_a_batch_larger_than_memory_before_tracing():
    # 1e10 rays (broadcast views: no memory of their own) at ~300 bytes each: 3 TB. The batch
    # was traced for seconds and failed allocating its results, or was killed.
    directions = np.broadcast_to(np.array([1.0, 0.5, 0.0]), (10**10, 3))
    with pytest.raises(ValueError, match=r"trace_rays: 10000000000 rays need at least .* split them into batches"):
        refracta.trace_rays(refracta.PhysicalAtmosphere(), [0.0, 1.5, 0.0], directions, max_length=10.0)


def test_a_scene_changed_from_its_render_progress_callback_is_refused_as_such():
    scene = refracta.Scene()
    scene.add_ground(0.0, 10.0)
    scene.set_sky((0.5, 0.5, 0.5))
    camera = refracta.Camera((0.0, 1.0, -3.0), (0.0, 0.0, 0.0), width=8, height=8)

    def change(done, total):
        scene.add_sphere((0.0, 1.0, 0.0), 0.5)

    with pytest.raises(RuntimeError, match="from their progress callback"):
        refracta.render(scene, camera, None, spp=1, progress=change)
