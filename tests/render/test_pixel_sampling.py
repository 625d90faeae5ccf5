"""The film's pixel samples (cpp/refracta/render/film.h): Kensler's correlated multi-jittered
pattern, and adaptive sampling at an equal budget (render/adaptive_sampling.h): its total sample
count, its unbiasedness, and images that depend neither on the thread count nor on tiles."""

import numpy as np
import pytest

import refracta
from refracta import _core, shading


@pytest.mark.parametrize("count", [1, 2, 7, 12, 16, 17, 64])
def test_each_of_the_n_columns_and_rows_of_the_pixel_holds_one_sample(count):
    # Correlated multi-jittered (Kensler 2013): an N-rooks pattern whatever the count, and for a
    # count m x n also one sample in each cell of the m x n grid (m the largest divisor <= sqrt).
    for seed in (0, 1, 12345):
        points = _core._cmj_pattern(count, seed)
        assert points.shape == (count, 2) and points.min() >= 0.0 and points.max() < 1.0
        for axis in (0, 1):
            assert np.array_equal(np.sort(np.floor(points[:, axis] * count).astype(int)), np.arange(count))
        columns = max(m for m in range(1, int(np.sqrt(count)) + 1) if count % m == 0)
        rows = count // columns
        cells = np.floor(points[:, 0] * columns).astype(int) * rows + np.floor(points[:, 1] * rows).astype(int)
        assert np.array_equal(np.sort(cells), np.arange(count))
    assert not np.array_equal(_core._cmj_pattern(16, 0), _core._cmj_pattern(16, 1))


def test_the_pattern_refuses_an_empty_count():
    with pytest.raises(ValueError, match="count must be >= 1"):
        _core._cmj_pattern(0, 0)


def poles():
    """Dark thin poles against a white sky over a grey ground: edges (coverage) and flat noise
    (the ground's sky lighting), straight rays."""
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0), (1.0, 1.0, 1.0))
    scene.add_ground(0.0, 100.0, material=shading.Diffuse(0.4))
    for z in (-2.0, -0.7, 0.45, 1.9):
        scene.add_box((10.0, 2.0, z), (0.13, 4.0, 0.13), material=shading.Diffuse(0.05))
    camera = refracta.Camera((0.0, 1.0, 0.0), (10.0, 1.0, 0.0), (0, 1, 0), 30.0, 48, 24)
    return scene, camera


def render(scene, camera, **options):
    return refracta.render(scene, camera, None, method="straight", progress=False, **options)


def test_adaptive_sampling_draws_exactly_width_x_height_x_spp_samples():
    scene, camera = poles()
    for spp in (3, 16, 25):
        image, stats = render(scene, camera, spp=spp, adaptive=True, return_stats=True)
        assert stats.samples == camera.width * camera.height * spp
        assert np.isfinite(image).all()
    # A part of the image: its pixels' samples and the pilot of the rest of its 32-pixel blocks.
    _, stats = render(scene, camera, spp=16, adaptive=True, return_stats=True, pixel_bounds=(4, 4, 12, 10))
    assert 0 < stats.samples < camera.width * camera.height * 16


def test_adaptive_sampling_puts_the_samples_where_the_edges_are():
    # Against a 1024-spp reference, the error of the columns holding the poles' edges falls at
    # the same budget (measured: 2.5x; the whole image 1.4x) and the whole image's does not grow.
    scene, camera = poles()
    reference = render(scene, camera, spp=1024, seed=99)

    def errors(image):
        return np.mean((image - reference) ** 2 / (reference**2 + 1e-2), axis=2)

    uniform = np.mean([errors(render(scene, camera, spp=16, seed=s)) for s in range(2)], axis=0)
    adaptive = np.mean([errors(render(scene, camera, spp=16, seed=s, adaptive=True)) for s in range(2)], axis=0)
    sky_rows = slice(0, 8)  # the poles against the sky: rows above the horizon
    edges = np.abs(np.diff(reference[sky_rows].mean(axis=(0, 2)), append=reference[sky_rows, -1].mean())) > 0.05
    assert edges.sum() >= 8
    assert adaptive[:, edges].mean() < 0.8 * uniform[:, edges].mean()  # 0.8: half the measured gain
    assert adaptive.mean() < uniform.mean()


def test_adaptive_sampling_leaves_a_flat_region_unbiased():
    # The ground's sky lighting (flat, noisy): the mean over its pixels with and without adaptive
    # sampling, 4 seeds each, agree within 4 standard errors of their difference (the pixels'
    # own spread over sqrt(pixels x seeds)); the pixels next to the poles get fewer samples.
    scene, camera = poles()
    ground = (slice(16, 24), slice(None))
    uniform = np.array([render(scene, camera, spp=8, seed=s)[ground] for s in range(4)])
    adaptive = np.array([render(scene, camera, spp=8, seed=10 + s, adaptive=True)[ground] for s in range(4)])
    error = np.sqrt(uniform.var() / uniform[..., 0].size + adaptive.var() / adaptive[..., 0].size)
    assert abs(adaptive.mean() - uniform.mean()) < 4.0 * error  # 4 sigma: fails by chance 6e-5 of the time


def test_adaptive_renders_do_not_depend_on_threads_tiles_or_pixel_bounds():
    scene, camera = poles()
    options = dict(spp=12, adaptive=True, aovs=["albedo", "normal"])
    whole, aovs = render(scene, camera, **options)
    refracta.set_threads(1)
    try:
        one, one_aovs = render(scene, camera, **options)
    finally:
        refracta.set_threads(None)
    assert np.array_equal(whole, one) and np.array_equal(aovs["normal"], one_aovs["normal"])
    part, _ = render(scene, camera, pixel_bounds=(5, 3, 40, 19), **options)
    assert np.array_equal(part, whole[3:19, 5:40])
    tiled, _ = render(scene, camera, tiles=(3, 2), **options)
    assert np.array_equal(tiled, whole)
    assert not np.array_equal(whole, render(scene, camera, spp=12, aovs=["albedo", "normal"])[0])


def test_adaptive_needs_a_ray_traced_method():
    scene, camera = poles()
    with pytest.raises(ValueError, match="adaptive needs method"):
        refracta.render(scene, camera, None, method="raster_march", adaptive=True, progress=False)
