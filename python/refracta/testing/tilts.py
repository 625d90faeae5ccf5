"""First-order tilts of level paths through a turbulence layer: the transverse gradient of
delta_n summed along straight level paths at random places and headings, vertical and horizontal.
For isotropic turbulence the two variances are equal; a lattice that held modes constant along
every level path made the vertical one grow as L^2 (media/turbulence_synthesis.h)."""

from __future__ import annotations

import math

import numpy as np

from refracta import _core


def level_path_tilts(
    layer: _core.TurbulenceLayer, length: float, paths: int, rng: np.random.Generator, step: float
) -> tuple[np.ndarray, np.ndarray]:
    """(vertical, horizontal): each (paths,) [rad], the tilt int grad(delta_n) . e ds over a level
    path of `length` [m] sampled every `step` [m] (midpoints), e up and across the path; starts
    uniform in a 1 km cube about the origin, headings uniform."""
    if not (length > 0.0 and step > 0.0 and paths >= 1):
        raise ValueError(
            f"level_path_tilts: length and step must be > 0 and paths >= 1 (got {length}, {step}, {paths})"
        )
    s = np.arange(0.0, length, step) + step / 2
    vertical, horizontal = np.empty(paths), np.empty(paths)
    for p in range(paths):
        heading = rng.uniform(0.0, 2.0 * math.pi)
        along = np.array([math.cos(heading), 0.0, math.sin(heading)])
        across = np.array([-math.sin(heading), 0.0, math.cos(heading)])
        _, gradient = layer.evaluate(rng.uniform(-500.0, 500.0, 3) + s[:, None] * along)
        vertical[p] = gradient[:, 1].sum() * step
        horizontal[p] = (gradient @ across).sum() * step
    return vertical, horizontal
