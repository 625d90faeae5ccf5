"""refracta.render: images of a scene seen through an atmosphere."""

from __future__ import annotations

from typing import Callable, Optional, Union

import numpy as np

from refracta import _core
from refracta._progress import ProgressBar


def render(
    scene: _core.Scene,
    camera: _core.Camera,
    field: Optional[_core.IndexField] = None,
    method: str = "curved",
    spp: int = 1,
    seed: int = 0,
    progress: Union[bool, Callable[[int, int], None]] = True,
    max_length: float = 5000.0,
    chord: float = 200.0,
    sagitta: float = 1e-3,
    tol: float = 1e-4,
    table: bool = True,
    integrator: Optional[str] = None,
    march: str = "rk45",
    step: float = 0.3,
    max_steps: int = 1000,
    guard_band: float = 0.1,
    texture_filter: bool = True,
    stats: Optional[dict] = None,
) -> np.ndarray:
    """Render `scene` from `camera` through `field`; returns linear HDR radiance, float32 (H, W, 3).

    method: 'curved' -- exact curved rays: the integrator's path (stratified for height-only
    fields, rk45 otherwise, to `tol` [m]) cut into chords tested against the scene -- at most
    `chord` [m] long and never farther than `sagitta` [m] from the path -- hits refined on the
    continuous path (height-only fields: every pixel served from one ElevationTable for the
    eye height, interpolated to `tol`; table=False traces each pixel; integrator='rk45' forces rk45
    per pixel); rays end after `max_length` [m] and show the sky in
    their last direction. 'straight' -- ray casting without atmosphere (the reference). With
    field=None both are straight. 'raster_march' -- the original editor's method: the scene is
    rasterized from the camera (with `guard_band`, a fraction of the image added on each side)
    and each pixel's curved ray is marched ('rk45' to `tol` over max_length, or march='rk4' with
    `step` [m] for at most `max_steps` steps: the original's 0.3 m x 1000) until a step lands
    behind the depth buffer; that raster pixel's colour is shown. It cannot show what no raster
    pixel shows (outside the view, hidden, beyond the curved Earth's horizon). Textures are filtered
    by OpenImageIO over each sample's ray-cone footprint (texture_filter=False point-samples them:
    only for references). stats: a dict to fill with counts ('samples', 'chords': Embree queries
    along the paths; raster_march does not count its marching). spp: samples per pixel (1: pixel centres; more: stratified
    jitter, soft sun shadows), seeded by `seed`. progress: a bar on stderr (True), a callable
    progress(done, total), or False. Runs on all cores with the GIL released; Ctrl-C stops it.
    """
    if isinstance(spp, bool) or int(spp) != spp:
        raise ValueError(f"spp must be a whole number >= 1 (got {spp!r})")
    if int(seed) != seed or seed < 0:
        raise ValueError(f"seed must be a whole number >= 0 (got {seed!r})")
    callback = ProgressBar("rendering") if progress is True else (progress or None)
    if isinstance(max_steps, bool) or int(max_steps) != max_steps:
        raise ValueError(f"max_steps must be a whole number >= 1 (got {max_steps!r})")
    if stats is not None and not isinstance(stats, dict):
        raise ValueError(f"stats must be a dict to fill (got {type(stats).__name__})")
    image, counts = _core._render(scene, camera, field, method, int(spp), int(seed), max_length, chord, sagitta, tol,
                                  bool(table), integrator, march, step, int(max_steps), guard_band,
                                  bool(texture_filter), callback)
    if stats is not None:
        stats.update(counts)
    return image
