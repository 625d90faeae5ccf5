"""Order-independent transparency for one pixel's fragments (Muenstermann et al. 2018).

``composite(depths, alphas, colors, background=(0, 0, 0), method, *, options=None, **fields)`` -> RGB,
method 'exact', 'peel', 'wboit' or 'mboit'. depths are view depths (> 0), alphas in [0, 1], colors (K, 3)
linear RGB (not premultiplied). The settings are a refracta.OitSettings (`options`, or its C++
defaults) changed by keywords: layers, weight ('eq7' / 'eq9'), and MBOIT's moments, basis ('power'
or 'trigonometric'; kind is its old name), beta, bias (None: the published value), storage ('fp32',
'unorm16': a GPU's; 'fp64': the method itself), z_range (near, far) [m] (default: the fragments' range).
'exact' sorts (= depth peeling with enough layers); 'peel' keeps the `layers` nearest; 'wboit' is
McGuire & Bavoil 2013; 'mboit' is moment-based OIT with power moments or trigonometric ones
(wrapping zone pi/10) and a log depth warp; MBOIT clamps each alpha to 0.999 (as vkQuake's
implementation: its absorbance -ln(1 - alpha) must stay finite), so an opaque fragment lets 1e-3 of
what lies behind it through.
"""

from __future__ import annotations

import math

import numpy as np

from refracta import _core
from refracta._checks import finite_pair, real_array
from refracta._raster_render import refuse_unused, undeprecated

# composite's keywords that name a field of OitSettings.mboit: keyword -> its dotted path (the one
# keyword rule, _core._build_options, follows it); layers and weight are OitSettings' own.
_MBOIT_PATHS = {
    "moments": "mboit.moments",
    "basis": "mboit.basis",
    "kind": "mboit.basis",
    "beta": "mboit.beta",
    "bias": "mboit.bias",
    "storage": "mboit.storage",
}
# The method each keyword applies to (another method's keywords are refused, not ignored).
_METHOD_OF = {"layers": "peel", "weight": "wboit", "z_range": "mboit"} | dict.fromkeys(_MBOIT_PATHS, "mboit")


def oit_settings(method: str, options: _core.OitSettings | None = None, **fields) -> _core.OitSettings:
    """A validated copy of `options` (None: the defaults) with `method` and `fields` set."""
    keywords: dict = {"method": method}
    refuse_unused(method, fields, "composite", _METHOD_OF, "method")
    for keyword, value in fields.items():
        if value is None:
            continue
        if keyword == "z_range":
            near, far = finite_pair(value) or (math.nan, math.nan)
            if not (near > 0 and far > near):
                raise ValueError(f"composite: z_range must be (near, far) with 0 < near < far (got {value!r})")
            keywords["mboit.z_near"], keywords["mboit.z_far"] = float(near), float(far)
        elif keyword in _MBOIT_PATHS or keyword in ("layers", "weight"):
            keywords[keyword] = value
        else:
            raise ValueError(
                f"composite: unknown option {keyword!r} (layers, weight, z_range, {', '.join(_MBOIT_PATHS)})"
            )
    keywords = undeprecated(keywords, _MBOIT_PATHS, "composite")
    return _core._build_options(_core.OitSettings, options, "composite", keywords, _MBOIT_PATHS)


def composite(
    depths,
    alphas,
    colors,
    background=(0.0, 0.0, 0.0),
    method: str = "exact",
    *,
    options: _core.OitSettings | None = None,
    **fields,
) -> np.ndarray:
    """The pixel's colour after compositing its fragments over `background` (see the module's
    docstring for the keywords). 'peel' needs `layers` (here or in options)."""
    if method == "peel" and fields.get("layers") is None and options is None:
        raise ValueError("composite: method 'peel' needs layers")
    settings = oit_settings(method, options, **fields)
    # Named, bools and strings refused (True was a depth of 1, "0.5" an alpha of 0.5: a trial).
    depths = real_array(depths, "composite: depths").ravel()
    alphas = real_array(alphas, "composite: alphas").ravel()
    colors = real_array(colors, "composite: colors")
    if colors.size % 3:  # (the fragments' counts are the C++ check's)
        raise ValueError(f"composite: colors must be (r, g, b) triples (got shape {colors.shape})")
    colors = colors.reshape(-1, 3)
    near, far = settings.mboit.z_near, settings.mboit.z_far  # 0, 0: the fragments' own range
    if settings.method == "mboit" and far > 0.0 and depths.size and not (near <= depths.min() and depths.max() <= far):
        # MBOIT warps depths in the range to [-1, 1]: those beyond it leave the moments' domain.
        raise ValueError(
            f"composite: z_range ({near:g}, {far:g}) must hold every fragment's depth "
            f"(got {depths.min():g} to {depths.max():g})"
        )
    # Checked here: C++'s converter is the one for points, and named (x, y, z) for a colour.
    backdrop = real_array(background, "composite: background")
    if backdrop.shape != (3,):
        raise ValueError(f"composite: background must be a colour (r, g, b), shape (3,) (got shape {backdrop.shape})")
    return _core._composite(depths, alphas, colors, backdrop, settings)
