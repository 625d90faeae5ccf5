"""Shadow maps from the CPU rasterizer, against Embree shadow rays and PCF (shared/MOMENTS.md)."""

import numpy as np
import pytest

import refracta
from refracta import compare


def boxes_in_sun():
    scene = refracta.Scene()
    scene.set_sun((-0.5, 0.6, 0.3), (2e4, 2e4, 2e4))
    scene.set_sky((0.5, 0.6, 0.8), (0.2, 0.3, 0.7))
    scene.add_ground(0.0, 200.0)
    scene.add_box((10, 2, 0), (2, 4, 2))
    scene.add_box((16, 1, 3), (3, 2, 1))
    scene.add_box((6, 0.5, -4), (1, 1, 1))
    return scene


CAMERA = refracta.Camera((-5, 8, -10), (10, 0, 0), (0, 1, 0), 50, 128, 80)
MAP = dict(resolution=512, shadow_distance=60.0)


def shadow(method, **kwargs):
    map_fields = MAP if method != "embree" else {}  # shadow rays use no map
    return refracta.render_raster(boxes_in_sun(), CAMERA, shadows=method, output="shadow", **map_fields, **kwargs)


def test_a_hard_shadow_map_matches_shadow_rays_away_from_edges():
    truth, mapped = shadow("embree"), shadow("hard")
    valid = (truth[..., 1] > 0) & (mapped[..., 1] > 0)
    in_shadow, lit = valid & (truth[..., 0] == 1), valid & (truth[..., 0] == 0)
    assert in_shadow.sum() > 50  # there are shadows to get right
    # Texels are 12 cm here: only pixels within a texel or two of an edge may differ.
    assert np.mean(mapped[..., 0][in_shadow] == 1) > 0.85
    assert np.mean(mapped[..., 0][lit] == 0) > 0.99  # lit pixels stay lit but within a texel of an edge (comment above)


# The raster pipeline's sky quadrature (8 x 8 BSDF strata per pixel) against the ray tracer's
# unbiased estimate: measured 0.3 % apart over the whole image; 1 % allows the quadrature error.
RASTER_QUADRATURE = 0.01


def test_radiance_with_shadow_rays_equals_the_straight_renderer():
    """Rasterized shading with Embree shadow rays estimates what the ray tracer estimates: its
    difference from a 64-seed mean of pixel-centre ray-traced renders stays within that mean's own
    noise (the difference between two such means), and the image means agree."""
    scene = boxes_in_sun()
    rasterized = refracta.render_raster(scene, CAMERA, shadows="embree")
    traced = [
        np.mean(
            [
                refracta.render(scene, CAMERA, None, method="straight", progress=False, seed=first + k)
                for k in range(64)
            ],
            axis=0,
        )
        for first in (0, 1000)
    ]
    scale = traced[0].max(axis=2) + 1e-6
    difference = np.abs(rasterized - traced[0]).max(axis=2) / scale
    noise = np.abs(traced[1] - traced[0]).max(axis=2) / scale
    for percentile in (50, 90):
        assert np.percentile(difference, percentile) <= np.percentile(noise, percentile)
    assert abs(rasterized.mean() - traced[0].mean()) < RASTER_QUADRATURE * traced[0].mean()


@pytest.mark.parametrize("kernel", [5, 9])
def test_filtered_moments_approach_pcf_with_the_same_kernel(kernel):
    rows, _ = compare.shadows(
        boxes_in_sun(),
        CAMERA,
        methods=("vsm", "msm_hamburger", "msm_hausdorff"),
        kernels=(kernel,),
        figure=False,
        **MAP,
    )
    errors = {r["method"]: r for r in rows}
    for r in rows:
        assert r["reference"] == f"pcf {kernel}x{kernel}" and r["nan_count"] == 0
        assert r["mean_error"] < 0.01  # filtered moments vs PCF of the same kernel: leak and bias of 1 % of full shadow
    # MOMENTS.md: Hamburger's bound is sharper than VSM's.
    assert errors["msm_hamburger"]["p99_error"] <= errors["vsm"]["p99_error"] + 1e-9


# The bounds are evaluated from fp32-filtered moments: their rounding (6e-8 relative), amplified by
# the 3 x 3 Hankel solve, reaches 1.3e-6 (measured); 2e-6 is rounding, not an ordering error.
ORDER_ROUNDING = 2e-6


def test_vsm_hamburger_hausdorff_are_ordered_per_pixel():
    """All three read the same filtered moments: VSM <= Hamburger <= Hausdorff (MOMENTS.md 2.4)."""
    vsm, hamburger, hausdorff = (shadow(m, kernel=7)[..., 0] for m in ("vsm", "msm_hamburger", "msm_hausdorff"))
    assert np.all(vsm <= hamburger + ORDER_ROUNDING)
    assert np.all(hamburger <= hausdorff + ORDER_ROUNDING)


@pytest.mark.parametrize("storage, depth_range", [("unorm16", "unit"), ("unorm16", "signed"), ("fp32", "signed")])
def test_storage_and_depth_range_change_little(storage, depth_range):
    reference = shadow("msm_hamburger", kernel=5, storage="fp64")[..., 0]
    other = shadow("msm_hamburger", kernel=5, storage=storage, depth_range=depth_range)[..., 0]
    assert np.all(np.isfinite(other))
    # unorm16's larger bias (3e-5 / 6e-5) lightens shadows slightly; the mean change stays small.
    assert np.abs(other - reference).mean() < 0.01


def test_compare_reports_bits_and_times():
    rows, fig = compare.shadows(
        boxes_in_sun(), CAMERA, methods=("hard", "msm_hamburger"), kernels=(1, 3), storage="unorm16", **MAP
    )
    bits = {(r["method"], r["kernel"]): r["bits_per_texel"] for r in rows}
    assert bits[("hard", 1)] == 32 and bits[("msm_hamburger", 3)] == 64
    assert all(r["seconds"] > 0 for r in rows)
    assert len(fig.axes) >= 4
    assert "msm_hamburger" in compare.format_table(rows)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(kernel=4), "kernel"),
        (dict(resolution=1), "resolution"),
        (dict(shadows="pcss"), "shadows must be"),
        (dict(storage="fp16"), "storage"),
        (dict(depth_range="half"), "depth_range"),
        (dict(bias=1.5), "bias"),
    ],
)
def test_bad_shadow_options_raise_value_error(kwargs, match):
    args = dict(shadows="msm_hamburger")
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        refracta.render_raster(boxes_in_sun(), CAMERA, **args)


def test_a_wide_ground_does_not_spread_the_suns_map_over_kilometres():
    # A trial (notebook 03's scene on a 2 km ground): the sun's map was fitted to every visible point,
    # the ground to its far edge, and at radii 1800-2100 m the 1.6 m boxes lost every shadow (0 of
    # Embree's 84 pixels). It is now fitted to the visible points some geometry lies over
    # (raster_visibility.cpp caster_bounds). Measured: 81-83 of 84 at 1500, 2000 and 2500 m.
    camera = refracta.Camera((-6, 3, -16), (12, 0, 0), (0, 1, 0), 60, 160, 100)
    for radius in (1500.0, 2000.0):
        scene = refracta.Scene()
        scene.set_sun((-0.5, 0.6, 0.3), (2e4,) * 3)
        scene.add_ground(0.0, radius)
        for i in range(4):
            for j in range(3):
                scene.add_box((4.0 + 6.0 * i, 0.8 + 0.5 * ((i + j) % 3), -6.0 + 6.0 * j), (1.6, 1.6 + (i + j) % 3, 1.6))

        def shadowed(scene=scene, **options):
            return int((refracta.render_raster(scene, camera, output="shadow", **options)[..., 0] > 0.5).sum())

        reference = shadowed(shadows="embree")
        assert reference > 50
        # Edge pixels may differ by a texel's filtering: within 10 % of the ray-traced count.
        for method in ("hard", "pcf", "msm_hamburger"):
            assert abs(shadowed(shadows=method) - reference) <= 0.1 * reference, (radius, method)
