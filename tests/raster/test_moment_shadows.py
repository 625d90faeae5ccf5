"""Moment shadow mapping against PCF and its own invariants (shared/MOMENTS.md 1-3)."""

import numpy as np
import pytest

import refracta
from refracta import moments as M

# Closed forms and the generic kernel agree to round-off of a 3x3 solve with moments in [0, 1].
KERNEL_AGREEMENT = 1e-9


def random_texels(rng, count=400, atoms=6, signed=False):
    """Filtered depth distributions: `atoms` depths with random filter weights, and receiver depths."""
    lo = -1.0 if signed else 0.0
    depths = rng.uniform(lo, 1.0, size=(count, atoms))
    weights = rng.dirichlet(np.ones(atoms), size=count)
    z_f = rng.uniform(lo, 1.0, size=count)
    pcf = np.sum(weights * (depths < z_f[:, None]), axis=1)
    return M.power_moments(depths, weights), z_f, pcf


@pytest.mark.parametrize("depth_range", ["unit", "signed"])
def test_bounds_are_ordered_vsm_hamburger_hausdorff_pcf(rng, depth_range):
    b, z_f, pcf = random_texels(rng, signed=depth_range == "signed")
    alpha = 3e-6 if depth_range == "unit" else 3e-7
    vsm = M.shadow_intensity(b, z_f, "vsm", depth_range)
    hamburger = M.shadow_intensity(b, z_f, "msm_hamburger", depth_range)
    hausdorff = M.shadow_intensity(b, z_f, "msm_hausdorff", depth_range)
    tol = 1e-9
    assert np.all(vsm <= hamburger + tol)
    assert np.all(hamburger <= hausdorff + tol)
    # The biased distribution (1 - a) Z + a Z* has at most a/2 more mass in front (MOMENTS.md 2.2).
    assert np.all(hausdorff <= pcf + alpha / 2 + tol)
    assert np.mean(hausdorff > hamburger + 1e-6) > 0.0  # the support constraint does sharpen some


def test_generic_kernel_matches_the_closed_form(rng):
    b, z_f, _ = random_texels(rng)
    np.testing.assert_allclose(
        M.shadow_intensity(b, z_f, "canonical"), M.shadow_intensity(b, z_f, "msm_hamburger"), atol=KERNEL_AGREEMENT
    )


def test_shadow_intensity_never_decreases_with_receiver_depth(rng):
    b, _, _ = random_texels(rng, count=50)
    z = np.linspace(0.0, 1.0, 201)
    for method in ("vsm", "msm_hamburger", "msm_hausdorff"):
        s = M.shadow_intensity(b[:, None, :], z[None, :], method)
        assert np.all(np.diff(s, axis=1) >= -1e-9), method


def test_three_atoms_with_the_receiver_on_one_are_recovered_exactly():
    # With <= n + 1 atoms and z_f on one of them the canonical representation is the distribution.
    depths, weights = np.array([0.15, 0.4, 0.8]), np.array([0.5, 0.2, 0.3])
    b = M.power_moments(depths, weights)
    for z in depths:
        expected = weights[depths < z].sum()
        assert M.shadow_intensity(b, z, "canonical", bias=0.0) == pytest.approx(expected, abs=1e-9)
        assert M.shadow_intensity(b, z, "msm_hamburger", bias=0.0) == pytest.approx(expected, abs=1e-9)


def test_filtering_commutes_with_the_moment_map(rng):
    depths = rng.uniform(0, 1, size=(2, 5))
    weights = rng.dirichlet(np.ones(5), size=2)
    mix = 0.3
    joint = M.power_moments(np.concatenate(depths), np.concatenate([mix * weights[0], (1 - mix) * weights[1]]))
    filtered = mix * M.power_moments(depths[0], weights[0]) + (1 - mix) * M.power_moments(depths[1], weights[1])
    np.testing.assert_allclose(joint, filtered, atol=1e-15)


@pytest.mark.parametrize("method", ["vsm", "msm_hamburger", "msm_hausdorff", "canonical"])
def test_degenerate_texels_never_give_nan(method):
    cases = [
        M.power_moments(np.full(4, 0.5)),
        M.power_moments(np.zeros(4)),
        M.power_moments(np.ones(4)),
        M.power_moments(np.array([0.0, 1.0])),
    ]
    for b in cases:
        for bias in (None, 0.0):
            s = M.shadow_intensity(b, np.linspace(0, 1, 11), method, bias=bias)
            assert np.all(np.isfinite(s)) and np.all((s >= 0) & (s <= 1))


def test_bad_arguments_raise():
    with pytest.raises(ValueError, match="method"):
        M.shadow_intensity(np.zeros(4), 0.5, "pcf")
    with pytest.raises(ValueError, match=r"\(\.\.\., 4\)"):
        M.shadow_intensity(np.zeros(3), 0.5)
    with pytest.raises(ValueError, match="depth_range"):
        M.shadow_intensity(np.zeros(4), 0.5, depth_range="half")
    with pytest.raises(ValueError, match="finite"):
        M.shadow_intensity([np.nan, 0, 0, 0], 0.5)


@pytest.mark.parametrize("depth_range, lo", [("unit", 0.0), ("signed", -1.0)])
def test_quantization_transforms_stay_in_the_unit_cube_and_round_trip(rng, depth_range, lo):
    z = np.linspace(lo, 1.0, 2001)
    q = M.quantize(M.power_moments(z[:, None]), depth_range)
    # MOMENTS.md: min ~ -6e-8 (the published constants' rounding), max ~ 1.
    assert q.min() >= -1e-7 and q.max() <= 1.0 + 1e-7
    b, _, _ = random_texels(rng, signed=depth_range == "signed")
    np.testing.assert_allclose(M.quantize(M.quantize(b, depth_range), depth_range, inverse=True), b, atol=1e-9)


def test_unorm16_storage_needs_its_larger_bias(rng):
    b, z_f, pcf = random_texels(rng)
    s = M.shadow_intensity(b, z_f, "msm_hamburger", storage="unorm16", bias=3e-5)
    assert np.all(np.isfinite(s))
    assert np.all(s <= pcf + 3e-5 / 2 + 2e-3)  # 16-bit rounding moves the bound by ~1e-3
    assert np.abs(s - M.shadow_intensity(b, z_f, "msm_hamburger", bias=3e-5)).mean() < 5e-3


def test_the_old_method_names_still_work_with_a_warning(rng):
    b, z_f, _ = random_texels(rng)
    for old, new in (("hamburger", "msm_hamburger"), ("hausdorff", "msm_hausdorff")):
        with pytest.warns(DeprecationWarning, match=new):
            legacy = M.shadow_intensity(b, z_f, old)
        np.testing.assert_array_equal(legacy, M.shadow_intensity(b, z_f, new))


@pytest.mark.parametrize("depth_range", ["unit", "signed"])
@pytest.mark.parametrize("storage", ["fp64", "fp32", "unorm16"])
def test_no_bias_means_the_published_one_for_the_storage(rng, depth_range, storage):
    # MomentShadowSettings.bias None: published_bias(depth_range, storage), the value render_raster's
    # shadow maps use too (one rule, in C++).
    b, z_f, _ = random_texels(rng, signed=depth_range == "signed")
    published = refracta.MomentShadowSettings.published_bias(depth_range, storage)
    assert (
        published
        == {
            ("unit", "unorm16"): 3e-5,
            ("signed", "unorm16"): 6e-5,
            ("unit", "fp32"): 3e-6,
            ("signed", "fp32"): 3e-7,
            ("unit", "fp64"): 3e-6,
            ("signed", "fp64"): 3e-7,
        }[(depth_range, storage)]
    )
    np.testing.assert_array_equal(
        M.shadow_intensity(b, z_f, depth_range=depth_range, storage=storage),
        M.shadow_intensity(b, z_f, depth_range=depth_range, storage=storage, bias=published),
    )


def test_array_checks_moved_into_the_library_name_their_argument():
    """raster/moment_arrays.cpp: receiver depths must be finite; the fast MBOIT bound takes 4, 6 or 8 moments."""
    with pytest.raises(ValueError, match="z_f must be finite"):
        M.shadow_intensity([0.5, 0.3, 0.2, 0.1], np.nan)
    from refracta import _core

    with pytest.raises(ValueError, match="m = 4, 6 or 8"):
        _core._power_moment_bound([1.0, 0.5, 0.3], [0.5])
