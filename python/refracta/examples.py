"""Ready-made mirage scenes and atmospheres, with values from ORACLES.md.

Scenes: hot_road(), cold_sea(), fata_morgana(), hot_spot() and green_flash() return an Example
with .scene, .camera, .field (procedural geometry; nothing to download). Atmospheres for ray fans: ATMOSPHERES maps a name to
(field, eye height [m], elevations [deg], max length [m]).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from refracta import _core, shading, spectrum

# Radiance unit of the example scenes. refracta.spectrum.PhysicalSky gives linear sRGB normalised
# by the integral of the CIE y-bar curve (a mean spectral radiance, W/(m^2 sr nm)); times that
# integral (106.86 nm, CIE 1931 2 deg) its Y is the y-bar-weighted radiance in W/(m^2 sr), so that
# 683 x Y is the luminance in cd/m^2 (a clear horizon sky: ~3000-5000 cd/m^2).
RADIANCE_SCALE = 106.857


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


def sun_direction(elevation: float, azimuth: float) -> np.ndarray:
    """Unit vector toward the sun at `elevation` above the horizon and `azimuth` [deg] measured
    from +x (the examples' viewing direction) toward +z; y is up."""
    e, a = np.radians(elevation), np.radians(azimuth)
    return np.array([np.cos(e) * np.cos(a), np.sin(e), np.cos(e) * np.sin(a)])


def set_physical_sky(scene: _core.Scene, direction, aerosol: float = 1.0, scale: float = RADIANCE_SCALE) -> None:
    """Light `scene` by Scene.set_physical_sky: a Nishita single-scattering sky and its sun disc
    (0.53 deg, coloured by extinction along the sun's path), both times `scale` (RADIANCE_SCALE:
    see above). direction: toward the sun (normalised), y up; aerosol: the Mie density scale.
    Below the horizon the sky continues from the horizon at each azimuth (below_horizon='horizon'):
    a path that ends at max_length still heading slightly down -- trapped in a duct over the sea, or
    not yet turned over the road -- would meet the water or the hot layer at a grazing angle and see
    the horizon sky there, not a black ground."""
    scene.set_physical_sky(direction, aerosol=aerosol, scale=scale, below_horizon="horizon")


# Materials (refracta.shading; shared/SHADING.md section 3). Indices of aluminium at ~650/550/450 nm
# (Rakic 1995, as tabulated by refractiveindex.info).
ALUMINIUM = dict(eta=(1.50, 0.96, 0.62), k=(7.60, 6.69, 5.30))


def _paint(colour):
    """Metallic car paint: a Burley principled base under a clear coat."""
    return shading.Principled(base_color=colour, metallic=0.75, roughness=0.35, clearcoat=1.0, clearcoat_gloss=0.9)


def _car(scene, x, z, colour, glass):
    """A car of boxes along x: painted body, dark interior behind thin glass, black tyres."""
    scene.add_box((x, 0.75, z), (4.2, 1.1, 1.8), material=_paint(colour))
    scene.add_box((x - 0.3, 1.55, z), (2.1, 0.48, 1.62), material=shading.Diffuse(0.0))  # unlit cabin
    scene.add_box((x - 0.3, 1.55, z), (2.2, 0.5, 1.7), material=glass)
    for dx in (-1.35, 1.35):
        for dz in (-0.92, 0.92):
            scene.add_box((x + dx, 0.32, z + dz), (0.64, 0.64, 0.1), material=shading.Diffuse(0.03))


def hot_road(width: int = 640, height: int = 240) -> Example:
    """Inferior mirage: cars on asphalt 10 K warmer than the air (e-folding 10 cm), eye at 1.4 m,
    an afternoon sun 35 deg high behind the camera under a physical sky. Below the horizon
    the sky's radiance and the cars' lower halves appear mirrored, like water on the road."""
    scene = _core.Scene()
    set_physical_sky(scene, sun_direction(35.0, 180.0))
    scene.add_ground(0.0, 20000.0, material=shading.Diffuse((0.05, 0.05, 0.055)))  # asphalt, albedo ~0.05
    glass = shading.ThinDielectric(1.5)
    colours = [(0.6, 0.04, 0.03), (0.05, 0.15, 0.55), (0.8, 0.8, 0.76), (0.05, 0.05, 0.05)]
    for i, (x, z) in enumerate([(180.0, -1.8), (260.0, 1.7), (340.0, -1.6), (430.0, 2.0)]):
        _car(scene, x, z, colours[i], glass)
    post = shading.RoughConductor(alpha=0.05, **ALUMINIUM)  # polished aluminium
    for x in np.arange(120.0, 600.0, 60.0):  # lamp posts on both sides
        for z in (-7.0, 7.0):
            scene.add_box((x, 3.0, z), (0.2, 6.0, 0.2), material=post)
    walls = [(0.55, 0.5, 0.45), (0.7, 0.62, 0.5), (0.45, 0.45, 0.48), (0.62, 0.42, 0.33)]
    for i, x in enumerate(np.arange(700.0, 1100.0, 55.0)):  # distant buildings
        h = 8.0 + 9.0 * ((i * 37) % 5) / 4
        scene.add_box((x, h / 2, -35.0 - 10 * (i % 3)), (30.0, h, 12.0),
                      material=shading.Diffuse(walls[i % len(walls)]))
    field = _core.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    camera = _camera((0.0, 1.4, 0.0), (300.0, 1.4 - 300.0 * np.tan(np.radians(0.15)), 0.0), 2.2, width, height)
    return Example("hot_road", scene, camera, field, 3000.0, hot_road.__doc__)


def _ship(scene, x, z, scale=1.0):
    """A freighter of boxes: dark hull (painted steel), white superstructure, red funnel."""
    hull = shading.Principled(base_color=(0.05, 0.06, 0.08), roughness=0.5)
    scene.add_box((x, 4.0 * scale, z), (18.0 * scale, 8.0 * scale, 110.0 * scale), material=hull)
    scene.add_box((x, 12.0 * scale, z + 20 * scale), (14.0 * scale, 8.0 * scale, 30.0 * scale),
                  material=shading.Plastic(reflectance=(0.8, 0.8, 0.76), alpha=0.3))
    scene.add_box((x, 21.0 * scale, z + 25 * scale), (4.0 * scale, 10.0 * scale, 4.0 * scale),
                  material=shading.Plastic(reflectance=(0.6, 0.1, 0.06), alpha=0.3))


def _sea():
    """Sea water: a wind-roughened water surface (n = 1.333, GGX alpha 0.25) over a dark blue-green body (what it
    scatters back from below, as a Lambertian base under the coat)."""
    return shading.Plastic(reflectance=(0.01, 0.03, 0.04), ior=1.333, alpha=0.25)


def cold_sea(width: int = 640, height: int = 240) -> Example:
    """Superior mirage (looming) over a cold sea on the curved Earth: warm air +7 K over the
    lowest 50 m lifts a ship 28 km away, below the geometric horizon, into view; eye at 5 m.
    Sunset: the sun 2.5 deg high, 25 deg right of the ship, reddened by its long path through the air."""
    scene = _core.Scene()
    set_physical_sky(scene, sun_direction(2.5, 25.0))
    scene.add_ground(0.0, 120000.0, material=_sea())
    _ship(scene, 28000.0, -150.0)
    base = _core.PhysicalAtmosphere(t_ground=278.15, inversion_dt=7.0, inversion_base=0.0, inversion_thickness=50.0)
    field = _core.CurvedEarth(base)
    camera = _camera((0.0, 5.0, 0.0), (28000.0, 12.0, 0.0), 0.3, width, height)
    return Example("cold_sea", scene, camera, field, 29000.0, cold_sea.__doc__)


def fata_morgana(width: int = 640, height: int = 240) -> Example:
    """Fata Morgana: a sharp inversion just above the eye (+10 K between 12 and 20 m) over cold
    water stretches and stacks a coastline 30 km away into towers and inverted copies; a late
    afternoon sun 12 deg high to the left."""
    scene = _core.Scene()
    set_physical_sky(scene, sun_direction(12.0, -120.0))
    scene.add_ground(0.0, 140000.0, material=_sea())
    rng = np.random.default_rng(7)
    land = [(0.35, 0.3, 0.22), (0.3, 0.32, 0.2), (0.6, 0.55, 0.45), (0.5, 0.3, 0.22)]
    for z in np.arange(-1500.0, 1500.0, 120.0):  # a low coastline of hills and houses
        h = float(rng.uniform(6.0, 25.0))
        colour = land[int(rng.integers(len(land)))]
        scene.add_box((30000.0 + rng.uniform(0, 200), h / 2, z), (150.0, h, 130.0), material=shading.Diffuse(colour))
    base = _core.PhysicalAtmosphere(t_ground=276.15, inversion_dt=10.0, inversion_base=12.0, inversion_thickness=8.0)
    field = _core.CurvedEarth(base)
    camera = _camera((0.0, 14.0, 0.0), (30000.0, 14.0, 0.0), 0.35, width, height)
    return Example("fata_morgana", scene, camera, field, 30500.0, fata_morgana.__doc__)


def hot_spot(width: int = 640, height: int = 240) -> Example:
    """An areal hot spot (refracta.HotSpot): the hot road's scene, its asphalt only 2 K warmer than
    the air but for a patch 220 m across centred 330 m down the road, 16 K warmer (a compact
    footprint: exactly zero outside it). The mirage -- the sky and the cars' lower halves mirrored
    -- lies over the patch alone, and its edges follow the patch."""
    example = hot_road(width, height)
    spot = _core.HotSpot(330.0, 0.0, 110.0, 16.0, footprint="compact")
    field = _core.PhysicalAtmosphere(surface_dt=2.0, surface_depth=0.1, hot_spots=[spot])
    return Example("hot_spot", example.scene, example.camera, field, example.max_length, hot_spot.__doc__)


# The setting sun's linear limb darkening (Neckel-like, at 550 nm).
SETTING_SUN_LIMB_DARKENING = 0.6


def green_flash(width: int = 160, height: int = 160, sun_elevation: float = -0.8) -> Example:
    """A green flash over a warm sea (an inferior-mirage profile): the sea 3 K warmer than the air,
    the excess e-folding over 2 m, the standard atmosphere above to 86 km, a spherical Earth; the
    eye 4 m above the water, looking at the setting sun. The sun's centre is `sun_elevation` [deg]
    above the true horizon (-0.8: its upper rim about to set). Render spectrally
    (refracta.render(..., spectral=True)): each wavelength is bent by its own air, blue and green
    lifted most, so the last sliver of the flattened sun turns green; below it the mirage of the
    warm sea squeezes the disc into an 'Etruscan vase' and cuts it off above the horizon."""
    scene = _core.Scene()
    # Sky and sun of a sun on the horizon (the light that reaches the eye runs within ~0.1 deg of
    # the horizontal): the physical sky's Nishita sky, and its sun's spectrum through the air's
    # horizontal column (~38 air masses of Rayleigh, aerosol and ozone extinction: at 450 nm 0.2 %
    # of 700 nm's, at 550 nm 11 %) -- what leaves the last gleam green, not blue.
    horizon_sun = sun_direction(0.0, 0.0)
    set_physical_sky(scene, horizon_sun)
    lam = np.arange(360.0, 831.0, 10.0)
    sun = spectrum.PhysicalSky(horizon_sun).sun_radiance(lam, 0.53) * RADIANCE_SCALE
    scene.set_sun(sun_direction(sun_elevation, 0.0), sun, angular_diameter=0.53,
                  limb_darkening=SETTING_SUN_LIMB_DARKENING, wavelengths=lam)
    scene.add_ground(0.0, 2.0e5, material=_sea())
    base = _core.PhysicalAtmosphere(surface_dt=3.0, surface_depth=2.0)
    field = _core.CurvedEarth(base)
    look = np.radians(-0.05)
    camera = _camera((0.0, 4.0, 0.0), (1000.0 * np.cos(look), 4.0 + 1000.0 * np.sin(look), 0.0), 0.7, width, height)
    return Example("green_flash", scene, camera, field, 1.5e6, green_flash.__doc__)


EXAMPLES = {"hot_road": hot_road, "cold_sea": cold_sea, "fata_morgana": fata_morgana, "hot_spot": hot_spot}


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
