"""The curved renderer's shortcuts against a strict reference (issue 12).

Height-only air is tabulated once per render (cubic Hermite to 1e-12 in n); camera rays walk
chord plans that may stray a quarter of a pixel's footprint; shadow and bounce rays too steep to
turn are cut into chords from Bouguer's invariant; escaping rays leave along the invariant's
direction. The reference forces rk45 per pixel (none of those shortcuts), a tolerance of 10 um
and chords within 0.1 mm. A quarter-pixel tolerance moves an edge by at most a quarter pixel,
so pixels on edges may flip at 1 spp (the pixel centre lands on the other side); pixels away
from edges may not change beyond what a quarter-pixel shift of their smooth surroundings gives.
The whole image's mean is not compared: at 1 spp it carries the random sum of the edge flips,
which grows with the scene's edges (the Fata Morgana's textured shore: 0.4-5e-4 of the mean over
six random layouts of the same scene, none of it bias).
"""

import numpy as np
import pytest

import refracta
from refracta import _core, examples


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


SMOOTH = 0.02  # relative variation of a pixel's 3 x 3 neighbourhood that counts as smooth


def smooth_pixels(lum):
    """Pixels (the border excluded) within SMOOTH (relative) of each of their 8 neighbours."""
    inner = lum[1:-1, 1:-1]
    ok = np.ones(inner.shape, bool)
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            shifted = lum[1 + dy : lum.shape[0] - 1 + dy, 1 + dx : lum.shape[1] - 1 + dx]
            ok &= np.abs(shifted - inner) <= SMOOTH * np.maximum(inner, 1e-3)
    mask = np.zeros(lum.shape, bool)
    mask[1:-1, 1:-1] = ok
    return mask


@pytest.mark.parametrize("name", ["hot_road", "cold_sea", "fata_morgana"])
def test_fast_render_matches_strict_per_pixel_rk45(name):
    example = getattr(examples, name)(160, 60)
    common = dict(max_length=example.max_length, progress=False)
    fast = luminance(refracta.render(example.scene, example.camera, example.field, **common))
    strict = luminance(
        refracta.render(
            example.scene,
            example.camera,
            example.field,
            trace="rk45",
            table=False,
            sagitta_pixels=0.0,
            tol=1e-5,
            sagitta=1e-4,
            **common,
        )
    )
    # Smooth pixels: within SMOOTH of each of their 8 neighbours in the strict image. A quarter
    # pixel's stray moves their sample across at most a quarter of that variation, so each may
    # differ by SMOOTH / 4; the strays' signs are random, so their mean over >= 1000 such pixels
    # has a standard deviation of at most (SMOOTH / 4) / sqrt(1000) = 1.6e-4, the bound (measured:
    # 6e-7 at most, and 5e-5 per pixel). A biased shortcut (a wrong table, chords leaning one
    # way) shifts them all alike.
    smooth = smooth_pixels(strict)
    assert smooth.sum() >= 1000, smooth.sum()
    beyond = np.abs(fast - strict)[smooth] > SMOOTH / 4 * np.maximum(strict[smooth], 1e-3)
    # Smooth at the pixels' centres can still hide structure within a pixel: since shadow rays leave
    # a surface by the float error of its own vertices (not 2e-6 of its distance, 6 cm at 30 km),
    # the cold sea's wave facets 30 km out shadow each other at a grazing sun, and one 1-spp pixel
    # of 3 869 differs by 0.502 % (0.056 % at 16 spp: sampling, not a bias). 0.1 % of them may.
    assert beyond.mean() <= 1e-3, f"{beyond.sum()} smooth pixels differ by more than SMOOTH / 4"
    assert abs(fast[smooth].mean() - strict[smooth].mean()) <= 1.6e-4 * strict[smooth].mean()
    off = np.abs(fast - strict) > 0.02 * np.maximum(strict, 1e-3)
    # The table and sagitta paths vs strict rk45 flip < 1.5 % of pixels (edges).
    assert off.mean() < 0.015, f"{off.sum()} of {off.size} pixels differ by more than 2 %"


@pytest.mark.parametrize(
    "field",
    [
        refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1),
        refracta.PhysicalAtmosphere(t_ground=278.15, inversion_dt=7.0, inversion_base=10.0, inversion_thickness=20.0),
        refracta.LogisticProfile(),
    ],
    ids=["hot_road", "inversion", "logistic"],
)
def test_tabulated_air_matches_the_field(field):
    table = _core._tabulate_heights(field, -1.0, 3000.0)
    rng = np.random.default_rng(7)
    heights = np.concatenate([rng.uniform(-1.0, 3000.0, 20000), rng.uniform(-1.0, 2.0, 20000)])
    points = np.zeros((heights.size, 3))
    points[:, 1] = heights
    # Refined until the cubic is within 1e-12 of n at every interval's quarter points; between
    # them the error of a smooth cubic fit stays of that order (2x margin).
    assert np.abs(table.ior(points) - field.ior(points)).max() < 2e-12
    # dn/dh is the cubic's derivative: one order of the spacing less accurate.
    grad, exact = table.grad_ior(points)[:, 1], field.grad_ior(points)[:, 1]
    assert np.abs(grad - exact).max() < 1e-4 * np.abs(exact).max()
    # Outside the table the field itself answers.
    outside = np.array([[0.0, 3500.0, 0.0], [0.0, -5.0, 0.0]])
    assert np.array_equal(table.ior(outside), field.ior(outside))


def test_curved_earth_tabulated_in_flat_heights_matches_it_at_every_dispersion():
    # The cold sea's inversion and the hot road's surface layer over a spherical Earth: n'(y') =
    # n(h) e^(y'/R) and, dispersed by s, (1 + s (n - 1)) e^(y'/R), from one table of e^(y'/R) and
    # (n - 1) e^(y'/R) on shared nodes.
    air = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1, inversion_dt=10.0, inversion_base=20.0)
    field = refracta.CurvedEarth(air)
    # Tabulated up to the top of the air (86 km) at least, where escaping rays are integrated to.
    table = _core._tabulate_heights(field, -1.0, 40000.0)
    assert _core._tabulate_heights(table, -1.0, 40000.0) is table  # tabulated once
    rng = np.random.default_rng(7)
    heights = np.concatenate([rng.uniform(-1.0, 86000.0, 20000), rng.uniform(-1.0, 40.0, 20000)])
    points = np.zeros((heights.size, 3))
    points[:, 1] = heights
    for wavelength in (None, 400.0, 700.0):
        exact = field if wavelength is None else refracta.dispersed_field(field, wavelength)
        tabulated = table if wavelength is None else refracta.dispersed_field(table, wavelength)
        # Each part's cubic of (n - 1) e^(y'/R) is within 1e-12 at its quarter points, that of
        # e^(y'/R) to rounding; between them a smooth cubic's error stays of that order (2x
        # margin, and s <= 1.02 scales the first).
        assert np.abs(tabulated.ior(points) - exact.ior(points)).max() < 2e-12
        # dn'/dy' is the cubics' derivative: one order of the spacing less accurate.
        grad, truth = tabulated.grad_ior(points)[:, 1], exact.grad_ior(points)[:, 1]
        assert np.abs(grad - truth).max() < 1e-4 * np.abs(truth).max()
        # Outside the table the exact (dispersed) CurvedEarth answers.
        outside = np.array([[0.0, 90000.0, 0.0], [0.0, -5.0, 0.0]])
        assert np.array_equal(tabulated.ior(outside), exact.ior(outside))


def test_tabulating_a_field_that_is_not_height_only_returns_it():
    field = refracta.CustomField(lambda p: 1.0 + 1e-4 * p[:, 0], lambda p: np.tile([1e-4, 0.0, 0.0], (len(p), 1)))
    assert _core._tabulate_heights(field, 0.0, 10.0) is field


def test_long_chords_do_not_cut_over_a_path_that_dips_under_the_sea():
    # Over the cold sea the rays just below the horizon come down to the sea 29 km out, where the
    # inversion's duct would turn them up again from under it (0.45 m down at 31.5 km). A chord
    # that reaches across that turn stays within its tolerance of the path (a quarter pixel's
    # footprint is ~0.8 m there) yet never crosses the sea: with chords of up to 20 km, 139 of
    # the 4 497 pixels that see the sea saw the coast behind it or the sky before chords stopped
    # at the path's turning points. What remains are single pixels at edges (2 measured).
    example = examples.cold_sea(160, 60)
    common = dict(max_length=example.max_length, progress=False, aovs=["object_id"])
    _, default = refracta.render(example.scene, example.camera, example.field, **common)
    _, long_chords = refracta.render(example.scene, example.camera, example.field, chord=20000.0, **common)
    sea = default["object_id"] == 0
    assert sea.sum() > 4000
    assert (sea & (long_chords["object_id"] != 0)).sum() <= 10


@pytest.mark.parametrize("azimuth_deg", [180.0, 90.0, 0.0])
def test_the_ceiling_by_azimuth_keeps_every_object_it_passes(azimuth_deg):
    # Camera rays stop testing chords once their path stays above the highest geometry at their
    # azimuth (render/azimuth_ceiling.h). Towers of different heights stand across the view --
    # looking along -x puts the bins' wrap at +-180 deg in its middle -- each the tallest thing in
    # its own azimuths: a ceiling taken from the wrong bins, or lost at the wrap, would cut the
    # taller towers' tops off. The rays through the table must see what rays traced per pixel see.
    heading = np.radians(azimuth_deg)
    ahead, side = np.array([np.cos(heading), 0.0, np.sin(heading)]), np.array([-np.sin(heading), 0.0, np.cos(heading)])
    scene = refracta.Scene()
    scene.add_ground(0.0, 20000.0, kd=0.3)
    for k, offset in enumerate(np.linspace(-60.0, 60.0, 7)):
        height = 5.0 + 6.0 * k
        centre = 800.0 * ahead + offset * side + np.array([0.0, height / 2, 0.0])
        scene.add_box(centre, (4.0, height, 4.0), kd=(0.8, 0.2, 0.2))
    scene.set_sky((0.5, 0.6, 0.9))
    eye = np.array([0.0, 2.0, 0.0])
    camera = refracta.Camera(eye, eye + ahead * 800.0 + np.array([0.0, 15.0, 0.0]), vfov=5.0, width=96, height=48)
    air = refracta.PhysicalAtmosphere(surface_dt=5.0, surface_depth=0.3)
    common = dict(max_length=5000.0, progress=False, aovs=["position"], transport="direct")
    _, table = refracta.render(scene, camera, air, **common)
    _, traced = refracta.render(scene, camera, air, table=False, **common)
    hit_table, hit_traced = np.isfinite(table["position"][..., 0]), np.isfinite(traced["position"][..., 0])
    # The towers' silhouettes: the same pixels hit (a quarter-pixel stray may flip a few edges).
    assert hit_traced.sum() > 500
    assert (hit_table != hit_traced).sum() <= 0.01 * hit_traced.sum()
    # Each tower's top row is seen through the table as traced per pixel.
    assert np.array_equal(hit_table.any(axis=1), hit_traced.any(axis=1))
