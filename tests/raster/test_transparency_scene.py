"""Transparency over a rasterized scene: per-pixel fragment lists composited by each OIT method
(shared/MOMENTS.md 4), against the exact sorted composite."""

import numpy as np
import pytest

import refracta
from refracta import compare

CAMERA = refracta.Camera((-2, 2, 0), (14, 1.2, 0), (0, 1, 0), 30, 96, 60)
SLABS = [((0.9, 0.1, 0.1), 6.0, -0.5), ((0.1, 0.9, 0.1), 8.0, 0.0), ((0.1, 0.1, 0.9), 10.0, 0.5)]


def glass_scene(slabs=SLABS, alpha=0.5, wall=True):
    scene = refracta.Scene()
    scene.set_sun((-0.5, 0.6, 0.3), (2e4, 2e4, 2e4))
    scene.set_sky((0.5, 0.6, 0.8), (0.2, 0.3, 0.7))
    scene.add_ground(0.0, 200.0)
    if wall:
        scene.add_box((14, 1.5, 0), (1, 3, 6), kd=(0.8, 0.8, 0.8))
    for colour, x, z in slabs:
        scene.add_box((x, 1.5, z), (0.3, 2.5, 3), kd=colour, alpha=alpha)
    return scene


def test_error_falls_with_more_moments():
    rows, _ = compare.transparency(
        glass_scene(), CAMERA, methods=("wboit eq7", "mboit 4", "mboit 6", "mboit 8"), figure=False, shadows="embree"
    )
    error = {r["method"]: r["mean_error"] for r in rows}
    assert error["mboit 8"] < error["mboit 6"] < error["mboit 4"] < error["wboit eq7"]
    assert all(r["nan_count"] == 0 for r in rows)


# Exact in exact arithmetic; the moment bias and fp32 moments leave at most 1.7e-4 relative (the
# worst of 17280 pixel channels, measured, at a slab's edge where its two faces nearly meet in depth).
MBOIT_EXACT = 2e-4


def test_mboit_is_exact_for_up_to_n_plus_one_fragments_with_beta_zero():
    """One slab: two faces per pixel, fewer than the 3 atoms 4 power moments resolve."""
    scene = glass_scene(slabs=SLABS[:1])
    exact = refracta.render_raster(scene, CAMERA, shadows="embree", transparency="exact")
    mboit = refracta.render_raster(scene, CAMERA, shadows="embree", transparency="mboit", moments=4, beta=0.0)
    np.testing.assert_allclose(mboit, exact, rtol=MBOIT_EXACT, atol=1e-5 * exact.max())


@pytest.mark.parametrize(
    "storage, tolerance",
    [
        ("fp64", 1e-7),  # the sums in double, the image in float32: its rounding
        # Single-precision sums: their order changes their rounding (2^-24), amplified by the biased
        # Hankel matrix (bias 5e-6 for 6 moments); measured 1.3e-5 of the image's 0.8.
        ("fp32", 1e-3),
    ],
)
def test_compositing_does_not_depend_on_submission_order(storage, tolerance):
    args = dict(shadows="embree", transparency="mboit", moments=6, oit_storage=storage)
    forward = refracta.render_raster(glass_scene(SLABS), CAMERA, **args)
    backward = refracta.render_raster(glass_scene(SLABS[::-1]), CAMERA, **args)
    np.testing.assert_allclose(forward, backward, rtol=1e-6, atol=tolerance)


@pytest.mark.parametrize("method", ["exact", "wboit", "mboit"])
def test_total_transmittance_is_the_product_of_one_minus_alpha(method):
    """Black slabs (no reflection) in front of the sky: each pixel is the sky times (1 - alpha)^k,
    k the faces crossed, for every method (WBOIT and MBOIT keep the total transmittance exactly)."""
    alpha = 0.3
    slabs = [((0.0, 0.0, 0.0), 6.0, 0.0), ((0.0, 0.0, 0.0), 8.0, 0.0)]
    scene = glass_scene(slabs=slabs, alpha=alpha, wall=False)
    scene.set_sun((-0.5, 0.6, 0.3), (0.0, 0.0, 0.0))  # no sun: black surfaces reflect nothing
    image = refracta.render_raster(scene, CAMERA, shadows="none", transparency=method)
    sky = refracta.render_raster(glass_scene(slabs=[], wall=False), CAMERA, shadows="none")
    u, v, _ = CAMERA.project([7.0, 2.2, 0.0])  # above the ground's horizon, through both slabs
    np.testing.assert_allclose(image[int(v), int(u)], sky[int(v), int(u)] * (1 - alpha) ** 4, rtol=1e-5)


def test_an_opaque_render_ignores_alpha_and_stats_count_fragments():
    scene = glass_scene()
    _, stats = refracta.render_raster(scene, CAMERA, shadows="embree", transparency="exact", return_stats=True)
    assert stats.transparent_fragments > 0 and stats.oit_bytes_per_pixel > 0
    _, opaque_stats = refracta.render_raster(scene, CAMERA, shadows="embree", return_stats=True)
    assert opaque_stats.transparent_fragments == 0
    legacy = {}
    with pytest.warns(DeprecationWarning, match="return_stats"):
        refracta.render_raster(scene, CAMERA, shadows="embree", stats=legacy)
    assert legacy["transparent_fragments"] == 0 and legacy["seconds"] > 0


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(transparency="sorted"), "method must be"),
        (dict(transparency="mboit", moments=5), "power moments"),
        (dict(transparency="mboit", kind="exp"), "kind"),
        (dict(transparency="wboit", weight="eq8"), "weight"),
    ],
)
def test_bad_transparency_options_raise_value_error(kwargs, match):
    with pytest.raises(ValueError, match=match):
        refracta.render_raster(glass_scene(), CAMERA, shadows="embree", **kwargs)


def test_alpha_outside_0_1_is_rejected():
    with pytest.raises(ValueError, match="alpha"):
        refracta.Scene().add_box((0, 0, 0), (1, 1, 1), alpha=1.5)


@pytest.mark.parametrize("moments, kind", [(4, "power"), (6, "power"), (8, "power"), (3, "trigonometric")])
def test_16_bit_rov_mboit_stays_close_to_full_precision(moments, kind):
    """MOMENTS.md 4.5: b0 in fp32, normalised moments re-quantised to 16 bits after every fragment.
    Rounding makes it (slightly) order dependent; its error against the sorted composite stays that
    of the method in full precision (the larger 16-bit bias, 6e-5 toward (0, .628, 0, .628), moves
    single pixels by ~3 %)."""
    scene = glass_scene()
    exact = refracta.render_raster(scene, CAMERA, shadows="embree", transparency="exact")
    args = dict(shadows="embree", transparency="mboit", moments=moments, kind=kind)
    fp64 = refracta.render_raster(scene, CAMERA, oit_storage="fp64", **args)
    unorm16 = refracta.render_raster(scene, CAMERA, oit_storage="unorm16", **args)
    reordered = refracta.render_raster(glass_scene(SLABS[::-1]), CAMERA, oit_storage="unorm16", **args)
    scale = exact.max()
    assert np.abs(unorm16 - exact).mean() < np.abs(fp64 - exact).mean() + 1e-4 * scale
    assert np.abs(unorm16 - fp64).max() < 0.05 * scale
    assert np.abs(reordered - unorm16).max() < 5e-3 * scale  # rounding order: a few per mille
    _, stats = refracta.render_raster(scene, CAMERA, oit_storage="unorm16", return_stats=True, **args)
    per_moment = 2 * (2 * moments if kind == "trigonometric" else moments)
    assert stats.oit_bytes_per_pixel == 4 + per_moment + 8


@pytest.mark.parametrize("count", [6, 8])
def test_16_bit_mboit_transforms_keep_every_valid_moment_vector_in_range(count, rng):
    """The 6- and 8-moment quantisation maps moments of any distribution on [-1, 1] into [0, 1]
    (else rounding would clamp): the 16-bit round trip then costs only the rounding, < 2e-3."""
    from refracta import _core

    for _ in range(300):
        k = rng.integers(1, 6)
        z, w = rng.uniform(-1, 1, k), rng.dirichlet(np.ones(k))
        b = [float(np.sum(w * z**j)) for j in range(1, count + 1)]
        np.testing.assert_allclose(_core._mboit_unorm16(b), b, atol=2e-3)


def test_water_is_opaque_to_the_rasterizer():
    # Water's roughness overrode Material.alpha, the raster's opacity: a sea was blended as a layer
    # of opacity 0.17-0.40, and a red lamp 1 m under it showed through at ~83 % (a trial).
    import numpy as np

    from refracta import shading

    scene = refracta.Scene()
    lamp = np.array([[-50, -1, -50], [50, -1, -50], [50, -1, 50], [-50, -1, 50.0]])
    scene.add_mesh(lamp, np.array([[0, 2, 1], [0, 3, 2]]), emission=(5.0, 0.0, 0.0), material=shading.Diffuse(0.0))
    scene.add_ground(0.0, 100.0, material=shading.Water())
    scene.set_sky(1.0)
    camera = refracta.Camera((0, 3, 0), (0, 0, 3), vfov=20, width=20, height=20)
    assert shading.Material.alpha.fget(shading.Water()) == 1.0
    opaque = refracta.render_raster(scene, camera)
    exact, stats = refracta.render_raster(scene, camera, transparency="exact", return_stats=True)
    assert stats.transparent_fragments == 0
    np.testing.assert_array_equal(exact, opaque)  # the lamp stays hidden: no red through the sea


@pytest.mark.parametrize("fragments", [-1.0, float("nan"), float("inf")])
def test_bytes_per_pixel_refuses_impossible_fragment_counts(fragments):
    # A trial: -1 fragments a pixel cost -20 bytes, NaN and inf passed through.
    with pytest.raises(ValueError, match="bytes_per_pixel: fragments_per_pixel must be finite and >= 0"):
        refracta.OitSettings(method="exact").bytes_per_pixel(fragments)
    assert refracta.OitSettings(method="exact").bytes_per_pixel(2.5) == 50.0  # 20 bytes a fragment
