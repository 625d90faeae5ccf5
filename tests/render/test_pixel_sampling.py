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
    for spp in (6, 16, 25):
        image, stats = render(scene, camera, spp=spp, adaptive=True, return_stats=True)
        assert stats.samples == camera.width * camera.height * spp
        assert np.isfinite(image).all()
    # A part of the image: its pixels' samples and the pilot of the rest of its 32-pixel blocks.
    _, stats = render(scene, camera, spp=16, adaptive=True, return_stats=True, pixel_bounds=(4, 4, 12, 10))
    assert 0 < stats.samples < camera.width * camera.height * 16


@pytest.mark.parametrize("spp", [2, 3, 4, 5])
def test_adaptive_sampling_below_its_pilot_is_refused(spp):
    # Its pilot takes 2 samples a pixel: below 3 it was silently off, and at 3-5 what the pilot left
    # was below every pixel's fewest samples, so every pixel got spp - 2 (a trial: relative error
    # 5x the plain render's at spp 3, 2.5x at 5).
    scene, camera = poles()
    left = f".*every pixel would get {spp - 2} " if spp > 2 else ": its pilot takes 2 samples a pixel"
    with pytest.raises(ValueError, match=rf"adaptive needs spp >= 6 \(got {spp}\){left}"):
        render(scene, camera, spp=spp, adaptive=True)
    _, aovs = render(scene, camera, spp=6, adaptive=True, aovs=["samples"])
    assert aovs["samples"].max() > 4  # from 6 on, the pilot leaves samples to move (at least 3 each)


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


def assert_independent_of_threads_tiles_and_bounds(scene, camera, **options):
    """Render with AOVs on two threads, on one, as a part (pixel_bounds) and in other tiles: the same
    image bit for bit (and the same normals on one thread). Returns the whole image."""
    whole, aovs = render(scene, camera, aovs=["albedo", "normal"], **options)
    refracta.set_threads(1)
    try:
        one, one_aovs = render(scene, camera, aovs=["albedo", "normal"], **options)
    finally:
        refracta.set_threads(None)
    assert np.array_equal(whole, one) and np.array_equal(aovs["normal"], one_aovs["normal"])
    part, _ = render(scene, camera, pixel_bounds=(5, 3, 40, 19), aovs=["albedo", "normal"], **options)
    assert np.array_equal(part, whole[3:19, 5:40])
    tiled, _ = render(scene, camera, tiles=(3, 2), aovs=["albedo", "normal"], **options)
    assert np.array_equal(tiled, whole)
    return whole


def test_adaptive_renders_do_not_depend_on_threads_tiles_or_pixel_bounds():
    scene, camera = poles()
    whole = assert_independent_of_threads_tiles_and_bounds(scene, camera, spp=12, adaptive=True)
    assert not np.array_equal(whole, render(scene, camera, spp=12, aovs=["albedo", "normal"])[0])


def test_adaptive_needs_a_ray_traced_method():
    scene, camera = poles()
    with pytest.raises(ValueError, match="adaptive needs method"):
        refracta.render(scene, camera, None, method="raster_march", adaptive=True, progress=False)


# Edge refinement (RenderOptions.edge_spp; film.h EdgeRefinement): pixels at edges between
# surfaces rendered again with edge_spp samples.
BAR_DISTANCE = 10.0  # [m] from the eye to the bar's plane, facing it


def tilted_bar(width_px, tilt_deg, size=48, vfov=30.0):
    """A black bar `width_px` pixels wide, tilted `tilt_deg` from the vertical, in a plane facing
    the eye against a white sky (radiance 1 everywhere; the bar 0), and the exact share of each
    pixel it covers: a plane facing a pinhole maps affinely onto the image (u = (z / (D t) + 1)
    size / 2, v = (1 - y / (D t)) size / 2, t = tan(vfov / 2)), so each pixel's coverage is the area
    of the bar's image clipped to the pixel's square (Sutherland-Hodgman)."""
    t = np.tan(np.radians(vfov / 2.0))
    metres_per_px = 2.0 * BAR_DISTANCE * t / size
    a = np.radians(tilt_deg)
    along, across = np.array([np.sin(a), np.cos(a)]), np.array([np.cos(a), -np.sin(a)])  # (z, y)
    half_length, half_width = 0.35 * size * metres_per_px, 0.5 * width_px * metres_per_px
    corners = [s * half_length * along + w * half_width * across for s, w in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    vertices = np.array([[BAR_DISTANCE, y, z] for z, y in corners])
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0), (1.0, 1.0, 1.0))
    scene.add_mesh(vertices, np.array([[0, 1, 2], [0, 2, 3]]), material=shading.Diffuse(0.0))
    camera = refracta.Camera((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0, 1, 0), vfov, size, size)
    polygon = [
        ((z / (BAR_DISTANCE * t) + 1.0) * size / 2.0, (1.0 - y / (BAR_DISTANCE * t)) * size / 2.0) for z, y in corners
    ]
    coverage = np.array([[_clipped_area(polygon, i, j) for i in range(size)] for j in range(size)])
    return scene, camera, coverage


def _clipped_area(polygon, i, j):
    """Area of `polygon` ((u, v) vertices) inside the pixel square [i, i + 1) x [j, j + 1)."""
    for axis, bound, keep_above in ((0, i, True), (0, i + 1, False), (1, j, True), (1, j + 1, False)):
        inside = [(p[axis] >= bound) == keep_above for p in polygon]
        clipped = []
        for k, p in enumerate(polygon):
            q = polygon[(k + 1) % len(polygon)]
            if inside[k]:
                clipped.append(p)
            if inside[k] != inside[(k + 1) % len(polygon)]:
                s = (bound - p[axis]) / (q[axis] - p[axis])
                clipped.append((p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])))
        polygon = clipped
        if not polygon:
            return 0.0
    u, v = np.array(polygon).T
    return 0.5 * abs(np.dot(u, np.roll(v, -1)) - np.dot(v, np.roll(u, -1)))


def coverage_errors(scene, camera, coverage, **options):
    image = render(scene, camera, **options)
    edge = (coverage > 0.0) & (coverage < 1.0)
    return (1.0 - image[..., 1] - coverage)[edge]


def jittered_rms_bound(spp):
    """The RMS coverage error of an edge pixel whose spp = m x n samples are jittered in the cells
    of an m x n grid (the correlated multi-jittered pattern's cells): only the cells an edge line
    crosses err, at most m + n - 1 of them per line, two lines for a bar; each by its sample's
    indicator less the cell's covered share a, over spp: variance a (1 - a) / spp^2 <= 1 / (4 spp^2),
    cells independent (CMJ's correlated placement within cells measured below it)."""
    columns = max(m for m in range(1, int(np.sqrt(spp)) + 1) if spp % m == 0)
    return np.sqrt(2 * (columns + spp // columns - 1)) / (2.0 * spp)


@pytest.mark.parametrize("width_px, spp", [(1.5, 1), (0.8, 4)])
def test_edge_refinement_weighs_a_tilted_bars_coverage_as_its_sample_pattern_allows(width_px, spp):
    # A bar wide enough that the base samples meet it in every row (1.5 px at the pixel centres,
    # 0.8 px at 4 spp's half-pixel spacing) marks every pixel its edges cross; refined with 64
    # samples each (8 x 8 cells), their coverage error's RMS stays under the jittered grid's bound
    # (0.043); the base samples alone leave several times that (the staircase or the comb).
    scene, camera, coverage = tilted_bar(width_px, 20.0)
    bound = jittered_rms_bound(64)
    for seed in (0, 1):
        base = coverage_errors(scene, camera, coverage, spp=spp, seed=seed)
        refined = coverage_errors(scene, camera, coverage, spp=spp, edge_spp=64, seed=seed)
        assert base.size >= 60
        assert np.sqrt(np.mean(refined**2)) < bound
        assert np.sqrt(np.mean(base**2)) > 3.0 * bound  # what refinement removes


def test_edge_refinement_keeps_every_other_pixel_as_the_base_pass_had_it():
    # Pixels away from edges (the ground's noisy sky lighting included) are the base render's, bit
    # for bit; the poles' edges are rendered again and drawn as edge_spp samples each.
    scene, camera = poles()
    base, base_stats = render(scene, camera, spp=2, seed=3, return_stats=True)
    refined, stats = render(scene, camera, spp=2, edge_spp=32, seed=3, return_stats=True)
    changed = np.any(base != refined, axis=2)
    assert 0 < changed.sum() < 0.5 * changed.size
    extra = stats.samples - base_stats.samples
    assert extra % 32 == 0 and extra // 32 >= changed.sum()  # each changed pixel drew 32 samples more


def test_edge_refined_renders_do_not_depend_on_threads_tiles_or_pixel_bounds():
    scene, camera = poles()
    whole = assert_independent_of_threads_tiles_and_bounds(scene, camera, spp=1, edge_spp=16)
    radiance_only = render(scene, camera, spp=1, edge_spp=16)  # the same pixels refined without AOVs
    assert np.array_equal(radiance_only, whole)


def test_edge_refinement_refuses_bad_settings():
    scene, camera = poles()
    with pytest.raises(ValueError, match="edge_spp must be >= 0"):
        render(scene, camera, edge_spp=-1)
    with pytest.raises(ValueError, match="edge_spp .* and adaptive cannot be combined"):
        render(scene, camera, spp=4, edge_spp=16, adaptive=True)
    with pytest.raises(ValueError, match="edge_spp needs method"):
        refracta.render(scene, camera, None, method="raster_march", edge_spp=4, progress=False)


def test_edge_refinement_leaves_a_sub_pixel_bar_unbiased():
    # A bar 0.2 px wide: the base samples of most pixels it crosses miss it. Whether a pixel is
    # rendered again is chosen from its neighbours' base samples, never its own (film.h
    # EdgeRefinement), so a pixel kept keeps samples the choice did not read: the bar's rendered
    # darkness, summed over the image and averaged over seeds, is its true area. Compared within 4
    # standard errors of that mean (measured 0.95 +- 0.04); when each pixel's own samples took part
    # in the choice, a pixel whose samples missed the bar stayed unrefined and short of it: 0.74
    # +- 0.03 (spp 2), 0.57 (spp 1 with its centre sample).
    scene, camera, coverage = tilted_bar(0.2, 20.0)
    darkness = np.array(
        [(1.0 - render(scene, camera, spp=2, edge_spp=16, seed=seed)[..., 1]).sum() for seed in range(16)]
    )
    ratio, standard_error = darkness.mean() / coverage.sum(), darkness.std(ddof=1) / 4.0 / coverage.sum()
    assert standard_error < 0.06  # the comparison can tell a bias of a quarter from chance
    assert abs(ratio - 1.0) < 4.0 * standard_error, (ratio, standard_error)


def test_edge_refinement_reports_both_passes_as_one_progress():
    # The base pass and the refinement are one progress total (a bar must not reach its end, and
    # close, after the base pass): the last report is done == total, two passes of tiles.
    scene, camera = poles()
    reports = []
    refracta.render(
        scene, camera, None, spp=2, edge_spp=16, tile=8, progress=lambda done, total: reports.append((done, total))
    )
    tiles = -(-camera.width // 8) * -(-camera.height // 8)
    assert all(done <= total for done, total in reports)
    assert reports[-1] == (2 * tiles, 2 * tiles)


def test_the_samples_aov_counts_each_pixels_samples():
    # Uniform: spp everywhere. Edge refinement: edge_spp exactly where the value changed from the
    # base pass, spp elsewhere, and with the base pass's samples of the refined pixels the counts
    # add up to the render's total. Adaptive: the pixels' own counts plus the 2-sample pilot of
    # every pixel are the total, and the poles' columns get more than the flat ground.
    scene, camera = poles()
    image, aovs = render(scene, camera, spp=4, aovs=["samples"])
    assert image.shape == (24, 48, 3) and image.flags.c_contiguous
    assert aovs["samples"].dtype == np.int32 and np.all(aovs["samples"] == 4)
    np.testing.assert_array_equal(image, render(scene, camera, spp=4))  # the image unchanged

    base = render(scene, camera, spp=2, seed=3)
    refined, aovs, stats = render(scene, camera, spp=2, edge_spp=32, seed=3, aovs=["samples"], return_stats=True)
    counts = aovs["samples"]
    assert set(np.unique(counts)) == {2, 32}
    changed = np.any(base != refined, axis=2)
    assert np.all(counts[changed] == 32)
    assert counts.sum() + 2 * np.sum(counts == 32) == stats.samples

    _, aovs, stats = render(scene, camera, spp=16, adaptive=True, aovs=["samples", "normal"], return_stats=True)
    counts = aovs["samples"]
    assert counts.sum() + 2 * counts.size == stats.samples
    sky_rows = slice(0, 8)
    assert counts[sky_rows].max() > 16 > counts[16:].min()  # edges above the mean budget, flat ground below


def test_the_samples_aov_is_the_same_in_tiles_and_parts():
    scene, camera = poles()
    whole = render(scene, camera, spp=12, adaptive=True, aovs=["samples"])[1]["samples"]
    part = render(scene, camera, spp=12, adaptive=True, aovs=["samples"], pixel_bounds=(5, 3, 40, 19))[1]["samples"]
    np.testing.assert_array_equal(part, whole[3:19, 5:40])
    tiled = render(scene, camera, spp=12, adaptive=True, aovs=["samples"], tiles=(3, 2))[1]["samples"]
    np.testing.assert_array_equal(tiled, whole)


def test_the_samples_aov_needs_a_ray_traced_method():
    scene, camera = poles()
    with pytest.raises(ValueError, match="needs method 'straight' or 'curved'"):
        refracta.render(scene, camera, None, method="raster_march", aovs=["samples"], progress=False)
