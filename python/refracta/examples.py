"""Ready-made atmospheres for demos and tutorials, with values from ORACLES.md.

Each function returns (field, eye_height [m], elevations [deg], max_length [m]) suited to a ray fan.
"""

from __future__ import annotations

import numpy as np

from refracta import _core


def hot_road_atmosphere():
    """Inferior mirage: asphalt 10 K warmer than the air, e-folding over 10 cm; eye at 1.5 m."""
    field = _core.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    return field, 1.5, np.linspace(-0.5, 0.3, 17), 1000.0


def cold_sea_atmosphere():
    """Superior mirage: cold water under a warm inversion (+8 K over 10-30 m); eye at 10 m."""
    field = _core.PhysicalAtmosphere(t_ground=278.15, surface_dt=-4.0, surface_depth=3.0,
                                     inversion_dt=8.0, inversion_base=10.0, inversion_thickness=20.0)
    return field, 10.0, np.linspace(-0.3, 0.5, 17), 20000.0


def editor_profile():
    """The original editor's logistic profile at its default start (scene units, n up to ~1.03)."""
    field = _core.LogisticProfile()
    return field, 1.5, np.linspace(-8.0, 4.0, 17), 60.0


ATMOSPHERES = {"hot_road": hot_road_atmosphere, "cold_sea": cold_sea_atmosphere, "editor": editor_profile}
