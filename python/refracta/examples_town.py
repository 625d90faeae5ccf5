"""The Fata Morgana's coast (refracta.examples.fata_morgana): what stands on a shore 20 km away
that a duct stretches into towers -- cliffs of different heights, a harbour town (houses,
warehouses, a church with a spire, grain silos, a crane), a lighthouse on its rock, a conifer
forest and a radio mast. A Fata Morgana magnifies the lowest few tens of metres of the far shore
several-fold; a shore with structure there -- bright walls beside dark rock and trees, each
its own height -- is what shows the stacking and stretching as the photographs do (Lehn 1979,
"Fata Morgana and its photographic documentation").

Along the shore (z [m], the camera at z = 0 sees about -360 to 360 with its 1000 mm lens):
a 30 m cliff with trees on top to -250, the harbour town on a 3 m quay to -110, a 12 m bluff to
-40, the lighthouse on an 8 m rock at 0 by a beach, the forest on low land from 40 to 200, a 38 m
cliff with a few houses and the radio mast beyond.
"""

from __future__ import annotations

import numpy as np

from refracta import shading
from refracta.examples_meshes import Mesh, box, cones, ellipse, prism


def shore_cliff(z):
    """The height [m] of the cliff or quay standing at the shore at `z` [m] (module docstring),
    each step rising over ~10 m of shore."""
    z = np.asarray(z, dtype=float)
    steps = [(-1e9, 30.0), (-250.0, 3.0), (-110.0, 12.0), (-40.0, 2.0), (40.0, 6.0), (200.0, 38.0), (420.0, 24.0)]
    height = np.full(z.shape, steps[0][1])
    for start, value in steps[1:]:
        height = height + (value - height) * np.clip((z - start) / 10.0 + 0.5, 0.0, 1.0)
    rock = np.where(np.abs(z) < 14.0, 8.0, 0.0)  # the lighthouse's rock
    return np.maximum(height, rock)


WALLS = [(0.78, 0.76, 0.7), (0.7, 0.55, 0.35), (0.55, 0.22, 0.15), (0.5, 0.5, 0.48)]  # white, ochre, red, grey
ROOF = (0.12, 0.08, 0.07)
FOREST = (0.035, 0.06, 0.03)  # spruce canopy (diffuse albedo, visible)


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


def town(coast, rng: np.random.Generator) -> list[Mesh]:
    """The closed meshes of everything standing on `coast` (examples._coast's (x, z, height) of the
    land shaped by shore_cliff), each named by its paint: 'wall0'..'wall3', 'roof', 'white', 'red',
    'steel', 'forest'."""
    land = _Coast(coast)
    parts: list[Mesh] = []

    def on_ground(x, z, inset=1.0):
        return land.ground(x, z) - inset  # foundations sunk into the slope

    # The harbour town on its quay: two rows of houses and warehouses, each its own height.
    for row, depth in ((0, 12.0), (1, 40.0)):
        z = -246.0
        while z < -114.0:
            width = float(rng.uniform(8.0, 14.0)) if row else float(rng.uniform(9.0, 30.0))
            tall = float(rng.uniform(5.0, 11.0)) if row else float(rng.choice([6.0, 9.0, 12.0, 16.0]))
            x = land.shore(z + width / 2) + depth + (0.0 if row else 4.0)
            base = on_ground(x, z + width / 2)
            parts.append(box((x, base + tall / 2, z + width / 2), (10.0, tall, width - 1.5), f"wall{rng.integers(4)}"))
            parts.append(box((x, base + tall + 0.6, z + width / 2), (11.0, 1.2, width - 0.8), "roof"))
            z += width
    # The church: a nave, a square tower and its spire (top 44 m above the quay).
    x = land.shore(-170.0) + 70.0
    base = on_ground(x, -170.0)
    parts.append(box((x + 10.0, base + 7.0, -170.0), (28.0, 14.0, 12.0), "wall0"))
    parts.append(box((x - 6.0, base + 13.0, -170.0), (7.0, 26.0, 7.0), "wall0"))
    square = [(x - 9.5, -173.5), (x - 2.5, -173.5), (x - 2.5, -166.5), (x - 9.5, -166.5)]
    parts.append(prism(square, base + 26.0, base + 44.0, "roof", top_scale=0.05))
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
    # Houses on the high cliff and the radio mast (70 m) behind them.
    for z in (236.0, 262.0, 300.0, 334.0):
        x = land.shore(z) + float(rng.uniform(15.0, 40.0))
        base = on_ground(x, z)
        tall = float(rng.uniform(6.0, 9.0))
        parts.append(box((x, base + tall / 2, z), (9.0, tall, 12.0), f"wall{rng.integers(2)}"))
        parts.append(box((x, base + tall + 0.6, z), (10.0, 1.2, 13.0), "roof"))
    x = land.shore(280.0) + 120.0
    parts.append(prism(ellipse((x, 280.0), (1.2, 1.2), 6), on_ground(x, 280.0), land.ground(x, 280.0) + 70.0, "red"))
    # Conifers (8-22 m) on the low land and along the cliff tops.
    bases, tree_heights = [], []
    for z0, z1, count, inland in (
        (40.0, 200.0, 150, (2.0, 160.0)),
        (-420.0, -255.0, 70, (10.0, 120.0)),
        (205.0, 420.0, 60, (40.0, 200.0)),
    ):
        for z in rng.uniform(z0, z1, count):
            x = land.shore(float(z)) + float(rng.uniform(*inland))
            bases.append((x, on_ground(x, float(z), 0.5), float(z)))
            tree_heights.append(float(rng.uniform(8.0, 22.0)))
    heights = np.array(tree_heights)
    parts.append(cones(bases, heights, 0.22 * heights, "forest"))
    return parts


def town_materials():
    """The paints of town()'s parts by name."""
    paints = {f"wall{k}": shading.Diffuse(c) for k, c in enumerate(WALLS)}
    paints.update(
        roof=shading.Diffuse(ROOF),
        white=shading.Diffuse(WALLS[0]),
        red=shading.Diffuse((0.55, 0.1, 0.07)),
        steel=shading.Diffuse((0.2, 0.2, 0.2)),
        forest=shading.Diffuse(FOREST),
    )
    return paints
