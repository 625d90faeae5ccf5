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


def ground_and_mirrored(example, camera, **options):
    """Per pixel of `camera` (or of options' pixel_bounds): where its straight ray meets the ground
    (position [m], NaN where it meets no ground), and whether through example.field it meets
    anything but the ground (sky, poles, cars, the ridge: the mirage) -- 1 spp, the pixel's centre."""
    common = dict(max_length=example.max_length, progress=False, transport="direct", spp=1, **options)
    _, plain = refracta.render(
        example.scene, camera, refracta.without_refraction(example.field), aovs=["distance", "position"], **common
    )
    _, air = refracta.render(example.scene, camera, example.field, aovs=["distance", "position"], **common)
    on_ground = np.isfinite(plain["distance"]) & (plain["position"][..., 1] < 0.1)  # sand 0, road 2 mm, paint 6 mm
    ground = np.where(on_ground[..., None], plain["position"], np.nan)
    mirrored = ~np.isfinite(air["distance"]) | (air["position"][..., 1] > 0.1)
    return ground, mirrored


def test_the_demos_lake_is_local():
    # examples.hot_spot: a stretch of hot ground 290-650 m down the road, nothing beyond 14 m of its
    # centre line. A ray that leaves the eye depressed by e turns above the ground if the air there
    # is less dense by n (1 - cos e) ~ n e^2 / 2 than at the eye (n cos e is conserved in layered
    # air). Judged by the air at the point its straight ray meets the ground: a column of the lake's
    # rows whose air there has twice that deficit is mirrored, one with half of it is ground.
    # The factor 2 either way covers the ray's ~20-40 m run through the bottom 10 cm before that
    # point, over air partly of another deficit (measured at 240x120: deficit ratio 1-1.5 -> 75 %
    # mirrored, 1.5-2 -> 99 %, 0.5-1 -> 7 %).
    example = examples.hot_spot(240, 120)
    camera = example.camera
    ground, mirrored = ground_and_mirrored(example, camera)
    x, z = ground[..., 0], ground[..., 2]
    lake_rows = (x > 300.0) & (x < 640.0)  # NaN compares false: ground pixels only
    points = np.where(lake_rows[..., None], ground, 0.0).reshape(-1, 3) * np.array([1.0, 0.0, 1.0])
    n_ground = example.field.ior(points).reshape(x.shape)
    n_eye = example.field.ior(np.asarray([camera.position]))[0]
    rays = np.array([[camera.ray(u + 0.5, v + 0.5)[1] for u in range(camera.width)] for v in range(camera.height)])
    depression = -np.arcsin(rays[..., 1] / np.linalg.norm(rays, axis=-1))
    ratio = (n_eye - n_ground) / (n_eye * depression**2 / 2)
    hot, cool = lake_rows & (ratio > 2.0), lake_rows & (ratio < 0.5)
    assert hot.sum() > 200 and mirrored[hot].all(), "the hot stretch's air mirrors"
    assert cool.sum() > 200 and not mirrored[cool].any(), "the mildly warm desert beside it does not"
    # The lake ends left and right: in its rows the sand beyond the spots' reach lies in the frame on
    # both sides and none of it is mirrored (1 K there: a mirage only within 0.08 deg of the horizon).
    beside = lake_rows & (np.abs(z) > examples.HOT_SPOT_RADIUS)
    assert (beside & (z < 0)).sum() > 50 and (beside & (z > 0)).sum() > 50
    assert not mirrored[beside].any()


def test_the_demos_lake_stays_on_the_ground_as_the_camera_walks():
    # The lake's near edge along the centre columns (the straight ray's ground point of the nearest
    # mirrored row) as the camera walks cli.HOT_SPOT_WALK (60 m) toward it: over the hot stretch it
    # stays near the stretch's start; over the uniformly hot road it moves with the camera.
    from refracta import cli

    def near_edge(example, walk):
        camera = cli._moved(example.camera, walk, example.camera.width, example.camera.height)
        ground, mirrored = ground_and_mirrored(example, camera, pixel_bounds=(316, 0, 324, 320))
        return np.nanmin(np.where(mirrored, ground[..., 0], np.nan))

    spot, road = examples.hot_spot(640, 320), examples.hot_road(640, 320)
    walk = cli.HOT_SPOT_WALK
    # A row spans x^2 / h * pixel angle of road: 9 m at 300 m from the 1.5 m eye (the tolerance on
    # the road's edge). The spot's edge may move by that and into the start of the stretch, where the
    # compact footprints' sum climbs over ~14 m: the walked eye looks down more steeply and needs
    # warmer air (measured: 307.6 -> 314.3 m; the road's 294.0 -> 354.0 m).
    spot_edge = near_edge(spot, 0.0)
    assert examples.HOT_SPOT_STRETCH[0] - 15.0 < spot_edge < examples.HOT_SPOT_STRETCH[0] + 30.0  # row + climb
    assert abs(near_edge(spot, walk) - spot_edge) < 15.0  # a row (9 m) and the footprints' climb
    assert abs(near_edge(road, walk) - near_edge(road, 0.0) - walk) < 9.0
