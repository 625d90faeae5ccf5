"""The Fata Morgana's coast (refracta.examples.fata_morgana): what stands on a shore 20 km away
that a duct stretches into towers -- cliffs of different heights, a harbour town (houses,
warehouses, a church with a spire, grain silos, a crane), a lighthouse on its rock, a conifer
forest and a radio mast. A Fata Morgana magnifies the lowest few tens of metres of the far shore
several-fold; a shore with structure there -- bright walls beside dark rock and trees, each
its own height -- is what shows the stacking and stretching as the photographs do (Lehn 1979,
"Fata Morgana and its photographic documentation").

Along the shore (z [m], the camera at z = 0 sees about -360 to 360 with its 1000 mm lens):
a 30 m granite cliff with trees on top to -250, the harbour town on a 3 m quay to -110, a 12 m
basalt bluff to -40, the lighthouse on an 8 m rock at 0 by a beach with boathouses and scrub, the
forest on low land from 40 to 200, a 38 m sandstone cliff with a few houses and the radio mast
beyond.

What the duct magnifies is what must not be flat: the cliffs' faces (cliff_faces) are ribbed by
buttresses and gullies that the low sun lights on one side -- stretched, they become the
columns of light and shade of the photographs -- and textured with strata, streaks, heath,
lichen and the black weed of the waterline; boulders lie at their feet and on the beach and
fishing boats at the quay (shore_rocks); the houses have gable roofs and windows, seven paints
and three roofings; spruce, pine and birch stand in the forest (town).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from refracta import shading
from refracta.examples_meshes import (
    HULL_BEAM,
    HULL_FREEBOARD,
    Mesh,
    _rings_to_mesh,
    _smoothstep,
    box,
    cones,
    ellipse,
    prism,
    ship_hull,
)


class _Coast:
    """The land of examples._coast's (x, z, height): the shore's x at each z and the ground's height
    at any (x, z) (its nearest node)."""

    def __init__(self, coast):
        self.x, self.z, self.height = coast

    def shore(self, z: float) -> float:
        j = int(np.argmin(np.abs(self.z - z)))
        return float(self.x[int(np.argmax(self.height[:, j] > 0.5))])

    def ground(self, x: float, z: float) -> float:
        i, j = int(np.argmin(np.abs(self.x - x))), int(np.argmin(np.abs(self.z - z)))
        return float(self.height[i, j])


# The shore from -z to +z: where each stretch starts [m], its height [m] and what it is made of
# (a ROCKS name). The lighthouse's rock (LIGHTHOUSE_ROCK) stands on the beach.
SHORE = [
    (-1e9, 30.0, "granite"),
    (-250.0, 3.0, "quay"),
    (-110.0, 12.0, "basalt"),
    (-40.0, 2.0, "beach"),
    (40.0, 6.0, "bank"),
    (200.0, 38.0, "sandstone"),
    (420.0, 24.0, "sandstone"),
]
LIGHTHOUSE_ROCK = (14.0, 8.0)  # [m] half its length along the shore, its height


def _shore_weights(z):
    """The weight (0..1) of each SHORE stretch at `z` [m], each step blending over ~10 m of shore;
    they sum to 1."""
    z = np.asarray(z, dtype=float)
    ramps = [np.ones(z.shape)] + [np.clip((z - start) / 10.0 + 0.5, 0.0, 1.0) for start, _, _ in SHORE[1:]]
    ramps.append(np.zeros(z.shape))
    return [ramps[k] - ramps[k + 1] for k in range(len(SHORE))]


def shore_cliff(z):
    """The height [m] of the cliff or quay standing at the shore at `z` [m] (module docstring),
    each step rising over ~10 m of shore."""
    z = np.asarray(z, dtype=float)
    height = sum(w * value for w, (_, value, _) in zip(_shore_weights(z), SHORE))
    half, top = LIGHTHOUSE_ROCK
    rock = np.where(np.abs(z) < half, top, 0.0)
    return np.maximum(height, rock)


# The shore's rock (diffuse albedos, linear; after the USGS spectral library, Kokaly et al. 2017:
# granite and gneiss 0.13-0.35, basalt 0.06-0.11, red sandstone 0.2-0.4 in red, glacial till
# 0.15-0.25): each a few tones its strata take in turn.
ROCKS = {
    "granite": [(0.3, 0.27, 0.24), (0.2, 0.19, 0.18), (0.13, 0.125, 0.12), (0.36, 0.32, 0.28)],
    "quay": [(0.27, 0.26, 0.24), (0.21, 0.205, 0.19), (0.32, 0.31, 0.29)],  # dressed granite blocks
    "basalt": [(0.085, 0.082, 0.08), (0.11, 0.1, 0.095), (0.06, 0.058, 0.056)],
    "beach": [(0.3, 0.28, 0.25)],  # shingle (the coast's own colour; no face is built there)
    "bank": [(0.2, 0.15, 0.1), (0.15, 0.12, 0.085), (0.26, 0.22, 0.16)],  # till: earth and stones
    "sandstone": [(0.33, 0.21, 0.14), (0.4, 0.33, 0.24), (0.2, 0.15, 0.11), (0.3, 0.19, 0.13)],
}
# How far [m] each rock's buttresses stand out of its face, gullies between: vertical ribs that the
# low sun lights on one side and leaves in shade on the other, as a Fata Morgana stretches them.
RELIEF = {"granite": 8.0, "quay": 0.0, "basalt": 5.0, "beach": 0.0, "bank": 1.5, "sandstone": 6.0}
# How strongly each rock's strata differ (1: its tones as they are, 0: all their mean): massive
# granite and basalt faintly, the sandstone's beds fully.
BANDING = {"granite": 0.3, "quay": 0.6, "basalt": 0.3, "beach": 0.0, "bank": 0.5, "sandstone": 0.7}
VEGETATION = (0.05, 0.08, 0.03)  # grass and crowberry heath on ledges and cliff tops
LICHEN = (0.42, 0.24, 0.07)  # orange Xanthoria lichen of the splash zone
WEED = (0.03, 0.03, 0.025)  # black lichen (Verrucaria) and wet wrack at the waterline
GUANO = (0.55, 0.55, 0.5)  # white streaks below the seabirds' ledges
# The faces: nodes every CLIFF_STEP along the shore (a pixel at 20 km through the 1000 mm lens is
# 1.1 m) and CLIFF_ROWS up; from CLIFF_FOOT (under the water) to at most CLIFF_TOP.
CLIFF_STEP = 1.0  # [m]
CLIFF_ROWS = 48
CLIFF_FOOT = -3.0  # [m]
CLIFF_TOP = 46.0  # [m] above the highest cliff (38 m) and its crest
CLIFF_MIN = 2.5  # [m] the shore's height from which it gets a face: the quay (3 m) up; the beach stays the coast's
# The coast's height field rises from the sea to a cliff's top within one node (8 m) of its first
# land node; the faces stand FRONT seaward of that node (before their relief) and reach DEPTH
# inland, so they hide it.
FRONT = 10.0  # [m]
DEPTH = 30.0  # [m]
TEXEL = (0.5, 0.25)  # [m] the faces' albedo texture: along the shore, up the face


def _rock_weights(z):
    """The weight (0..1) of each ROCKS name at `z` [m]: SHORE's stretches, the lighthouse's rock
    of basalt; they sum to 1."""
    z = np.asarray(z, dtype=float)
    weights = {name: np.zeros(z.shape) for name in ROCKS}
    for w, (_, _, name) in zip(_shore_weights(z), SHORE):
        weights[name] = weights[name] + w
    rock = np.abs(z) < LIGHTHOUSE_ROCK[0]
    weights["basalt"] = np.where(rock, weights["basalt"] + weights["beach"], weights["basalt"])
    weights["beach"] = np.where(rock, 0.0, weights["beach"])
    return weights


def _noise(rng, z, scale, octaves=4, y=None):
    """The coast's fractal noise (examples._fbm, values roughly in [-1, 1]) along the shore at `z`
    [m] (y None) or over a face at (z, y) [m]; features of `scale` [m]."""
    from refracta.examples import _fbm  # examples imports this module: imported when called

    z = np.asarray(z, dtype=float)
    return _fbm(rng, np.zeros_like(z) if y is None else np.asarray(y, dtype=float), z, scale, octaves)


def _face_line(land, z):
    """The x [m] of the faces' base line at `z` [m] (before FRONT and their relief): the coast's
    first land node, its lowest within 10 m, averaged over +-8 m (smooth, never past the node)."""
    first = land.x[np.argmax(land.height > 0.5, axis=0)]
    node = first[np.abs(land.z[None, :] - z[:, None]).argmin(axis=1)]
    reach, smooth = int(10.0 / CLIFF_STEP), int(8.0 / CLIFF_STEP)
    lowest = np.lib.stride_tricks.sliding_window_view(np.pad(node, reach, mode="edge"), 2 * reach + 1).min(axis=1)
    padded = np.pad(lowest, smooth, mode="edge")
    return np.convolve(padded, np.ones(2 * smooth + 1) / (2 * smooth + 1), mode="valid")


@dataclass(eq=False)  # arrays: == would be ambiguous (equal by identity)
class CliffFaces:
    """The shore's cliff and quay faces: `mesh` (closed slabs, one per stretch, wound outward),
    `uvs` (n, 2) per vertex (u along the shore, v up), `albedo` (rows, columns, 3) its linear
    texture (the first row at v = 1, the top); `z` [m] the nodes along the shore and `toe` [m] the
    x of the most seaward buttress at each (where rocks fall)."""

    mesh: Mesh
    uvs: np.ndarray
    albedo: np.ndarray
    z: np.ndarray
    toe: np.ndarray


def cliff_faces(coast, rng: np.random.Generator, z_range=(-420.0, 420.0)) -> CliffFaces:
    """The rock faces of shore_cliff's cliffs, the bluff, the lighthouse's rock, the bank and the
    quay wall along `z_range` [m] of `coast` (examples._coast's (x, z, height)), in front of the
    height field's own face: ribbed by buttresses and gullies (RELIEF), stepped by strata, the top
    irregular and rounded. Their texture: strata of the rock's tones dipping along the shore,
    vertical streaks, wet and mossy gullies, heath on ledges and the top, orange lichen above the
    black weed of the waterline, white streaks below bird ledges."""
    land = _Coast(coast)
    z = np.arange(z_range[0], z_range[1] + 0.5 * CLIFF_STEP, CLIFF_STEP)
    # Fields along the shore, on the texture's columns; the mesh reads them at its nodes.
    tz = np.arange(z[0] + 0.5 * TEXEL[0], z[-1], TEXEL[0])
    # 1: a buttress, 0: a gully's back; ribs 5-20 m apart with steep sides (tanh), rough in the small.
    relief = np.clip(0.5 + 0.5 * np.tanh(4.0 * _noise(rng, tz, 12.0, 4)) + 0.1 * _noise(rng, tz, 3.0, 2), 0.0, 1.0)
    crest = 0.5 + 0.5 * _noise(rng, tz, 30.0)
    weights = _rock_weights(tz)
    amplitude = sum(weights[k] * RELIEF[k] for k in ROCKS)
    top = shore_cliff(tz) + 0.3 + 0.6 * amplitude * crest
    # Strata: layers 0.6-3.5 m thick, each its tone, brightness and setback (hard layers stand out),
    # dipping 0.8 % along the shore and warped over ~150 m.
    bounds = CLIFF_FOOT - 10.0 + np.cumsum(rng.uniform(0.6, 3.5, 64))
    tone, bright, setback = rng.integers(0, 12, 64), rng.uniform(0.8, 1.2, 64), rng.uniform(0.0, 1.0, 64)
    dip = 0.008 * tz + 0.8 * _noise(rng, tz, 150.0, 2)

    def stratum(y, at):
        return np.searchsorted(bounds, y + np.interp(at, tz, dip))

    # The mesh: per node along the shore a ring -- the face from its foot to its top, then the
    # slab's back -- joined ring to ring (examples_meshes's tube), one slab per stretch of cliff.
    line = _face_line(land, z)
    amp_z, relief_z, top_z = (np.interp(z, tz, f) for f in (amplitude, relief, top))
    t = np.linspace(0.0, 1.0, CLIFF_ROWS)
    y = CLIFF_FOOT + (top_z - CLIFF_FOOT)[:, None] * t[None, :]
    ribs = np.minimum(amp_z / 2.0, 1.0)[:, None]  # strata and rim only where the rock is rough
    front = (
        (line - FRONT - amp_z * relief_z)[:, None]
        + ribs * setback[np.clip(stratum(y, z[:, None]), 0, 63)]
        + ribs * 1.5 * _smoothstep((y - top_z[:, None] + 2.0) / 2.0)  # the weathered rim
    )
    back = line - FRONT + DEPTH
    rings = np.concatenate(
        [
            np.stack([front, y, np.broadcast_to(z[:, None], y.shape)], axis=-1),
            np.stack([back, top_z, z], axis=-1)[:, None],
            np.stack([back, np.full(z.shape, CLIFF_FOOT), z], axis=-1)[:, None],
        ],
        axis=1,
    )
    built = shore_cliff(z) >= CLIFF_MIN
    edges = np.flatnonzero(np.diff(np.concatenate([[0], built.astype(int), [0]])))
    slabs = [_rings_to_mesh(rings[a:b], "cliff") for a, b in zip(edges[::2], edges[1::2]) if b - a >= 2]
    offsets = np.cumsum([0] + [len(m.vertices) for m in slabs[:-1]])
    vertices = np.concatenate([m.vertices for m in slabs])
    triangles = np.concatenate([m.triangles + o for m, o in zip(slabs, offsets)])
    z0, z1 = z[0], z[-1]
    uvs = np.column_stack([(vertices[:, 2] - z0) / (z1 - z0), (vertices[:, 1] - CLIFF_FOOT) / (CLIFF_TOP - CLIFF_FOOT)])
    # The texture, its first row the top.
    ty = np.arange(CLIFF_TOP - 0.5 * TEXEL[1], CLIFF_FOOT, -TEXEL[1])
    Y, Z = np.meshgrid(ty, tz, indexing="ij")
    layer = np.clip(stratum(Y, Z), 0, 63)
    albedo = np.zeros(Y.shape + (3,))
    for name, palette in ROCKS.items():
        w = weights[name][None, :, None]
        if w.max() > 0.0:
            course = np.floor((Y - CLIFF_FOOT) / 0.7).astype(int) % 64 if name == "quay" else layer
            tones = np.asarray(palette)
            tones = tones.mean(axis=0) + BANDING[name] * (tones - tones.mean(axis=0))
            albedo = albedo + w * tones[tone[course] % len(palette)] * bright[course][..., None]
    rough = np.clip(amplitude / 2.0, 0.0, 1.0)[None, :, None]  # the natural rock's share
    streaks = 1.0 + 0.2 * _noise(rng, tz, 3.0, 3)  # vertical streaks: the rock's grain, seepage
    albedo = albedo * (1.0 + rough * (streaks[None, :, None] - 1.0))
    albedo = albedo * (1.0 - rough * 0.35 * (1.0 - relief)[None, :, None] ** 2)  # wet gullies
    wet = np.clip((_noise(rng, tz, 6.0, 3) - 0.35) / 0.15, 0.0, 1.0)[None, :, None]  # dark seepage lines
    albedo = albedo * (1.0 - 0.45 * rough * wet)
    birds = ((weights["granite"] + weights["basalt"]) * np.clip((_noise(rng, tz, 4.0, 3) - 0.4) / 0.1, 0, 1))[None, :]
    birds = birds * (Y > 0.35 * top[None, :]) * (Y < 0.85 * top[None, :])
    albedo = albedo + (np.asarray(GUANO) - albedo) * (0.6 * birds)[..., None]

    def cover(colour, amount):
        nonlocal albedo
        albedo = albedo + (np.asarray(colour) - albedo) * np.clip(amount, 0.0, 1.0)[..., None]

    # Heath: a fringe over the top, down the gullies, on the ledges where a layer steps back.
    heath = 0.4 + 2.5 * np.clip(0.5 + _noise(rng, tz, 10.0), 0.0, 1.0)
    patches = np.clip(0.5 + _noise(rng, Z, 8.0, 3, y=Y * 4.0), 0.0, 1.0)  # taller than wide: y scaled
    ledge = (Y + np.interp(Z, tz, dip) - bounds[np.clip(layer - 1, 0, 63)] < 0.6) & (
        setback[layer] > setback[np.clip(layer - 1, 0, 63)]
    )
    cover(VEGETATION, rough[..., 0] * ((Y > top[None, :] - heath[None, :]) + 0.8 * ledge * patches))
    cover(VEGETATION, rough[..., 0] * 0.6 * (1.0 - relief)[None, :] ** 2 * patches)
    cover(VEGETATION, weights["bank"][None, :] * 0.7 * patches)
    # The splash zone: orange lichen over the black of the tidal zone, both wandering.
    tide = 1.0 + 0.4 * _noise(rng, tz, 12.0)
    lichen = (Y > tide[None, :] + 0.3) & (Y < tide[None, :] + 2.5 + 1.5 * crest[None, :])
    cover(LICHEN, 0.45 * lichen * np.clip(patches - 0.3, 0.0, 1.0) * (1.0 - weights["bank"])[None, :])
    cover(WEED, _smoothstep((tide[None, :] - Y) / 0.3))
    # The most seaward buttress at each node: the foot of the face at the waterline, at its widest.
    toe = line - FRONT - amp_z
    return CliffFaces(Mesh(vertices, triangles, "cliff"), uvs, albedo.astype(np.float32), z, toe)


def shore_rocks(coast, faces: CliffFaces, rng: np.random.Generator) -> list[Mesh]:
    """Boulders fallen at the foot of the cliffs and lying on the beach (closed, lumpy truncated
    cones 1.5-5 m across, 'boulder0'..'boulder2'), and fishing boats moored along the quay ('boat0'..
    'boat2' hulls, white wheelhouses, 'steel' masts)."""
    land = _Coast(coast)
    parts: list[Mesh] = []
    cliff = shore_cliff(faces.z)
    quay = _rock_weights(faces.z)["quay"] > 0.5
    k = 0
    while k < len(faces.z):
        z = float(faces.z[k])
        size = float(rng.uniform(1.5, 5.0))
        if not quay[k]:
            if cliff[k] >= CLIFF_MIN:  # a talus of fallen blocks before the face
                x = float(faces.toe[k]) - float(rng.uniform(0.0, 5.0))
            else:  # boulders over the beach, in the surf and on the shingle
                x = land.shore(z) - float(rng.uniform(-4.0, 14.0))
            corners = int(rng.integers(5, 9))
            angle = np.sort(rng.uniform(0.0, 2.0 * np.pi, corners))
            radius = 0.5 * size * rng.uniform(0.7, 1.1, corners)
            outline = np.column_stack([x + radius * np.cos(angle), z + radius * np.sin(angle)])
            top = float(rng.uniform(0.35, 0.75)) * size
            shift = rng.uniform(-0.2, 0.2, 2) * size
            parts.append(
                prism(outline, -1.0, top, f"boulder{rng.integers(3)}", top_shift=shift, top_scale=rng.uniform(0.3, 0.6))
            )
        k += int(rng.integers(2, 7))
    # Fishing boats (13-16 m) along the quay's face, a few metres off it.
    for z in (-232.0, -205.0, -171.0, -140.0):
        scale = float(rng.uniform(0.12, 0.15))
        x = float(np.interp(z, faces.z, faces.toe)) - 0.5 * scale * HULL_BEAM - 1.5
        hull = ship_hull().moved((x, 0.0, z), scale)
        parts.append(Mesh(hull.vertices, hull.triangles, f"boat{rng.integers(3)}"))
        deck = HULL_FREEBOARD * scale
        parts.append(box((x, deck + 1.1, z + 3.0 * scale / 0.12), (1.8, 2.2, 3.0), "white"))  # the wheelhouse
        parts.append(prism(ellipse((x, z - 2.0), (0.15, 0.15), 6), deck, deck + 7.0, "steel"))
    return parts


WALLS = [
    (0.78, 0.76, 0.7),  # white
    (0.7, 0.55, 0.35),  # ochre
    (0.38, 0.09, 0.06),  # Falu red
    (0.5, 0.5, 0.48),  # grey
    (0.75, 0.66, 0.4),  # pale yellow
    (0.42, 0.5, 0.56),  # blue-grey
    (0.14, 0.1, 0.07),  # tarred wood
]
ROOFS = [(0.12, 0.08, 0.07), (0.3, 0.09, 0.05), (0.15, 0.16, 0.17)]  # black felt, red tile, slate
WINDOW = (0.02, 0.025, 0.03)  # glazing and open doors: dark
# Conifer and birch canopies (diffuse albedos, visible): spruce, pine, birch in new leaf.
FOREST = [(0.035, 0.06, 0.03), (0.05, 0.065, 0.03), (0.09, 0.14, 0.05)]
BOULDERS = [(0.12, 0.115, 0.11), (0.2, 0.18, 0.16), (0.08, 0.075, 0.07)]
BOATS = [(0.5, 0.07, 0.05), (0.06, 0.15, 0.4), (0.75, 0.75, 0.72)]  # red, blue and white hulls


def _gable(x, z, base, depth, width, ridge, part):
    """A closed gable roof: its eaves at `base` [m] along z over `width` [m], `depth` [m] across
    (x), the ridge `ridge` [m] above the eaves."""
    section = [(x - depth / 2, base), (x + depth / 2, base), (x, base + ridge)]
    rings = np.array([[(px, py, zz) for px, py in section] for zz in (z - width / 2, z + width / 2)])
    return _rings_to_mesh(rings, part)


def _house(x, z, base, size, wall, roof, rng, door=False):
    """A house or warehouse facing the sea (-x): its walls (`size` (depth, height, width) [m]), a
    gable roof and dark windows on the seaward wall, a floor every 3 m (a warehouse: a wide door
    and one high row)."""
    depth, tall, width = size
    parts = [
        box((x, base + tall / 2, z), size, wall),
        _gable(x, z, base + tall, depth + 1.0, width + 0.8, 0.35 * depth, roof),
    ]
    face = x - depth / 2
    if door:
        door_height = min(4.5, tall - 1.5)
        parts.append(box((face, base + 1.0 + door_height / 2, z), (0.2, door_height, min(5.0, width / 3)), "window"))
        floors = [base + tall - 2.2] if tall > 8.0 else []
    else:
        floors = list(np.arange(base + 1.9, base + tall - 1.5, 3.0))
    spacing = float(rng.uniform(2.4, 3.4))
    columns = np.arange(z - width / 2 + 1.6, z + width / 2 - 1.2, spacing)
    for y in floors:
        for c in columns:
            if not door or abs(c - z) > min(5.0, width / 3) / 2 + 1.0:
                parts.append(box((face, y + 0.65, c), (0.2, 1.3, 1.1), "window"))
    return parts


def town(coast, rng: np.random.Generator) -> list[Mesh]:
    """The closed meshes of everything standing on `coast` (examples._coast's (x, z, height) of the
    land shaped by shore_cliff), each named by its paint: 'wall0'..'wall6', 'roof0'..'roof2',
    'window', 'white', 'red', 'steel', 'forest0'..'forest2'."""
    land = _Coast(coast)
    parts: list[Mesh] = []

    def on_ground(x, z, inset=1.0):
        return land.ground(x, z) - inset  # foundations sunk into the slope

    # The harbour town on its quay: warehouses along the quay, a row of houses behind, each its own
    # height and paint.
    for row, depth in ((0, 12.0), (1, 40.0)):
        z = -246.0
        while z < -114.0:
            width = float(rng.uniform(8.0, 14.0)) if row else float(rng.uniform(9.0, 30.0))
            tall = float(rng.uniform(5.0, 11.0)) if row else float(rng.choice([6.0, 9.0, 12.0, 16.0]))
            x = land.shore(z + width / 2) + depth + (0.0 if row else 4.0)
            base = on_ground(x, z + width / 2)
            wall = f"wall{rng.integers(len(WALLS))}"
            roof = f"roof{rng.integers(len(ROOFS))}"
            parts += _house(x, z + width / 2, base, (10.0, tall, width - 1.5), wall, roof, rng, door=not row)
            z += width
    # The church: a nave, a square tower and its spire (top 44 m above the quay).
    x = land.shore(-170.0) + 70.0
    base = on_ground(x, -170.0)
    parts.append(box((x + 10.0, base + 7.0, -170.0), (28.0, 14.0, 12.0), "wall0"))
    parts.append(box((x - 6.0, base + 13.0, -170.0), (7.0, 26.0, 7.0), "wall0"))
    square = [(x - 9.5, -173.5), (x - 2.5, -173.5), (x - 2.5, -166.5), (x - 9.5, -166.5)]
    parts.append(prism(square, base + 26.0, base + 44.0, "roof0", top_scale=0.05))
    # Grain silos and a harbour crane at the quay's end.
    for k in range(3):
        z = -128.0 + 8.0 * k
        x = land.shore(z) + 25.0
        parts.append(prism(ellipse((x, z), (3.8, 3.8), 14), on_ground(x, z), 24.0, "white", top_scale=0.98))
    x = land.shore(-236.0) + 4.0
    parts.append(box((x, 15.0, -236.0), (2.0, 30.0, 2.0), "red"))
    parts.append(box((x - 6.0, 30.0, -236.0), (26.0, 1.6, 1.6), "red"))  # the jib over the water
    # The lighthouse on its rock: a tapering white tower, a red band and the lantern.
    x = land.shore(0.0) + 6.0
    base = on_ground(x, 0.0)
    parts.append(prism(ellipse((x, 0.0), (2.6, 2.6), 16), base, base + 20.0, "white", top_scale=0.75))
    parts.append(prism(ellipse((x, 0.0), (1.96, 1.96), 16), base + 20.0, base + 23.0, "red"))
    parts.append(box((x, base + 24.3, 0.0), (2.6, 2.6, 2.6), "steel"))
    # Boathouses of Falu red on the beach either side of the rock, their doors to the sea.
    for z in (-33.0, -23.0, 23.0, 32.0):
        x = land.shore(z) + 5.0
        parts += _house(x, z, on_ground(x, z), (7.0, 4.5, 6.0), "wall2", "roof0", rng, door=True)
    # Houses on the high cliff and the radio mast (70 m) behind them.
    for z in (236.0, 262.0, 300.0, 334.0):
        x = land.shore(z) + float(rng.uniform(15.0, 40.0))
        base = on_ground(x, z)
        tall = float(rng.uniform(6.0, 9.0))
        parts += _house(x, z, base, (9.0, tall, 12.0), f"wall{rng.integers(len(WALLS))}", "roof0", rng)
    x = land.shore(280.0) + 120.0
    parts.append(prism(ellipse((x, 280.0), (1.2, 1.2), 6), on_ground(x, 280.0), land.ground(x, 280.0) + 70.0, "red"))
    # Conifers (8-22 m) on the low land and along the cliff tops, birches among them; a grove on
    # the bluff and scrub behind the beach.
    trees: dict[int, list] = {k: [] for k in range(len(FOREST))}
    for z0, z1, count, inland, sizes in (
        (40.0, 200.0, 150, (2.0, 160.0), (8.0, 22.0)),
        (-420.0, -255.0, 70, (10.0, 120.0), (8.0, 22.0)),
        (205.0, 420.0, 60, (40.0, 200.0), (8.0, 22.0)),
        (-105.0, -45.0, 25, (15.0, 90.0), (5.0, 14.0)),  # a grove on the bluff
        (-40.0, 40.0, 90, (15.0, 250.0), (1.5, 4.0)),  # juniper scrub behind the beach
    ):
        for z in rng.uniform(z0, z1, count):
            x = land.shore(float(z)) + float(rng.uniform(*inland))
            kind = int(rng.choice(len(FOREST), p=[0.55, 0.3, 0.15]))
            trees[kind].append(((x, on_ground(x, float(z), 0.5), float(z)), float(rng.uniform(*sizes))))
    for kind, group in trees.items():
        if group:
            heights = np.array([h for _, h in group])
            spread = 0.35 if kind == 2 else 0.22  # birches: broader crowns
            parts.append(cones([b for b, _ in group], heights, spread * heights, f"forest{kind}"))
    return parts


def town_materials():
    """The paints of town()'s and shore_rocks()'s parts by name."""
    paints = {f"wall{k}": shading.Diffuse(c) for k, c in enumerate(WALLS)}
    paints.update({f"roof{k}": shading.Diffuse(c) for k, c in enumerate(ROOFS)})
    paints.update({f"forest{k}": shading.Diffuse(c) for k, c in enumerate(FOREST)})
    paints.update({f"boulder{k}": shading.Diffuse(c) for k, c in enumerate(BOULDERS)})
    paints.update({f"boat{k}": shading.Diffuse(c) for k, c in enumerate(BOATS)})
    paints.update(
        window=shading.Diffuse(WINDOW),
        white=shading.Diffuse(WALLS[0]),
        red=shading.Diffuse((0.55, 0.1, 0.07)),
        steel=shading.Diffuse((0.2, 0.2, 0.2)),
    )
    return paints
