"""Per-pixel transparency: exact compositing and its approximations (shared/MOMENTS.md 4)."""

import itertools

import numpy as np
import pytest

import refracta
import refracta.raster
from refracta import oit

# The published fp32 biases move the moments by <= 5e-5; transmittances follow to ~1e-4.
BIAS_TOLERANCE = 2e-4


def random_pixel(rng, count):
    return rng.uniform(1.0, 50.0, count), rng.uniform(0.05, 0.9, count), rng.uniform(0, 1, (count, 3))


def test_exact_is_front_to_back_compositing():
    depths, alphas = [3.0, 1.0, 2.0], [0.5, 0.25, 0.8]
    colors = [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    # Front to back: green (1 m), blue (2 m), red (3 m).
    expected = 0.25 * np.array([0, 1, 0]) + 0.75 * 0.8 * np.array([0, 0, 1]) + 0.75 * 0.2 * 0.5 * np.array([1, 0, 0])
    expected = expected + 0.75 * 0.2 * 0.5 * np.array([0.1, 0.2, 0.3])
    # A few products of exact inputs in double: rounding.
    np.testing.assert_allclose(oit.composite(depths, alphas, colors, (0.1, 0.2, 0.3)), expected, atol=1e-15)


def test_peeling_with_enough_layers_is_exact_and_fewer_drop_the_farthest(rng):
    depths, alphas, colors = random_pixel(rng, 6)
    exact = oit.composite(depths, alphas, colors, method="exact")
    np.testing.assert_array_equal(oit.composite(depths, alphas, colors, method="peel", layers=6), exact)
    near = np.argsort(depths)[:3]
    # The same compositing arithmetic on the same 3 layers: rounding.
    np.testing.assert_allclose(
        oit.composite(depths, alphas, colors, method="peel", layers=3),
        oit.composite(depths[near], alphas[near], colors[near]),
        atol=1e-15,
    )


VARIANTS = [("power", 4), ("power", 6), ("power", 8), ("trigonometric", 2), ("trigonometric", 3), ("trigonometric", 4)]


# fp32 storage sums in single precision: the order of the sums changes their rounding (2^-24 of
# each), which the biased Hankel matrix amplifies by at most ~1/bias (5e-7 .. 5e-5 for power moments,
# 2e-4 trigonometric): a bound of 2^-24 / 5e-7 = 0.12 in the worst case; measured <= 3e-5 here.
FP32_ORDER_TOLERANCE = 1e-3


@pytest.mark.parametrize("kind, moments", VARIANTS)
def test_mboit_is_order_independent(rng, kind, moments):
    depths, alphas, colors = random_pixel(rng, 5)
    for storage, tolerance in [("fp64", 1e-12), ("fp32", FP32_ORDER_TOLERANCE)]:
        args = dict(method="mboit", moments=moments, kind=kind, storage=storage)
        reference = oit.composite(depths, alphas, colors, **args)
        for order in itertools.islice(itertools.permutations(range(5)), 0, 120, 7):
            order = list(order)
            # Order independence: the moments are sums whose order only changes rounding (in double
            # for fp64: 1e-12).
            np.testing.assert_allclose(
                oit.composite(depths[order], alphas[order], colors[order], **args), reference, atol=tolerance
            )


@pytest.mark.parametrize("kind, moments", VARIANTS)
def test_mboit_total_transmittance_is_exact(rng, kind, moments):
    depths, alphas, _ = random_pixel(rng, 7)
    black = np.zeros((7, 3))
    exact = np.prod(1 - alphas)
    args = dict(method="mboit", moments=moments, kind=kind)
    result = oit.composite(depths, alphas, black, (1.0, 1.0, 1.0), storage="fp64", **args)
    # Black layers: the moments' total transmittance is exact up to double rounding.
    np.testing.assert_allclose(result, exact, rtol=1e-12)
    fp32 = oit.composite(depths, alphas, black, (1.0, 1.0, 1.0), storage="fp32", **args)
    # fp32 sums the 7 absorbances in single precision: ln T is off by at most 7 roundings of 2^-24.
    np.testing.assert_allclose(fp32, exact, rtol=7 * 2.0**-24 * -np.log(exact) + 1e-12)


def test_fp32_storage_rounds_the_moments_to_single_precision(rng):
    # A trial: 'fp32' summed in double, up to 3.4e-3 from a float emulation. Absorbances whose sum
    # float cannot hold: 1e-9 beside 6.9 is lost in fp32 and kept in fp64.
    depths, alphas, colors = [2.0, 40.0], [0.999, 1e-9], [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    args = dict(method="mboit", moments=4, beta=0.0, bias=0.0)
    fp32 = oit.composite(depths, alphas, colors, (0.0, 0.0, 0.0), storage="fp32", **args)
    fp64 = oit.composite(depths, alphas, colors, (0.0, 0.0, 0.0), storage="fp64", **args)
    assert not np.array_equal(fp32, fp64)
    for _ in range(50):
        depths, alphas, colors = random_pixel(rng, 5)
        args = dict(method="mboit", moments=4)
        # Single-precision rounding, amplified as above.
        np.testing.assert_allclose(
            oit.composite(depths, alphas, colors, storage="fp32", **args),
            oit.composite(depths, alphas, colors, storage="fp64", **args),
            atol=FP32_ORDER_TOLERANCE,
        )


@pytest.mark.parametrize("moments", [4, 6, 8])
def test_mboit_is_exact_for_up_to_n_plus_one_fragments_with_beta_zero(rng, moments):
    for count in range(1, moments // 2 + 2):
        depths, alphas, colors = random_pixel(rng, count)
        exact = oit.composite(depths, alphas, colors, (0.2, 0.3, 0.4))
        mboit = oit.composite(depths, alphas, colors, (0.2, 0.3, 0.4), method="mboit", moments=moments, beta=0.0)
        np.testing.assert_allclose(mboit, exact, atol=BIAS_TOLERANCE)


@pytest.mark.parametrize("kind, moments", VARIANTS)
def test_a_single_fragment_is_exact_for_any_beta(kind, moments):
    for beta in (0.0, 0.25, 1.0):
        # One layer: MBOIT's closed form, rounding only.
        np.testing.assert_allclose(
            oit.composite(
                [4.0], [0.6], [[0.9, 0.5, 0.1]], (0, 0, 1), method="mboit", beta=beta, kind=kind, moments=moments
            ),
            [0.54, 0.3, 0.06 + 0.4],
            atol=1e-12,
        )


@pytest.mark.parametrize("kind, counts", [("power", (4, 6, 8)), ("trigonometric", (2, 3, 4))])
def test_mboit_error_falls_with_more_moments(rng, kind, counts):
    errors = {m: [] for m in counts}
    for _ in range(200):
        depths, alphas, colors = random_pixel(rng, 8)
        exact = oit.composite(depths, alphas, colors)
        for m in errors:
            result = oit.composite(depths, alphas, colors, method="mboit", moments=m, kind=kind)
            errors[m].append(np.abs(result - exact).mean())
    means = [np.mean(errors[m]) for m in counts]
    assert means[0] > means[1] > means[2], means


def test_wboit_is_exact_for_one_fragment_and_keeps_coverage(rng):
    # Default rtol 1e-7: one fragment's closed form, rounding only.
    np.testing.assert_allclose(oit.composite([10.0], [0.4], [[1, 0, 0]], (0, 0, 1), method="wboit"), [0.4, 0, 0.6])
    depths, alphas, colors = random_pixel(rng, 5)
    for weight in ("eq7", "eq9"):
        result = oit.composite(depths, alphas, np.zeros((5, 3)), (1, 1, 1), method="wboit", weight=weight)
        # Black layers: WBOIT's total transmittance is the exact product, rounding only.
        np.testing.assert_allclose(result, np.prod(1 - alphas), rtol=1e-12)


@pytest.mark.parametrize("method", ["exact", "wboit", "mboit", "mboit_trig"])
def test_degenerate_pixels_never_give_nan(method):
    kind = "trigonometric" if method == "mboit_trig" else "power"
    method = "mboit" if method == "mboit_trig" else method
    # MBOIT's own keywords (the other methods refuse them).
    mboit = dict(kind=kind, moments=3 if kind == "trigonometric" else 4) if method == "mboit" else {}
    cases = [
        ([], [], np.zeros((0, 3))),
        ([5.0] * 4, [0.5] * 4, np.ones((4, 3))),
        ([2.0, 3.0], [1.0, 1.0], np.ones((2, 3))),
        ([2.0, 3.0], [0.0, 0.0], np.ones((2, 3))),
    ]
    for depths, alphas, colors in cases:
        result = oit.composite(
            depths,
            alphas,
            colors,
            (0.5, 0.5, 0.5),
            method=method,
            **mboit,
        )
        assert np.all(np.isfinite(result)), (depths, alphas)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(alphas=[1.5]), r"alphas\[0\] must be in \[0, 1\]"),
        (dict(depths=[np.nan]), "depths must be finite"),
        (dict(depths=[-1.0]), r"depths\[0\] must be > 0"),
        (dict(method="mboit", moments=5), "moments must be 4, 6 or 8"),
        (dict(method="sorted"), "method must be"),
        (dict(method="mboit", kind="complex"), "kind='complex': basis must be 'power' or 'trigonometric'"),
        (dict(method="mboit", basis="trigonometric", moments=6), "trigonometric moments must be 2, 3 or 4"),
        (dict(method="peel"), "needs layers"),
        (dict(colors=[[1, 0, 0], [0, 1, 0]]), "same fragments"),
    ],
)
def test_bad_arguments_raise(kwargs, message):
    args = dict(depths=[2.0], alphas=[0.5], colors=[[1, 0, 0]])
    args.update(kwargs)
    with pytest.raises(ValueError, match=message):
        oit.composite(**args)


# MBOIT's per-pixel fast path (the Hankel matrix factorised once, closed-form roots for 4 moments,
# Christoffel weights) against the generic canonical_bound (LDLT per query, companion-matrix
# roots, Vandermonde weights). 1e-5: the brief's round-off budget; the largest difference seen
# (2.8e-5 in w0 alone, 8 moments, atoms 1e-4 apart) is the Vandermonde solve's, which clamps a
# negative weight to 0 where the Christoffel number 1 / K(z, z) stays positive.
FAST_BOUND_TOLERANCE = 1e-5
FP32_BIAS = {
    4: ([0, 0.375, 0, 0.375], 5e-7),
    6: ([0, 0.48, 0, 0.451, 0, 0.45], 5e-6),
    8: ([0, 0.75, 0, 0.676667, 0, 0.63, 0, 0.600303], 5e-5),
}


@pytest.mark.parametrize("moments", [4, 6, 8])
def test_per_pixel_fast_bound_equals_the_general_solver(rng, moments):
    from refracta import _core

    target, strength = FP32_BIAS[moments]
    for trial in range(150):
        count = int(rng.integers(1, 12))
        atoms = rng.uniform(-1, 1, count)
        if trial % 3 == 0:  # near-degenerate: every atom within ~1e-4 of the first (Hankel nearly singular)
            atoms = atoms[0] + rng.normal(0.0, 1e-4, count)
        weights = rng.uniform(0.01, 1.0, count)
        weights /= weights.sum()
        b = np.array([np.sum(weights * atoms**j) for j in range(moments + 1)])
        b[1:] = (1 - strength) * b[1:] + strength * np.array(target)
        queries = np.concatenate([rng.uniform(-1.0, 1.0, 12), atoms, atoms + 1e-6])
        lower, at_query, fallback = _core._power_moment_bound(list(b), queries)
        for i, z in enumerate(queries):
            general = _core._canonical_bound(list(b), float(z))
            assert bool(fallback[i]) == general[2], (trial, z)
            assert abs(lower[i] - general[0]) <= FAST_BOUND_TOLERANCE, (trial, z, lower[i], general)
            assert abs((lower[i] + 0.25 * at_query[i]) - (general[0] + 0.25 * general[1])) <= FAST_BOUND_TOLERANCE


@pytest.mark.parametrize("moments", [4, 6, 8])
def test_fast_bound_falls_back_like_the_general_solver_on_a_singular_hankel_matrix(moments):
    from refracta import _core

    b = [0.3**j for j in range(moments + 1)]  # one atom at 0.3, unbiased: rank-1 Hankel matrix
    lower, at_query, fallback = _core._power_moment_bound(b, [0.1, 0.3, 0.7])
    assert np.all(fallback == 1.0) and np.all(lower == 0.0) and np.all(at_query == 1.0)
    assert all(_core._canonical_bound(b, z)[2] for z in (0.1, 0.3, 0.7))


@pytest.mark.parametrize("kind, moments", VARIANTS)
def test_a_clear_fragment_changes_nothing_even_first(rng, kind, moments):
    # alpha = 0 adds no absorbance; as the first fragment it once made the running normalisation
    # 0 / 0 and the whole pixel fell back to beta. A fixed warp range keeps the moments comparable.
    depths, alphas, colors = random_pixel(rng, 5)
    storages = ["fp32", "unorm16"] if kind == "power" or moments == 3 else ["fp32"]
    for storage in storages:
        options = dict(method="mboit", moments=moments, kind=kind, storage=storage, z_range=(0.5, 60.0))
        with_clear = oit.composite(
            np.r_[0.5 * depths.min(), depths],
            np.r_[0.0, alphas],
            np.r_[[[1, 1, 1]], colors],
            (0.2, 0.3, 0.4),
            **options,
        )
        plain = oit.composite(depths, alphas, colors, (0.2, 0.3, 0.4), **options)
        # A clear (alpha 0) fragment adds zeros: rounding only.
        np.testing.assert_allclose(with_clear, plain, atol=1e-12)


@pytest.mark.parametrize("moments", [4, 6, 8])
def test_sixteen_bit_moments_depend_on_the_fragments_order_by_rounding_only(moments):
    # A trial: 8 moments at 16 bits gave (0.34, 0.35, 0.31) for 4 of the 6 orders of these three
    # fragments and (0.027, 0.85, 0.11) for the other 2 and for fp32: rounding in the re-quantised
    # moments left the moment space and every fragment got the fallback's transmittance.
    depths, alphas, colors = np.array([35.0, 1.9, 19.1]), np.array([0.83, 0.87, 0.76]), np.eye(3)
    fp32 = oit.composite(depths, alphas, colors, method="mboit", moments=moments)
    for order in itertools.permutations(range(3)):
        order = list(order)
        stored = oit.composite(
            depths[order], alphas[order], colors[order], method="mboit", moments=moments, storage="unorm16"
        )
        # 16-bit rounding and the re-biased moments move the colour by ~1e-5 (4, 6 moments) and
        # 7.5e-4 (8: bias 5e-3 instead of 5e-4), against the method's own error of 0.016 here.
        np.testing.assert_allclose(stored, fp32, atol=1e-3)


def test_the_old_trig_spelling_still_works_with_a_warning():
    depths, alphas, colors = [2.0, 5.0, 9.0], [0.5, 0.3, 0.6], [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
    with pytest.warns(DeprecationWarning, match="trigonometric"):
        legacy = oit.composite(depths, alphas, colors, method="mboit", moments=3, kind="trig")
    np.testing.assert_array_equal(
        legacy, oit.composite(depths, alphas, colors, method="mboit", moments=3, basis="trigonometric")
    )


def test_composite_and_shadow_intensity_refuse_bools_and_strings_naming_them():
    # A trial: True was a depth of 1 and "0.5" an alpha of 0.5; mismatched colours failed in numpy.
    from refracta import moments

    with pytest.raises(ValueError, match="composite: alphas must be numbers"):
        oit.composite([1, 2], [True, "0.5"], [[1, 0, 0], [0, 1, 0]])
    with pytest.raises(ValueError, match=r"composite: colors must be \(r, g, b\) triples \(got shape \(2, 2\)\)"):
        oit.composite([1, 2, 3], [0.5] * 3, np.eye(2))
    assert np.allclose(oit.composite([1.0], [0.5], [1.0, 0.0, 0.0]), [0.5, 0.0, 0.0])  # one fragment, flat colour
    b = moments.power_moments(np.array([0.3]))
    with pytest.raises(ValueError, match="shadow_intensity: z_f must be numbers"):
        moments.shadow_intensity(b, True)
    with pytest.raises(ValueError, match="rasterize: guard_band must be a number"):
        refracta.raster.rasterize(refracta.Scene(), refracta.Camera((0, 1, 0), (1, 1, 0)), guard_band=True)
