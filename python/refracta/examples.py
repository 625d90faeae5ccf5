"""Ready-made mirage scenes and atmospheres, with values from ORACLES.md.

Scenes: hot_road(), cold_sea(), fata_morgana(), hot_spot() and green_flash() return an Example
with .scene, .camera, .field (procedural geometry; nothing to download). Atmospheres for ray fans:
ATMOSPHERES maps a name to (field, eye height [m], elevations [deg], max length [m]).
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


def set_physical_sky(scene: _core.Scene, direction, aerosol: float = 1.0, scale: float = RADIANCE_SCALE,
                     visibility=None) -> None:
    """Light `scene` by Scene.set_physical_sky: a Nishita single-scattering sky and its sun disc
    (0.53 deg, coloured by extinction along the sun's path), both times `scale` (RADIANCE_SCALE:
    see above). direction: toward the sun (normalised), y up; aerosol: the Mie density scale.
    Below the horizon the sky continues from the horizon at each azimuth (below_horizon='horizon'):
    a path that ends at max_length still heading slightly down -- trapped in a duct over the sea, or
    not yet turned over the road -- would meet the water or the hot layer at a grazing angle and see
    the horizon sky there, not a black ground. Aerial perspective is on (the sky's own air greys
    and blues distant objects); visibility [km]: the meteorological visibility that sets the
    aerosol instead (None: `aerosol`)."""
    if visibility is None:
        scene.set_physical_sky(direction, aerosol=aerosol, scale=scale, below_horizon="horizon")
    else:
        scene.set_physical_sky(direction, scale=scale, below_horizon="horizon", visibility=visibility)


def _paint(colour):
    """Metallic car paint: a Burley principled base under a clear coat."""
    return shading.Principled(base_color=colour, metallic=0.75, roughness=0.35, clearcoat=1.0, clearcoat_gloss=0.9)


def _car(scene, x, z, colour, glass):
    """A car of boxes along x: painted body, a cabin of windows (`glass`), black tyres."""
    scene.add_box((x, 0.75, z), (4.2, 1.1, 1.8), material=_paint(colour))
    scene.add_box((x - 0.3, 1.55, z), (2.2, 0.5, 1.7), material=glass)
    for dx in (-1.35, 1.35):
        for dz in (-0.92, 0.92):
            scene.add_box((x + dx, 0.32, z + dz), (0.64, 0.64, 0.1), material=shading.Diffuse(0.03))


# The hot road's view: a 500 mm telephoto on full frame from a standing eye 1.5 m above the
# asphalt, aimed 0.25 deg below the horizon. The mirage band lies between the horizon and the
# critical depression theta_c = arccos(n(0)/n(h_eye)) below it (0.30 deg for 15 K: ORACLES.md);
# a long lens makes it a large part of the frame (500 mm: 2.06 deg vertically at 2:1, so
# ~14 % of the height; a 50 mm lens would show it as 1.5 %).
HOT_ROAD_FOCAL_LENGTH = 500.0  # [mm]
HOT_ROAD_EYE = 1.5  # [m]
HOT_ROAD_TILT = 0.25  # [deg] below the horizon: the horizon 38 % from the top, the road below


def hot_road(width: int = 640, height: int = 320) -> Example:
    """Inferior mirage, the "wet road": a straight desert road whose asphalt is 15 K warmer than
    the air (e-folding 10 cm: 1.5 K/cm at the surface, ORACLES.md), seen as a photographer does,
    through a 500 mm lens from 1.5 m, toward an afternoon sun 30 deg high and 25 deg to the right
    (out of frame), under a physical sky with desert haze (visibility 40 km). From ~300 m on the
    road turns into a bright pool: the sky below the horizon, the lower halves of the cars and the
    telegraph poles mirrored upside down; a distant ridge greyed by the air."""
    scene = _core.Scene()
    set_physical_sky(scene, sun_direction(30.0, 25.0), visibility=40.0)
    scene.add_ground(0.0, 20000.0, material=shading.Diffuse((0.42, 0.34, 0.25)))  # desert sand
    # The road: asphalt (albedo ~0.06) along +x, 8 m wide, its top 2 mm above the sand; a dashed
    # centre line and edge lines of white paint 4 mm thick.
    scene.add_box((2500.0, -0.024, 0.0), (5000.0, 0.052, 8.0), material=shading.Diffuse((0.06, 0.06, 0.065)))
    paint = shading.Diffuse((0.7, 0.7, 0.65))
    for x in np.arange(15.0, 2500.0, 12.0):
        scene.add_box((x, 0.002, 0.0), (3.0, 0.004, 0.15), material=paint)
    for z in (-3.7, 3.7):
        scene.add_box((2500.0, 0.002, z), (5000.0, 0.004, 0.15), material=paint)
    glass = shading.Plastic(reflectance=(0.01, 0.01, 0.012), ior=1.5, alpha=0.05)  # tinted windows
    colours = [(0.05, 0.15, 0.55), (0.6, 0.04, 0.03), (0.8, 0.8, 0.76), (0.05, 0.05, 0.05), (0.7, 0.55, 0.1)]
    for i, (x, z) in enumerate([(260.0, 1.7), (380.0, -1.9), (560.0, 1.8), (820.0, -1.9), (1150.0, 1.9)]):
        _car(scene, x, z, colours[i], glass)
    pole = shading.Diffuse((0.18, 0.13, 0.09))  # weathered wood: telegraph poles 8 m tall every 55 m
    for x in np.arange(90.0, 3000.0, 55.0):
        scene.add_box((x, 4.0, -8.0), (0.25, 8.0, 0.25), material=pole)
        scene.add_box((x, 7.6, -8.0), (0.15, 0.15, 2.4), material=pole)
    # A low ridge 9-10 km away, 10-50 m high (under 0.3 deg): its foot and the sky below its
    # crest are what the mirage band mirrors.
    rock = [(0.5, 0.32, 0.22), (0.46, 0.3, 0.22), (0.52, 0.36, 0.26)]
    for i, z in enumerate(np.arange(-1200.0, 1200.0, 60.0)):
        h = 10.0 + 25.0 * (0.5 + 0.5 * np.sin(z / 170.0)) + 15.0 * np.sin(z / 60.0 + 1.0) ** 2
        scene.add_box((9000.0 + 300.0 * np.sin(z / 400.0), h / 2, z), (400.0, h, 60.0),
                      material=shading.Diffuse(rock[i % 3]))
    field = _core.PhysicalAtmosphere(surface_dt=15.0, surface_depth=0.1)
    eye, look = HOT_ROAD_EYE, 300.0  # look_at on the line of sight 300 m out (a pinhole: only its direction counts)
    camera = _core.Camera.photographic((0.0, eye, 0.0), (look, eye - look * np.tan(np.radians(HOT_ROAD_TILT)), 0.0),
                                       HOT_ROAD_FOCAL_LENGTH, width=width, height=height)
    return Example("hot_road", scene, camera, field, 12000.0, hot_road.__doc__ or "")  # None under python -OO


def _ship(scene, x, z, scale=1.0):
    """A freighter of boxes: dark hull (painted steel), white superstructure, red funnel."""
    hull = shading.Principled(base_color=(0.05, 0.06, 0.08), roughness=0.5)
    scene.add_box((x, 4.0 * scale, z), (18.0 * scale, 8.0 * scale, 110.0 * scale), material=hull)
    scene.add_box((x, 12.0 * scale, z + 20 * scale), (14.0 * scale, 8.0 * scale, 30.0 * scale),
                  material=shading.Plastic(reflectance=(0.8, 0.8, 0.76), alpha=0.3))
    scene.add_box((x, 21.0 * scale, z + 25 * scale), (4.0 * scale, 10.0 * scale, 4.0 * scale),
                  material=shading.Plastic(reflectance=(0.6, 0.1, 0.06), alpha=0.3))


def _sea(wind_speed: float = 5.0, temperature_c: float = 10.0):
    """Sea water: refracta.shading.Water, a Cox-Munk rough surface (Beckmann, alpha^2 = 0.003 +
    5.12e-3 U) of water's own index over a deep, absorbing and back-scattering body (35 g/kg)."""
    return shading.Water(wind_speed=wind_speed, temperature_c=temperature_c)


def _coast(scene, distance, rng, half_width=2500.0, heights=(20.0, 90.0), spacing=140.0):
    """A low coastline `distance` [m] away: hills, headlands and white houses as boxes 60-150 m
    across every `spacing` [m]."""
    land = [(0.3, 0.3, 0.2), (0.25, 0.28, 0.18), (0.55, 0.5, 0.4), (0.4, 0.33, 0.25), (0.8, 0.78, 0.72)]
    for z in np.arange(-half_width, half_width, spacing):
        h = float(rng.uniform(*heights))
        x, width = distance + float(rng.uniform(0.0, 400.0)), float(rng.uniform(60.0, 150.0))
        scene.add_box((x, h / 2, z), (300.0, h, width), material=shading.Diffuse(land[int(rng.integers(len(land)))]))


# Clear polar air over a cold sea: 80 km of meteorological visibility leaves a coast 36 km away
# 17 % of its contrast (Koschmieder, exp(-3.912 d / V)); 30 km would leave 1 %.
COLD_SEA_VISIBILITY = 80.0  # [km]
# Over the sea photographers use long lenses: 1000 mm on full frame sees 2.06 deg across, and at
# 8:3 0.77 deg high -- the few tenths of a degree where looming and the superior mirage live.
SEA_FOCAL_LENGTH = 1000.0  # [mm]


def cold_sea(width: int = 640, height: int = 240) -> Example:
    """Looming and a superior mirage over a cold sea on the curved Earth: warm air +7 K over the
    lowest 50 m (stronger than the 0.13 K/m that bends rays with the Earth) lifts a freighter 28 km
    away, below the geometric horizon of the 5 m eye, and a coast 36-40 km away into view,
    stretched tall (its 110-125 m slice is also imaged inverted above the erect image, but
    against the light the coast is a silhouette and its images merge into one towering wall).
    Evening: the sun 3 deg high, 0.5 deg left of the view's centre (above the frame), lays a
    glitter path on the water (shading.Water, 4 m/s wind, 5 deg C); the clear polar air
    (visibility 80 km) greys the distance. A 1000 mm lens."""
    scene = _core.Scene()
    set_physical_sky(scene, sun_direction(3.0, -0.5), visibility=COLD_SEA_VISIBILITY)
    scene.add_ground(0.0, 120000.0, material=_sea(4.0, 5.0))
    _ship(scene, 28000.0, -150.0)
    _ship(scene, 19000.0, 260.0, scale=0.7)
    _coast(scene, 36000.0, np.random.default_rng(11), heights=(40.0, 140.0))
    base = _core.PhysicalAtmosphere(t_ground=278.15, inversion_dt=7.0, inversion_base=0.0, inversion_thickness=50.0)
    field = _core.CurvedEarth(base)
    look = np.radians(0.1)
    camera = _core.Camera.photographic((0.0, 5.0, 0.0), (30000.0, 5.0 + 30000.0 * np.tan(look), 0.0),
                                       SEA_FOCAL_LENGTH, width=width, height=height)
    return Example("cold_sea", scene, camera, field, 41000.0, cold_sea.__doc__ or "")


def fata_morgana(width: int = 640, height: int = 240) -> Example:
    """Fata Morgana: a sharp inversion just above the eye (+10 K between 12 and 20 m) over cold
    water stacks a coastline 20 km away: its lower 16-43 m shown erect, above it the same
    heights inverted, stretched into walls and towers; an afternoon sun 15 deg high behind the
    left shoulder, clear air (visibility 80 km); a 1000 mm lens from 14 m (a ship's bridge)."""
    scene = _core.Scene()
    set_physical_sky(scene, sun_direction(15.0, -140.0), visibility=COLD_SEA_VISIBILITY)
    scene.add_ground(0.0, 140000.0, material=_sea(6.0, 3.0))
    _coast(scene, 20000.0, np.random.default_rng(7), half_width=1000.0, heights=(10.0, 45.0), spacing=120.0)
    base = _core.PhysicalAtmosphere(t_ground=276.15, inversion_dt=10.0, inversion_base=12.0, inversion_thickness=8.0)
    field = _core.CurvedEarth(base)
    look = np.radians(0.02)
    camera = _core.Camera.photographic((0.0, 14.0, 0.0), (20000.0, 14.0 + 20000.0 * np.tan(look), 0.0),
                                       SEA_FOCAL_LENGTH, width=width, height=height)
    return Example("fata_morgana", scene, camera, field, 21000.0, fata_morgana.__doc__ or "")


def hot_spot(width: int = 640, height: int = 320) -> Example:
    """An areal hot spot (refracta.HotSpot): the hot road's scene and view, its asphalt and sand
    only 2 K warmer than the air but for a patch centred 350 m down the road, 25 K warmer at its
    centre (a compact footprint of radius 300 m: exactly zero outside it, above 11 K within 100 m).
    The "lake" -- the sky and the cars' lower halves mirrored -- lies over the patch alone: it
    belongs to the ground, so it stays there when the camera moves (the demo walks 60 m toward it)."""
    example = hot_road(width, height)
    spot = _core.HotSpot(350.0, 0.0, 300.0, 25.0, footprint="compact")
    field = _core.PhysicalAtmosphere(surface_dt=2.0, surface_depth=0.1, hot_spots=[spot])
    return Example("hot_spot", example.scene, example.camera, field, example.max_length, hot_spot.__doc__ or "")


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
    return Example("green_flash", scene, camera, field, 1.5e6, green_flash.__doc__ or "")


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
