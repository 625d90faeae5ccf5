"""An image that cannot fit in memory is refused before anything is allocated, naming its size in
bytes (issue 13): a 100000 x 100000 render asked for 120 GB of float RGB."""

import pytest

import refracta


@pytest.mark.parametrize(
    "render, needed",
    [
        (lambda s, c: refracta.render(s, c, None, progress=False), 240000000000),
        (lambda s, c: refracta.render(s, c, refracta.PhysicalAtmosphere(), progress=False), 240000000000),
        (lambda s, c: refracta.render_raster(s, c), 440000000000),
    ],
    ids=["straight", "curved", "raster"],
)
def test_a_camera_too_large_for_memory_is_refused_naming_the_bytes(render, needed):
    camera = refracta.Camera([0, 1, 0], [1, 1, 0], width=100_000, height=100_000)
    # 24 bytes per pixel at least: float32 RGB in C++ and its numpy copy; the raster renderer's
    # visibility buffer 20 more (a code review: its check counted 24 and let 30000^2 through).
    with pytest.raises(ValueError, match=rf"a 100000 x 100000 image needs at least {needed} bytes"):
        render(refracta.Scene(), camera)


def test_a_tile_of_that_camera_renders():
    # pixel_bounds: only the tile is allocated.
    camera = refracta.Camera([0, 1, 0], [1, 1, 0], width=100_000, height=100_000)
    with pytest.warns(refracta.SceneWarning, match="no light"):  # an empty scene: black, and said so
        tile = refracta.render(refracta.Scene(), camera, None, progress=False, pixel_bounds=(0, 0, 4, 2))
    assert tile.shape == (2, 4, 3)
