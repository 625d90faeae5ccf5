"""Defects found by a read-through of the C++ core on 7 December: image sides and tiles were checked
only from below, and the int arithmetic on them overflowed (rasterize with tile=2**31-1 and the
raster march of a camera 858993460 pixels wide crashed; render and render_raster with that tile
returned black images); the memory checks missed the raster march's guard-banded view and
rasterize; trace_ray kept nodes without bound but max_steps; a tiny turbulence_step overflowed
its step count into one step."""

import numpy as np
import pytest

import refracta
from refracta import raster


def sky_and_ground(width=8, height=4):
    scene = refracta.Scene()
    scene.add_ground(0.0)
    scene.set_sky(1.0)
    return scene, refracta.Camera((0, 1.6, 0), (0, 1, -10), width=width, height=height)


@pytest.mark.parametrize("side", [2**24 + 1, 858993460, 2**31 - 1])
def test_a_camera_side_past_2_to_the_24_is_refused(side):
    with pytest.raises(ValueError, match=r"Camera: sides must be at most 16777216 pixels"):
        refracta.Camera((0, 1.6, 0), (0, 1, -10), width=side, height=1)
    with pytest.raises(ValueError, match=r"Camera: sides must be at most 16777216 pixels"):
        refracta.Camera((0, 1.6, 0), (0, 1, -10), width=1, height=side)


def test_the_largest_camera_side_still_renders_a_window():
    # 2**24 pixels wide: the last pixel of the last tile is rendered (x0 + tile overflowed near 2**31).
    scene, _ = sky_and_ground()
    side = 2**24
    camera = refracta.Camera((0, 1.6, 0), (0, 1, -10), vfov=1e-3, width=side, height=1)
    image = refracta.render(scene, camera, method="straight", pixel_bounds=(side - 17, 0, side, 1), progress=False)
    assert image.shape == (1, 17, 3)
    # The image's far edge, seen at nearly one angle: one surface's radiance in every pixel, none
    # left black (the sky is 1.0, the lit ground 0.3).
    assert np.all(image > 0.1) and np.all(image == image[0, 0])


@pytest.mark.parametrize("tile", [2**16 + 1, 2**31 - 1])
def test_a_tile_past_2_to_the_16_is_refused_not_rendered_black(tile):
    scene, camera = sky_and_ground()
    with pytest.raises(ValueError, match=r"tile must be in \[1, 65536\] pixels"):
        refracta.render(scene, camera, method="straight", tile=tile, progress=False)
    with pytest.raises(ValueError, match=r"tile must be in \[1, 65536\] pixels"):
        refracta.render_raster(scene, camera, tile=tile, progress=False)
    with pytest.raises(ValueError, match=r"tile must be a whole number in \[1, 65536\]"):
        raster.rasterize(scene, camera, tile=tile)


def test_the_largest_tile_renders_what_the_default_does():
    scene, camera = sky_and_ground()
    default = refracta.render(scene, camera, method="straight", progress=False)
    one_tile = refracta.render(scene, camera, method="straight", tile=2**16, progress=False)
    np.testing.assert_array_equal(one_tile, default)  # tiles do not change a pixel's samples


def test_the_raster_march_refuses_a_guard_band_view_larger_than_memory():
    # 100000^2 pixels with guard bands of 2 sides each way: a view of 5e11 pixels (10 TB of
    # buffer) behind a 4-pixel window, which the window's own memory check let through.
    scene, _ = sky_and_ground()
    camera = refracta.Camera((0, 1.6, 0), (0, 1, -10), width=100_000, height=100_000)
    with pytest.raises(ValueError, match=r"render \(raster_march's view\): a 500000 x 500000 image needs at least"):
        refracta.render(scene, camera, method="raster_march", guard_band=2.0, pixel_bounds=(0, 0, 4, 1), progress=False)


def test_rasterize_refuses_an_image_larger_than_memory():
    scene, _ = sky_and_ground()
    camera = refracta.Camera((0, 1.6, 0), (0, 1, -10), width=100_000, height=100_000)
    with pytest.raises(ValueError, match=r"rasterize: a 100000 x 100000 image needs at least"):
        raster.rasterize(scene, camera)


def test_trace_ray_refuses_a_path_whose_nodes_cannot_fit_in_memory():
    # rk4 in 10 um steps over 1000 km: 1e11 nodes of 88 bytes (8.8 TB, past any machine), under a
    # max_steps of 1e12 (a trial's 1e9 nodes in 1 mm steps asked for 88 GB).
    air = refracta.PhysicalAtmosphere()
    with pytest.raises(
        ValueError,
        match=r"trace_ray: a path of max_length 1000000 m in steps of 1e-05 m keeps 100000000000 nodes of 88 bytes",
    ):
        refracta.trace_ray(air, (0, 1, 0), (1, 0, 0), trace="rk4", step=1e-5, max_length=1e6, max_steps=10**12)
    # The same path at a step that fits is traced as before.
    path = refracta.trace_ray(air, (0, 1, 0), (1, 0, 0), trace="rk4", step=10.0, max_length=1e3)
    assert len(path.points) == 101  # 1000 m in 10 m steps, both ends


def test_a_turbulence_step_below_a_hundredth_of_a_cell_is_refused():
    with pytest.raises(ValueError, match=r"turbulence_step must be in \[0.01, 16\] cells \(got 1e-300\)"):
        refracta.RenderOptions(turbulence_step=1e-300)
    assert refracta.RenderOptions(turbulence_step=0.01).turbulence_step == 0.01


MANY_MAPS = """
import resource, sys
import refracta
# 8 GB of address space: were the maps built without the check, the first few would fail to
# allocate (MemoryError) instead of the machine running out of memory.
resource.setrlimit(resource.RLIMIT_AS, (8 << 30, 8 << 30))
scene = refracta.Scene()
scene.add_ground(0.0)
for i in range(2000):
    scene.add_spot_light((i * 0.01, 5.0, 0.0), (0.0, -1.0, 0.0), angle=30.0)
camera = refracta.Camera((0, 1.6, 5), (0, 0, 0), width=8, height=4)
try:
    refracta.render_raster(scene, camera, shadows="msm_hamburger", resolution=4096)
except ValueError as error:
    print(error)
    sys.exit(0)
sys.exit(1)
"""


def test_render_raster_refuses_shadow_maps_that_cannot_live_together():
    # 2000 spot lights' 4096^2 moment maps (36 bytes a texel): 1.2 TB together, each checked
    # alone 0.6 GB; eleven 8192^2 ones took 25 GB.
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-c", MANY_MAPS], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "render_raster's 2000 shadow maps: a 4096 x 4096 image needs at least" in done.stdout


def test_a_perturbed_walk_of_more_than_1e8_steps_is_refused():
    # 0.01 of a 0.1 mm cell over 1.5 km: 1.5e9 steps a ray, near an int's count (which overflowed
    # into one step); the strict trace's own bound (1e7 rk45 steps of half 8 cells) lets it by.
    from refracta import examples

    road = examples.hot_road(8, 4)
    air = refracta.PhysicalAtmosphere(
        **road.field.params, turbulence=refracta.Turbulence(1e-10, cells=16, spacing=1e-4, depth=0.1)
    )
    with pytest.raises(ValueError, match=r"turbulence_trace 'perturbed': steps of 1e-06 m .* would be more than 1e8"):
        refracta.render(road.scene, road.camera, air, turbulence_step=0.01, max_length=1500.0, progress=False)
