"""The generated meshes of the example scenes (refracta.examples_meshes, examples_town): closed
and wound outward, with the stated dimensions; and the green flash's chroma filter
(refracta.examples_chroma)."""

import numpy as np
import pytest

from refracta import examples, examples_chroma, examples_meshes, examples_town


def _is_closed(mesh):
    """Every edge is shared by exactly two triangles that run it in opposite directions (a closed,
    consistently wound 2-manifold): each directed edge once, and its reverse present."""
    t = mesh.triangles
    edges = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    directed = set(map(tuple, edges))
    return len(directed) == len(edges) and all((b, a) in directed for a, b in directed)


def test_every_part_of_the_ship_is_closed_and_wound_outward():
    for mesh in examples_meshes.ship():
        assert _is_closed(mesh), mesh.part
        assert examples_meshes.signed_volume(mesh.vertices, mesh.triangles) > 0, mesh.part


def test_the_hull_has_the_stated_dimensions_a_sheer_line_and_a_raked_stem():
    hull = examples_meshes.ship_hull()
    v = hull.vertices
    lo, hi = v.min(axis=0), v.max(axis=0)
    # Rounding: the extremes are vertices placed exactly at the stated numbers (sections reach
    # the full half-beam at theta = 0 and pi and the keel at pi / 2; the stem head and transom are
    # the end stations').
    assert hi[0] - lo[0] == pytest.approx(examples_meshes.HULL_BEAM, rel=1e-12)
    assert hi[2] - lo[2] == pytest.approx(examples_meshes.HULL_LENGTH, rel=1e-12)  # rounding only
    assert lo[1] == pytest.approx(-examples_meshes.HULL_DRAUGHT, rel=1e-12)  # rounding only

    # The deck edge of each station (the first point of its section; the two caps' centres last),
    # from the transom (+z) to the stem (-z): the sheer line. Its lowest point is the freeboard
    # (examples.SHIP_HULL); it rises to both ends, most at the raised forecastle at the bow.
    stations = v[:-2].reshape(examples_meshes.HULL_STATIONS, examples_meshes.HULL_SECTION_POINTS, 3)
    sheer = stations[:, 0, 1]
    assert sheer.min() == pytest.approx(
        examples.SHIP_HULL, rel=1e-12
    )  # rounding only: a station sits at the sheer's low point
    low = int(np.argmin(sheer))
    assert 0 < low < len(sheer) - 1
    assert np.all(np.diff(sheer[: low + 1]) <= 0) and np.all(np.diff(sheer[low:]) >= 0)  # fair: no dips
    assert sheer[-1] > sheer[0] > sheer.min() + 1.0
    # The stem rakes forward: its head (at the deck) lies ahead of its foot (at the keel).
    bow = v[v[:, 2] < -40.0]
    head = bow[bow[:, 1] > examples_meshes.HULL_FREEBOARD][:, 2].min()
    foot = bow[bow[:, 1] < -1.0][:, 2].min()
    assert head < foot - 5.0, (head, foot)


def test_the_ship_stands_to_its_funnel_top_within_its_length_and_beam():
    vertices = np.concatenate([m.vertices for m in examples_meshes.ship()])
    assert vertices[:, 1].max() == pytest.approx(examples.SHIP_HEIGHT, rel=1e-12)  # the funnel's top cap
    assert vertices[:, 0].max() - vertices[:, 0].min() <= examples_meshes.HULL_BEAM
    assert vertices[:, 2].max() - vertices[:, 2].min() <= examples_meshes.HULL_LENGTH


def test_cones_are_closed_with_the_volume_of_their_polygonal_base():
    trees = examples_meshes.cones([[0.0, 0.0, 0.0], [10.0, 1.0, 0.0]], [5.0, 8.0], [1.0, 2.0], "forest", points=8)
    assert _is_closed(trees)
    # An inscribed regular octagon's area: (8/2) r^2 sin(2 pi / 8); a cone's volume: area x h / 3.
    octagon = 4.0 * np.sin(np.pi / 4)
    expected = octagon * (1.0 * 5.0 + 4.0 * 8.0) / 3.0
    assert examples_meshes.signed_volume(trees.vertices, trees.triangles) == pytest.approx(
        expected, rel=1e-12
    )  # rounding of the sum


def test_the_fata_morgana_shore_has_cliffs_of_several_heights_and_a_town_on_it():
    z = np.linspace(-360.0, 360.0, 721)  # the 1000 mm view's width at 20 km
    heights = examples_town.shore_cliff(z)
    # Several distinct levels between 2 and 40 m: the stacked images need structure there.
    levels = np.unique(np.round(heights[np.abs(np.gradient(heights)) < 1e-9]))
    assert len(levels) >= 5 and levels.min() <= 3.0 and levels.max() >= 30.0, (
        levels
    )  # the quay ~2-3 m, the cliffs 30 and 38 m
    rng = np.random.default_rng(0)
    x = np.arange(19500.0, 20500.0, 6.0)
    land = np.clip((x[:, None] - 20000.0) / 6.0, 0.0, 1.0) * examples_town.shore_cliff(z[::6])[None, :]
    parts = examples_town.town((x, z[::6], land), rng)
    assert all(_is_closed(m) for m in parts)
    tops = np.array([m.vertices[:, 1].max() for m in parts])
    assert tops.max() > 60.0 and np.sum((tops > 5.0) & (tops < 30.0)) >= 20  # a mast; many lower roofs


def _synthetic_shore():
    """A coast like examples._coast's around shore_cliff: sea bed, then the cliff rising over 6 m
    from x = 20000 m (nodes every 6 m across, 6 m along the shore)."""
    x = np.arange(19500.0, 20500.0, 6.0)
    z = np.arange(-420.0, 426.0, 6.0)
    land = np.clip((x[:, None] - 20000.0) / 6.0, 0.0, 1.0) * examples_town.shore_cliff(z)[None, :]
    return x, z, np.where(x[:, None] < 20000.0, 0.04 * (x[:, None] - 20000.0), land)


# The cliffs' buttresses: a face turned 17 deg or more to the side (|n_z| > 0.3) is lit by the
# FATA_MORGANA sun (15 deg high, 125 deg round) at n.l <= 0.32 or >= 0.77, against 0.55 facing the
# sea -- the light-and-shade ribs a Fata Morgana stretches into columns. A fifth of the face's area.
RIBBED_AREA = 0.2


def test_the_cliff_faces_are_closed_ribbed_and_stand_before_the_coasts_own_face():
    coast = _synthetic_shore()
    faces = examples_town.cliff_faces(coast, np.random.default_rng(0))
    mesh = faces.mesh
    assert _is_closed(mesh)
    assert examples_meshes.signed_volume(mesh.vertices, mesh.triangles) > 0
    assert len(faces.uvs) == len(mesh.vertices) and np.all((faces.uvs >= 0.0) & (faces.uvs <= 1.0))
    # Every vertex of the faces below the land's top stands seaward of the land at its height (the
    # height field's own smooth face hidden behind them), and no face is built over the beach.
    x, z, height = coast
    v = mesh.vertices
    column = np.abs(z[None, :] - v[:, 2:3]).argmin(axis=1)
    below = (v[:, 1] > 0.5) & (v[:, 1] < examples_town.shore_cliff(v[:, 2]) - 0.5)
    land_x = np.array([np.interp(y, height[:, j], x) for y, j in zip(v[below, 1], column[below])])
    assert np.all(v[below, 0] < land_x - 1.0), (v[below, 0] - land_x).max()
    assert np.all(examples_town.shore_cliff(v[:, 2]) >= examples_town.CLIFF_MIN - 0.5)
    # Ribbed: the share of the seaward face's area turned to the side.
    a, b, c = (v[mesh.triangles[:, i]] for i in range(3))
    n = np.cross(b - a, c - a)
    area = np.linalg.norm(n, axis=1)
    n = n / area[:, None]
    seaward = n[:, 0] < -0.3
    assert np.sum(area[seaward & (np.abs(n[:, 2]) > 0.3)]) >= RIBBED_AREA * np.sum(area[seaward])


def test_the_boulders_and_boats_are_closed_and_lie_at_the_waterline():
    coast = _synthetic_shore()
    rng = np.random.default_rng(0)
    faces = examples_town.cliff_faces(coast, rng)
    parts = examples_town.shore_rocks(coast, faces, rng)
    for mesh in parts:
        assert _is_closed(mesh), mesh.part
        assert examples_meshes.signed_volume(mesh.vertices, mesh.triangles) > 0, mesh.part
    boulders = [m for m in parts if m.part.startswith("boulder")]
    assert len(boulders) >= 100  # one every 2-6 m of the 840 m of shore but the quay's 140 m
    for mesh in boulders:
        lo, hi = mesh.vertices.min(axis=0), mesh.vertices.max(axis=0)
        assert lo[1] < 0.0 < hi[1] <= 3.75  # sunk into the sea bed, at most 0.75 x 5 m above it
    assert sum(m.part.startswith("boat") for m in parts) == 4


def test_the_cliff_faces_texture_varies_as_rock_heath_and_weed_do():
    faces = examples_town.cliff_faces(_synthetic_shore(), np.random.default_rng(0))
    albedo = faces.albedo
    rows, columns, _ = albedo.shape
    y = examples_town.CLIFF_TOP - (np.arange(rows) + 0.5) * examples_town.TEXEL[1]
    z = faces.z[0] + (np.arange(columns) + 0.5) * examples_town.TEXEL[0]
    lum = albedo @ np.array([0.2126, 0.7152, 0.0722])
    granite = z < -270.0  # the 30 m cliff
    face = (y > 4.0) & (y < 20.0)  # above the splash zone, below the heath of its top
    # Along the shore: streaks, gullies, bird lime; up the face: strata (coefficients of variation;
    # a uniformly painted face: 0).
    along = lum[face][:, granite].mean(axis=0)
    up = lum[face][:, granite].mean(axis=1)
    assert along.std() / along.mean() > 0.15 and up.std() / up.mean() > 0.05  # measured 0.29, 0.18: half that
    # Heath on ledges and tops: green texels (g above r and b) on the natural rock, a few percent.
    green = (albedo[..., 1] > albedo[..., 0]) & (albedo[..., 1] > albedo[..., 2])
    assert 0.02 < green[y > 0.0][:, granite].mean() < 0.6  # a few percent: present, not a green face
    # The tidal zone: black weed below the waterline's wander (the tide line at 1.0 +- 0.4 m).
    assert lum[y < 0.4].mean() < 0.05
    # The quay's dressed stone: plain grey, no heath.
    quay = (z > -240.0) & (z < -120.0)
    assert not green[(y > 1.5) & (y < 3.0)][:, quay].any()


def test_chroma_filter_removes_colour_noise_and_keeps_a_sharp_coloured_edge():
    rng = np.random.default_rng(1)
    h, w = 64, 64
    truth = np.zeros((h, w, 3))
    truth[:, :32] = (1.0, 0.5, 0.1)  # an orange disc ...
    truth[:, 32:] = (0.001, 0.01, 0.02)  # ... beside a dim blue sky, 100x darker
    # Colour noise of one-wavelength samples: each pixel's channels scaled by independent factors
    # of mean 1 (its luminance kept), as a sample's colour scatters about the pixel's mean colour.
    noisy = truth * rng.gamma(2.0, 0.5, size=truth.shape)
    luminance = truth @ examples_chroma.LUMINANCE
    out = examples_chroma.chroma_filter(noisy, luminance)
    chroma = out / out.sum(axis=2, keepdims=True)
    expected = truth / truth.sum(axis=2, keepdims=True)
    noisy_chroma = noisy / noisy.sum(axis=2, keepdims=True)
    inside = (slice(8, -8), slice(4, 26))
    # Noise: the raw chroma scatters by ~0.2; averaged over ~800 pixels it should fall below 0.02.
    assert np.abs(noisy_chroma[inside] - expected[inside]).std() > 0.1
    assert np.abs(chroma[inside] - expected[inside]).max() < 0.03  # ~0.2 / sqrt(800) x 4 sigma, rounded up
    # The edge: the column next to it on each side keeps its own colour (the filter does not cross
    # a 100x step in luminance; 0.03: the same averaging error as inside).
    assert np.abs(chroma[8:-8, 31] - expected[8:-8, 31]).max() < 0.03
    assert np.abs(chroma[8:-8, 32] - expected[8:-8, 32]).max() < 0.03  # as inside
    # Its luminance is the guide's.
    np.testing.assert_allclose(out @ examples_chroma.LUMINANCE, luminance, rtol=1e-5)  # float32 output


def test_chroma_filter_names_bad_input():
    with pytest.raises(ValueError, match="luminance"):
        examples_chroma.chroma_filter(np.ones((4, 4, 3)), np.ones((4, 5)))
    with pytest.raises(ValueError, match="sigma"):
        examples_chroma.chroma_filter(np.ones((4, 4, 3)), np.ones((4, 4)), sigma=0.0)
    with pytest.raises(ValueError, match="finite"):
        examples_chroma.chroma_filter(np.full((4, 4, 3), np.nan), np.ones((4, 4)))
