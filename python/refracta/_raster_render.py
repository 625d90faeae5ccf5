"""refracta.render_raster: the real-time pipeline on the CPU (rasterized view, shadow maps).

Its options are refracta.RasterRenderOptions (with .shadow_map and .transparency); the keywords
render_raster takes besides `options` set those fields through the package's one keyword rule
(_core._build_options; _PATHS maps the flat names to nested fields). No default is written here:
a keyword left out keeps the C++ default.
"""

from __future__ import annotations

from typing import Callable

import numpy as np

from refracta import _core
from refracta._checks import flag
from refracta._progress import progress_callback
from refracta._render import _check_scene
from refracta._warn import deprecated

# render_raster's keywords that name a nested field of RasterRenderOptions: keyword -> its dotted
# path, which the one keyword rule (_core._build_options) follows. Any other keyword must be a
# field of RasterRenderOptions itself.
_PATHS: dict[str, str] = {
    "resolution": "shadow_map.resolution",
    "kernel": "shadow_map.kernel",
    "depth_bias": "shadow_map.depth_bias",
    "normal_offset": "shadow_map.normal_offset",
    "bleeding_reduction": "shadow_map.bleeding_reduction",
    "depth_range": "shadow_map.moments.depth_range",
    "storage": "shadow_map.moments.storage",
    "bias": "shadow_map.moments.bias",
    "bias_vector": "shadow_map.moments.bias_vector",
    "layers": "transparency.layers",
    "weight": "transparency.weight",
    "moments": "transparency.mboit.moments",
    "basis": "transparency.mboit.basis",
    "kind": "transparency.mboit.basis",
    "beta": "transparency.mboit.beta",
    "oit_storage": "transparency.mboit.storage",
}

# The keywords that configure one transparency method: given with another they would change nothing,
# so render_raster refuses them (with every surface opaque, _build_options refuses them already).
_TRANSPARENCY_METHOD_OF = {"layers": "peel", "weight": "wboit"}
_TRANSPARENCY_METHOD_OF.update(dict.fromkeys(("moments", "basis", "kind", "beta", "oit_storage"), "mboit"))


# The keywords that configure some shadow methods only (a ShadowMapOptions.method, or 'embree' and
# 'none', which use no map): given with another they changed nothing (a trial: shadows='hard' with
# kernel=9, 'pcf' with storage=).
_MAPS = ("hard", "pcf", "vsm", "msm_hamburger", "msm_hausdorff")
_MOMENT_MAPS = ("vsm", "msm_hamburger", "msm_hausdorff")
_SHADOW_METHODS_OF: dict[str, str | tuple[str, ...]] = dict.fromkeys(
    ("resolution", "normal_offset", "shadow_centre", "shadow_half_size", "shadow_distance"), _MAPS
)
_SHADOW_METHODS_OF.update(kernel=("pcf", *_MOMENT_MAPS), depth_bias=("hard", "pcf"), bleeding_reduction="vsm")
_SHADOW_METHODS_OF.update(dict.fromkeys(("depth_range", "storage", "bias", "bias_vector"), _MOMENT_MAPS))


def shadow_fields_for(method: str, fields: dict) -> dict:
    """The entries of `fields` (render_raster keywords) that shadows=`method` uses: the others would
    be refused (compare.shadows gives each method its own)."""
    uses = {k: (v,) if isinstance(v, str) else v for k, v in _SHADOW_METHODS_OF.items()}
    return {k: v for k, v in fields.items() if k not in uses or method in uses[k]}


def refuse_unused(
    method: str, fields: dict, owner: str, method_of: dict[str, str] | dict[str, str | tuple[str, ...]], name: str
) -> None:
    """ValueError for a keyword of `fields` given (not None) that only the method (or methods)
    method_of[keyword] use, when `method` (the argument `name`) is another."""
    for keyword, value in fields.items():
        wanted = method_of.get(keyword)
        if value is None or wanted is None:
            continue
        methods = (wanted,) if isinstance(wanted, str) else wanted
        if method not in methods:
            listed = " or ".join(repr(m) for m in methods)
            raise ValueError(f"{owner}: {keyword} applies to {name}={listed}, not with {name}={method!r}")


# Spellings kept one release with a DeprecationWarning: MomentBasis 'trig' (now 'trigonometric').
_DEPRECATED_VALUES = {("basis", "trig"): "trigonometric"}


def undeprecated(fields: dict, paths: dict[str, str], owner: str) -> dict:
    """`fields` with deprecated values (_DEPRECATED_VALUES, by the field a keyword sets) replaced,
    each with a DeprecationWarning naming the keyword."""
    for keyword, value in fields.items():
        field = paths.get(keyword, keyword).rsplit(".", 1)[-1]
        if isinstance(value, str) and (field, value) in _DEPRECATED_VALUES:
            new = _DEPRECATED_VALUES[(field, value)]
            deprecated(f"{owner}: {keyword}={value!r} is deprecated; write {keyword}={new!r}")
            fields[keyword] = new
    return fields


def _select_lights(lights):
    """(use the sun, spot indices or None for all) from render_raster's `lights`."""
    if isinstance(lights, str):
        if lights == "sun":
            return True, []
        if lights == "spots":
            return False, None
        raise ValueError(f"lights must be None, 'sun', 'spots' or a list of 'sun' and spot indices (got {lights!r})")
    if isinstance(lights, _core.IndexField):
        raise ValueError(
            "lights must be None, 'sun', 'spots' or a list of 'sun' and spot indices (got an index field: "
            "render_raster takes no atmosphere; render(..., method='raster_march') marches rays through one)"
        )
    if not isinstance(lights, (list, tuple, np.ndarray)):
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


def _shadow_fields(shadows) -> dict:
    """render_raster's `shadows` as fields: a RasterRenderOptions.shadows source ('embree', 'none',
    'map') or a ShadowMapOptions.method (then shadows='map'); which one, the bound classes say."""
    probe = _core.RasterRenderOptions()
    try:
        probe.shadows = shadows
        return {"shadows": shadows}
    except (TypeError, ValueError):
        pass
    try:
        probe.shadow_map.method = shadows
    except (TypeError, ValueError) as error:
        raise ValueError(
            f"render_raster: shadows must be 'embree', 'none' or a ShadowMapOptions.method ({error})"
        ) from None
    return {"shadows": "map", "shadow_map.method": shadows}


def raster_render_options(options=None, lights=None, shadows=None, transparency=None, **fields):
    """A validated copy of `options` (RasterRenderOptions, None: the defaults) with render_raster's
    keywords applied: lights, shadows (a ShadowMapOptions method, 'embree' or 'none'), transparency
    (an OIT method name, an OitSettings, or None), then each of `fields` (a None value: left as is),
    all through the one keyword rule (_core._build_options, with _PATHS for the flat names)."""
    keywords: dict = {}
    if lights is not None:
        both = [name for name in ("use_sun", "spots") if fields.get(name) is not None]
        if both:  # lights=["sun"] with spots=[0] lit spot 0 all the same
            raise ValueError(
                f"render_raster: give lights= or {' and '.join(both)}=, not both (they select the same lights)"
            )
        keywords["use_sun"], keywords["spots"] = _select_lights(lights)
    if fields.get("shadow_light") is not None and fields.get("output") != "shadow":
        output = options.output if isinstance(options, _core.RasterRenderOptions) else None
        if output != "shadow":  # it picks the light whose shadow output='shadow' shows: else ignored
            raise ValueError("render_raster: shadow_light applies to output='shadow'")
    if shadows is not None:
        keywords.update(_shadow_fields(shadows))
    if isinstance(transparency, _core.OitSettings):
        keywords["transparency"] = transparency
    elif transparency is not None:
        given = options.transparency if isinstance(options, _core.RasterRenderOptions) else None
        if given is None:
            keywords["transparency"] = _core.OitSettings()
        keywords["transparency.method"] = transparency
    keywords.update(undeprecated({k: v for k, v in fields.items() if v is not None}, _PATHS, "render_raster"))
    settings = _core._build_options(_core.RasterRenderOptions, options, "render_raster", keywords, _PATHS)
    shadow_method = settings.shadow_map.method if settings.shadows == "map" else settings.shadows
    refuse_unused(shadow_method, fields, "render_raster", _SHADOW_METHODS_OF, "shadows")
    if settings.transparency is not None:
        refuse_unused(settings.transparency.method, fields, "render_raster", _TRANSPARENCY_METHOD_OF, "transparency")
    return settings


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
    transparent_fragments, oit_bytes_per_pixel). No refraction: this is the straight-ray view
    (its air's haze, a physical sky's aerial perspective, is applied as the ray renderers apply it).

    The options are a refracta.RasterRenderOptions (`options`, or its defaults, defined once in
    C++: see help(refracta.RasterRenderOptions)), changed by these keywords (None or absent: left
    as they are):

    lights: which of the scene's sun and spot lights shine: None (all), "sun", "spots", or a list
    of "sun" and spot-light indices (as returned by Scene.add_spot_light). Its other lights (point,
    sphere and area lights, the sky and environment maps) always shine, each by light_strata^2
    light samples and as many BSDF samples, MIS-combined; lights=[] leaves them on.

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

    Other keywords set fields (_PATHS maps the flat ones to nested fields): resolution, kernel,
    depth_bias, normal_offset, bleeding_reduction (shadow_map); depth_range ('unit' [0, 1], I3D
    2015, or 'signed' [-1, 1], JCGT 2017), storage ('fp64', 'fp32', 'unorm16'), bias, bias_vector
    (shadow_map.moments; None: the published value for the storage and depth range); layers,
    weight, moments, basis (kind: its old name), beta, oit_storage (transparency); and any field
    of RasterRenderOptions: output ('radiance' or 'shadow': shadow intensity in [0, 1] and 1 where
    the light reaches the surface, zeros elsewhere, for the sun, shadow_light=-1, or the scene's
    spot light `shadow_light`), shadow_centre, shadow_half_size, shadow_distance, tile, light_strata.
    A keyword that only other methods use (kernel with 'hard', storage with 'pcf', any map keyword
    with 'embree'; shadow_light without output='shadow') raises ValueError, as lights= with
    use_sun= or spots= does.

    stats: deprecated (a dict filled with the statistics); use return_stats=True.
    """
    settings = raster_render_options(options, lights, shadows, transparency, **fields)
    named_sun = lights == "sun" if isinstance(lights, str) else isinstance(lights, (list, tuple)) and "sun" in lights
    has_sun = isinstance(scene, _core.Scene) and any(isinstance(light, _core.SunLight) for light in scene.lights)
    if named_sun and isinstance(scene, _core.Scene) and not has_sun:  # it rendered the others without a word
        raise ValueError(
            "render_raster: lights names the sun, but the scene has none (Scene.set_sun or set_physical_sky)"
        )
    flag(return_stats, "render_raster: return_stats")  # 'no' would return the statistics too
    if stats is not None:
        if not isinstance(stats, dict):
            raise ValueError(f"stats must be a dict to fill (got {type(stats).__name__})")
        deprecated(
            "render_raster(stats=dict) is deprecated: pass return_stats=True and read the returned RasterRenderStats"
        )
    callback = progress_callback(progress, "rasterizing")
    image, counts = _core._render_raster(scene, camera, settings, callback)
    _check_scene(scene, camera, None, "raster", where="render_raster")
    if stats is not None:
        stats.update({name: getattr(counts, name) for name in dir(counts) if not name.startswith("_")})
    if settings.output == "shadow":
        image = image[..., :2]
    return (image, counts) if return_stats else image
