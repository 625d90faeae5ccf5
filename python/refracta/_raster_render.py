"""refracta.render_raster: the real-time pipeline on the CPU (rasterized view, shadow maps)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Callable

import numpy as np

from refracta import _core
from refracta._progress import ProgressBar

#: Shadow methods of render_raster: the classic shadow map, PCF, VSM, the two 4MSMs, the Embree
#: reference and none.
SHADOW_METHODS = {"hard": "hard", "pcf": "pcf", "vsm": "vsm", "msm_hamburger": "hamburger",
                  "msm_hausdorff": "hausdorff", "embree": "embree", "none": "none"}


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


def render_raster(
    scene: _core.Scene,
    camera: _core.Camera,
    lights=None,
    shadows: str = "msm_hamburger",
    *,
    resolution: int = 1024,
    kernel: int = 1,
    depth_range: str = "unit",
    bias: float | None = None,
    bias_vector: Sequence[float] | None = None,
    storage: str = "fp32",
    depth_bias: float = 2e-4,
    normal_offset: float = 1.5,
    bleeding_reduction: float = 0.0,
    shadow_centre=None,
    shadow_half_size: float | None = None,
    shadow_distance: float | None = None,
    output: str = "radiance",
    transparency: str | None = None,
    moments: int = 4,
    kind: str = "power",
    beta: float = 0.25,
    layers: int = 4,
    weight: str = "eq7",
    shadow_light: int = -1,
    oit_storage: str = "fp32",
    stats: dict | None = None,
    progress: bool | Callable[[int, int], None] = False,
) -> np.ndarray:
    """Render `scene` from `camera` by rasterization, the lights' shadows from shadow maps.

    lights: which of the scene's lights shine: None (all: its sun and spot lights), "sun", "spots",
    or a list of "sun" and spot-light indices (as returned by Scene.add_spot_light).

    shadows: 'hard' (one depth compare), 'pcf' (k x k compares), 'vsm', 'msm_hamburger',
    'msm_hausdorff' (moments filtered k x k by separable running sums, cost independent of k),
    'embree' (shadow rays: the reference) or 'none'. The map is `resolution`^2 texels over the
    visible points within shadow_distance [m] seen from the sun (or shadow_centre, shadow_half_size
    [m]). depth_range: 'unit' ([0, 1], I3D 2015) or 'signed' ([-1, 1], JCGT 2017); bias (alpha) and
    bias_vector default to the published values for the storage ('fp64', 'fp32': 3e-6 / 3e-7;
    'unorm16': 3e-5 / 6e-5 through the optimised quantisation transforms). depth_bias: hard / PCF
    compare offset (normalised depth); normal_offset: receivers moved along their normal, in texels;
    bleeding_reduction: VSM's light-bleeding reduction amount.
    output: 'radiance' (float32 (H, W, 3) linear) or 'shadow' ((H, W, 2): shadow intensity in [0, 1]
    and 1 where the light reaches the surface, zeros elsewhere) for the sun (shadow_light=-1) or the
    scene's spot light `shadow_light`. Spot lights get perspective shadow maps covering their cones;
    'embree' samples an area spot light (radius > 0) with 64 shadow rays (soft reference).
    transparency: None (every surface opaque) or how surfaces with alpha < 1 are composited over the
    opaque ones from the rasterizer's per-pixel fragment lists: 'exact' (sorted), 'peel' (`layers`
    nearest), 'wboit' (McGuire & Bavoil, weight 'eq7' / 'eq9'), 'mboit' (`moments` 4/6/8 power or
    2/3/4 trigonometric with kind='trig', overestimation `beta`, log depth warp over the frame's
    fragment range; oit_storage 'unorm16': the 16-bit ROV variant). Shadows treat every surface as
    opaque.
    stats: a dict to fill with 'seconds', 'shadow_build_seconds', 'bytes_per_texel',
    'transparent_fragments', 'oit_bytes_per_pixel'. No atmosphere: this is the straight-ray view.
    """
    use_sun, spots = _select_lights(lights)
    if shadows not in SHADOW_METHODS:
        raise ValueError(f"shadows must be one of {', '.join(SHADOW_METHODS)} (got {shadows!r})")
    if depth_range not in ("unit", "signed"):
        raise ValueError(f"depth_range must be 'unit' or 'signed' (got {depth_range!r})")
    if output not in ("radiance", "shadow"):
        raise ValueError(f"output must be 'radiance' or 'shadow' (got {output!r})")
    for name, value in (("resolution", resolution), ("kernel", kernel)):
        if isinstance(value, bool) or int(value) != value:
            raise ValueError(f"{name} must be a whole number (got {value!r})")
    if stats is not None and not isinstance(stats, dict):
        raise ValueError(f"stats must be a dict to fill (got {type(stats).__name__})")
    callback = ProgressBar("rasterizing") if progress is True else (progress or None)
    image, counts = _core._render_raster(
        scene, camera, SHADOW_METHODS[shadows], int(resolution), int(kernel), depth_range == "signed", bias,
        None if bias_vector is None else [float(v) for v in bias_vector], storage, depth_bias, normal_offset,
        bleeding_reduction, shadow_centre, shadow_half_size, shadow_distance, output == "shadow", transparency,
        int(moments), kind, float(beta), int(layers), weight, int(shadow_light), use_sun, spots,
        oit_storage, callback)
    if stats is not None:
        stats.update(counts)
    return image[..., :2] if output == "shadow" else image
