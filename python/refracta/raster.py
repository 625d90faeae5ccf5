"""refracta.raster: the CPU rasterizer's buffers, for inspection and tests.

rasterize(scene, camera) draws the scene's triangles (spheres tessellated) with refracta's own
rasterizer -- near-plane and guard-band clipping, perspective-correct barycentrics, a z-buffer,
tiles over threads -- into a visibility buffer. The renderers use the same code
(render(method='raster_march')).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from refracta import _core
from refracta._checks import is_number, number

__all__ = ["RasterBuffers", "rasterize"]


@dataclass(eq=False)  # arrays: == would be ambiguous (equal by identity)
class RasterBuffers:
    """depth (H, W) float32 view depth [m] (inf where empty); geometry, primitive (H, W) int64
    (-1 where empty); barycentric (H, W, 3) float32 weights of the triangle's vertices; offset:
    (x, y) of the camera image's pixel (0, 0) inside the buffers (the guard band); counts."""

    depth: np.ndarray = field(repr=False)
    geometry: np.ndarray = field(repr=False)
    primitive: np.ndarray = field(repr=False)
    barycentric: np.ndarray = field(repr=False)
    offset: tuple
    triangles: int
    screen_triangles: int
    fragments: int


def rasterize(
    scene: _core.Scene, camera: _core.Camera, guard_band: float = 0.0, tile: int | None = None
) -> RasterBuffers:
    """Rasterize `scene` from `camera` (its image widened by guard_band on each side, as a fraction
    of it; 0: none) in square tiles of `tile` pixels (None: the renderers' own, 32)."""
    guard_band = number(guard_band, "rasterize: guard_band")  # True was a guard band of 1 (a trial)
    if tile is not None and not (is_number(tile) and math.isfinite(tile) and int(tile) == tile):
        raise ValueError(f"rasterize: tile must be a whole number >= 1 (got {tile!r})")
    depth, geometry, primitive, barycentric, offset, *counts = _core._rasterize(
        scene, camera, guard_band, None if tile is None else int(tile)
    )
    return RasterBuffers(depth, geometry, primitive, barycentric.reshape(depth.shape + (3,)), tuple(offset), *counts)
