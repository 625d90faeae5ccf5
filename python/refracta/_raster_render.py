"""refracta.render_raster: the real-time pipeline on the CPU (rasterized view, shadow maps).

Its options are refracta.RasterRenderOptions (with .shadow_map and .transparency); the keywords
render_raster takes besides `options` set those fields, through one table (_KEYWORDS). No default
is written here: a keyword left out keeps the C++ default.
"""

from __future__ import annotations

import copy
import warnings
from typing import Callable

import numpy as np

from refracta import _core
from refracta._progress import ProgressBar

# render_raster's keywords that name a nested field: keyword -> path of attributes from
# RasterRenderOptions. Any other keyword must be a field of RasterRenderOptions itself.
_KEYWORDS: dict[str, tuple[str, ...]] = {
    "resolution": ("shadow_map", "resolution"),
    "kernel": ("shadow_map", "kernel"),
    "depth_bias": ("shadow_map", "depth_bias"),
    "normal_offset": ("shadow_map", "normal_offset"),
    "bleeding_reduction": ("shadow_map", "bleeding_reduction"),
    "depth_range": ("shadow_map", "moments", "depth_range"),
    "storage": ("shadow_map", "moments", "storage"),
    "bias": ("shadow_map", "moments", "bias"),
    "bias_vector": ("shadow_map", "moments", "bias_vector"),
    "layers": ("transparency", "layers"),
    "weight": ("transparency", "weight"),
    "moments": ("transparency", "mboit", "moments"),
    "basis": ("transparency", "mboit", "basis"),
    "kind": ("transparency", "mboit", "basis"),
    "beta": ("transparency", "mboit", "beta"),
    "oit_storage": ("transparency", "mboit", "storage"),
}

# Spellings kept one release with a DeprecationWarning: MomentBasis 'trig' (now 'trigonometric').
_DEPRECATED_VALUES = {("basis", "trig"): "trigonometric"}


def assign(options, path: tuple[str, ...], value, keyword: str, owner: str) -> None:
    """Sets options.<path> = value; a refused value raises ValueError naming `keyword`."""
    target = options
    for name in path[:-1]:
        target = getattr(target, name)
        if target is None:
            raise ValueError(f"{owner}: {keyword}= sets {'.'.join(path)}, but {name} is None (set transparency=)")
    field = path[-1]
    if isinstance(value, str) and (field, value) in _DEPRECATED_VALUES:
        new = _DEPRECATED_VALUES[(field, value)]
        warnings.warn(
            f"{owner}: {keyword}={value!r} is deprecated; write {keyword}={new!r}", DeprecationWarning, stacklevel=4
        )
        value = new
    try:
        setattr(target, field, value)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{owner}: {keyword}={value!r}: {error}") from None


def _select_lights(lights):
    """(use the sun, spot indices or None for all) from render_raster's `lights`."""
    if lights is None:
        return True, None
    if isinstance(lights, str):
        if lights == "sun":
            return True, []
        if lights == "spots":
            return False, None
        raise ValueError(f"lights must be None, 'sun', 'spots' or a list of 'sun' and spot indices (got {lights!r})")
    use_sun, spots = False, []
    for light in lights:
        if light == "sun":
            use_sun = True
        elif isinstance(light, (int, np.integer)) and not isinstance(light, bool):
            spots.append(int(light))
        else:
            raise ValueError(f"lights entries must be 'sun' or spot-light indices (got {light!r})")
    return use_sun, spots


def raster_render_options(options=None, lights=None, shadows=None, transparency=None, **fields):
    """A validated copy of `options` (RasterRenderOptions, None: the defaults) with render_raster's
    keywords applied: lights, shadows (a ShadowMapOptions method, 'embree' or 'none'), transparency
    (an OIT method name, an OitSettings, or None), then each of `fields` (a None value: left as is)."""
    if options is None:
        result = _core.RasterRenderOptions()
    elif isinstance(options, _core.RasterRenderOptions):
        result = copy.deepcopy(options)  # through its fields (pickling): the caller's stays as it is
    else:
        raise ValueError(
            f"render_raster: options must be a refracta.RasterRenderOptions or None (got {type(options).__name__})"
        )
    if lights is not None:
        result.use_sun, result.spots = _select_lights(lights)
    if shadows is not None:
        try:
            result.shadows = shadows
        except (TypeError, ValueError):
            try:
                result.shadow_map.method = shadows
            except (TypeError, ValueError) as error:
                raise ValueError(
                    f"render_raster: shadows must be 'embree', 'none' or a ShadowMapOptions.method ({error})"
                ) from None
            result.shadows = "map"
    if isinstance(transparency, _core.OitSettings):
        result.transparency = transparency
    elif transparency is not None:
        if result.transparency is None:
            result.transparency = _core.OitSettings()
        assign(result, ("transparency", "method"), transparency, "transparency", "render_raster")
    for keyword, value in fields.items():
        if value is None:
            continue
        path = _KEYWORDS.get(keyword, (keyword,))
        if len(path) == 1 and not isinstance(getattr(type(result), keyword, None), property):
            raise ValueError(
                f"render_raster: unknown option {keyword!r} (keywords: lights, shadows, transparency, "
                f"{', '.join(_KEYWORDS)}, and any field of refracta.RasterRenderOptions)"
            )
        assign(result, path, value, keyword, "render_raster")
    result.validate()
    return result


def render_raster(
    scene: _core.Scene,
    camera: _core.Camera,
    lights=None,
    shadows: str | None = None,
    *,
    options: _core.RasterRenderOptions | None = None,
    transparency=None,
    return_stats: bool = False,
    stats: dict | None = None,
    progress: bool | Callable[[int, int], None] = False,
    **fields,
):
    """Render `scene` from `camera` by rasterization, the lights' shadows from shadow maps; returns
    float32 (H, W, 3) linear radiance (output='shadow': (H, W, 2)), or with return_stats=True the
    pair (image, refracta.RasterRenderStats: seconds, shadow_build_seconds, bytes_per_texel,
    transparent_fragments, oit_bytes_per_pixel). No atmosphere: this is the straight-ray view.

    The options are a refracta.RasterRenderOptions (`options`, or its defaults, defined once in
    C++: see help(refracta.RasterRenderOptions)), changed by these keywords (None or absent: left
    as they are):

    lights: which of the scene's lights shine: None (all: its sun and spot lights), "sun", "spots",
    or a list of "sun" and spot-light indices (as returned by Scene.add_spot_light).

    shadows: a shadow map's method (shadow_map.method: 'hard', one depth compare; 'pcf', k x k
    compares; 'vsm', 'msm_hamburger', 'msm_hausdorff': moments filtered k x k by separable running
    sums, cost independent of k), 'embree' (shadow rays: the reference) or 'none'. The sun's map
    covers the visible points within shadow_distance [m] (or shadow_centre, shadow_half_size [m]);
    spot lights get perspective maps covering their cones; 'embree' samples an area spot light
    (radius > 0) with 64 shadow rays (soft reference).

    transparency: None (every surface opaque), an OitSettings, or the name of its method: 'exact'
    (sorted), 'peel' (`layers` nearest), 'wboit' (McGuire & Bavoil, `weight` 'eq7' / 'eq9'),
    'mboit' (`moments` 4/6/8 power or 2/3/4 trigonometric with basis='trigonometric', overestimation
    `beta`, log depth warp over the frame's fragment range; oit_storage 'unorm16': the 16-bit ROV
    variant). Shadows treat every surface as opaque.

    Other keywords set fields (_KEYWORDS maps the flat ones to nested fields): resolution, kernel,
    depth_bias, normal_offset, bleeding_reduction (shadow_map); depth_range ('unit' [0, 1], I3D
    2015, or 'signed' [-1, 1], JCGT 2017), storage ('fp64', 'fp32', 'unorm16'), bias, bias_vector
    (shadow_map.moments; None: the published value for the storage and depth range); layers,
    weight, moments, basis (kind: its old name), beta, oit_storage (transparency); and any field
    of RasterRenderOptions: output ('radiance' or 'shadow': shadow intensity in [0, 1] and 1 where
    the light reaches the surface, zeros elsewhere, for the sun, shadow_light=-1, or the scene's
    spot light `shadow_light`), shadow_centre, shadow_half_size, shadow_distance, tile, light_strata.

    stats: deprecated (a dict filled with the statistics); use return_stats=True.
    """
    settings = raster_render_options(options, lights, shadows, transparency, **fields)
    if stats is not None:
        if not isinstance(stats, dict):
            raise ValueError(f"stats must be a dict to fill (got {type(stats).__name__})")
        warnings.warn(
            "render_raster(stats=dict) is deprecated: pass return_stats=True and read the returned RasterRenderStats",
            DeprecationWarning,
            stacklevel=2,
        )
    callback = ProgressBar("rasterizing") if progress is True else (progress or None)
    image, counts = _core._render_raster(scene, camera, settings, callback)
    if stats is not None:
        stats.update({name: getattr(counts, name) for name in dir(counts) if not name.startswith("_")})
    if settings.output == "shadow":
        image = image[..., :2]
    return (image, counts) if return_stats else image
