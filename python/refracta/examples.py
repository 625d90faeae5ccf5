"""Ready-made mirage scenes and atmospheres, with values from ORACLES.md.

Scenes: hot_road(), cold_sea(), fata_morgana() return an Example with .scene, .camera, .field
(procedural geometry; nothing to download). Atmospheres for ray fans: ATMOSPHERES maps a name to
(field, eye height [m], elevations [deg], max length [m]).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from refracta import _core

SUN = dict(direction=(-0.35, 0.45, 0.25), radiance=(2.6e4, 2.45e4, 2.2e4))
SKY = dict(horizon=(0.75, 0.82, 0.92), zenith=(0.22, 0.42, 0.85))


@dataclass
class Example:
    """A scene, a camera and the atmosphere that makes its mirage."""

    name: str
    scene: _core.Scene
    camera: _core.Camera
    field: _core.IndexField
    max_length: float
    description: str


def _camera(position, look_at, vfov, width, height):
    return _core.Camera(position, look_at, (0.0, 1.0, 0.0), vfov, width, height)


def hot_road(width: int = 640, height: int = 240) -> Example:
    """Inferior mirage: cars on asphalt 10 K warmer than the air (e-folding 10 cm), eye at 1.4 m.
    The sky and the cars' lower halves appear mirrored below the horizon, like water."""
    scene = _core.Scene()
    scene.set_sun(**SUN)
    scene.set_sky(**SKY)
    scene.add_ground(0.0, 20000.0, kd=(0.09, 0.09, 0.1))
    colours = [(0.75, 0.08, 0.05), (0.1, 0.25, 0.7), (0.85, 0.85, 0.8), (0.1, 0.1, 0.1)]
    for i, (x, z) in enumerate([(180.0, -1.8), (260.0, 1.7), (340.0, -1.6), (430.0, 2.0)]):
        scene.add_box((x, 0.75, z), (4.2, 1.1, 1.8), kd=colours[i], ks=(0.25, 0.25, 0.25), ns=60.0)
        scene.add_box((x - 0.3, 1.55, z), (2.2, 0.5, 1.7), kd=(0.15, 0.18, 0.22), ks=(0.3, 0.3, 0.3), ns=80.0)
    for x in np.arange(120.0, 600.0, 60.0):  # lamp posts on both sides
        for z in (-7.0, 7.0):
            scene.add_box((x, 3.0, z), (0.2, 6.0, 0.2), kd=(0.35, 0.35, 0.35))
    for i, x in enumerate(np.arange(700.0, 1100.0, 55.0)):  # distant buildings
        h = 8.0 + 9.0 * ((i * 37) % 5) / 4
        scene.add_box((x, h / 2, -35.0 - 10 * (i % 3)), (30.0, h, 12.0), kd=(0.55, 0.5, 0.45))
    field = _core.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    camera = _camera((0.0, 1.4, 0.0), (300.0, 1.4 - 300.0 * np.tan(np.radians(0.15)), 0.0), 2.2, width, height)
    return Example("hot_road", scene, camera, field, 3000.0, hot_road.__doc__)


def _ship(scene, x, z, scale=1.0):
    scene.add_box((x, 4.0 * scale, z), (18.0 * scale, 8.0 * scale, 110.0 * scale), kd=(0.12, 0.12, 0.14))
    scene.add_box((x, 12.0 * scale, z + 20 * scale), (14.0 * scale, 8.0 * scale, 30.0 * scale), kd=(0.85, 0.85, 0.8))
    scene.add_box((x, 21.0 * scale, z + 25 * scale), (4.0 * scale, 10.0 * scale, 4.0 * scale), kd=(0.7, 0.15, 0.1))


def cold_sea(width: int = 640, height: int = 240) -> Example:
    """Superior mirage (looming) over a cold sea on the curved Earth: warm air +7 K over the
    lowest 50 m lifts a ship 28 km away, below the geometric horizon, into view; eye at 5 m."""
    scene = _core.Scene()
    scene.set_sun(**SUN)
    scene.set_sky(**SKY)
    scene.add_ground(0.0, 120000.0, kd=(0.04, 0.08, 0.12), ks=(0.05, 0.05, 0.05), ns=200.0)
    _ship(scene, 28000.0, -150.0)
    base = _core.PhysicalAtmosphere(t_ground=278.15, inversion_dt=7.0, inversion_base=0.0, inversion_thickness=50.0)
    field = _core.CurvedEarth(base)
    camera = _camera((0.0, 5.0, 0.0), (28000.0, 12.0, 0.0), 0.3, width, height)
    return Example("cold_sea", scene, camera, field, 29000.0, cold_sea.__doc__)


def fata_morgana(width: int = 640, height: int = 240) -> Example:
    """Fata Morgana: a sharp inversion just above the eye (+10 K between 12 and 20 m) over cold
    water stretches and stacks a coastline 30 km away into towers and inverted copies."""
    scene = _core.Scene()
    scene.set_sun(**SUN)
    scene.set_sky(**SKY)
    scene.add_ground(0.0, 140000.0, kd=(0.04, 0.08, 0.12))
    rng = np.random.default_rng(7)
    for z in np.arange(-1500.0, 1500.0, 120.0):  # a low coastline of hills and houses
        h = float(rng.uniform(6.0, 25.0))
        scene.add_box((30000.0 + rng.uniform(0, 200), h / 2, z), (150.0, h, 130.0), kd=(0.35, 0.3, 0.22))
    base = _core.PhysicalAtmosphere(t_ground=276.15, inversion_dt=10.0, inversion_base=12.0, inversion_thickness=8.0)
    field = _core.CurvedEarth(base)
    camera = _camera((0.0, 14.0, 0.0), (30000.0, 14.0, 0.0), 0.35, width, height)
    return Example("fata_morgana", scene, camera, field, 30500.0, fata_morgana.__doc__)


EXAMPLES = {"hot_road": hot_road, "cold_sea": cold_sea, "fata_morgana": fata_morgana}


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
