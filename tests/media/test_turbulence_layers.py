"""The lattice's modes with no horizontal wavenumber are layers as wide as the scene, which the wind
never moves (a trial of 7 December): with them each seed gave the mean profile its own lasting
change and level paths a vertical tilt growing as L^2. Their variance now sits in the modes beside
them (media/turbulence_synthesis.h)."""

import math

import numpy as np
import pytest

import refracta
from refracta.testing.tilts import level_path_tilts


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_every_level_plane_averages_to_the_calm_air(seed):
    # 20000 points spread over 4 km x 4 km at three heights of one 3.2 m tile: the plane means of
    # delta_n and of its vertical gradient, over their spread. Chance alone gives ~1/sqrt(20000) =
    # 0.007 (the tile repeats, so fewer independent samples: measured up to 0.018); with the layers
    # the gradient's mean was about half its spread (the helper's +55e-6 /m beside a spread of ~1e-4).
    air = refracta.Turbulence(1e-10, cells=64, depth=None, seed=seed)
    rng = np.random.default_rng(seed)
    points = np.column_stack([rng.uniform(-2000, 2000, 20_000), np.zeros(20_000), rng.uniform(-2000, 2000, 20_000)])
    for height in (0.0, 1.0, 2.0):
        points[:, 1] = height
        delta_n, gradient = air.evaluate(points)
        assert abs(delta_n.mean()) < 0.05 * delta_n.std()
        assert abs(gradient[:, 1].mean()) < 0.05 * gradient[:, 1].std()


def test_level_paths_tilt_alike_in_both_transverse_axes():
    # First-order tilt (the transverse gradient summed along the path) of 200 level paths 75 m long
    # (23 tiles of 3.2 m) at random places and headings over 4 seeds. Isotropic turbulence gives a
    # ratio of 1; the lattice's few modes near the plane kappa . t = 0 scatter it (0.55 here, 0.7-0.9
    # at 256^3 over 300 m: benchmarks' level_path_tilt_vertical_over_horizontal). With the layers,
    # which are constant along every level path, it was 5-12 at such lengths.
    rng = np.random.default_rng(5)
    vertical, horizontal = [], []
    for seed in range(4):
        layer = refracta.Turbulence(1e-10, cells=64, depth=None, seed=seed).layer
        v, h = level_path_tilts(layer, 75.0, 50, rng, step=0.025)
        vertical.extend(v)
        horizontal.extend(h)
    assert 0.4 < np.var(vertical) / np.var(horizontal) < 2.5  # tolerance: the scatter above, 5-12 excluded


def test_the_layers_variance_is_moved_to_their_neighbours_not_dropped():
    # Independently of the C++ table: Phi_n averaged over a mode's cell of wavenumber space by 8^3
    # midpoints (what the lowest modes carry), from the public von_Karman spectrum. The layer
    # (0, j, 0) holds nothing; each of its four horizontal neighbours holds its own cell's
    # variance plus a quarter of the layer's, so every vertical wavenumber keeps its total.
    from refracta import turbulence as tb

    air = refracta.Turbulence(1e-10, cells=16, depth=None)
    dk = 2.0 * math.pi / air.size
    offsets = (np.arange(8) + 0.5) / 8 - 0.5
    x, y, z = np.meshgrid(offsets, offsets, offsets, indexing="ij")

    def cell(i, j, k):
        kappa = dk * np.sqrt((i + x) ** 2 + (j + y) ** 2 + (k + z) ** 2)
        return float(np.mean(tb.von_karman_spectrum(kappa.ravel(), 1.0, air.inner_scale, air.outer_scale))) * dk**3

    for j in (1, 2, 3):
        assert air._mode_variance(0, [j], [0])[0, 0] == 0.0
        for i, k in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            expected = cell(i, j, k) + 0.25 * cell(0, j, 0)
            assert air._mode_variance(i, [j], [k])[0, 0] == pytest.approx(expected, rel=1e-12)  # tolerance: round-off
        assert air._mode_variance(1, [j], [1])[0, 0] == pytest.approx(cell(1, j, 1), rel=1e-12)  # untouched
