"""The curved renderer's shortcuts against a strict reference (issue 12).

Height-only air is tabulated once per render (cubic Hermite to 1e-12 in n); camera rays walk
chord plans that may stray a quarter of a pixel's footprint; shadow and bounce rays too steep to
turn are cut into chords from Bouguer's invariant; escaping rays leave along the invariant's
direction. The reference forces rk45 per pixel (none of those shortcuts), a tolerance of 10 um
and chords within 0.1 mm. A quarter-pixel tolerance moves an edge by at most a quarter pixel,
so pixels on edges may differ at 1 spp; the image mean may not (a shift of edges changes a
mean only by the edges' share, here < 0.3 % of the pixels).
"""

import numpy as np
import pytest

import refracta
from refracta import _core, examples


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


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
    assert abs(fast.mean() - strict.mean()) <= 2e-4 * strict.mean()
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


def test_tabulating_a_field_that_is_not_height_only_returns_it():
    field = refracta.CustomField(lambda p: 1.0 + 1e-4 * p[:, 0], lambda p: np.tile([1e-4, 0.0, 0.0], (len(p), 1)))
    assert _core._tabulate_heights(field, 0.0, 10.0) is field
