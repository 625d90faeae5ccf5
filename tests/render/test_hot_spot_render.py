"""Rendering through air with areal hot spots (issue 10): the height-only machinery serves the
rays that stay outside every spot's region, rk45 traces the legs inside. Against a strict
reference (rk45 through the full field per pixel, tolerance 10 um, chords 0.1 mm: no shortcut),
and exactly the height-only render where no ray comes near a spot.

The fast path may stray a quarter of a pixel's footprint (as tests/render/test_fast_paths.py
allows), so pixels on edges may differ at 1 spp: on this road a mirage ray passes the white car's
bottom edge 0.4 mm above it at 340 m, 1/500 of a pixel. Such edge pixels move the image mean by
their share (< 0.3 % of the pixels here) times their contrast: 0.5 % is allowed, where a wrong
leg (entering or leaving a spot's region on the wrong path) moved it by 1.8 %."""

import numpy as np
import pytest

import refracta
from refracta import examples


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def road_with(spot):
    example = examples.hot_road(160, 60)
    return example, refracta.PhysicalAtmosphere(**example.field.params, hot_spots=[spot])


@pytest.mark.slow
@pytest.mark.parametrize(
    "spot",
    [
        refracta.HotSpot(400.0, 0.0, 150.0, 15.0, footprint="compact"),  # a patch of hot asphalt 300 m long
        refracta.HotSpot(350.0, 0.0, 40.0, 20.0, footprint="gaussian"),
        refracta.HotSpot(150.0, 0.0, 8.0, 15.0, footprint="gaussian"),  # small: every column crosses its region
    ],
    ids=["compact", "gaussian", "small"],
)
def test_hot_spot_render_matches_strict_per_pixel_rk45(spot):
    # Over otherwise standard air the spot alone makes the mirage.
    example = examples.hot_road(160, 60)
    field = refracta.PhysicalAtmosphere(hot_spots=[spot])
    common = dict(max_length=example.max_length, progress=False)
    fast = luminance(refracta.render(example.scene, example.camera, field, **common))
    strict = luminance(
        refracta.render(
            example.scene, example.camera, field, trace="rk45", sagitta_pixels=0.0, tol=1e-5, sagitta=1e-4, **common
        )
    )
    assert abs(fast.mean() - strict.mean()) <= 5e-3 * strict.mean()
    off = np.abs(fast - strict) > 0.02 * np.maximum(strict, 1e-3)
    # The fast renderer's table and sagitta vs strict rk45 flip < 1.5 % of pixels (edges).
    assert off.mean() < 0.015, f"{off.sum()} of {off.size} pixels differ by more than 2 %"
    if spot.radius > 10.0:  # the large spots show: a mirage the spot-free air does not have
        plain = luminance(refracta.render(example.scene, example.camera, refracta.PhysicalAtmosphere(), **common))
        # The spot's mirage changes more than 1 % of the pixels by > 2 %.
        assert (np.abs(fast - plain) > 0.02 * np.maximum(plain, 1e-3)).mean() > 0.01


# Camera rays only: emitters seen directly (the sky where a ray escapes, black on objects), so a
# pixel depends on nothing but its camera ray's path.
CAMERA_RAYS_ONLY = dict(transport="path", max_depth=0)


def test_rays_that_miss_a_compact_spot_see_the_height_only_air_exactly():
    # A compact spot far to the side, under no camera ray: the render is the height-only one,
    # bit for bit (same table, same chords; no ray enters the region).
    example, field = road_with(refracta.HotSpot(150.0, 40.0, 5.0, 30.0, footprint="compact"))
    common = dict(max_length=example.max_length, progress=False, **CAMERA_RAYS_ONLY)
    with_spot = refracta.render(example.scene, example.camera, field, **common)
    plain = refracta.render(example.scene, example.camera, example.field, **common)
    np.testing.assert_array_equal(with_spot, plain)


def test_spot_changes_only_the_columns_whose_rays_cross_it():
    # A narrow compact spot on the camera's axis: columns whose rays pass its cylinder may change,
    # the others (their rays never come within its radius) are the height-only render exactly.
    example, field = road_with(refracta.HotSpot(120.0, 0.0, 1.5, 25.0, footprint="compact"))
    common = dict(max_length=example.max_length, progress=False, **CAMERA_RAYS_ONLY)
    with_spot = refracta.render(example.scene, example.camera, field, **common)
    plain = refracta.render(example.scene, example.camera, example.field, **common)
    changed_columns = np.nonzero(np.any(with_spot != plain, axis=(0, 2)))[0]
    assert changed_columns.size > 0
    # A column's rays lie in vertical planes through the eye (the height-only air bends them
    # there): column u's plane passes the spot's centre at lateral offset 120 tan(azimuth).
    camera = example.camera
    azimuths = np.array(
        [np.arctan2(camera.ray(u + 0.5, 30.0)[1][2], camera.ray(u + 0.5, 30.0)[1][0]) for u in range(camera.width)]
    )
    offsets = np.abs(120.0 * np.tan(azimuths))
    # The column's rays span its pixel: half a pixel's footprint of slack.
    slack = 0.5 * 120.0 * camera.pixel_angle
    assert np.all(offsets[changed_columns] < 1.5 + slack), "a column changed whose rays never come near the spot"
