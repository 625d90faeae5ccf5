"""Generated meshes of the example scenes (refracta.examples): a freighter's hull with its sheer line
and raked stem, the prisms of its superstructure and funnel, and cones for trees. Everything is
built here from a few numbers (nothing downloaded); every mesh is closed (each edge shared by
exactly two triangles, wound counter-clockwise seen from outside), so it casts and receives
shadows as a solid does.

Conventions: y up, metres; the ship lies along z with its bow toward -z, its keel's midpoint under
(0, 0), the waterline at y = 0.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(eq=False)  # arrays: == would be ambiguous (equal by identity)
class Mesh:
    """Vertices (n, 3) [m] and triangles (m, 3) (indices), closed and wound outward; `part` names
    what it is (the material the scene gives it: 'hull', 'white', 'funnel', ...)."""

    vertices: np.ndarray
    triangles: np.ndarray
    part: str

    def moved(self, offset, scale: float = 1.0) -> Mesh:
        """The mesh scaled by `scale` about the origin, then moved by `offset` [m]."""
        return Mesh(self.vertices * scale + np.asarray(offset, dtype=float), self.triangles, self.part)


def signed_volume(vertices: np.ndarray, triangles: np.ndarray) -> float:
    """The volume [m^3] a closed mesh encloses, positive when its triangles wind outward
    (divergence theorem: the sum of the tetrahedra from the origin to each triangle)."""
    a, b, c = (vertices[triangles[:, i]] for i in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def _rings_to_mesh(rings: np.ndarray, part: str) -> Mesh:
    """A closed tube through `rings` (stations, points, 3) -- each a closed polygon, consecutive
    rings joined by quads -- capped at both ends by a fan around the ring's centroid; wound
    outward (flipped if its signed volume comes out negative)."""
    count, points, _ = rings.shape
    vertices = rings.reshape(-1, 3)
    index = np.arange(count * points).reshape(count, points)
    a, b = index[:-1], index[1:]
    a2, b2 = np.roll(a, -1, axis=1), np.roll(b, -1, axis=1)
    pieces = [np.stack([a, b, b2], -1).reshape(-1, 3), np.stack([a, b2, a2], -1).reshape(-1, 3)]
    centres = [len(vertices), len(vertices) + 1]
    vertices = np.concatenate([vertices, rings[0].mean(axis=0)[None], rings[-1].mean(axis=0)[None]])
    ring = np.arange(points)
    pieces.append(np.stack([np.full(points, centres[0]), ring, np.roll(ring, -1)], -1))
    last = index[-1]
    pieces.append(np.stack([np.full(points, centres[1]), np.roll(last, -1), last], -1))
    triangles = np.concatenate(pieces)
    if signed_volume(vertices, triangles) < 0:
        triangles = triangles[:, ::-1]
    return Mesh(vertices, np.ascontiguousarray(triangles), part)


def _smoothstep(t):
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


# A small general-cargo freighter (scale 1): 110 m overall, 18 m beam, the deck 8 m above the
# waterline amidships (SHIP_HULL in refracta.examples) and 6 m of draught; the sheer line rises
# 1.5 m toward the stern and 3 m toward the bow, the forecastle 2.5 m above that; the stem raked
# forward 7 m from keel to deck, the transom aft 2 m.
HULL_LENGTH = 110.0  # [m] overall, stem head to transom
HULL_BEAM = 18.0  # [m]
HULL_FREEBOARD = 8.0  # [m] deck above the waterline amidships
HULL_DRAUGHT = 6.0  # [m]
HULL_STATIONS = 48
HULL_SECTION_POINTS = 25  # odd: the keel (theta = pi / 2) is a node


def ship_hull(
    length: float = HULL_LENGTH,
    beam: float = HULL_BEAM,
    freeboard: float = HULL_FREEBOARD,
    draught: float = HULL_DRAUGHT,
) -> Mesh:
    """A freighter's hull, closed: stations from the transom (z = +length/2) to the stem (z =
    -length/2), each a closed section -- a superellipse (exponent 6: flat bottom, rounded bilge,
    near-vertical sides) from the keel up to the deck edge, closed across the deck. The half-beam
    runs from 0.8 of the full at the transom through a parallel midbody to a sharp stem (a fine
    entrance over the forward 35 %); the deck edge follows the sheer line (highest at the bow, with
    a raised forecastle); the stem rakes forward and the transom aft with height."""
    s = np.concatenate([[0.0], np.linspace(0.0, 1.0, HULL_STATIONS)[1:-1] ** 0.9, [1.0]])  # 0 stern, 1 bow
    half = (
        0.5
        * beam
        * np.where(
            s < 0.15,
            0.8 + 0.2 * np.sqrt(_smoothstep(s / 0.15)),
            np.where(s > 0.65, np.sqrt(np.clip(1.0 - ((s - 0.65) / 0.35) ** 2, 0.0, 1.0)), 1.0),
        )
    )
    half = np.maximum(half, 0.01 * beam)  # the stem: a sharp edge, not a point (no degenerate ring)
    deck = (
        freeboard
        + 1.5 * np.clip((0.4 - s) / 0.4, 0.0, 1.0) ** 2
        + 3.0 * np.clip((s - 0.45) / 0.55, 0.0, 1.0) ** 2
        + 2.5 * _smoothstep((s - 0.84) / 0.03)  # the forecastle
    )
    keel = -draught + 0.6 * draught * _smoothstep((s - 0.9) / 0.1)  # the forefoot rises to the stem
    theta = np.linspace(0.0, np.pi, HULL_SECTION_POINTS)  # starboard deck edge, keel, port deck edge
    c, si = np.cos(theta), np.sin(theta)
    x = half[:, None] * np.sign(c) * np.abs(c) ** (2.0 / 6.0)
    rise = np.abs(si) ** (2.0 / 6.0)  # 0 at the deck edges, 1 at the keel
    y = deck[:, None] - (deck - keel)[:, None] * rise
    up = (y - keel[:, None]) / (deck - keel)[:, None]  # 0 at the keel, 1 at the deck
    z = 0.5 * length - s[:, None] * (length - 9.0)  # the stem's foot 7 m and the transom's 2 m inside
    z = z - 7.0 * up * _smoothstep((s - 0.8) / 0.2)[:, None] + 2.0 * up * _smoothstep((0.1 - s) / 0.1)[:, None]
    rings = np.stack([x, y, z], axis=-1)
    return _rings_to_mesh(rings, "hull")


def prism(outline, bottom: float, top: float, part: str, top_shift=(0.0, 0.0), top_scale: float = 1.0) -> Mesh:
    """A closed prism: the polygon `outline` [(x, z), ...] (convex, either winding) at height
    `bottom` [m], and at `top` the same polygon scaled by `top_scale` about its centroid and moved
    by `top_shift` (dx, dz) [m] (a raked, tapering funnel or mast)."""
    outline = np.asarray(outline, dtype=float)
    centre = outline.mean(axis=0)
    upper = centre + (outline - centre) * top_scale + np.asarray(top_shift, dtype=float)
    rings = np.stack(
        [
            np.column_stack([outline[:, 0], np.full(len(outline), bottom), outline[:, 1]]),
            np.column_stack([upper[:, 0], np.full(len(outline), top), upper[:, 1]]),
        ]
    )
    return _rings_to_mesh(rings, part)


def box(centre, size, part: str) -> Mesh:
    """An axis-aligned box as a closed mesh: centre (x, y, z) and size (dx, dy, dz) [m]."""
    (cx, cy, cz), (dx, dy, dz) = centre, size
    outline = [
        (cx - dx / 2, cz - dz / 2),
        (cx + dx / 2, cz - dz / 2),
        (cx + dx / 2, cz + dz / 2),
        (cx - dx / 2, cz + dz / 2),
    ]
    return prism(outline, cy - dy / 2, cy + dy / 2, part)


def ellipse(centre, radii, points: int = 16):
    """The outline [(x, z), ...] of an ellipse: centre (x, z), radii (rx, rz) [m]."""
    t = np.linspace(0.0, 2.0 * np.pi, points, endpoint=False)
    return np.column_stack([centre[0] + radii[0] * np.cos(t), centre[1] + radii[1] * np.sin(t)])


# The freighter's upper works (scale 1, z from the hull's middle; the bow toward -z): an
# accommodation block of three tiers aft with the bridge and its wings on top, a funnel raked aft
# (its top SHIP_HEIGHT = 28 m above the waterline), a foremast and a mainmast with cross-trees,
# two deck cranes between the holds, and containers stacked two and three high on the hatches.
SHIP_FUNNEL_TOP = 28.0  # [m]


def ship(rng: np.random.Generator | None = None) -> list[Mesh]:
    """A general-cargo freighter at scale 1 (ship_hull and its upper works), its parts named
    'hull', 'white' (superstructure), 'funnel', 'funnel_top', 'mast' (masts and cranes) and
    'cargo0'..'cargo2' (container colours); every part closed. rng: draws the container stacks'
    heights and colours (None: a fixed one, the same ship every time)."""
    rng = np.random.default_rng(3) if rng is None else rng
    deck = HULL_FREEBOARD
    parts = [ship_hull()]
    # Accommodation aft: tiers stepping back, the bridge above with wings over the full beam.
    for bottom, height, front, back, half in ((deck, 2.8, 24.0, 50.0, 7.5), (deck + 2.8, 2.8, 26.0, 48.0, 7.0)):
        parts.append(box((0.0, bottom + height / 2, (front + back) / 2), (2 * half, height, back - front), "white"))
    parts.append(box((0.0, deck + 7.0, 38.0), (13.0, 2.8, 20.0), "white"))
    parts.append(box((0.0, deck + 9.6, 34.0), (17.6, 2.4, 7.0), "white"))  # the bridge and its wings
    parts.append(box((0.0, deck + 11.4, 34.5), (5.0, 1.2, 4.0), "white"))  # the compass deck
    # The funnel: an oval raked aft behind the bridge, a black top band.
    funnel = ellipse((0.0, 44.0), (2.4, 3.6))
    rake = 0.12  # aft per metre up
    parts.append(prism(funnel, deck + 5.0, SHIP_FUNNEL_TOP - 2.0, "funnel", top_shift=(0.0, rake * 15.0)))
    top_funnel = funnel + [0.0, rake * 15.0]
    parts.append(prism(top_funnel, SHIP_FUNNEL_TOP - 2.0, SHIP_FUNNEL_TOP, "funnel_top", top_shift=(0.0, rake * 2.0)))
    # Masts: the foremast on the forecastle, the mainmast on the bridge; each with a cross-tree.
    for z, foot, top in ((-44.0, deck + 4.5, 24.0), (32.0, deck + 12.0, 26.0)):
        parts.append(prism(ellipse((0.0, z), (0.35, 0.35), 8), foot, top, "mast", top_scale=0.6))
        parts.append(box((0.0, top - 3.0, z), (6.0, 0.3, 0.3), "mast"))
    # Two deck cranes between the holds: a pedestal and a jib raised toward the bow.
    for z in (-14.0, 8.0):
        parts.append(prism(ellipse((0.0, z), (1.2, 1.2), 10), deck, deck + 9.0, "mast"))
        jib = [(-0.4, z - 0.4), (0.4, z - 0.4), (0.4, z + 0.4), (-0.4, z + 0.4)]
        parts.append(prism(jib, deck + 8.0, deck + 17.0, "mast", top_shift=(0.0, -11.0), top_scale=0.6))
    # Containers (12.2 x 2.6 x 2.4 m: 40 ft) on the hatches, stacks 1-3 high across the beam.
    for z0, z1 in ((-38.0, -18.0), (-10.0, 4.0), (12.0, 22.0)):
        for z in np.arange(z0 + 1.2, z1, 2.5):
            stack = int(rng.integers(1, 4))
            parts.append(box((0.0, deck + 1.0 + 1.3 * stack, z), (12.2, 2.6 * stack, 2.4), f"cargo{rng.integers(3)}"))
    return parts


def cones(bases, heights, radii, part: str, points: int = 8) -> Mesh:
    """Many closed cones in one mesh (a conifer forest): apexes `heights` [m] above `bases` (n, 3)
    [m], base `radii` [m], `points` around each."""
    bases = np.asarray(bases, dtype=float)
    heights, radii = np.broadcast_to(heights, len(bases)), np.broadcast_to(radii, len(bases))
    t = np.linspace(0.0, 2.0 * np.pi, points, endpoint=False)
    ring = np.column_stack([np.cos(t), np.zeros(points), np.sin(t)])
    # Per cone: the base ring, the base's centre, the apex.
    rim = bases[:, None, :] + radii[:, None, None] * ring[None]
    centre, apex = bases, bases + np.column_stack([np.zeros(len(bases)), heights, np.zeros(len(bases))])
    vertices = np.concatenate([rim.reshape(-1, 3), centre, apex])
    n = len(bases)
    first = (np.arange(n) * points)[:, None]
    i, j = first + np.arange(points)[None], first + np.roll(np.arange(points), -1)[None]
    c, a = (n * points + np.arange(n))[:, None], (n * points + n + np.arange(n))[:, None]
    sides = np.stack([i, np.broadcast_to(a, i.shape), j], -1)  # seen from outside: counter-clockwise
    bottom = np.stack([i, j, np.broadcast_to(c, i.shape)], -1)
    triangles = np.concatenate([sides.reshape(-1, 3), bottom.reshape(-1, 3)])
    if signed_volume(vertices, triangles) < 0:
        triangles = triangles[:, ::-1]
    return Mesh(vertices, np.ascontiguousarray(triangles), part)


def add_meshes(scene, meshes: list[Mesh], materials: dict) -> None:
    """Add `meshes` to `scene`, one mesh per part name (their paint: materials[part])."""
    by_part: dict[str, list[Mesh]] = {}
    for mesh in meshes:
        by_part.setdefault(mesh.part, []).append(mesh)
    for part, group in by_part.items():
        offsets = np.cumsum([0] + [len(m.vertices) for m in group[:-1]])
        vertices = np.concatenate([m.vertices for m in group])
        triangles = np.concatenate([m.triangles + o for m, o in zip(group, offsets)])
        scene.add_mesh(vertices, triangles, material=materials[part])
