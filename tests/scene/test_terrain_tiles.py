"""Tiles of elevation data given to Scene.add_terrain as a list: tiles on one lattice are joined
into one grid (pixel-is-area GeoTIFF tiles left a crack one sample wide between their grids), SRTM
tiles' shared edge samples are taken once, tiles on different lattices stay apart (warned where a
crack may show), and a geographic grid all around the Earth is closed where its columns wrap."""

import math
import warnings

import numpy as np
import pytest

import refracta
from refracta import geo, terrain

from .test_terrain import write_geotiff, write_hgt

# Vertices are float32 in Embree: 1 mm covers their rounding at the few kilometres (and heights of
# a few hundred metres) of these scenes, and the hits are re-solved in double against them.
FLOAT32 = 1e-3  # [m]
STEP = 0.001  # [deg] the tiles' sample spacing (~110 m of latitude)


def hill(rows, cols):
    """Heights [m] of a smooth hill over a (rows, cols) grid: a different height at every sample."""
    r, c = np.mgrid[0:rows, 0:cols]
    return (300.0 + 1500.0 * np.exp(-(((r - rows / 2) / 8.0) ** 2 + ((c - cols / 2) / 10.0) ** 2)) + c).astype(
        np.float32
    )


def tiles_and_whole(tmp_path, heights, split, west=7.0, north=46.02):
    """A pixel-is-area GeoTIFF of ``heights`` and the same split at column ``split`` into a west and
    an east tile (GDAL's tiling: the east tile's corner one pixel-width after the west's last pixel)."""
    whole = write_geotiff(tmp_path / "whole.tif", heights, (west, north), (STEP, STEP))
    w = write_geotiff(tmp_path / "west.tif", heights[:, :split], (west, north), (STEP, STEP))
    e = write_geotiff(tmp_path / "east.tif", heights[:, split:], (west + split * STEP, north), (STEP, STEP))
    return whole, w, e


def added(paths, frame):
    """A scene with the terrain of ``paths`` and its ids, failing on any warning."""
    scene = refracta.Scene()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ids = scene.add_terrain(paths, frame=frame)
    return scene, ids.terrain


def test_pixel_is_area_tiles_are_joined_into_the_grid_they_were_cut_from(tmp_path):
    heights = hill(20, 40)
    whole, west, east = tiles_and_whole(tmp_path, heights, split=20)
    frame = geo.LocalFrame(46.01, 7.02, earth_radius=geo.radius_of_curvature(46.01, 0.0))
    one, one_ids = added(whole, frame)
    joined, joined_ids = added([west, east], frame)
    assert joined_ids == [0]  # one grid, not one per tile
    # Across the former crack: between the west tile's last sample centre (7.0195 E) and the east
    # tile's first (7.0205 E), and on either side of it, on every row of cells.
    for lat in 46.02 - STEP * (np.arange(1.5, 19.0, 1.7)):
        for lon in (7.0192, 7.0197, 7.02, 7.0203, 7.0208):
            p = frame.to_scene(lat, lon, 0.0)
            expected = one.terrain_height(p[0], p[2])
            assert expected is not None
            got = joined.terrain_height(p[0], p[2])
            assert got is not None, (lat, lon)
            # The same samples at the same places give the same float32 vertices; 1 um allows only
            # the hit's re-solve in double.
            assert got == pytest.approx(expected, abs=1e-6), (lat, lon)
    assert one_ids == [0]


def test_an_orthophoto_is_draped_over_joined_tiles_by_its_georeference(tmp_path):
    # The grid joined from two tiles gets the uvs of the whole grid: 8 texels of 0.0025 deg over
    # 7.0-7.02 E, three red, two green over the former crack (7.0095-7.0105 E), three blue.
    _, west, east = tiles_and_whole(tmp_path, np.full((20, 20), 100.0, np.float32), split=10)
    photo = np.zeros((8, 8, 3), dtype=np.uint8)
    photo[:, :3] = (255, 0, 0)
    photo[:, 3:5] = (0, 255, 0)
    photo[:, 5:] = (0, 0, 255)
    ortho = write_geotiff(tmp_path / "ortho.tif", photo, (7.0, 46.02), (0.0025, 0.0025))
    frame = geo.LocalFrame(46.01, 7.01, earth_radius=math.inf)
    scene = refracta.Scene()
    assert scene.add_terrain([west, east], frame=frame, orthophoto=ortho).terrain == [0]
    scene.set_sun((0.0, 1.0, 0.0), (1.0, 1.0, 1.0))
    # Each at least one texel from another colour (texels are filtered over their neighbours).
    for lon, colour in ((7.004, 0), (7.01, 1), (7.016, 2)):
        p = frame.to_scene(46.01, lon, 100.0)
        camera = refracta.Camera(p + [0.0, 50.0, 0.0], p, up=(0.0, 0.0, -1.0), vfov=1.0, width=4, height=4)
        pixel = refracta.render(scene, camera, None, progress=False)[2, 2]
        others = [pixel[k] for k in range(3) if k != colour]
        assert pixel[colour] > 5 * max(others), (lon, pixel)  # the texel's colour, not its neighbours'


def test_srtm_tiles_share_their_edge_samples_once(tmp_path):
    # Two 1201 x 1201 tiles (3 arc-seconds) side by side: the east tile's column 0 is the west
    # tile's column 1200, 8 E. The joined grid holds it once, unshifted: 2401 columns from 7 E.
    n = 1201
    rng = np.random.default_rng(7)
    mosaic = rng.integers(0, 3000, (n, 2 * n - 1)).astype(np.int16)
    mosaic[600, 1200] = -32768  # a void on the west tile's edge: the east tile has the sample
    west = write_hgt(tmp_path, "N46E007.hgt", mosaic[:, :n])
    east_heights = mosaic[:, n - 1 :].copy()
    east_heights[600, 0] = 1234
    east = write_hgt(tmp_path, "N46E008.hgt", east_heights)
    # The joined grid, read and joined as add_terrain does (placing it would take ~4 s of pyproj).
    (grid,) = terrain._tile_grids([str(west), str(east)])
    expected = mosaic.astype(np.float64)
    expected[600, 1200] = 1234.0  # the first tile's void, filled by the second tile's sample
    assert grid.heights.shape == (n, 2 * n - 1)
    assert np.array_equal(grid.heights, expected)
    assert (grid.x0, grid.y0, grid.dx, grid.dy, grid.epsg) == (7.0, 47.0, 1.0 / 1200, 1.0 / 1200, 4326)


def test_tiles_sharing_edge_samples_are_placed_as_the_grid_they_were_cut_from(tmp_path):
    # Pixel-is-point GeoTIFF tiles sharing a column of samples, as SRTM tiles do (small enough to place).
    heights = hill(20, 41)
    point = {"scale": (STEP, STEP), "raster": 2}
    whole = write_geotiff(tmp_path / "whole.tif", heights, (7.0, 46.02), **point)
    west = write_geotiff(tmp_path / "west.tif", heights[:, :21], (7.0, 46.02), **point)
    east = write_geotiff(tmp_path / "east.tif", heights[:, 20:], (7.02, 46.02), **point)
    frame = geo.LocalFrame(46.01, 7.02, earth_radius=math.inf)
    one, _ = added(whole, frame)
    joined, ids = added([west, east], frame)
    assert ids == [0]
    for lat in (46.0185, 46.0103, 46.0021):
        for lon in (7.0193, 7.01999, 7.02, 7.02001, 7.0207):
            p = frame.to_scene(lat, lon, 0.0)
            expected = one.terrain_height(p[0], p[2])
            assert expected is not None
            # The same samples at the same places: the same float32 vertices (1 um: the hit's re-solve).
            assert joined.terrain_height(p[0], p[2]) == pytest.approx(expected, abs=1e-6), (lat, lon)


def test_tiles_either_side_of_the_antimeridian_are_joined(tmp_path):
    heights = np.full((10, 20), 250.0, np.float32)
    east = write_geotiff(tmp_path / "east.tif", heights, (179.98, -17.0), (STEP, STEP))  # Fiji: 179.98-180 E
    west = write_geotiff(tmp_path / "west.tif", heights, (-180.0, -17.0), (STEP, STEP))  # 180-179.98 W
    frame = geo.LocalFrame(-17.005, 180.0, earth_radius=math.inf)
    scene, ids = added([east, west], frame)
    assert ids == [0]
    p = frame.to_scene(-17.005, 180.0, 250.0)  # in the former crack, on the antimeridian
    assert scene.terrain_height(p[0], p[2]) == pytest.approx(250.0, abs=FLOAT32)


def test_tiles_on_one_lattice_that_do_not_touch_stay_apart_without_a_warning(tmp_path):
    heights = hill(10, 10)
    a = write_geotiff(tmp_path / "a.tif", heights, (7.0, 46.02), (STEP, STEP))
    b = write_geotiff(tmp_path / "b.tif", heights, (7.05, 46.02), (STEP, STEP))  # 40 samples east of a
    _, ids = added([a, b], geo.LocalFrame(46.01, 7.03, earth_radius=math.inf))
    assert ids == [0, 1]  # nothing between them to join: two grids, not one mostly of NaN


def test_touching_tiles_too_sparse_to_join_stay_apart_with_a_warning(tmp_path):
    # 4 x 4-sample tiles touching corner to corner along a diagonal. Two of them fill half of
    # their 8 x 8 grid and are joined; three fill a third of their 12 x 12 grid: kept apart.
    heights = np.full((4, 4), 100.0, np.float32)
    paths = [
        write_geotiff(tmp_path / f"d{k}.tif", heights, (7.0 + 4 * k * STEP, 46.02 - 4 * k * STEP), (STEP, STEP))
        for k in range(3)
    ]
    frame = geo.LocalFrame(46.01, 7.01, earth_radius=math.inf)
    _, ids = added(paths[:2], frame)
    assert ids == [0]
    scene = refracta.Scene()
    with pytest.warns(refracta.SceneWarning, match=r"d0.tif.*d1.tif.*d2.tif.*too sparse to join.*crack may show"):
        assert scene.add_terrain(paths, frame=frame).terrain == [0, 1, 2]


@pytest.mark.parametrize(
    "scale, corner",
    [
        ((2 * STEP, 2 * STEP), (7.01, 46.02)),  # a coarser tile beside the fine one
        ((STEP, STEP), (7.01, 46.02 + 0.5 * STEP)),  # the same spacing, half a sample north
    ],
)
def test_tiles_on_different_lattices_meeting_edge_to_edge_stay_apart_with_a_warning(tmp_path, scale, corner):
    fine = write_geotiff(tmp_path / "fine.tif", np.full((10, 10), 100.0, np.float32), (7.0, 46.02), (STEP, STEP))
    other = write_geotiff(tmp_path / "other.tif", np.full((10, 10), 100.0, np.float32), corner, scale)
    scene = refracta.Scene()
    with pytest.warns(refracta.SceneWarning, match=r"fine.tif.*other.tif.*crack may show"):
        ids = scene.add_terrain([fine, other], frame=geo.LocalFrame(46.01, 7.01, earth_radius=math.inf))
    assert ids.terrain == [0, 1]


def test_tiles_on_different_lattices_that_overlap_or_lie_apart_are_not_warned_of(tmp_path):
    # No crack can show: an inset of finer samples over a coarse tile covers ground the coarse tile
    # covers too; tiles far apart have nothing between them.
    frame = geo.LocalFrame(46.01, 7.01, earth_radius=math.inf)
    coarse = write_geotiff(tmp_path / "coarse.tif", np.full((10, 10), 100.0, np.float32), (7.0, 46.02), (0.002, 0.002))
    inset = write_geotiff(tmp_path / "inset.tif", np.full((6, 6), 100.0, np.float32), (7.005, 46.015), (STEP, STEP))
    far = write_geotiff(tmp_path / "far.tif", np.full((6, 6), 100.0, np.float32), (7.1, 46.015), (0.0015, 0.0015))
    _, ids = added([coarse, inset, far], frame)
    assert ids == [0, 1, 2]


def test_a_grid_all_around_the_earth_is_closed_across_the_antimeridian(tmp_path):
    # A polar cap in EPSG:4326: 360 pixel-is-area columns of 1 deg from 180 W, rows of 0.1 deg
    # from 90 N: sample centres 179.5 W ... 179.5 E, 89.95 ... 88.95 N. The 1-deg wedge between
    # the last and first columns was left open.
    rows, cols = 11, 360
    heights = (100.0 + np.arange(cols)[None, :] + np.zeros((rows, 1))).astype(np.float32)  # 100 m at 179.5 W
    cap = write_geotiff(tmp_path / "cap.tif", heights, (-180.0, 90.0), (1.0, 0.1))
    frame = geo.LocalFrame(89.5, 180.0, earth_radius=math.inf)
    scene, ids = added(cap, frame)
    assert ids == [0]
    for lon in (179.9, -179.9):
        p = frame.to_scene(89.5, lon, 0.0)
        h = scene.terrain_height(p[0], p[2])
        assert h is not None, lon
        # Between the wedge's corner samples: 459 m at 179.5 E, 100 m at 179.5 W (float32 vertices).
        assert 100.0 - FLOAT32 <= h <= 459.0 + FLOAT32, (lon, h)
    # A 2-deg-wide strip inside the grid is as it was: its own samples (float32 vertices).
    p = frame.to_scene(89.45, 0.5, 0.0)
    assert scene.terrain_height(p[0], p[2]) == pytest.approx(100.0 + 180.0, abs=FLOAT32)
    # Nothing is made up beyond the first row (89.95 N): the pole stays open.
    p = frame.to_scene(89.99, 0.0, 0.0)
    assert scene.terrain_height(p[0], p[2]) is None
