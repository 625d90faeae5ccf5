"""Terrain from elevation data (issue 20, section 1): Scene.add_terrain's placement (flat and on
CurvedEarth's flattened Earth), holes, a ridge 100 km away against exact traces, SRTM and GeoTIFF
files written here (nothing downloaded), orthophoto uvs, water, TerrainShading and bad input."""

import math
import warnings

import numpy as np
import pytest

import refracta
from refracta import geo, shading, terrain

# Vertices are float32 in Embree: a coordinate c carries ~6e-8 |c| of rounding (1 m at 100 km
# would be 6 mm); the hits are re-solved in double against those float vertices.
FLOAT32 = 1e-7
R = 6371000.0


def vertical_hit(scene, x, z, top=10000.0):
    """The y of the first hit straight down at (x, z), or None."""
    hit = scene.intersect((x, top, z), (0.0, -1.0, 0.0))
    return None if hit is None else hit[0][1]


def test_samples_land_at_origin_plus_spacing_with_their_heights():
    rng = np.random.default_rng(3)
    heights = rng.uniform(0.0, 50.0, (4, 6))  # rows along +z, columns along +x
    scene = refracta.Scene()
    ids = scene.add_terrain(heights, origin=(100.0, -20.0), spacing=(2.0, 3.0))
    assert ids == terrain.TerrainGeometry([0], None)
    for r in range(1, 3):  # inner samples: a ray down the outer edge may pass beside the grid
        for c in range(1, 5):
            y = vertical_hit(scene, 100.0 + 2.0 * c, -20.0 + 3.0 * r)
            assert y == pytest.approx(heights[r, c], abs=FLOAT32 * 1e4)  # float32 vertices: 1e-3 m at 10 km
    lower, upper = scene.bounds
    np.testing.assert_allclose(lower, [100.0, heights.min(), -20.0], rtol=FLOAT32)
    np.testing.assert_allclose(upper, [110.0, heights.max(), -11.0], rtol=FLOAT32)


def test_inside_a_cell_the_surface_is_its_two_triangles():
    # A saddle cell: y = 0 at (row 0, col 0) and (row 1, col 1), 10 at (row 1, col 0), 4 at
    # (row 0, col 1). The diagonal runs from (row 1, col 0) to (row 0, col 1) (Embree's quads):
    # (x, z) = (0.1, 0.6) lies on the triangle with corner (0, 0): y = 0.1 * 4 + 0.6 * 10; the
    # point (0.75, 0.75) on the other, with corner (1, 1): y = 0.25 * 10 + 0.25 * 4 = 3.5.
    # Across the other diagonal the surface would be y = 0 there: the split matters.
    heights = np.array([[0.0, 4.0], [10.0, 0.0]])
    scene = refracta.Scene()
    scene.add_terrain(heights, origin=(0.0, 0.0), spacing=(1.0, 1.0))
    assert vertical_hit(scene, 0.75, 0.75) == pytest.approx(3.5, abs=1e-5)  # float32 vertices of a 10 m cell
    assert vertical_hit(scene, 0.1, 0.6) == pytest.approx(
        0.1 * 4.0 + 0.6 * 10.0, abs=1e-5
    )  # float32 vertices of a 10 m cell


def test_holes_leave_out_exactly_the_cells_around_them():
    heights = np.zeros((6, 7))
    heights[2, 3] = np.nan
    scene = refracta.Scene()
    scene.add_terrain(heights, origin=(0.0, 0.0), spacing=(1.0, 1.0))
    for r in range(5):
        for c in range(6):
            touches = r in (1, 2) and c in (2, 3)
            assert (vertical_hit(scene, c + 0.5, r + 0.5) is None) == touches, (r, c)


def test_all_nan_or_no_whole_cell_is_refused():
    scene = refracta.Scene()
    with pytest.raises(ValueError, match="all NaN"):
        scene.add_terrain(np.full((3, 3), np.nan), origin=(0, 0), spacing=(1, 1))
    checker = np.zeros((4, 4))
    checker[::2, ::2] = np.nan  # every cell touches a hole
    with pytest.raises(ValueError, match="no cell has four valid corners"):
        scene.add_terrain(checker, origin=(0, 0), spacing=(1, 1))


def test_shading_normals_come_from_the_neighbouring_samples_not_the_facet():
    # y = x^2 / 2 sampled at x = 0, 1, 2, 3: the central differences give slopes of 45 deg at x = 1
    # and 63.4 deg at x = 2, the facet between them 56.3 deg. Near x = 1 the smooth normal slopes
    # ~47 deg: TerrainShading with its rock line at 51 deg (blend +-2.5 deg) shows vegetation there;
    # a facet normal would show rock.
    x = np.arange(4.0)
    heights = np.tile(0.5 * x**2, (4, 1))
    scene = refracta.Scene()
    scene.add_terrain(heights, origin=(0.0, 0.0), spacing=(1.0, 1.0), material=shading.TerrainShading(rock_slope=51.0))
    scene.set_sun((0.0, 1.0, 0.0), (1.0, 1.0, 1.0))
    target = np.array([1.08, 0.5 * 1.08**2, 1.5])
    eye = target + [0.0, 20.0, 0.0]
    camera = refracta.Camera(eye, target, up=(0.0, 0.0, -1.0), vfov=0.2, width=3, height=3)
    red, green, _ = refracta.render(scene, camera, None, progress=False)[1, 1]
    vegetation, rock = shading.TerrainShading().parameters["vegetation"], shading.TerrainShading().parameters["rock"]
    assert red / green == pytest.approx(vegetation[0] / vegetation[1], rel=0.05)  # spectral round trip of the albedo
    assert rock[0] / rock[1] > 1.5 * vegetation[0] / vegetation[1]  # the two covers are told apart


def test_curved_earth_heights_are_flattened_as_curved_earth_puts_the_ground():
    heights = np.array([[0.0, 1000.0, 4000.0], [8848.0, -400.0, 10.0]])
    scene = refracta.Scene()
    scene.add_terrain(heights, origin=(0.0, 0.0), spacing=(100.0, 100.0), earth_radius=R)
    earth = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius=R)
    for r in range(2):
        for c in range(3):
            expected = earth.flat_height(heights[r, c])
            assert expected == pytest.approx(R * math.log1p(heights[r, c] / R), rel=1e-12)  # the same map
            y = vertical_hit(scene, 100.0 * c, 100.0 * r, top=20000.0)
            assert y == pytest.approx(expected, abs=FLOAT32 * 1e4)  # float32 vertices: 1e-3 m at 10 km
    # 8848 m lands 6.1 m lower than on a flat Earth: the flattening is there, not y = h.
    assert heights[1, 0] - vertical_hit(scene, 0.0, 100.0, top=20000.0) == pytest.approx(6.14, abs=0.01)  # h^2 / 2R


def ridge_scene(earth_radius):
    """A black 1 km ridge 100 km east of the origin (heights along x, the same on every row) under a
    uniform white sky."""
    xs = np.linspace(95000.0, 105000.0, 401)  # 25 m spacing
    h = 1000.0 * np.exp(-(((xs - 100000.0) / 1500.0) ** 2))
    heights = np.tile(h, (5, 1))
    scene = refracta.Scene()
    scene.add_terrain(
        heights,
        origin=(xs[0], -2000.0),
        spacing=(xs[1] - xs[0], 1000.0),
        material=shading.Diffuse(0.0),
        earth_radius=earth_radius,
    )
    scene.add_light(refracta.lights.ConstantEnvironment((1.0, 1.0, 1.0)))
    flat = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius=earth_radius).flat_height(h)
    return scene, xs, np.asarray(flat)


def traced_hits(field, camera, xs, flat):
    """Per pixel row (column 0): whether the exact trace of its ray meets the ridge's surface,
    y(x) piecewise linear through the flat heights (rows identical: the grid's triangles)."""
    hits = []
    for j in range(camera.height):
        origin, direction = camera.ray(0.5, j + 0.5)
        path = refracta.trace_ray(field, origin, direction, max_length=110000.0)
        p = path.sample(22001)  # 5 m apart: the ray's height changes < 0.1 m between samples near the crest
        inside = (p[:, 0] >= xs[0]) & (p[:, 0] <= xs[-1])
        hits.append(bool(np.any(p[inside, 1] <= np.interp(p[inside, 0], xs, flat))))
    return np.array(hits)


def test_a_ray_grazing_a_ridge_100_km_away_meets_it_where_the_exact_trace_does():
    scene, xs, flat = ridge_scene(R)
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius=R)
    eye = np.array([0.0, 10.0, 0.0])
    # Around the crest's apparent elevation: (1000 - 785) m over 100 km, lifted by refraction.
    look = math.radians(0.15)
    camera = refracta.Camera(eye, eye + [math.cos(look), math.sin(look), 0.0], vfov=0.12, width=1, height=48)
    image = refracta.render(scene, camera, field, max_length=110000.0, progress=False)
    rendered = image[:, 0, :].sum(axis=1) < 0.5  # the black ridge against the white sky
    exact = traced_hits(field, camera, xs, flat)
    # Without the air's bending the crest stands lower by k d / 2R ~ 0.05 deg: many rows, so
    # agreement within a row is a test of the placement and of the curved trace together.
    straight = traced_hits(refracta.without_refraction(field), camera, xs, flat)
    assert exact.any() and not exact.all()
    assert abs(int(exact.sum()) - int(straight.sum())) > 10
    # Both take the pixel centre (1 spp); the boundary row may still differ by one where its ray
    # passes the crest within the float32 vertices' ~1 cm or the caster's 1 mm chord sagitta.
    assert abs(int(rendered.sum()) - int(exact.sum())) <= 1


def write_hgt(folder, name, heights):
    path = folder / name
    np.asarray(heights, dtype=">i2").tofile(path)
    return path


def test_an_srtm_tile_is_placed_by_the_frame_with_voids_as_holes(tmp_path):
    n = 1201
    heights = np.full((n, n), 500, dtype=np.int16)
    heights[600, 600] = -32768  # a void: its four cells are left out
    heights[0, 0] = 1500  # the north-west corner: 47 N, 7 E
    path = write_hgt(tmp_path, "N46E007.hgt", heights)
    frame = geo.LocalFrame(46.5, 7.5, earth_radius=math.inf)
    scene = refracta.Scene()
    ids = scene.add_terrain(path, frame=frame)
    assert ids.terrain == [0]
    edge = np.linspace(0.0, 1.0, n)
    west = frame.to_scene(46.0 + edge, 7.0, 500.0)  # the tile's west and north edges
    north = frame.to_scene(47.0, 7.0 + edge, 500.0)
    lower, upper = scene.bounds
    assert upper[1] == pytest.approx(1500.0, abs=1e-3)  # float32 at 1.5 km
    assert lower[0] == pytest.approx(west[:, 0].min(), rel=1e-6)  # float32
    assert lower[2] == pytest.approx(north[:, 2].min(), rel=1e-6)  # north is -z
    step = 1.0 / (n - 1)
    void = frame.to_scene(47.0 - 600 * step, 7.0 + 600 * step, 500.0)
    assert vertical_hit(scene, void[0] + 5.0, void[2] + 5.0) is None
    beside = frame.to_scene(47.0 - 500 * step, 7.0 + 500 * step, 500.0)
    assert vertical_hit(scene, beside[0], beside[2]) == pytest.approx(500.0, abs=1e-3)  # float32


@pytest.mark.slow  # two 1201 x 1201 tiles through pyproj: ~4 s
def test_neighbouring_tiles_share_their_edge(tmp_path):
    n = 1201
    west = write_hgt(tmp_path, "N46E007.hgt", np.full((n, n), 100))
    east = write_hgt(tmp_path, "N46E008.hgt", np.full((n, n), 100))
    frame = geo.LocalFrame(46.5, 8.0, earth_radius=math.inf)
    scene = refracta.Scene()
    assert scene.add_terrain([west, east], frame=frame).terrain == [0]  # joined into one grid (terrain._tile_grids)
    seam = frame.to_scene(46.5, 8.0, 100.0)
    for dx in (-1.0, 0.0, 1.0):  # either side of and on the shared meridian
        assert vertical_hit(scene, seam[0] + dx, seam[2]) == pytest.approx(100.0, abs=1e-3)  # float32


def write_geotiff(
    path, data, tiepoint, scale, model=2, epsg=4326, raster=1, nodata=None, georeference=True, compression=None
):
    import tifffile

    extratags = []
    if georeference:
        crs_key = 2048 if model == 2 else 3072
        keys = [1, 1, 0, 3, 1024, 0, 1, model, 1025, 0, 1, raster, crs_key, 0, 1, epsg]
        extratags = [
            (33550, "d", 3, (scale[0], scale[1], 0.0), False),
            (33922, "d", 6, (0.0, 0.0, 0.0, tiepoint[0], tiepoint[1], 0.0), False),
            (34735, "H", len(keys), keys, False),
        ]
    if nodata is not None:
        extratags.append((42113, "s", 0, str(nodata), False))
    tifffile.imwrite(path, data, extratags=extratags, compression=compression)
    return path


def test_a_geotiff_placed_by_a_model_transformation_reads_as_by_scale_and_tiepoint(tmp_path):
    """GDAL may georeference a north-up grid by ModelTransformation (scale and shift only) instead
    of ModelPixelScale and ModelTiepoint: a trial's file was refused as "a rotated or sheared grid".
    It reads as the same grid placed by scale and tiepoint; a rotated one, or one stored south-up,
    is refused saying why."""
    import tifffile

    data = (300.0 + np.arange(8 * 9).reshape(8, 9)).astype(np.float32)
    by_tiepoint = terrain.read_elevation(write_geotiff(tmp_path / "tie.tif", data, (7.0, 46.1), (0.01, 0.02)))
    keys = [1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326]

    def transformed(name, matrix):
        path = tmp_path / name
        tags = [(34264, "d", 16, matrix, False), (34735, "H", len(keys), keys, False)]
        tifffile.imwrite(path, data, extratags=tags)
        return path

    north_up = [0.01, 0, 0, 7.0, 0, -0.02, 0, 46.1, 0, 0, 0, 0, 0, 0, 0, 1]
    read = terrain.read_elevation(transformed("matrix.tif", north_up))
    assert np.array_equal(read.heights, by_tiepoint.heights)
    assert (read.x0, read.y0, read.dx, read.dy) == (by_tiepoint.x0, by_tiepoint.y0, by_tiepoint.dx, by_tiepoint.dy)
    rotated = [0.01, 0.001, 0, 7.0, 0.001, -0.02, 0, 46.1, 0, 0, 0, 0, 0, 0, 0, 1]
    with pytest.raises(ValueError, match=r"rotated\.tif'?: a rotated or sheared grid .*only north-up"):
        terrain.read_elevation(transformed("rotated.tif", rotated))
    south_up = [0.01, 0, 0, 7.0, 0, 0.02, 0, 46.0, 0, 0, 0, 0, 0, 0, 0, 1]
    with pytest.raises(ValueError, match=r"south\.tif'?: pixel scale \(0\.01, -0\.02\) .*only north-up"):
        terrain.read_elevation(transformed("south.tif", south_up))


@pytest.mark.parametrize("compression", ["lzw", "zlib"])
def test_compressed_geotiffs_read_as_the_uncompressed_one(tmp_path, compression):
    """Elevation downloads (SRTM/Copernicus GeoTIFFs) are LZW- or Deflate-compressed: read through
    imagecodecs, they give the same samples as the uncompressed file."""
    data = (100.0 + np.arange(12 * 15).reshape(12, 15)).astype(np.float32)
    plain = terrain.read_elevation(write_geotiff(tmp_path / "plain.tif", data, (7.0, 46.0), (0.001, 0.001)))
    packed = write_geotiff(tmp_path / "packed.tif", data, (7.0, 46.0), (0.001, 0.001), compression=compression)
    read = terrain.read_elevation(packed)
    assert np.array_equal(read.heights, plain.heights) and np.array_equal(read.heights, data)


def test_a_geographic_geotiff_is_placed_like_the_same_samples_given_by_latitude(tmp_path):
    rows, cols = 40, 50
    data = (200.0 + 10.0 * np.arange(rows)[:, None] + np.arange(cols)[None, :]).astype(np.float32)
    data[5, 5] = -9999.0
    scale = (0.001, 0.0008)  # [deg] per pixel: lon, lat
    path = write_geotiff(tmp_path / "dem.tif", data, (7.0, 46.0), scale, nodata=-9999)
    frame = geo.LocalFrame(45.99, 7.02, earth_radius=geo.radius_of_curvature(45.99, 0.0))
    scene = refracta.Scene()
    scene.add_terrain(path, frame=frame)
    # Pixel-is-area: sample (r, c) at the pixel's centre.
    for r, c in ((1, 1), (10, 30), (38, 48)):  # inner samples (a ray down the outer edge may pass beside)
        lat, lon = 46.0 - (r + 0.5) * scale[1], 7.0 + (c + 0.5) * scale[0]
        p = frame.to_scene(lat, lon, float(data[r, c]))
        assert vertical_hit(scene, p[0], p[2]) == pytest.approx(p[1], abs=2e-3)  # float32 at ~3 km from the origin
    hole = frame.to_scene(46.0 - 5.5 * scale[1], 7.0 + 5.5 * scale[0], 250.0)
    assert vertical_hit(scene, hole[0] + 1.0, hole[2] + 1.0) is None


def test_a_geotiff_across_the_meridian_of_its_convention_is_placed_as_the_wrapped_one(tmp_path):
    """A grid written in [0, 360] longitudes may run across 360 E (a trial's 359.9-360.1 E was
    refused): it is the same ground as the grid from -0.1 E, sample by sample."""
    data = (50.0 + np.arange(8 * 21).reshape(8, 21)).astype(np.float32)
    scale = (0.01, 0.01)
    across = terrain.read_elevation(write_geotiff(tmp_path / "across.tif", data, (359.9, 51.5), scale))
    wrapped = terrain.read_elevation(write_geotiff(tmp_path / "wrapped.tif", data, (-0.1, 51.5), scale))
    rows = slice(0, 8)
    lat, lon = across.coordinates(rows)
    lat_w, lon_w = wrapped.coordinates(rows)
    assert np.array_equal(lat, lat_w)
    assert np.allclose(lon, lon_w, rtol=0.0, atol=1e-9)  # [deg] the same longitudes, 360 apart, rounded
    frame = geo.LocalFrame(51.45, 0.0, earth_radius=math.inf)
    scene = refracta.Scene()
    scene.add_terrain(write_geotiff(tmp_path / "across2.tif", data, (359.9, 51.5), scale), frame=frame)
    r, c = 3, 12  # 0.025 E, east of the meridian the grid crosses
    p = frame.to_scene(51.5 - (r + 0.5) * scale[1], -0.1 + (c + 0.5) * scale[0], float(data[r, c]))
    assert vertical_hit(scene, p[0], p[2]) == pytest.approx(p[1], abs=2e-3)  # float32 at ~5 km from the origin


def test_a_projected_geotiff_goes_through_its_crs(tmp_path):
    import pyproj

    data = np.full((10, 12), 300.0, dtype=np.float32)
    # UTM 32N (EPSG:32632) around 46 N, 7.5 E.
    east, north = pyproj.Transformer.from_crs(4326, 32632, always_xy=True).transform(7.5, 46.0)
    path = write_geotiff(tmp_path / "utm.tif", data, (east, north), (30.0, 30.0), model=1, epsg=32632, raster=2)
    frame = geo.LocalFrame(46.0, 7.5, earth_radius=math.inf)
    scene = refracta.Scene()
    scene.add_terrain(path, frame=frame)
    # Pixel-is-point: sample (0, 0) at the tiepoint, which is the frame's origin.
    assert vertical_hit(scene, 1.0, 1.0) == pytest.approx(300.0, abs=1e-3)  # float32
    assert vertical_hit(scene, -1.0, 0.0) is None  # west of the first column
    assert vertical_hit(scene, 0.0, -1.0) is None  # north of the first row


@pytest.mark.parametrize(
    "tiepoint, epsg, message",
    [
        ((420000.0, 5.0e8), 32632, "outside the domain of EPSG:32632"),  # placed at -0.92, -170.28: a trial
        ((-5.0e7, 5.1e6), 32632, "outside the domain of EPSG:32632"),  # pyproj's ProjError, unnamed
        ((4.0e6, 6.0e5), 4978, r"EPSG:4978 \(WGS 84\) is not a projected coordinate system"),  # geocentric
        ((4.0e6, 6.0e5), 5773, r"EPSG:5773 .* is not a projected coordinate system"),  # a vertical datum
    ],
)
def test_a_projected_geotiff_outside_its_crs_is_refused_naming_the_file(tmp_path, tiepoint, epsg, message):
    path = write_geotiff(
        tmp_path / "bad.tif", np.full((5, 5), 100.0, np.float32), tiepoint, (30.0, 30.0), model=1, epsg=epsg
    )
    with pytest.raises(ValueError, match=f"read_elevation: '.*bad.tif'.*{message}"):
        terrain.read_elevation(path)
    with pytest.raises(ValueError, match=f"add_terrain: '.*bad.tif'.*{message}"):
        refracta.Scene().add_terrain(path, frame=geo.LocalFrame(46.0, 7.5))


def test_an_orthophoto_is_draped_by_its_georeference(tmp_path):
    # A 16 x 16-pixel orthophoto over the DEM's extent: its northern half red in the west, blue in
    # the east, its southern half green (a trial found the image mirrored north-south: v rose with
    # the rows).
    dem = write_geotiff(
        tmp_path / "dem.tif", np.full((21, 21), 100.0, np.float32), (7.0, 46.0), (0.001, 0.001), raster=2
    )
    photo = np.zeros((16, 16, 3), dtype=np.uint8)
    photo[:8, :8] = (255, 0, 0)
    photo[:8, 8:] = (0, 0, 255)
    photo[8:] = (0, 255, 0)
    ortho = write_geotiff(tmp_path / "ortho.tif", photo, (7.0, 46.0), (0.00125, 0.00125))
    frame = geo.LocalFrame(45.99, 7.01, earth_radius=math.inf)
    scene = refracta.Scene()
    scene.add_terrain(dem, frame=frame, orthophoto=ortho)
    scene.set_sun((0.0, 1.0, 0.0), (1.0, 1.0, 1.0))
    # 4 texels either side of the edges between the quarters (the DEM spans 45.98-46.0 N, 7.0-7.02 E).
    for lat, lon, colour in ((45.995, 7.005, 0), (45.995, 7.015, 2), (45.985, 7.005, 1), (45.985, 7.015, 1)):
        p = frame.to_scene(lat, lon, 100.0)
        eye = p + [0.0, 50.0, 0.0]
        camera = refracta.Camera(eye, p, up=(0.0, 0.0, -1.0), vfov=1.0, width=4, height=4)
        image = refracta.render(scene, camera, None, progress=False)
        pixel = image[2, 2]
        others = [pixel[k] for k in range(3) if k != colour]
        assert pixel[colour] > 5 * max(others), (lat, lon, pixel)


def test_a_water_level_adds_water_over_the_extent_below_which_samples_are_under_water():
    heights = np.array([[-5.0, -5.0, 20.0], [-5.0, -5.0, 20.0]])
    scene = refracta.Scene()
    ids = scene.add_terrain(heights, origin=(0.0, 0.0), spacing=(10.0, 10.0), water_level=0.0, earth_radius=R)
    assert ids.water == 1
    assert isinstance(scene.material(ids.water), shading.Water)
    assert isinstance(scene.material(ids.terrain[0]), shading.TerrainShading)
    point, _, geometry = scene.intersect((2.0, 100.0, 5.0), (0.0, -1.0, 0.0))
    assert geometry == ids.water and point[1] == pytest.approx(0.0, abs=1e-9)  # flat_height(0) = 0
    point, _, geometry = scene.intersect((19.0, 100.0, 5.0), (0.0, -1.0, 0.0))
    assert geometry == ids.terrain[0] and point[1] > 0.0


def test_terrain_shading_spells_a_flat_earth_as_inf_like_the_rest_of_the_library():
    # An API review: TerrainShading's flat Earth was earth_radius=0 where Camera.project and
    # AerialPerspective say inf; both now mean y is the height (the default inf), a finite R turns
    # y back into h = R (exp(y / R) - 1): at y = 1900 m and R = 10 km, h = 2092 m, above the tree line.
    def seen(material):
        scene = refracta.Scene()
        scene.add_terrain(np.full((4, 4), 1900.0), origin=(0.0, 0.0), spacing=(1.0, 1.0), material=material)
        scene.set_sun((0.0, 1.0, 0.0), (1.0, 1.0, 1.0))
        camera = refracta.Camera(
            (1.5, 1920.0, 1.5), (1.5, 1900.0, 1.5), up=(0.0, 0.0, -1.0), vfov=1.0, width=2, height=2
        )
        return refracta.render(scene, camera, None, progress=False)

    flat = seen(shading.TerrainShading())
    assert shading.TerrainShading().parameters["earth_radius"] == math.inf
    np.testing.assert_array_equal(flat, seen(shading.TerrainShading(earth_radius=0.0)))
    curved = seen(shading.TerrainShading(earth_radius=1e4))
    # Rock's red/green (0.25/0.23) is 1.63x forest's (0.06/0.09): 1.5 leaves room for the spectral round trip.
    assert curved[0, 0, 0] / curved[0, 0, 1] > 1.5 * flat[0, 0, 0] / flat[0, 0, 1]
    with pytest.raises(ValueError, match="earth_radius must be >= 0"):
        shading.TerrainShading(earth_radius=-1.0)


def test_terrain_shading_snow_rock_and_vegetation():
    t = shading.TerrainShading(snow_line=3000.0, tree_line=2000.0, rock_slope=35.0)
    p = t.parameters
    assert t.reflectance(500.0, 5.0) == pytest.approx(
        p["vegetation"]
    )  # the blend's rounding (each cover is exact away from its edges)
    assert t.reflectance(500.0, 60.0) == pytest.approx(p["rock"])  # steep: bare rock
    assert t.reflectance(2500.0, 5.0) == pytest.approx(p["rock"])  # above the tree line
    assert t.reflectance(4000.0, 10.0) == pytest.approx(p["snow"])
    assert t.reflectance(4000.0, 70.0) == pytest.approx(p["rock"])  # snow slides off cliffs
    assert refracta.shading.TerrainShading(**p).parameters == p
    with pytest.raises(ValueError, match="rock_slope"):
        shading.TerrainShading(rock_slope=95.0)


def test_bad_input_raises_clear_errors(tmp_path):
    scene = refracta.Scene()
    ok = np.zeros((3, 3))
    with pytest.raises(ValueError, match="spacing must be > 0"):
        scene.add_terrain(ok, origin=(0, 0), spacing=(0.0, 1.0))
    with pytest.raises(ValueError, match=r"\(rows, cols\)"):
        scene.add_terrain(np.zeros(5), origin=(0, 0), spacing=(1, 1))
    with pytest.raises(ValueError, match="origin="):
        scene.add_terrain(ok)
    with pytest.raises(ValueError, match="array of real numbers"):
        scene.add_terrain([["a", "b"], ["c", "d"]], origin=(0, 0), spacing=(1, 1))
    with pytest.raises(FileNotFoundError):
        scene.add_terrain(tmp_path / "N46E007.hgt", frame=geo.LocalFrame(46, 7))
    text = tmp_path / "N46E007.hgt"
    text.write_text("not elevation data")
    with pytest.raises(ValueError, match="not SRTM elevation data"):
        scene.add_terrain(text, frame=geo.LocalFrame(46, 7))
    with pytest.raises(ValueError, match="frame="):
        scene.add_terrain(text)
    bare = write_geotiff(tmp_path / "bare.tif", np.zeros((4, 4), np.float32), (0, 0), (1, 1), georeference=False)
    with pytest.raises(ValueError, match="no georeference"):
        scene.add_terrain(bare, frame=geo.LocalFrame(46, 7))
    rgb = write_geotiff(tmp_path / "rgb.tif", np.zeros((4, 4, 3), np.uint8), (7.0, 46.0), (0.001, 0.001))
    with pytest.raises(ValueError, match="not elevation data"):
        scene.add_terrain(rgb, frame=geo.LocalFrame(46, 7))
    polar = write_geotiff(tmp_path / "polar.tif", np.zeros((4, 4), np.float32), (7.0, 91.0), (0.001, 0.001))
    with pytest.raises(ValueError, match=r"outside \[-90, 90\]"):
        scene.add_terrain(polar, frame=geo.LocalFrame(46, 7))
    (tmp_path / "somewhere.hgt").write_bytes(b"\0" * 8)
    with pytest.raises(ValueError, match="N46E007.hgt"):
        scene.add_terrain(tmp_path / "somewhere.hgt", frame=geo.LocalFrame(46, 7))
    assert scene.geometry_count == 0


def test_broken_and_implausible_geotiffs_are_refused_naming_the_file(tmp_path):
    """A new-user trial's files: each gave an error from a library underneath, or was accepted."""
    scene, frame = refracta.Scene(), geo.LocalFrame(46, 7)
    grid = np.linspace(0.0, 100.0, 12).reshape(3, 4).astype(np.float32)
    good = write_geotiff(tmp_path / "good.tif", grid, (7.0, 46.0), (0.001, 0.001))
    garbled = tmp_path / "garbled.tif"
    garbled.write_bytes(b"II*\x00garbage" * 10)  # a TIFF header, then nothing a TIFF reader can follow
    with pytest.raises(ValueError, match=r"'.*garbled.tif' is not a readable TIFF file"):  # was IndexError: 0
        scene.add_terrain(garbled, frame=frame)
    truncated = tmp_path / "truncated.tif"
    truncated.write_bytes(good.read_bytes()[:64])
    with pytest.raises(ValueError, match=r"'.*truncated.tif' is not a TIFF file \("):
        scene.add_terrain(truncated, frame=frame)
    row = write_geotiff(tmp_path / "row.tif", grid[:1], (7.0, 46.0), (0.001, 0.001))
    with pytest.raises(ValueError, match="1 x 4 samples; a grid needs 2 x 2"):  # was ZeroDivisionError
        scene.add_terrain(row, frame=frame)
    hole = grid.copy()
    hole[1, 2] = np.inf
    infinite = write_geotiff(tmp_path / "inf.tif", hole, (7.0, 46.0), (0.001, 0.001))
    with pytest.raises(ValueError, match=r"inf.tif': sample \(row 1, column 2\) is inf"):
        scene.add_terrain(infinite, frame=frame)
    voids = write_geotiff(tmp_path / "voids.tif", hole * -1.0, (7.0, 46.0), (0.001, 0.001), nodata="-inf")
    assert np.isnan(terrain.read_elevation(voids).heights[1, 2])  # -inf as GDAL_NODATA: a void, not refused
    wide = write_geotiff(tmp_path / "wide.tif", grid, (7.0, 46.0), (150.0, 0.001))
    with pytest.raises(ValueError, match="span 450.0 deg of longitude"):
        scene.add_terrain(wide, frame=frame)
    tiny = write_geotiff(tmp_path / "tiny.tif", grid, (7.0, 46.0), (1e-300, 1e-300))
    with pytest.raises(ValueError, match="samples would coincide"):
        scene.add_terrain(tiny, frame=frame)
    unknown = write_geotiff(tmp_path / "crs.tif", grid, (400000.0, 5150000.0), (100.0, 100.0), model=1, epsg=12345)
    with pytest.raises(ValueError, match="EPSG:12345 is not a coordinate system pyproj knows"):
        scene.add_terrain(unknown, frame=frame)
    png = tmp_path / "photo.png"
    refracta.io.write_image(png, np.full((4, 4, 3), 0.5, np.float32), exposure=1.0)
    with pytest.raises(ValueError, match="orthophoto '.*photo.png' is not a readable GeoTIFF"):
        scene.add_terrain(good, frame=frame, orthophoto=png)
    assert scene.geometry_count == 0


def test_a_terrain_scene_pickles_with_its_holes():
    import pickle

    heights = np.arange(20.0).reshape(4, 5)
    heights[1, 2] = np.nan
    scene = refracta.Scene()
    scene.add_terrain(heights, origin=(0.0, 0.0), spacing=(1.0, 1.0))
    copy = pickle.loads(pickle.dumps(scene))
    for x, z in ((0.5, 0.5), (2.5, 1.5), (3.5, 2.5), (1.2, 2.7)):
        assert vertical_hit(copy, x, z) == vertical_hit(scene, x, z)
    assert vertical_hit(copy, 2.5, 1.5) is None  # beside the hole
    assert isinstance(copy.material(0), shading.TerrainShading)


def test_terrain_height_is_the_ground_under_a_point_and_render_warns_an_eye_inside_it():
    # A 1 500 m cone of 100 m cells: at its apex 1 500 m, 1 000 m out 1 000 m (on a sample: exact in
    # the bilinear cells' triangles); none beyond the grid. A box on the apex is looked through.
    x = np.linspace(-2000.0, 2000.0, 41)
    cone = np.clip(1500.0 - 0.5 * np.hypot(x[None, :], x[:, None]), 0.0, None)
    scene = refracta.Scene()
    scene.set_sky((0.5, 0.6, 0.9), (0.8, 0.8, 0.9))
    scene.add_ground(0.0, 2.0e4)
    scene.add_terrain(cone, origin=(-2000.0, -2000.0), spacing=(100.0, 100.0))
    scene.add_box((-10.0, 1490.0, -10.0), (10.0, 1600.0, 10.0))
    assert scene.terrain_height(0.0, 0.0) == pytest.approx(1500.0, abs=1e-3)  # float32 vertices
    assert scene.terrain_height(1000.0, 0.0) == pytest.approx(1000.0, abs=1e-3)
    assert scene.terrain_height(5000.0, 0.0) is None  # the sea plane is not terrain
    with pytest.raises(ValueError, match="x and z must be finite"):
        scene.terrain_height(float("nan"), 0.0)
    # The trial's eye 1.7 m above sea level on the hillside: its rays started inside the hill and
    # showed open sea, without a word.
    inside = refracta.Camera((500.0, 1.7, 0.0), (-1000.0, 1.7, 0.0), vfov=20.0, width=8, height=4)
    with pytest.warns(refracta.SceneWarning, match=r"below the scene's terrain \(y = 1250 m under it\)"):
        refracta.render(scene, inside, None, progress=False)
    above = refracta.Camera((500.0, 1251.7, 0.0), (-1000.0, 600.0, 0.0), vfov=20.0, width=8, height=4)
    with warnings.catch_warnings():
        warnings.simplefilter("error", refracta.SceneWarning)
        refracta.render(scene, above, None, progress=False)


def test_files_keep_to_what_they_say_and_fail_whole(tmp_path):
    """A terrain trial's files: int16 -32768 with no GDAL_NODATA was a 32.8 km pit (now SRTM's void,
    as in .hgt files); radians in GeogAngularUnitsGeoKey were read as degrees; a band too large for
    the machine was decoded before anything checked it; a list whose second grid failed left the
    first in the scene."""
    import tifffile

    data = np.full((6, 6), 500, np.int16)
    data[2, 3] = -32768
    void = terrain.read_elevation(write_geotiff(tmp_path / "void.tif", data, (10.0, 46.0), (0.001, 0.001)))
    assert np.isnan(void.heights[2, 3]) and np.nanmin(void.heights) == 500.0
    keys = [1, 1, 0, 4, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326, 2054, 0, 1, 9101]  # 9101: radians
    tags = [(33550, "d", 3, (1e-5, 1e-5, 0.0), False), (33922, "d", 6, (0, 0, 0, 0.17, 0.8, 0), False)]
    tifffile.imwrite(tmp_path / "radians.tif", data, extratags=[*tags, (34735, "H", len(keys), keys, False)])
    with pytest.raises(ValueError, match="GeogAngularUnitsGeoKey"):
        terrain.read_elevation(tmp_path / "radians.tif")
    with pytest.raises(ValueError, match="more than this machine's"):  # 10^12 samples: ~40 TB on the way in
        terrain._check_fits("huge.tif", (10**6, 10**6))
    small_machine = pytest.MonkeyPatch()  # the reader's own message, not "not a TIFF file (...)"
    small_machine.setattr(terrain._core, "physical_memory_bytes", lambda: 1000)
    try:
        with pytest.raises(ValueError, match=r"void.tif': 6 x 6 samples need .* more than this machine's") as refused:
            terrain.read_elevation(tmp_path / "void.tif")
        assert "not a TIFF file" not in str(refused.value)
    finally:
        small_machine.undo()
    # Every other sample void: no cell has four valid corners, so the second grid fails to build.
    checker = np.where((np.arange(6)[:, None] + np.arange(6)[None, :]) % 2 == 0, 300.0, np.nan).astype(np.float32)
    good = write_geotiff(tmp_path / "good.tif", np.full((6, 6), 500.0, np.float32), (10.0, 46.0), (0.001, 0.001))
    bad = write_geotiff(tmp_path / "checker.tif", checker, (10.1, 46.0), (0.001, 0.001))
    frame = geo.LocalFrame(45.997, 10.003)
    scene = refracta.Scene()
    with pytest.raises(ValueError, match="four valid corners"):
        scene.add_terrain([good, bad], frame=frame)
    above = frame.to_scene(45.997, 10.003, 2000.0)
    assert scene.intersect(above, (0.0, -1.0, 0.0)) is None  # the first grid is gone with the call
    with pytest.raises(ValueError, match="water_level"):  # the water's own error, after the terrain was placed
        scene.add_terrain(good, frame=frame, water_level=float("nan"))
    assert scene.intersect(above, (0.0, -1.0, 0.0)) is None


def test_a_file_finer_than_single_precision_resolves_is_refused(tmp_path):
    # A trial: 1e-8 deg samples 387 km from the frame's origin fell on one float32 x, unannounced
    # (the array form refused the same). Here 1e-7 deg (1.1 cm) 111 km off, where float32 steps by
    # 7.8 mm: under the 8 steps the array form asks for.
    data = np.full((20, 20), 100.0, np.float32)
    fine = write_geotiff(tmp_path / "fine.tif", data, (11.0, 46.0), (1e-7, 1e-7))
    with pytest.raises(ValueError, match="finer than single-precision positions resolve"):
        refracta.Scene().add_terrain(fine, frame=geo.LocalFrame(46.0, 9.56))
    refracta.Scene().add_terrain(fine, frame=geo.LocalFrame(46.0, 10.999))  # 80 m off: resolved
