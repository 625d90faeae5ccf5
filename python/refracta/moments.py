"""Moment shadow mapping, one texel at a time (Peters & Klein 2015; Peters et al. 2017).

shadow_intensity(moments, z_f, method='msm_hamburger'|'msm_hausdorff'|'vsm'|'canonical',
depth_range='unit'|'signed', bias=None, bias_vector=None, storage='fp64'): the shadow intensity
(mass of the filtered depth distribution in front of z_f, a lower bound of PCF) from its power
moments (b1, b2, b3, b4), vectorised over leading axes. Depths are in [0, 1] ('unit', I3D 2015) or
[-1, 1] ('signed', JCGT 2017). bias and bias_vector default (None) to the published values of
refracta.MomentShadowSettings for the depth range and storage: fp64 / fp32 3e-6 toward
(0.5, 0.5, 0.5, 0.5) (unit) and 3e-7 toward (0, 0.375, 0, 0.375) (signed); unorm16 3e-5 / 6e-5.
'canonical' is the generic kernel (the canonical representation that MBOIT solves for 4, 6 and 8
moments) on these four moments, a cross-check of the closed forms.
The 4MSMs' old names 'hamburger' and 'hausdorff' still work, with a DeprecationWarning.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from refracta import _core
from refracta._checks import is_flag, is_seed, real_array
from refracta._warn import deprecated

# The moment methods use at most 8; beyond this, one numpy pass per moment made count=10**9 a hang
# (a trial), and z^1024 of a depth below 0.5 is already under double's smallest normal number.
_MOST_MOMENTS = 1024


def power_moments(depths, weights=None, count: int = 4) -> np.ndarray:
    """(b_1 .. b_count) of the distributions sum_l w_l delta(z_l) along the last axis (weights sum to 1)."""
    depths = real_array(depths, "power_moments: depths")
    if depths.ndim < 1 or depths.shape[-1] < 1:
        raise ValueError(f"power_moments: depths must hold at least one depth along the last axis (got {depths.shape})")
    if not (is_seed(count) and 1 <= count <= _MOST_MOMENTS):
        raise ValueError(f"power_moments: count must be a whole number in [1, {_MOST_MOMENTS}] (got {count!r})")
    if weights is None:
        weights = np.full_like(depths, 1.0 / depths.shape[-1])
    else:
        weights = real_array(weights, "power_moments: weights")
        if weights.shape != depths.shape:
            raise ValueError(f"power_moments: weights must have depths' shape {depths.shape} (got {weights.shape})")
    if not (np.all(np.isfinite(depths)) and np.all(np.isfinite(weights))):
        raise ValueError("power_moments: depths and weights must be finite")
    # A distribution: weights >= 0 summing to 1 (1e-9: a sum's rounding over many atoms).
    if np.any(weights < 0.0) or not np.allclose(weights.sum(axis=-1), 1.0, rtol=0.0, atol=1e-9):
        raise ValueError("power_moments: weights must be >= 0 and sum to 1 along the last axis")
    with np.errstate(over="ignore"):
        moments = np.stack([np.sum(weights * depths**j, axis=-1) for j in range(1, count + 1)], axis=-1)
    if not np.all(np.isfinite(moments)):
        raise ValueError(
            f"power_moments: the moments of these depths overflow (largest |z| = "
            f"{np.max(np.abs(depths)):g}; depths belong in [-1, 1])"
        )
    return moments


def quantize(moments, depth_range: str = "unit", inverse: bool = False) -> np.ndarray:
    """The optimised quantisation transform (unit: I3D 2015 dense; signed: JCGT 2017 Theta*_4) of
    (..., 4) moments, or its inverse. Moments of any depth in range map into [0, 1]^4."""
    moments = real_array(moments, "quantize: moments")
    if moments.shape[-1:] != (4,):
        raise ValueError(f"quantize: moments must have shape (..., 4) (got {moments.shape})")
    if not is_flag(inverse):
        raise ValueError(f"quantize: inverse must be True or False (got {inverse!r})")
    flat = np.ascontiguousarray(moments.reshape(-1, 4))
    return _core._quantize_moments(flat, depth_range, bool(inverse)).reshape(moments.shape)


# The 4MSMs' names before they matched render_raster's (kept one release, with a DeprecationWarning).
_OLD_METHODS = {"hamburger": "msm_hamburger", "hausdorff": "msm_hausdorff"}


def shadow_intensity(
    moments,
    z_f,
    method: str = "msm_hamburger",
    depth_range: str = "unit",
    bias: float | None = None,
    bias_vector: Sequence[float] | None = None,
    storage: str = "fp64",
) -> np.ndarray:
    """Shadow intensity in [0, 1] from (..., 4) moments at receiver depths (...).

    storage emulates how the moments were kept: 'fp64', 'fp32', or 'unorm16' (quantised through
    the optimised transform, as RGBA16_UNORM on a GPU, with the larger published bias)."""
    if method in _OLD_METHODS:
        deprecated(f"shadow_intensity: method {method!r} is now {_OLD_METHODS[method]!r}")
        method = _OLD_METHODS[method]
    settings = _core.MomentShadowSettings(
        depth_range=depth_range,
        storage=storage,
        bias=bias,
        bias_vector=None if bias_vector is None else list(real_array(bias_vector, "bias_vector", (4,))),
    )
    moments = real_array(moments, "shadow_intensity: moments")
    if moments.shape[-1:] != (4,):
        raise ValueError(f"moments must have shape (..., 4) (got {moments.shape})")
    z_f = real_array(z_f, "shadow_intensity: z_f")  # a bool or "0.5" was read as a depth
    shape = np.broadcast_shapes(moments.shape[:-1], z_f.shape)
    flat_b = np.broadcast_to(moments, shape + (4,)).reshape(-1, 4)
    flat_z = np.broadcast_to(z_f, shape).reshape(-1)
    out = _core._shadow_intensity(np.ascontiguousarray(flat_b), np.ascontiguousarray(flat_z), method, settings)
    return out.reshape(shape)
