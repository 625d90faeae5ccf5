"""Part of an image renders exactly as in the whole (RenderOptions.pixel_bounds), so a render
split into tiles -- on any executor -- is bit-identical to the local render: curved and straight
rays, direct and path transport, RGB and spectral, raster_march."""

import concurrent.futures

import numpy as np
import pytest

from refracta._render import tile_bounds
from tests.scale import scenes


@pytest.fixture(scope="module")
def setup(tmp_path_factory):
    texture = scenes.write_texture(tmp_path_factory.mktemp("tiles") / "checker.exr")
    return scenes.every_kind_scene(texture, "environment"), scenes.camera(), scenes.hot_road()


CASES = [
    dict(method="curved", transport="direct", spp=4),
    dict(method="curved", transport="path", spp=4),
    dict(method="curved", transport="direct", spp=2, table=False),  # every pixel traced
    dict(method="straight", transport="direct", spp=4),
    dict(method="straight", transport="path", spp=4),
    dict(method="curved", transport="path", spp=2, spectral=True),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: "-".join(str(v) for v in c.values()))
def test_tiles_assemble_to_the_local_render_bit_for_bit(setup, case):
    scene, camera, field = setup
    local, stats = scenes.render_quietly(scene, camera, field, return_stats=True, **case)
    tiled, tiled_stats = scenes.render_quietly(scene, camera, field, tiles=(3, 2), return_stats=True, **case)
    assert tiled.dtype == np.float32 and tiled.shape == local.shape
    assert np.array_equal(tiled, local)
    assert tiled_stats.samples == stats.samples == camera.width * camera.height * case["spp"]


def test_pixel_bounds_render_is_the_same_part_of_the_image(setup):
    scene, camera, field = setup
    local = scenes.render_quietly(scene, camera, field, transport="path", spp=4)
    part = scenes.render_quietly(scene, camera, field, transport="path", spp=4, pixel_bounds=(5, 3, 17, 11))
    assert part.shape == (8, 12, 3) and np.array_equal(part, local[3:11, 5:17])


def test_raster_march_tiles_equal_the_local_render(setup):
    scene, camera, field = setup
    local = scenes.render_quietly(scene, camera, field, method="raster_march", spp=2)
    assert np.array_equal(scenes.render_quietly(scene, camera, field, method="raster_march", spp=2, tiles=7), local)


def test_tiles_of_a_thread_pool_and_of_a_region(setup):
    scene, camera, field = setup
    local = scenes.render_quietly(scene, camera, field, spp=2)
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        tiled = scenes.render_quietly(scene, camera, field, spp=2, executor=pool, tiles=5)
        region = scenes.render_quietly(
            scene, camera, field, spp=2, executor=pool, tiles=(2, 2), pixel_bounds=(4, 2, 20, 15)
        )
    assert np.array_equal(tiled, local) and np.array_equal(region, local[2:15, 4:20])


def test_tile_bounds_cover_the_image_once():
    for tiles in [(1, 1), (3, 2), (24, 16), 5, 100]:
        cover = np.zeros((16, 24), int)
        for x0, y0, x1, y1 in tile_bounds(24, 16, tiles):
            cover[y0:y1, x0:x1] += 1
        assert (cover == 1).all(), tiles


@pytest.mark.parametrize(
    "bad",
    [
        dict(pixel_bounds=(0, 0, 25, 16)),
        dict(pixel_bounds=(3, 3, 3, 5)),
        dict(pixel_bounds=(1, 2, 3)),
        dict(tiles=(0, 2)),
        dict(tiles=(25, 1)),
        dict(tiles=0),
        dict(tiles="4x4"),
        dict(tiles=(1.5, 2)),
    ],
)
def test_bad_bounds_and_tiles_raise_value_errors(setup, bad):
    scene, camera, field = setup
    with pytest.raises(ValueError):
        scenes.render_quietly(scene, camera, field, **bad)
