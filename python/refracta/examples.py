"""Ready-made mirage scenes and atmospheres, with values typical of the phenomena they show.

Scenes: hot_road(), cold_sea(), fata_morgana(), hot_spot() and green_flash() return an Example
with .scene, .camera, .field (procedural geometry; nothing to download); real_place() a geographic
one (terrain from a shipped, synthetic elevation file; .frame its refracta.geo.LocalFrame). Atmospheres for ray fans:
ATMOSPHERES maps a name to (field, eye height [m], elevations [deg], max length [m]).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from refracta import _core, _options, examples_meshes, examples_town, shading, spectrum
from refracta._checks import is_number, is_seed

# Radiance unit of the example scenes. refracta.spectrum.PhysicalSky gives linear sRGB normalised
# by the integral of the CIE y-bar curve (a mean spectral radiance, W/(m^2 sr nm)); times that
# integral (106.86 nm, CIE 1931 2 deg) its Y is the y-bar-weighted radiance in W/(m^2 sr), so that
# 683 x Y is the luminance in cd/m^2 (a clear horizon sky: ~3000-5000 cd/m^2).
RADIANCE_SCALE = spectrum.cie_y_integral()


@dataclass
class Example:
    """A scene, a camera and the atmosphere that makes its mirage."""

    name: str
    scene: _core.Scene
    camera: _core.Camera
    field: _core.IndexField
    max_length: float
    description: str
    frame: Any = None  # a geographic scene's refracta.geo.LocalFrame (render(..., frame=) for "geographic")


def _size(width, height, owner: str) -> tuple[int, int]:
    """(width, height) as whole numbers of pixels >= 1 (8.0 is 8, as for every whole-number option),
    else ValueError naming them and `owner`."""

    def whole(value) -> bool:
        return is_seed(value) or (is_number(value) and math.isfinite(float(value)) and float(value).is_integer())

    if not all(whole(v) and v >= 1 for v in (width, height)):
        raise ValueError(
            f"examples.{owner}: width and height must be whole numbers of pixels >= 1 (got {width!r}, {height!r})"
        )
    return int(width), int(height)


def _camera(position, look_at, vfov, width, height):
    return _core.Camera(position, look_at, (0.0, 1.0, 0.0), vfov, width, height)


def _finite(value, name: str, function: str) -> float:
    """`value` as a float; ValueError naming `function`'s argument `name` unless it is a finite real
    number (a bool or a string is not one: Python's float() would take True as 1 and '1' as 1.0)."""
    if not is_number(value):
        raise ValueError(f"{function}: {name} must be a number (got {value!r})")
    if not np.isfinite(value):
        raise ValueError(f"{function}: {name} must be finite (got {value!r})")
    return float(value)


def sun_direction(elevation: float, azimuth: float) -> np.ndarray:
    """Unit vector toward the sun at `elevation` above the horizon and `azimuth` [deg] measured
    from +x (the examples' viewing direction) toward +z; y is up. ValueError unless elevation is in
    [-90, 90] and azimuth finite."""
    for name, value in (("elevation", elevation), ("azimuth", azimuth)):
        if not is_number(value):
            raise ValueError(f"sun_direction: {name} must be a number [deg] (got {value!r})")
    if not -90.0 <= elevation <= 90.0:
        raise ValueError(f"sun_direction: elevation must be in [-90, 90] deg (got {elevation!r})")
    if not np.isfinite(azimuth):
        raise ValueError(f"sun_direction: azimuth must be finite (got {azimuth!r})")
    e, a = np.radians(elevation), np.radians(azimuth)
    return np.array([np.cos(e) * np.cos(a), np.sin(e), np.cos(e) * np.sin(a)])


def set_physical_sky(
    scene: _core.Scene,
    sun_direction=None,
    aerosol: float | None = None,
    scale: float = RADIANCE_SCALE,
    visibility=None,
    **deprecated,
) -> None:
    """Light `scene` by Scene.set_physical_sky: a Nishita sky (Hillaire 2020's multiple scattering) and its sun disc
    (0.53 deg, coloured by extinction along the sun's path), both times `scale` (RADIANCE_SCALE:
    see above). sun_direction (Scene.set_physical_sky's name; direction= is its deprecated
    spelling): toward the sun (normalised), y up; aerosol: the Mie density scale (None:
    Scene.set_physical_sky's, a clear sky).
    Below the horizon the sky continues from the horizon at each azimuth (below_horizon='horizon'):
    a path that ends at max_length still heading slightly down -- trapped in a duct over the sea, or
    not yet turned over the road -- would meet the water or the hot layer at a grazing angle and see
    the horizon sky there, not a black ground. Aerial perspective is on (the sky's own air greys
    and blues distant objects); visibility [km]: the meteorological visibility that sets the
    aerosol instead (give one of them)."""
    if sun_direction is not None and "direction" in deprecated:
        raise TypeError("examples.set_physical_sky: pass sun_direction only (direction= is its deprecated spelling)")
    kw = _options.renamed(dict(deprecated), {"direction": "sun_direction"}, "examples.set_physical_sky")
    sun_direction = kw.pop("sun_direction", sun_direction)
    if kw:
        raise TypeError(f"examples.set_physical_sky: unexpected keyword {next(iter(kw))!r}")
    if sun_direction is None:
        raise TypeError("examples.set_physical_sky: give sun_direction (toward the sun, y up)")
    scene.set_physical_sky(sun_direction, aerosol=aerosol, scale=scale, below_horizon="horizon", visibility=visibility)


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
# critical depression theta_c = arccos(n(0)/n(h_eye)) below it (0.30 deg for 15 K);
# a long lens makes it a large part of the frame (500 mm: 2.06 deg vertically at 2:1, so
# ~14 % of the height; a 50 mm lens would show it as 1.5 %).
HOT_ROAD_FOCAL_LENGTH = 500.0  # [mm]
HOT_ROAD_EYE = 1.5  # [m]
HOT_ROAD_TILT = 0.25  # [deg] below the horizon: the horizon 38 % from the top, the road below
# The cars (x, z) [m]: all beyond ~320 m, where the rays that turn above the asphalt begin to meet
# what stands on it, so each shows its lower part mirrored below it (at 420 m its lowest ~0.7 m;
# a car at 260 m showed none).
HOT_ROAD_CARS = [(420.0, 1.7), (500.0, -1.9), (640.0, 1.8), (880.0, -1.9), (1150.0, 1.9)]


def hot_road(width: int = 640, height: int = 320) -> Example:
    """Inferior mirage, the "wet road": a straight desert road whose asphalt is 15 K warmer than
    the air (e-folding 10 cm: 1.5 K/cm at the surface), seen as a photographer does,
    through a 500 mm lens from 1.5 m, toward an afternoon sun 30 deg high and 25 deg to the right
    (out of frame), under a physical sky with desert haze (visibility 40 km). From ~300 m on the
    road turns into a bright pool: the sky below the horizon, the lower halves of the cars and the
    telegraph poles mirrored upside down; a distant ridge greyed by the air."""
    width, height = _size(width, height, "hot_road")
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
    for i, (x, z) in enumerate(HOT_ROAD_CARS):
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
        scene.add_box(
            (9000.0 + 300.0 * np.sin(z / 400.0), h / 2, z), (400.0, h, 60.0), material=shading.Diffuse(rock[i % 3])
        )
    field = _core.PhysicalAtmosphere(surface_dt=15.0, surface_depth=0.1)
    eye, look = HOT_ROAD_EYE, 300.0  # look_at on the line of sight 300 m out (a pinhole: only its direction counts)
    camera = _core.Camera.photographic(
        (0.0, eye, 0.0),
        (look, eye - look * np.tan(np.radians(HOT_ROAD_TILT)), 0.0),
        HOT_ROAD_FOCAL_LENGTH,
        width=width,
        height=height,
    )
    return Example("hot_road", scene, camera, field, 12000.0, hot_road.__doc__ or "")  # None under python -OO


def _fbm(rng, x, z, scale, octaves=5, gain=0.5):
    """Fractal value noise (sum of `octaves` octaves, each twice the frequency and `gain` times the
    amplitude of the last) at points (x, z) [m], features of `scale` [m] in the first octave; values
    roughly in [-1, 1]. Each octave: random values on a square lattice, interpolated by smoothstep."""
    total, amplitude, norm = np.zeros(np.broadcast(x, z).shape), 1.0, 0.0
    for octave in range(octaves):
        cell = scale / 2.0**octave
        u, v = (x - x.min()) / cell, (z - z.min()) / cell
        i, j = np.floor(u).astype(int), np.floor(v).astype(int)
        lattice = rng.uniform(-1.0, 1.0, (int(i.max()) + 2, int(j.max()) + 2))
        fu, fv = u - i, v - j
        fu, fv = fu * fu * (3 - 2 * fu), fv * fv * (3 - 2 * fv)
        top = lattice[i, j] * (1 - fv) + lattice[i, j + 1] * fv
        bottom = lattice[i + 1, j] * (1 - fv) + lattice[i + 1, j + 1] * fv
        total = total + amplitude * (top * (1 - fu) + bottom * fu)
        norm += amplitude
        amplitude *= gain
    return total / norm


def _smoothstep(t):
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


# Rock, tundra, shingle and snow of a northern coast (diffuse albedos; Kokaly et al. 2017, USGS
# spectral library: dark basalt ~0.1, lichen tundra ~0.15-0.2, old snow ~0.8).
COAST_COLOURS = {
    "rock": (0.11, 0.1, 0.09),
    "tundra": (0.2, 0.18, 0.11),
    "shingle": (0.3, 0.28, 0.25),
    "snow": (0.8, 0.82, 0.86),
}


def _coast_texture(name, colours):
    """Write the (rows, columns, 3) linear albedo `colours` as a float EXR texture (kept linear)
    under the temporary folder, once per content, and return its path."""
    import hashlib
    import os
    import tempfile
    import threading

    from refracta import io

    colours = np.ascontiguousarray(colours, dtype=np.float32)
    folder = os.path.join(tempfile.gettempdir(), "refracta_examples")
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, f"{name}_{hashlib.sha1(colours.tobytes()).hexdigest()[:16]}.exr")
    if not os.path.exists(path):
        # Written whole, then renamed: safe for parallel builders, threads of one process too (a
        # name of the pid alone was shared by threads, and the later one's rename failed).
        partial = f"{path}.{os.getpid()}.{threading.get_ident()}.exr"
        io.write_image(partial, colours)
        os.replace(partial, path)
    return path


def _coast(
    scene,
    distance,
    rng,
    z_range,
    peak,
    depth=3000.0,
    cell=(20.0, 5.0),
    tip=None,
    snow_line=None,
    rise=600.0,
    inlets=False,
    name="coast",
    cliff=None,
    wander=260.0,
):
    """A coastline `distance` [m] away (+x) over z in z_range [m]: one height-field mesh of fractal
    noise (_fbm) -- hills up to ~`peak` [m] rising over `rise` [m] from a shore that wanders by a few
    hundred metres into bays and headlands, the sea bed sloping away below it -- on `cell` (dx, dz)
    [m] nodes, smooth-shaded. tip: z [m] past which the land sinks into the sea over 300 m (a
    headland). inlets: valleys down to the sea cut the land into headlands every few hundred m.
    cliff: a function of z [m] giving the height [m] of a cliff (or quay) standing at the shore,
    rising over its first 6 m inland (None: none). wander: how far [m] the shore wanders.
    Its albedo, a texture over the mesh: rock where steep, shingle at the waterline, snow above
    `snow_line` [m] where gentle (None: none), tundra elsewhere, blended smoothly. Returns the
    nodes' x [m], z [m] and heights (len(x), len(z)) [m]."""
    x = np.arange(distance - 500.0, distance + depth, cell[0])
    z = np.arange(z_range[0], z_range[1] + cell[1], cell[1])
    X, Z = np.meshgrid(x, z, indexing="ij")
    shore = distance + wander * _fbm(rng, np.zeros_like(z), z, 700.0, octaves=4)
    inland = X - shore[None, :]
    relief = np.clip(0.55 + 0.9 * _fbm(rng, X, Z, 1200.0, octaves=6), 0.05, None)
    height = peak * relief**1.4 * _smoothstep(inland / rise) + 6.0 * _smoothstep(inland / 40.0)
    if inlets:
        height = height * _smoothstep((_fbm(rng, np.zeros_like(Z), Z, 260.0, octaves=3) + 0.05) / 0.2)
    if cliff is not None:
        height = np.maximum(height, np.asarray(cliff(z))[None, :] * _smoothstep(inland / 6.0))
    if tip is not None:
        height = height * _smoothstep((tip + 300.0 - Z) / 300.0) - 8.0 * _smoothstep((Z - tip) / 300.0)
    height = np.where(inland < 0.0, np.minimum(height, 0.04 * inland), height)  # the sea bed: 4 % down
    nx, nz = X.shape
    vertices = np.stack([X, height, Z], axis=-1).reshape(-1, 3)
    gx, gz = np.gradient(height, cell[0], cell[1])
    normals = np.stack([-gx, np.ones_like(height), -gz], axis=-1)
    normals /= np.linalg.norm(normals, axis=-1, keepdims=True)
    index = np.arange(nx * nz).reshape(nx, nz)
    a, b, c, d = index[:-1, :-1], index[1:, :-1], index[1:, 1:], index[:-1, 1:]
    # Counter-clockwise seen from above (+y): x then z is clockwise, so (a, d, c) and (a, c, b).
    triangles = np.concatenate([np.stack([a, d, c], -1).reshape(-1, 3), np.stack([a, c, b], -1).reshape(-1, 3)])
    triangles = triangles[height.reshape(-1)[triangles].max(axis=1) > -2.0]  # the sea bed out of sight
    # The albedo at every node, blended by weights in [0, 1].
    slope = np.hypot(gx, gz)
    speckle = _fbm(rng, X, Z, 120.0, octaves=4)  # patchy snow and outcrops
    colour = {k: np.array(v) for k, v in COAST_COLOURS.items()}
    rock = _smoothstep((slope + 0.3 * speckle - 0.3) / 0.25)[..., None]
    face = np.zeros_like(height)  # 1 on the nodes of a cliff's face (its foot and top), else 0
    cliff_rock = colour["rock"]
    if cliff is not None:  # cliff faces of bare rock to the waterline, banded: pale and dark rock, gullies
        face = (np.abs(inland) <= cell[0]) * _smoothstep((np.asarray(cliff(z))[None, :] - 4.0) / 4.0)
        rock = np.maximum(rock, face[..., None])
        bands = 1.0 + 1.6 * np.clip(_fbm(rng, np.zeros_like(Z), Z, 40.0, octaves=3), -0.5, 1.0)
        cliff_rock = cliff_rock * bands[..., None]
    albedo = colour["tundra"] * (1 - rock) + cliff_rock * rock
    if snow_line is not None:
        snow = _smoothstep((height + 50.0 * speckle - snow_line) / 25.0) * (1 - _smoothstep((slope - 0.35) / 0.2))
        albedo = albedo * (1 - snow[..., None]) + colour["snow"] * snow[..., None]
    wet = ((1 - _smoothstep((height - 1.0) / 4.0)) * (1 - face))[..., None]
    albedo = albedo * (1 - wet) + colour["shingle"] * wet
    # uvs: u along z, v along x; the texture's first row is v = 1 (the far side).
    uvs = np.stack([(Z - z[0]) / (z[-1] - z[0]), (X - x[0]) / (x[-1] - x[0])], axis=-1).reshape(-1, 2)
    texture = _coast_texture(name, albedo[::-1])
    scene.add_mesh(
        vertices, triangles, material=shading.Diffuse(1.0, texture=texture), normals=normals.reshape(-1, 3), uvs=uvs
    )
    return x, z, height


SHIP_HEIGHT = examples_meshes.SHIP_FUNNEL_TOP  # [m] _ship's funnel top above the waterline at scale 1
SHIP_HULL = examples_meshes.HULL_FREEBOARD  # [m] its deck amidships at scale 1 (upper works above; length 110 m)


def _ship_materials():
    """The freighter's paints by part (examples_meshes.ship): a black hull (painted steel), white
    upper works, a red funnel with a black top, grey masts and cranes, containers of three colours."""
    plastic = shading.Plastic
    return {
        "hull": plastic(reflectance=(0.03, 0.035, 0.045), alpha=0.4),
        "white": plastic(reflectance=(0.8, 0.8, 0.76), alpha=0.3),
        "funnel": plastic(reflectance=(0.6, 0.1, 0.06), alpha=0.3),
        "funnel_top": shading.Diffuse(0.03),
        "mast": shading.Diffuse((0.55, 0.53, 0.5)),
        "cargo0": shading.Diffuse((0.55, 0.12, 0.08)),
        "cargo1": shading.Diffuse((0.1, 0.25, 0.45)),
        "cargo2": shading.Diffuse((0.45, 0.4, 0.1)),
    }


def _ship(scene, x, z, scale=1.0):
    """A general-cargo freighter broadside on (its length along z, the bow toward -z): the closed
    meshes of examples_meshes.ship -- a hull with its sheer line, forecastle and raked stem, white
    upper works aft, a raked funnel, masts, deck cranes and containers -- `scale` times its 110 m,
    one mesh per paint."""
    meshes = [mesh.moved((x, 0.0, z), scale) for mesh in examples_meshes.ship()]
    examples_meshes.add_meshes(scene, meshes, _ship_materials())


def _sea(wind_speed: float = 5.0, temperature_c: float = 10.0):
    """Sea water: refracta.shading.Water, a Cox-Munk rough surface (Beckmann, alpha^2 = 0.003 +
    5.12e-3 U) of water's own index over a deep, absorbing and back-scattering body (35 g/kg)."""
    return shading.Water(wind_speed=wind_speed, temperature_c=temperature_c)


# Clear polar air over a cold sea: 80 km of meteorological visibility leaves a coast 30 km away
# 23 % of its contrast (Koschmieder, exp(-3.912 d / V)); 30 km would leave 2 %.
COLD_SEA_VISIBILITY = 80.0  # [km]
# Over the sea photographers use long lenses: 1000 mm on full frame sees 2.06 deg across, and at
# 8:3 0.77 deg high -- the few tenths of a degree where looming and the superior mirage live.
SEA_FOCAL_LENGTH = 1000.0  # [mm]
# The cold sea's inversion: +10 K between 20 and 30 m over water at 5 deg C (1 K/m: the strong
# Arctic inversions that show ships' inverted images; Lehn 1979, Wegener 1918). The eye at 5 m is
# under it; rays rising 0.0-0.1 deg are bent back down by it and meet a ship 20 km away from above.
COLD_SEA_INVERSION: dict[str, Any] = dict(
    t_ground=278.15, inversion_dt=10.0, inversion_base=20.0, inversion_thickness=10.0
)
COLD_SEA_EYE = 5.0  # [m]
COLD_SEA_SHIP = (20000.0, 220.0)  # [m] (x, z) of the freighter, against the open horizon
COLD_SEA_COAST = 30000.0  # [m]
# Sun glitter through a 2-degree lens. A facet of the sea mirrors the sun into a view that meets the
# water at a grazing gamma (0.1-0.3 deg here) when its normal bisects the sun's direction and the
# reversed view: for the sun at elevation e and dphi to the side, it leans toward the eye by
# ~(e - gamma)/2 and sideways by tan b = sin(dphi) cos(e) / (sin e + sin gamma) -- a sideways lean
# turns a grazing reflection little, so the glitter is a narrow path under the sun, of half-width
# ~alpha tan(e) in azimuth (Cox & Munk's Beckmann alpha^2 = 0.003 + 5.12e-3 U). Light air, U = 1 m/s
# (the still air a sharp inversion needs: alpha^2 = 0.0081, alpha = 0.09), and the sun 10 deg high:
# a path 0.9 deg wide each side of the sun's azimuth, 2.3 deg right of the view, so 1.27 deg beyond
# the frame's right edge. Across the frame the sideways lean the glitter needs grows from 0.12
# (1.4 alpha) at the right edge to 0.32 (3.6 alpha) at the left: the facets that mirror the sun
# are e^-11 rarer on the left, and the path's flank lights the sea in the frame's lower right and
# the far sea the inversion lifts into view (the lean toward the eye, 4.9 deg, costs e^-0.9 all
# over). A lower sun narrows the path but turns the whole frame orange (the sunlight in linear RGB
# 1 : 0.51 : 0.12 at 4 deg, 1 : 0.69 : 0.36 at 10); a higher one or more wind spreads the glitter
# over the whole frame (at 4 m/s and 10 deg it is 1.5 deg wide each side). A sun farther to the
# side leaves no glitter in the frame (30 deg aside, 30 deg high: a lean of 45 deg, e^-121 at
# alpha 0.09), so the ships and the coast stand against the light.
COLD_SEA_SUN = (10.0, 2.3)  # [deg] (elevation, azimuth from the view toward +z: to the right)
COLD_SEA_WIND = 1.0  # [m/s] 12.5 m above the sea (Cox & Munk's height)


def cold_sea(width: int = 640, height: int = 240) -> Example:
    """A superior mirage over a cold sea on the curved Earth: a sharp inversion (+10 K between 20 and
    30 m, COLD_SEA_INVERSION) over water at 5 deg C. A freighter 20 km away, hull-down to the 5 m
    eye, shows its upper part erect and above it its whole image upside down, stretched, against
    the bright horizon sky; a smaller ship 13 km away shows erect, inverted and erect again; the
    foot of a snow-patched coast 30 km away (a fractal height field) is drawn out into a thin
    inverted strip and its hills loom above the horizon. Evening light: the sun 10 deg high just
    beyond the frame's right edge (COLD_SEA_SUN) lays the flank of its glitter path on the sea in
    the frame's lower right and on the far sea the inversion lifts into view, behind the
    freighter's inverted image; the ships and the coast stand against the light, and the clear
    polar air (visibility 80 km) greys and warms the distance. The sea is shading.Water (Cox-Munk,
    light air of 1 m/s, 5 deg C: at these ranges one pixel spans 10-60 m of sea, many waves, so
    the microfacet statistics are the resolved picture -- the glitter is their mean, not single
    sparkles). A 1000 mm lens."""
    width, height = _size(width, height, "cold_sea")
    scene = _core.Scene()
    set_physical_sky(scene, sun_direction(*COLD_SEA_SUN), visibility=COLD_SEA_VISIBILITY)
    scene.add_ground(0.0, 120000.0, material=_sea(COLD_SEA_WIND, 5.0))
    _ship(scene, *COLD_SEA_SHIP)
    _ship(scene, 13000.0, -120.0, scale=0.7)
    _coast(
        scene,
        COLD_SEA_COAST,
        np.random.default_rng(11),
        (-1500.0, 400.0),
        peak=170.0,
        tip=-150.0,
        snow_line=110.0,
        name="cold_sea_coast",
    )
    field = _core.CurvedEarth(_core.PhysicalAtmosphere(**COLD_SEA_INVERSION))
    look = np.radians(0.1)
    eye = COLD_SEA_EYE
    camera = _core.Camera.photographic(
        (0.0, eye, 0.0), (30000.0, eye + 30000.0 * np.tan(look), 0.0), SEA_FOCAL_LENGTH, width=width, height=height
    )
    return Example("cold_sea", scene, camera, field, 41000.0, cold_sea.__doc__ or "")


# Arctic air after a cold front: 150 km visibility leaves the coast 20 km away 59 % of its contrast.
FATA_MORGANA_VISIBILITY = 150.0  # [km]
FATA_MORGANA_COAST = 20000.0  # [m] to the shore (it wanders by ~60 m)
# The sun behind the left shoulder, far enough to the side that it rakes the cliffs: a buttress's
# side toward it lit 3x as much as the side away (n.l 0.8 against 0.25 for faces turned 20 deg).
FATA_MORGANA_SUN_AZIMUTH = -125.0  # [deg] from the view (+x) toward +z


def fata_morgana(width: int = 640, height: int = 240) -> Example:
    """Fata Morgana: a sharp inversion just above the eye (+12 K between 15 and 25 m) over cold
    water stacks the shore 20 km away -- cliffs of 2-38 m, a harbour town, a lighthouse on its rock,
    a conifer forest (examples_town) before hills to ~240 m: in the middle column the shore's
    lowest ~17 m show four times over, erect, inverted, erect (a thin strip) and inverted again
    above (tests/render/test_examples.py traces it), so houses, windows and roofs repeat
    mirrored, the lighthouse becomes a tall white column, the trees a palisade, and the cliffs'
    buttresses -- lit on the side toward the sun, in shade on the other -- columns of light and
    shade over strata, heath and the black weed of the waterline; above them a band of mirrored
    sea and the hill tops. An afternoon sun 15 deg high behind the left shoulder, raking the
    cliffs (FATA_MORGANA_SUN_AZIMUTH), clear Arctic air (visibility 150 km); a 1000 mm lens from
    14 m (a ship's bridge)."""
    width, height = _size(width, height, "fata_morgana")
    scene = _core.Scene()
    set_physical_sky(scene, sun_direction(15.0, FATA_MORGANA_SUN_AZIMUTH), visibility=FATA_MORGANA_VISIBILITY)
    scene.add_ground(0.0, 140000.0, material=_sea(6.0, 3.0))
    rng = np.random.default_rng(7)
    coast = _coast(
        scene,
        FATA_MORGANA_COAST,
        rng,
        (-700.0, 700.0),
        peak=240.0,
        depth=1500.0,
        rise=500.0,
        cell=(8.0, 4.0),
        name="fata_morgana_coast",
        cliff=examples_town.shore_cliff,
        wander=60.0,
    )
    faces = examples_town.cliff_faces(coast, rng)
    rock = shading.Diffuse(1.0, texture=_coast_texture("fata_morgana_cliffs", faces.albedo))
    scene.add_mesh(faces.mesh.vertices, faces.mesh.triangles, material=rock, uvs=faces.uvs)
    parts = examples_town.town(coast, rng) + examples_town.shore_rocks(coast, faces, rng)
    examples_meshes.add_meshes(scene, parts, examples_town.town_materials())
    base = _core.PhysicalAtmosphere(t_ground=276.15, inversion_dt=12.0, inversion_base=15.0, inversion_thickness=10.0)
    field = _core.CurvedEarth(base)
    look = np.radians(0.02)
    camera = _core.Camera.photographic(
        (0.0, 14.0, 0.0), (20000.0, 14.0 + 20000.0 * np.tan(look), 0.0), SEA_FOCAL_LENGTH, width=width, height=height
    )
    return Example("fata_morgana", scene, camera, field, 21000.0, fata_morgana.__doc__ or "")


# The hot spot's patch (examples.hot_spot): a sun-baked stretch of the road and its shoulders, a row
# of HOT_SPOT_COUNT compact spots along the road's centre line from HOT_SPOT_STRETCH[0] to [1], 7.1 m
# (half a radius) apart so that their sum ripples by 6 %, each HOT_SPOT_DT warmer at its centre:
# the air over the centre line is 26-27 K warmer than over the rest of the ground, 23 K 2 m off it,
# 15 K at the road's edges (4 m), 8 K at 6 m, 3 K at 8 m, nothing beyond 14 m. The rest of the
# desert only HOT_SPOT_GROUND_DT warmer than the air: its own mirage stays within ~0.08 deg of the
# horizon (critical angle sqrt(2 dn), dn ~ 1e-6 per K), where the ridge 9 km away stands.
HOT_SPOT_STRETCH = (290.0, 650.0)  # [m] along the road (+x)
HOT_SPOT_RADIUS = 14.0  # [m] each spot's compact footprint
HOT_SPOT_COUNT = 52
HOT_SPOT_DT = 20.0  # [K] each spot at its centre
HOT_SPOT_GROUND_DT = 1.0  # [K] the rest of the ground


def hot_spot(width: int = 640, height: int = 320) -> Example:
    """A local "lake" (refracta.HotSpot): the hot road's scene and view, its sand and asphalt only
    1 K warmer than the air but for a sun-baked stretch of the road 290-650 m ahead and a few metres
    of sand either side (HOT_SPOT_STRETCH: a row of compact spots, the air over the road's centre
    line ~27 K warmer, nothing beyond 14 m of it). The lake -- the sky, the poles and the cars'
    lower halves mirrored -- lies over the stretch alone: it ends left and right on the sand, the
    desert beside it is not mirrored, and it belongs to the ground, so it stays there when the
    camera moves (the demo walks 60 m toward it)."""
    width, height = _size(width, height, "hot_spot")
    example = hot_road(width, height)
    spots = [
        _core.HotSpot(float(x), 0.0, HOT_SPOT_RADIUS, HOT_SPOT_DT, footprint="compact")
        for x in np.linspace(*HOT_SPOT_STRETCH, HOT_SPOT_COUNT)
    ]
    field = _core.PhysicalAtmosphere(surface_dt=HOT_SPOT_GROUND_DT, surface_depth=0.1, hot_spots=spots)
    return Example("hot_spot", example.scene, example.camera, field, example.max_length, hot_spot.__doc__ or "")


# The setting sun's linear limb darkening (Neckel-like, at 550 nm).
SETTING_SUN_LIMB_DARKENING = 0.6


# A calm evening sea under the setting sun. Its glitter path: a facet mirrors the sun (seen from the
# water at a launch elevation e of a few tenths of a degree, the refraction lifting it from below
# the true horizon) into a view meeting the water at a grazing gamma when it leans sideways by
# tan b = sin(dphi) cos(e) / (sin e + sin gamma), so the path is ~alpha (e + gamma) wide each side of
# the sun's azimuth, and its peak, D G / (4 cos i cos o) with D ~ 1 / alpha^2 and Smith's G ~ 1 /
# alpha at grazing, ~1 / alpha^3: at 5 m/s (alpha^2 0.0286) the path spanned the 0.7-deg frame at
# 2-4x the sea beside it; at 1 m/s (alpha^2 0.0081) it is ~2x narrower and ~6x brighter.
GREEN_FLASH_WIND = 1.0  # [m/s] 12.5 m above the sea (Cox & Munk's height)


def green_flash(width: int = 160, height: int = 160, sun_elevation: float = -0.776) -> Example:
    """A green flash over a warm sea (an inferior-mirage profile): the sea 3 K warmer than the air,
    the excess e-folding over 2 m, the standard atmosphere above to 86 km, a spherical Earth; the
    eye 4 m above the water, looking at the setting sun. The sun's centre is `sun_elevation` [deg]
    above the true horizon: -0.776 (the default) shows the last gleam, green; -0.768 the lens,
    orange inside a green rim; -0.74 the lens the sun's top and its mirror image make; -0.45 the
    flattened disc cut by the mirage (make demo's frames). From about -0.778 its green is gone
    (530 nm's last light: -0.7781); a fainter blue gleam lasts to about -0.787 (400 nm), below
    which the frame shows only the sky and the sea. Render spectrally
    (refracta.render(..., spectral=True)): each wavelength is bent by its own air, blue and green
    lifted most, so the last sliver of the flattened sun turns green; below it the mirage of the
    warm sea squeezes the disc into an 'Etruscan vase' and cuts it off above the horizon."""
    width, height = _size(width, height, "green_flash")
    sun_elevation = _finite(sun_elevation, "sun_elevation", "examples.green_flash")
    scene = _core.Scene()
    # Sky and sun of a sun on the horizon (the light that reaches the eye runs within ~0.1 deg of
    # the horizontal): the physical sky's Nishita sky, and its sun's spectrum through the air's
    # horizontal column (~38 air masses of Rayleigh, aerosol and ozone extinction: at 450 nm 0.2 %
    # of 700 nm's, at 550 nm 11 %) -- what leaves the last gleam green, not blue.
    horizon_sun = sun_direction(0.0, 0.0)
    set_physical_sky(scene, horizon_sun)
    lam = np.arange(360.0, 831.0, 10.0)
    sun = spectrum.PhysicalSky(horizon_sun).sun_radiance(lam) * RADIANCE_SCALE
    scene.set_sun(
        sun_direction(sun_elevation, 0.0),
        sun,
        angular_diameter=0.53,
        limb_darkening=SETTING_SUN_LIMB_DARKENING,
        wavelengths=lam,
    )
    scene.add_ground(0.0, 2.0e5, material=_sea(GREEN_FLASH_WIND))
    base = _core.PhysicalAtmosphere(surface_dt=3.0, surface_depth=2.0)
    field = _core.CurvedEarth(base)
    look = np.radians(-0.05)
    camera = _camera((0.0, 4.0, 0.0), (1000.0 * np.cos(look), 4.0 + 1000.0 * np.sin(look), 0.0), 0.7, width, height)
    return Example("green_flash", scene, camera, field, 1.5e6, green_flash.__doc__ or "")


# A real place (issue 20): Teide seen from Gran Canaria across ~93 km of the Atlantic. The observer
# stands on the cliffs above Puerto de las Nieves, Agaete (28.0975 N, 15.7125 W), 30 m above the sea,
# and looks at Teide's summit (REAL_PLACE_SUMMITS). The elevation file is SYNTHETIC (shipped in
# refracta/data with the script that makes it; nothing downloaded): an island shaped after Tenerife
# around the real summits' positions and heights -- not the real topography.
REAL_PLACE_OBSERVER = (28.0975, -15.7125)  # [deg] (lat, lon)
REAL_PLACE_EYE = 30.0  # [m] above the sea
REAL_PLACE_SUMMITS = {"Teide": (28.2724, -16.6425, 3715.0), "Pico Viejo": (28.2567, -16.6622, 3135.0)}
REAL_PLACE_FOCAL_LENGTH = 300.0  # [mm] on full frame
REAL_PLACE_TILT = 0.95  # [deg] the camera's elevation: the sea horizon near the bottom, the summit high
# Canary air on a clear winter morning after rain: 300 km of visibility leaves the island 93 km away
# exp(-3.912 x 93 / 300) = 30 % of its contrast (Koschmieder) -- faint and bluish, as photographed.
REAL_PLACE_VISIBILITY = 300.0  # [km]
REAL_PLACE_SUN = (110.0, 35.0)  # [deg] (azimuth, elevation): mid-morning, behind the left shoulder


def real_place_elevation_path() -> str:
    """The path of real_place's synthetic elevation GeoTIFF (refracta/data/tenerife_synthetic.tif,
    made by refracta/data/make_tenerife.py)."""
    import os

    return os.path.join(os.path.dirname(__file__), "data", "tenerife_synthetic.tif")


def real_place(width: int = 640, height: int = 320, field=None) -> Example:
    """A real place: Teide (3715 m) on Tenerife seen across ~93 km of sea from the cliffs of Agaete,
    Gran Canaria (REAL_PLACE_OBSERVER), 30 m up, through a 300 mm lens. The terrain is an elevation
    file placed by refracta.geo.LocalFrame (Scene.add_terrain, TerrainShading with a winter snow line);
    its relief is SYNTHETIC (refracta/data/make_tenerife.py: an island shaped after Tenerife around
    the real summits), the positions of observer and summits real. The Earth is curved
    (CurvedEarth, the radius of curvature along the view azimuth, Euler) under the standard
    atmosphere (k about 0.17): the island's lower ~340 m lie hidden behind the sea's bulge (426 m without air). A
    physical sky with a mid-morning sun behind the left shoulder; 300 km visibility greys and
    blues the island. field: another height-only field (true heights) for the air, put over the
    same Earth (None: PhysicalAtmosphere(), the standard atmosphere)."""
    width, height = _size(width, height, "real_place")
    from refracta import geo, terrain

    lat, lon = REAL_PLACE_OBSERVER
    s_lat, s_lon, _ = REAL_PLACE_SUMMITS["Teide"]
    distance, azimuth, _ = geo.inverse(lat, lon, s_lat, s_lon)
    radius = geo.radius_of_curvature(lat, azimuth)
    frame = geo.LocalFrame(lat, lon, earth_radius=radius)
    scene = _core.Scene()
    set_physical_sky(scene, frame.direction(*REAL_PLACE_SUN), visibility=REAL_PLACE_VISIBILITY)
    scene.add_ground(0.0, 2.6 * distance, material=_sea(6.0, 19.0))  # the Atlantic off the Canaries
    terrain.add_terrain(
        scene,
        real_place_elevation_path(),
        frame=frame,
        material=shading.TerrainShading(snow_line=2600.0, tree_line=2000.0, earth_radius=radius),
    )
    if field is not None and not isinstance(field, _core.IndexField):
        raise ValueError(f"real_place: field must be a refracta field (an IndexField; got {type(field).__name__})")
    base = _core.PhysicalAtmosphere() if field is None else field
    camera = frame.camera(
        REAL_PLACE_EYE,
        azimuth % 360.0,
        REAL_PLACE_TILT,
        focal_length_mm=REAL_PLACE_FOCAL_LENGTH,
        image_width=width,
        image_height=height,
    )
    field = _core.CurvedEarth(base, radius)
    return Example("real_place", scene, camera, field, 1.25 * distance, real_place.__doc__ or "", frame)


EXAMPLES = {"hot_road": hot_road, "cold_sea": cold_sea, "fata_morgana": fata_morgana, "hot_spot": hot_spot}


def hot_road_atmosphere():
    """A ray-fan air for an inferior mirage (not hot_road()'s, whose asphalt is 15 K warmer): asphalt
    10 K warmer than the air, e-folding over 10 cm; eye at 1.5 m.

    Returns (field, eye_height [m], elevations [deg] of a fan of rays, max_length [m]), what the
    arguments refracta.plot.ray_fan takes."""
    field = _core.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    return field, 1.5, np.linspace(-0.5, 0.3, 17), 1000.0


def cold_sea_atmosphere():
    """A ray-fan air for a superior mirage (flat, not cold_sea()'s curved Earth with +10 K over
    20-30 m and the eye at 5 m): cold water under a warm inversion (+8 K over 10-30 m); eye at 10 m.

    Returns (field, eye_height [m], elevations [deg] of a fan of rays, max_length [m]), what the
    arguments refracta.plot.ray_fan takes."""
    field = _core.PhysicalAtmosphere(
        t_ground=278.15,
        surface_dt=-4.0,
        surface_depth=3.0,
        inversion_dt=8.0,
        inversion_base=10.0,
        inversion_thickness=20.0,
    )
    return field, 10.0, np.linspace(-0.3, 0.5, 17), 20000.0


def editor_profile():
    """The original editor's logistic profile at its default start (scene units, n up to ~1.03).

    Returns (field, eye_height, elevations [deg] of a fan of rays, max_length), as
    hot_road_atmosphere."""
    field = _core.LogisticProfile()
    return field, 1.5, np.linspace(-8.0, 4.0, 17), 60.0


ATMOSPHERES = {"hot_road": hot_road_atmosphere, "cold_sea": cold_sea_atmosphere, "editor": editor_profile}
