"""refracta.terrain: terrain from elevation data -- ``Scene.add_terrain`` (issue 20, section 1).

Reading elevation files is I/O, so it lives here; the geometry is C++ (scene/terrain.h): Embree
grid geometry, one float3 vertex per sample (12 bytes), smooth normals from the neighbouring
samples, holes (NaN samples, SRTM voids) left out cell by cell. A 3601 x 3601 SRTM tile loads and
renders within 1 GB (benchmarks/bench_terrain.py measures it).

Two forms of :func:`add_terrain` (bound as ``Scene.add_terrain``):

- an array of heights [m], (rows, cols): rows along +z, columns along +x, element [0, 0] at scene
  (x0, z0) = ``origin``, samples ``spacing`` = (dx, dz) [m] apart. With ``earth_radius`` R (the
  radius of the scene's :class:`refracta.CurvedEarth`), the array lies on the curved Earth:
  x and z are distances along the Earth's surface (CurvedEarth's flat frame) and a height h above
  the sea-level sphere lands at y = R ln(1 + h / R), exactly where CurvedEarth puts the ground;
  without it y = h (a flat Earth).
- elevation files in a geographic scene: an SRTM ``.hgt`` tile (big-endian int16, 1201 x 1201 or
  3601 x 3601 samples, the name giving its south-west corner, e.g. ``N46E007.hgt``; -32768 marks a
  void), a GeoTIFF (read with tifffile: ModelTiepoint + ModelPixelScale and its GeoKeys; geographic
  WGS84 (EPSG:4326) or a projected CRS with an EPSG code, through pyproj; GDAL_NODATA samples are
  holes, and an int16 band's -32768 where no GDAL_NODATA names a void), or a list of such files.
  Tiles of a list on one lattice (one CRS, equal spacings, their samples a whole number of samples
  apart) that touch are joined into one grid before they are
  placed: NaN where no tile covers, the first file's sample where tiles overlap (neighbouring SRTM
  tiles share their edge samples), so that pixel-is-area GeoTIFF tiles, whose edge samples lie one
  spacing apart, meet without a crack. Tiles on different lattices (another CRS or spacing, or
  shifted by a fraction of a sample) stay separate grids, as do touching tiles of one lattice too
  sparse to join (a grid over twice their samples): a SceneWarning names them where a crack may
  show between them (tiles of one CRS that meet edge to edge without sharing an area of samples).
  A geographic grid all around the Earth (columns x spacing = 360 deg) is closed across the
  meridian where its columns wrap; its polar caps, beyond its first and last rows, stay open.
  Each sample goes to ``frame.to_scene(lat, lon, h)``
  (:class:`refracta.geo.LocalFrame`: azimuthal equidistant about the observer, flat heights with
  ``frame.earth_radius`` -- give the scene's CurvedEarth the same radius).

Colour: ``material=None`` gives :class:`refracta.shading.TerrainShading` (vegetation low, rock above
the tree line and on steep slopes, snow above the snow line), told the Earth radius so that it
reads true heights; ``orthophoto=`` an image draped over the terrain (a GeoTIFF placed by its
georeference in the file forms; in the array form any image, stretched over the grid: its left
edge along column 0, its top edge along row 0, the -z side: north up in a geographic scene); a material of your
own may use the terrain's uvs the same way. ``water_level`` [m] adds a water surface (default
:class:`refracta.shading.Water`) over the terrain's extent at that true height: samples below it
are under water.
"""

from __future__ import annotations

import contextlib
import logging
import math
import os
import re
import stat
import threading
import warnings
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, replace
from typing import Any, NamedTuple

import numpy as np

from refracta import _core
from refracta._checks import is_number, number_pair

__all__ = ["Elevation", "ElevationFileNotFoundError", "TerrainGeometry", "add_terrain", "read_elevation"]

# SRTM's marker of a void sample (NASA SRTM Data Product Specification).
_SRTM_VOID = -32768
# Samples a side of the two SRTM tile sizes: 3 and 1 arc-second spacing over one degree.
_SRTM_SIZES = (1201, 3601)
# Rows placed per call of LocalFrame.to_scene: bounds the float64 temporaries of a 3601 x 3601 tile
# (~90 MB of them per 256 rows x 3601 columns x ~12 arrays would be far more for the whole tile).
_ROWS_PER_CHUNK = 256
# GeoTIFF tags and GeoKeys (GeoTIFF 1.1, OGC 19-008r4).
_TAG_PIXEL_SCALE, _TAG_TIEPOINT, _TAG_TRANSFORM, _TAG_NODATA = 33550, 33922, 34264, 42113
_KEY_MODEL_TYPE, _KEY_RASTER_TYPE, _KEY_GEOGRAPHIC_TYPE, _KEY_PROJECTED_TYPE = 1024, 1025, 2048, 3072
_MODEL_PROJECTED, _MODEL_GEOGRAPHIC = 1, 2
# VerticalUnitsGeoKey: the heights' unit, EPSG unit code -> metres (US elevation products come in
# feet; without it a tile stood 3.28 times too tall).
_KEY_VERTICAL_UNITS = 4099
_KEY_ANGULAR_UNITS, _ANGULAR_DEGREE = 2054, 9102  # GeogAngularUnitsGeoKey: EPSG's degree
_FARTHEST_HEIGHT = 1e5  # [m] from sea level: no terrain (the deepest trench is 11 km, the highest peak 8.8 km)
# [m] the finest sample spacing: below it samples fall on one point in the scene's single-precision
# geometry (float32 resolves 6e-5 m at 1 km from the origin).
_FINEST_SPACING = 1e-4
# The least spacing of the array form in single-precision units of its farthest coordinate.
_SINGLE_PRECISION_STEPS = 8
_VERTICAL_UNITS = {9001: 1.0, 9002: 0.3048, 9003: 1200.0 / 3937.0, 9036: 1000.0}
_RASTER_PIXEL_IS_POINT = 2
_EPSG_WGS84 = 4326
# Tiles lie on one lattice when their first samples are a whole number of samples apart to this
# fraction of a sample: GeoTIFF writers' doubles put them ~1e-12 of a sample off, a tile resampled
# with a shifted origin is off by a visible fraction.
_LATTICE_TOLERANCE = 1e-6
# ... and their spacings agree to this fraction: across a mosaic 1e5 samples wide the two lattices
# part by at most 1e-4 of a sample (double-precision scales of one spacing agree to ~1e-16).
_SPACING_TOLERANCE = 1e-9
# A mosaic of touching tiles holds at most this many times their samples (NaN where none covers:
# two tiles meeting at a corner fill half of theirs); sparser ones stay separate grids (warned).
_MOSAIC_FILL = 2.0


class TerrainGeometry(NamedTuple):
    """What :func:`add_terrain` added: the terrain's geometry ids (one per grid: one for an array or
    a file; for a list, one per set of touching tiles joined into one grid and one per tile left
    alone, in the order of their first files) and the water surface's id (None without ``water_level``)."""

    terrain: list[int]
    water: int | None


@dataclass(eq=False)  # arrays: == would be ambiguous (equal by identity)
class Elevation:
    """Heights [m] on a regular geographic or projected grid, as :func:`read_elevation` returns them.

    heights: (rows, cols) float64, NaN at voids; row 0 is the northern (top) edge. Sample (r, c) lies
    at x = x0 + c * dx, y = y0 - r * dy in the CRS ``epsg`` (x = longitude, y = latitude [deg] for
    EPSG:4326; easting, northing [m] for a projected CRS)."""

    heights: np.ndarray
    x0: float
    y0: float
    dx: float
    dy: float
    epsg: int

    def coordinates(self, rows: slice) -> tuple[np.ndarray, np.ndarray]:
        """(lat, lon) [deg] of the samples in ``rows``, each (n, cols)."""
        r = np.arange(self.heights.shape[0], dtype=np.float64)[rows][:, None]
        c = np.arange(self.heights.shape[1], dtype=np.float64)[None, :]
        x, y = np.broadcast_arrays(self.x0 + c * self.dx, self.y0 - r * self.dy)
        if self.epsg == _EPSG_WGS84:
            lat, lon = y, (x + 180.0) % 360.0 - 180.0  # a grid across 360 E runs on past it (read_elevation)
        else:
            import pyproj

            to_lonlat = pyproj.Transformer.from_crs(
                _projected_crs(self.epsg, "elevation grid"), _EPSG_WGS84, always_xy=True
            )
            try:
                lon, lat = to_lonlat.transform(x, y, errcheck=True)
            except pyproj.exceptions.ProjError as error:
                raise ValueError(f"elevation grid: samples outside the domain of EPSG:{self.epsg} ({error})") from None
        lat, lon = np.asarray(lat, dtype=np.float64), np.asarray(lon, dtype=np.float64)
        if not (np.all(np.abs(lat) <= 90.0)):
            raise ValueError(f"elevation grid: latitudes outside [-90, 90] deg (from {lat.min()} to {lat.max()})")
        return lat, lon


class ElevationFileNotFoundError(_core.MissingFileError):
    """An elevation file that does not exist: a refracta.MissingFileError (an IoError and a
    FileNotFoundError), as every loader's missing file."""


def _missing(path: str, what: str = "elevation file") -> None:
    """Refuses a missing elevation file (or orthophoto: `what`), and before opening anything that
    is not a regular file: reading a FIFO (or a device) waits for a writer that may never come."""
    if not os.path.exists(path):
        raise ElevationFileNotFoundError(f"no such {what}: {path!r}")
    if not stat.S_ISREG(os.stat(path).st_mode):
        raise _core.IoError(f"cannot read {what} {path!r}: not a regular file")


def _read_hgt(path: str) -> Elevation:
    """An SRTM .hgt tile: big-endian int16, n x n samples, n in (1201, 3601), named by its SW corner."""
    name = os.path.basename(path)
    match = re.fullmatch(r"([NS])(\d{2})([EW])(\d{3})\.hgt", name, flags=re.IGNORECASE)
    if not match:
        raise ValueError(f"{path!r} is not an SRTM tile name like N46E007.hgt (the name gives its corner)")
    lat = int(match[2]) * (1 if match[1].upper() == "N" else -1)
    lon = int(match[4]) * (1 if match[3].upper() == "E" else -1)
    if not (-90 <= lat <= 89) or not (-180 <= lon <= 179):
        raise ValueError(f"{path!r}: corner latitude {lat} must be in [-90, 89], longitude in [-180, 179]")
    size = os.path.getsize(path)
    n = next((n for n in _SRTM_SIZES if size == 2 * n * n), None)
    if n is None:
        raise ValueError(f"{path!r} is not SRTM elevation data: {size} bytes, not 2 x 1201^2 or 2 x 3601^2")
    raw = np.fromfile(path, dtype=">i2").reshape(n, n)
    heights = raw.astype(np.float64)
    heights[raw == _SRTM_VOID] = np.nan
    step = 1.0 / (n - 1)
    return Elevation(heights, float(lon), float(lat + 1), step, step, _EPSG_WGS84)


# Reads in progress that silenced tifffile, and its level before the first: threads that read
# together restore it once, after the last (each saving and restoring its own left it silenced).
_tifffile_quiet = threading.Lock()
_tifffile_readers = 0
_tifffile_level = logging.NOTSET


@contextlib.contextmanager
def _quiet_tifffile():
    """tifffile's log lines off while it reads ("invalid offset to first page" on stderr): what is
    wrong with a file is raised, named, instead."""
    global _tifffile_readers, _tifffile_level
    logger = logging.getLogger("tifffile")
    with _tifffile_quiet:
        if _tifffile_readers == 0:
            _tifffile_level = logger.level
            logger.setLevel(logging.CRITICAL + 1)
        _tifffile_readers += 1
    try:
        yield
    finally:
        with _tifffile_quiet:
            _tifffile_readers -= 1
            if _tifffile_readers == 0:
                logger.setLevel(_tifffile_level)


# Bytes a terrain sample takes on its way into the scene: the file's band (up to 8), its heights
# in float64 (8), the positions in float32 (12) and the mesh's vertex (12).
_BYTES_PER_SAMPLE = 40


class _TooLargeError(ValueError):
    """A band too large for the machine (raised through the reader's own ValueError handler)."""


def _check_fits(path: str, shape: tuple) -> None:
    """ValueError before decoding a band whose samples would not fit in this machine's memory (a
    trial's 7 MB zlib file claimed 40 000 x 40 000 floats: ~64 GB on the way in)."""
    samples = math.prod(int(n) for n in shape)
    need, have = samples * _BYTES_PER_SAMPLE, int(_core.physical_memory_bytes())
    if have > 0 and need > have:
        raise _TooLargeError(
            f"{path!r}: {' x '.join(str(int(n)) for n in shape)} samples need ~{need / 2**30:.0f} GiB on their way "
            f"into the scene, more than this machine's {have / 2**30:.0f} GiB: crop or resample the file"
        )


def _read_geotiff(path: str) -> Elevation:
    """A single-band GeoTIFF with ModelPixelScale + ModelTiepoint (north up) and its GeoKeys."""
    import tifffile

    try:
        with _quiet_tifffile(), tifffile.TiffFile(path) as tif:
            page = tif.pages.first
            tags = {tag.code: tag.value for tag in page.tags.values()}
            _check_fits(path, page.shape)
            data = page.asarray()
    except _TooLargeError:
        raise
    except (tifffile.TiffFileError, ValueError) as error:
        raise ValueError(f"{path!r} is not a TIFF file ({error})") from None
    except (KeyError, ImportError, NotImplementedError) as error:  # tifffile without the file's codec
        raise ValueError(
            f"{path!r}: its compression cannot be decoded here ({error!r}); "
            "compressed GeoTIFFs are read through the imagecodecs package"
        ) from None
    except MemoryError:
        raise
    except Exception as error:  # a truncated or corrupt file fails inside tifffile in many ways
        raise ValueError(
            f"{path!r} is not a readable TIFF file: damaged or truncated? (tifffile: {type(error).__name__}: {error})"
        ) from None
    if data.ndim == 3 and data.shape[-1] == 1:
        data = data[..., 0]
    if data.ndim != 2 or not (np.issubdtype(data.dtype, np.integer) or np.issubdtype(data.dtype, np.floating)):
        raise ValueError(
            f"{path!r} is not elevation data: a single band of numbers is needed "
            f"(got shape {data.shape}, dtype {data.dtype})"
        )
    if data.shape[0] < 2 or data.shape[1] < 2:
        raise ValueError(f"{path!r}: {data.shape[0]} x {data.shape[1]} samples; a grid needs 2 x 2 or more")
    if not _placed(tags) or 34735 not in tags:
        raise ValueError(
            f"{path!r} has no georeference (GeoTIFF ModelPixelScale, ModelTiepoint and GeoKeys are needed)"
        )
    keys = _geokeys(tags[34735], path)
    model = keys.get(_KEY_MODEL_TYPE)
    if model == _MODEL_GEOGRAPHIC:
        epsg = keys.get(_KEY_GEOGRAPHIC_TYPE, _EPSG_WGS84)
        if epsg != _EPSG_WGS84:
            raise ValueError(f"{path!r}: geographic CRS EPSG:{epsg}; only WGS84 (EPSG:4326) is supported")
        angular = keys.get(_KEY_ANGULAR_UNITS, _ANGULAR_DEGREE)
        if angular != _ANGULAR_DEGREE:  # a trial's radians were read as degrees
            raise ValueError(f"{path!r}: angles in EPSG unit {angular} (GeogAngularUnitsGeoKey); only degrees (9102)")
    elif model == _MODEL_PROJECTED and keys.get(_KEY_PROJECTED_TYPE) not in (None, 32767):
        epsg = int(keys[_KEY_PROJECTED_TYPE])
    else:
        raise ValueError(f"{path!r}: its GeoKeys name no EPSG geographic or projected CRS (model {model})")
    x0, y0, sx, sy = _placement(tags, keys, path)
    # The smallest spacing a grid may have: 0.1 mm (1e-9 deg of latitude); below it, samples fall
    # on one point in the scene's single-precision geometry.
    smallest = 1e-9 if epsg == _EPSG_WGS84 else _FINEST_SPACING
    if sx < smallest or sy < smallest:
        raise ValueError(f"{path!r}: pixel scale ({sx}, {sy}) is below {smallest}: samples would coincide")
    if epsg == _EPSG_WGS84 and (data.shape[1] - 1) * sx > 360.0 * (1.0 + 1e-12):
        raise ValueError(
            f"{path!r}: {data.shape[1]} columns of {sx} deg span {(data.shape[1] - 1) * sx} deg "
            "of longitude (at most 360)"
        )
    heights = data.astype(np.float64)
    unit = keys.get(_KEY_VERTICAL_UNITS, 9001)
    if unit not in _VERTICAL_UNITS:
        raise ValueError(
            f"{path!r}: heights in EPSG unit {unit} (VerticalUnitsGeoKey); supported: metre (9001), foot (9002), "
            "US survey foot (9003), kilometre (9036)"
        )
    nodata = tags.get(_TAG_NODATA)
    if nodata is not None:
        try:
            value = float(str(nodata).strip().rstrip("\x00"))
        except ValueError:
            raise ValueError(f"{path!r}: GDAL_NODATA {nodata!r} is not a number") from None
        # Compared in the band's own type, as GDAL does: float32's -3.4028235e+38 is the band's
        # lowest float32, though not the double that text reads as.
        if np.issubdtype(data.dtype, np.floating):
            with np.errstate(over="ignore"):
                heights[data == data.dtype.type(value)] = np.nan
        else:
            heights[data == value] = np.nan
    elif data.dtype == np.int16:  # SRTM's void, as in .hgt files, where no GDAL_NODATA names one (a trial's
        heights[data == _SRTM_VOID] = np.nan  # -32768 was a 32.8 km pit)
    heights *= _VERTICAL_UNITS[unit]  # NaN voids stay NaN
    if np.isinf(heights).any():
        r, c = np.argwhere(np.isinf(heights))[0]
        raise ValueError(
            f"{path!r}: sample (row {r}, column {c}) is {heights[r, c]}; heights must be finite "
            "(voids: NaN or the GDAL_NODATA value)"
        )
    # No terrain lies 100 km from sea level: such a sample is a void the file's GDAL_NODATA does not
    # name (float32's lowest, written as a shorter text), which reached CurvedEarth's bounds unnamed.
    beyond = _beyond_any_terrain(heights)
    if beyond is not None:
        r, c = beyond
        named = "no GDAL_NODATA" if nodata is None else f"GDAL_NODATA {nodata!r} is not it in the band's type"
        raise ValueError(
            f"{path!r}: sample (row {r}, column {c}) is {heights[r, c]:g} m, beyond {_FARTHEST_HEIGHT:g} m of any "
            f"terrain: a void value? ({named})"
        )
    if epsg != _EPSG_WGS84:
        _check_projected(path, epsg, x0, y0, x0 + (data.shape[1] - 1) * sx, y0 - (data.shape[0] - 1) * sy)
    else:
        top, bottom = y0, y0 - (data.shape[0] - 1) * sy
        if not (-90.0 <= bottom <= top <= 90.0):
            raise ValueError(f"{path!r}: latitudes {bottom} to {top} deg are outside [-90, 90]")
        # Either convention ([-180, 180] or [0, 360]) for the west edge; a grid may run on across
        # the meridian where its convention wraps (359.9 to 360.1 E), at most once around (above).
        if not (-360.0 <= x0 <= 360.0):
            raise ValueError(f"{path!r}: its west edge, longitude {x0} deg, is outside [-360, 360]")
    return Elevation(heights, x0, y0, sx, sy, epsg)


def _beyond_any_terrain(heights: np.ndarray) -> tuple[int, int] | None:
    """(row, column) of the first height farther than _FARTHEST_HEIGHT from sea level (NaN holes
    aside), or None."""
    with np.errstate(invalid="ignore"):
        beyond = np.abs(heights) > _FARTHEST_HEIGHT
    if not beyond.any():
        return None
    r, c = np.argwhere(beyond)[0]
    return int(r), int(c)


def _projected_crs(epsg: int, where: str):
    """The pyproj CRS of a projected EPSG code, else ValueError naming `where`."""
    import pyproj

    try:
        crs = pyproj.CRS.from_epsg(epsg)
    except pyproj.exceptions.CRSError:
        raise ValueError(f"{where}: EPSG:{epsg} is not a coordinate system pyproj knows") from None
    if not crs.is_projected:  # a geocentric (4978) or vertical (5773) code read as map coordinates
        raise ValueError(f"{where}: EPSG:{epsg} ({crs.name}) is not a projected coordinate system")
    return crs


def _check_projected(path: str, epsg: int, west: float, north: float, east: float, south: float) -> None:
    """A projected grid's corners must lie in its projection's domain: they map to latitude and
    longitude and back to where they were (a northing of 5e8 m came back as -2e7 m, and the tile
    was placed somewhere arbitrary: a trial)."""
    import pyproj

    crs = _projected_crs(epsg, repr(path))
    x = np.array([west, east, west, east, 0.5 * (west + east)])
    y = np.array([north, north, south, south, 0.5 * (north + south)])
    try:
        lon, lat = pyproj.Transformer.from_crs(crs, _EPSG_WGS84, always_xy=True).transform(x, y, errcheck=True)
        to_crs = pyproj.Transformer.from_crs(_EPSG_WGS84, crs, always_xy=True)
        back_x, back_y = to_crs.transform(lon, lat, errcheck=True)
    except pyproj.exceptions.ProjError:
        lon = back_x = back_y = np.full_like(x, np.nan)
    # 1 m: far above a projection's round trip (micrometres), far below any grid that fits its domain.
    off = np.hypot(np.asarray(back_x) - x, np.asarray(back_y) - y)
    if not (np.all(off <= 1.0) and np.all(np.isfinite(lon))):
        raise ValueError(
            f"{path!r}: its corners, x {west:g} to {east:g} and y {south:g} to {north:g} m, lie outside the domain of "
            f"EPSG:{epsg} ({crs.name}): is the georeference (ModelTiepoint, ModelPixelScale) right?"
        )


def _geokeys(directory, path: str) -> dict[int, Any]:
    """GeoKeyDirectory: (version, revision, minor, count) then count entries (key, location, count,
    value); short values only (location 0), which is where the CRS codes live."""
    try:
        d = [int(v) for v in np.ravel(directory)]
    except (TypeError, ValueError):
        d = []
    if len(d) < 4 or len(d) < 4 + 4 * d[3]:
        raise ValueError(f"{path!r}: its GeoKeyDirectory tag is malformed (got {directory!r})")
    return {d[k]: d[k + 3] for k in range(4, 4 + 4 * d[3], 4) if d[k + 1] == 0}


def _tag_numbers(tags: dict, code: int, count: int, path: str, name: str) -> list[float]:
    """The first `count` numbers of a GeoTIFF tag, else ValueError naming the file and the tag."""
    try:
        values = [float(v) for v in np.ravel(tags[code])[:count]]
    except (TypeError, ValueError):
        values = []
    if len(values) < count:
        raise ValueError(f"{path!r}: its {name} tag must hold {count} numbers (got {tags[code]!r})")
    return values


def _placed(tags: dict) -> bool:
    """Whether a GeoTIFF says where its grid lies: ModelPixelScale and ModelTiepoint, or ModelTransformation."""
    return (_TAG_PIXEL_SCALE in tags and _TAG_TIEPOINT in tags) or _TAG_TRANSFORM in tags


def _placement(tags: dict, keys: dict, path: str) -> tuple[float, float, float, float]:
    """(x0, y0, dx, dy): the first sample's centre in the CRS and the pixel scale, from the
    ModelPixelScale and ModelTiepoint tags (pixel-is-area: the tiepoint is a pixel's corner), or
    from a ModelTransformation that only scales and shifts (as GDAL may write a north-up grid)."""
    centre = 0.0 if keys.get(_KEY_RASTER_TYPE) == _RASTER_PIXEL_IS_POINT else 0.5
    if _TAG_TRANSFORM in tags:
        # X = a i + b j + d, Y = e i + f j + h (row-major 4 x 4; raster (i, j) = (column, row)).
        a, b, _, d, e, f, _, h = _tag_numbers(tags, _TAG_TRANSFORM, 8, path, "ModelTransformation")
        if b != 0.0 or e != 0.0:
            raise ValueError(
                f"{path!r}: a rotated or sheared grid (ModelTransformation with terms {b}, {e} off its "
                "diagonal) is not supported; only north-up, east-right grids are read"
            )
        sx, sy, x, y, i, j = a, -f, d, h, 0.0, 0.0
    else:
        sx, sy = _tag_numbers(tags, _TAG_PIXEL_SCALE, 2, path, "ModelPixelScale")
        i, j, _, x, y, _ = _tag_numbers(tags, _TAG_TIEPOINT, 6, path, "ModelTiepoint")
    x0, y0 = x + (centre - i) * sx, y - (centre - j) * sy
    # North up, east right: a negative scale (a mirrored grid) or a zero one is not a placement.
    if not (0.0 < sx < math.inf and 0.0 < sy < math.inf) or not (math.isfinite(x0) and math.isfinite(y0)):
        raise ValueError(
            f"{path!r}: pixel scale ({sx}, {sy}) must be finite and > 0 (only north-up, east-right grids "
            "are read: rows from north to south, columns from west to east), and the tiepoint finite"
        )
    return x0, y0, sx, sy


@contextlib.contextmanager
def _named(where: str):
    """The file readers' errors (ValueError, refracta.IoError) prefixed by the public call that read."""
    try:
        yield
    except (ValueError, _core.IoError) as error:
        error.args = (f"{where}: {error}",)  # the error itself, whatever its constructor takes
        raise


def read_elevation(path: str | os.PathLike) -> Elevation:
    """Read an elevation file (an SRTM ``.hgt`` tile or a GeoTIFF) into an :class:`Elevation`.

    refracta.IoError for a missing file (ElevationFileNotFoundError, also a FileNotFoundError) or
    one that is not a regular file; ValueError for files that are not elevation data, have
    no georeference, or whose latitudes fall outside [-90, 90] deg."""
    with _named("read_elevation"):
        return _read_elevation(os.fspath(path))


def _read_elevation(path: str) -> Elevation:
    _missing(path)
    if path.lower().endswith(".hgt"):
        return _read_hgt(path)
    if path.lower().endswith((".tif", ".tiff")):
        return _read_geotiff(path)
    raise ValueError(f"{path!r}: elevation files are SRTM .hgt tiles or GeoTIFFs (.tif, .tiff)")


def _orthophoto_uv(orthophoto: str, grid: Elevation) -> np.ndarray:
    """(2, 3): (u, v) of the orthophoto at a sample's (col, row, 1)."""
    photo = _read_geotiff_frame(orthophoto)
    if photo.epsg != grid.epsg:
        raise ValueError(
            f"orthophoto {orthophoto!r} is in EPSG:{photo.epsg}, the elevation in EPSG:{grid.epsg}: "
            "give both in the same CRS"
        )
    width, height = photo.heights.shape[1], photo.heights.shape[0]
    # Texture coordinates from the image's left and top edges (its pixels' corners):
    # s = (x - left) / (width dx), t = (top - y) / (height dy); v = 1 - t. A grid sample (c, r) lies at
    # x = x0 + c dx, y = y0 - r dy (row 0 north), so v falls by dy per row.
    left, top = photo.x0 - 0.5 * photo.dx, photo.y0 + 0.5 * photo.dy
    su = 1.0 / (width * photo.dx)
    st = 1.0 / (height * photo.dy)
    x0 = grid.x0
    if grid.epsg == _EPSG_WGS84:  # the grid's longitudes in the photo's convention ([-180, 180] or [0, 360])
        turns = (_middle(photo.x0, photo.dx, width) - _middle(grid.x0, grid.dx, grid.heights.shape[1])) / 360.0
        x0 += 360.0 * round(turns)
    return np.array(
        [
            [grid.dx * su, 0.0, (x0 - left) * su],
            [0.0, -grid.dy * st, 1.0 - (top - grid.y0) * st],
        ]
    )


def _read_geotiff_frame(path: str) -> Elevation:
    """An orthophoto's georeference (its pixels as an Elevation's grid; the values unused)."""
    import tifffile

    _missing(path, "orthophoto")
    try:
        with _quiet_tifffile(), tifffile.TiffFile(path) as tif:
            page = tif.pages.first
            tags = {tag.code: tag.value for tag in page.tags.values()}
            shape = page.shape
    except MemoryError:
        raise
    except Exception as error:  # not a TIFF, or a corrupt one
        raise ValueError(
            f"orthophoto {path!r} is not a readable GeoTIFF ({type(error).__name__}: {error}); "
            "an orthophoto placed by a georeferenced terrain must be a GeoTIFF"
        ) from None
    if not _placed(tags) or 34735 not in tags:
        raise ValueError(f"orthophoto {path!r} has no georeference (a GeoTIFF is needed)")
    keys = _geokeys(tags[34735], path)
    epsg = keys.get(_KEY_GEOGRAPHIC_TYPE, _EPSG_WGS84) if keys.get(_KEY_MODEL_TYPE) == _MODEL_GEOGRAPHIC else None
    if epsg is None:
        epsg = int(keys.get(_KEY_PROJECTED_TYPE, 0))
    try:
        x0, y0, sx, sy = _placement(tags, keys, path)  # elevation GeoTIFFs' checks of the scale too
    except ValueError as error:
        raise ValueError(f"orthophoto {error}") from None
    return Elevation(np.empty((shape[0], shape[1], 0)), x0, y0, sx, sy, epsg)


def _array_positions(heights, origin, spacing, earth_radius) -> np.ndarray:
    """(rows, cols, 3) float32 scene positions of the array form (NaN rows at NaN heights)."""
    # numpy reads "100" and True as numbers, and drops a complex height's imaginary part with a warning
    try:
        h = None if np.asarray(heights).dtype.kind in "bUSc" else np.asarray(heights, dtype=np.float64)
    except (TypeError, ValueError):
        h = None
    if h is None:
        raise ValueError("add_terrain: heights must be a (rows, cols) array of real numbers [m]")
    if h.ndim != 2 or h.shape[0] < 2 or h.shape[1] < 2:
        raise ValueError(
            f"add_terrain: heights must be a (rows, cols) array with rows, cols >= 2 (got shape {h.shape})"
        )
    if np.isinf(h).any():
        raise ValueError("add_terrain: heights must be finite (NaN marks a hole; got an infinity)")
    if np.isnan(h).all():
        raise ValueError("add_terrain: heights are all NaN (holes): nothing to add")
    beyond = _beyond_any_terrain(h)
    if beyond is not None:  # as the files' samples are (read_elevation)
        row, column = beyond
        raise ValueError(
            f"add_terrain: heights[{row}, {column}] is {h[row, column]:g} m, "
            f"beyond {_FARTHEST_HEIGHT:g} m of any terrain"
        )
    x0, z0 = _pair(origin, "origin", positive=False)
    dx, dz = _pair(spacing, "spacing", positive=True)
    if min(dx, dz) < _FINEST_SPACING:
        raise ValueError(
            f"add_terrain: spacing ({dx:g}, {dz:g}) m is below {_FINEST_SPACING:g} m: samples would coincide"
        )
    if earth_radius is None:
        y = h
    else:
        r = _earth_radius(earth_radius)
        if not (r > 0.0 and math.isfinite(r)):
            raise ValueError(f"add_terrain: earth_radius must be > 0 [m] (got {earth_radius!r})")
        if np.nanmin(h) <= -r:
            raise ValueError("add_terrain: heights must be above -earth_radius")
        y = _flat_height(np.where(np.isnan(h), 0.0, h), r)
        y[np.isnan(h)] = np.nan
    rows, cols = h.shape
    reach = float(_core._SCENE_REACH)  # scene coordinates end there (single-precision geometry)
    extents = {  # the heights are within _FARTHEST_HEIGHT (above)
        "origin and spacing (x)": max(abs(x0), abs(x0 + dx * (cols - 1))),
        "origin and spacing (z)": max(abs(z0), abs(z0 + dz * (rows - 1))),
    }
    for name, extent in extents.items():
        if not extent <= reach:
            raise ValueError(
                f"add_terrain: {name} reach {extent:.4g} m from the origin, beyond the scene's reach of {reach:g} m"
            )
    for name, step, extent in (
        ("x", dx, extents["origin and spacing (x)"]),
        ("z", dz, extents["origin and spacing (z)"]),
    ):
        resolution, least = _least_resolved_step(extent)
        if step < least:
            raise ValueError(
                f"add_terrain: spacing {step:g} m along {name} is finer than single-precision positions resolve "
                f"{extent:.4g} m from the origin (steps of {resolution:g} m; at least "
                f"{least:g} m there): put the origin nearer the terrain"
            )
    positions = np.empty((rows, cols, 3), dtype=np.float32)
    positions[..., 0] = (x0 + dx * np.arange(cols))[None, :]
    positions[..., 1] = y
    positions[..., 2] = (z0 + dz * np.arange(rows))[:, None]
    return positions


def _flat_height(h: np.ndarray, radius: float) -> np.ndarray:
    """CurvedEarth's flat heights y' = R ln(1 + h / R) of true heights h [m] (its C++ map, any shape)."""
    # The base field only makes a CurvedEarth to ask; flat_height depends on the radius alone.
    earth = _core.CurvedEarth(_core.PhysicalAtmosphere(), radius=radius)
    return np.asarray(earth.flat_height(h.ravel()), dtype=np.float64).reshape(h.shape)


def _earth_radius(value) -> float:
    """The array form's earth_radius [m]: a number, or a CurvedEarth's radius (as LocalFrame takes)."""
    if isinstance(value, _core.CurvedEarth):
        return float(value.radius)
    if not is_number(value):
        raise ValueError(f"add_terrain: earth_radius must be a number [m] or a CurvedEarth (got {value!r})")
    return float(value)


def _pair(value, name: str, positive: bool) -> tuple[float, float]:
    pair = number_pair(value)
    if pair is None:
        raise ValueError(f"add_terrain: {name} must be two numbers [m] (got {value!r})")
    a, b = pair
    if not (math.isfinite(a) and math.isfinite(b)):
        raise ValueError(f"add_terrain: {name} must be finite (got {value!r})")
    if positive and not (a > 0.0 and b > 0.0):
        raise ValueError(f"add_terrain: {name} must be > 0 in both directions (got {value!r})")
    return a, b


def _geographic_positions(grid: Elevation, frame) -> np.ndarray:
    """(rows, cols, 3) float32: each sample through frame.to_scene, a band of rows at a time."""
    rows, cols = grid.heights.shape
    positions = np.empty((rows, cols, 3), dtype=np.float32)
    for start in range(0, rows, _ROWS_PER_CHUNK):
        band = slice(start, min(rows, start + _ROWS_PER_CHUNK))
        lat, lon = grid.coordinates(band)
        h = grid.heights[band]
        holes = np.isnan(h)
        positions[band] = frame.to_scene(lat, lon, np.where(holes, 0.0, h))
        positions[band][holes] = np.nan
    _check_resolved(positions, grid)
    return positions


def _least_resolved_step(extent: float) -> tuple[float, float]:
    """(float32's step at `extent` [m] from the origin, the least sample spacing allowed there): the
    positions are single precision, and a spacing under _SINGLE_PRECISION_STEPS of its steps moves
    the samples by up to 1/16 of it, under 1 merges them (a trial's 1e-4 m at 9.9e6 m: one point)."""
    resolution = float(np.spacing(np.float32(extent)))
    return resolution, _SINGLE_PRECISION_STEPS * resolution


def _check_resolved(positions: np.ndarray, grid: Elevation) -> None:
    """ValueError where a file's samples are closer than the scene's single-precision positions
    resolve where they lie (the array form's rule, _SINGLE_PRECISION_STEPS): a trial's 1e-8 deg
    tile 387 km from the frame's origin collapsed its 20 columns onto one x. The median step along
    the middle row and the middle column (a polar row's meeting meridians do not count; the whole
    grid's steps would cost a 3601^2 tile some 600 MB), against the farthest coordinate."""
    rows, cols = positions.shape[:2]
    middle_row = positions[rows // 2, :, [0, 2]].T.astype(np.float64)  # (cols, 2): x, z
    middle_column = positions[:, cols // 2][:, [0, 2]].astype(np.float64)  # (rows, 2)
    # Voids (NaN) skipped without numpy's warnings (a warnings filter is the whole process's, and
    # threads reading terrain together left "ignore" in force).
    steps = []
    for line in (middle_row, middle_column):
        step_lengths = np.linalg.norm(np.diff(line, axis=0), axis=-1)
        step_lengths = step_lengths[np.isfinite(step_lengths)]
        steps.append(float(np.median(step_lengths)) if step_lengths.size else math.nan)
    # fmax / fmin skip NaN (nan only where every sample is one), without a copy of the grid.
    extent = max(
        float(max(np.fmax.reduce(positions[..., a], axis=None), -np.fmin.reduce(positions[..., a], axis=None)))
        for a in (0, 2)
    )
    resolution, least = _least_resolved_step(extent)
    step = min(steps)
    if step < least:
        raise ValueError(
            f"add_terrain: an elevation grid's samples ({grid.dx:g} x {grid.dy:g}) lie {step:.3g} m apart, finer "
            f"than single-precision positions resolve {extent / 1e3:.4g} km from the frame's origin (steps of "
            f"{resolution:g} m; at least {least:g} m there): put the frame's origin "
            "nearer the terrain or resample the file"
        )


def _tile_grids(paths: list[str]) -> Iterator[Elevation]:
    """The grids of a list of elevation files, one at a time: touching tiles of one lattice joined
    into one (:func:`_tile_sets`), a geographic grid all around the Earth closed (:func:`_closed_around`).
    The tiles are read first (every file's error before any grid is placed); each one's heights go
    as its grid is made."""
    read = []
    for path in paths:
        with _named("add_terrain"):
            read.append(_read_elevation(path))
        if np.isnan(read[-1].heights).all():
            raise ValueError(f"add_terrain: {path!r} holds only voids: nothing to add")
    sets = _tile_sets(paths, read)
    tiles: list[Elevation | None] = list(read)  # each tile leaves as its grid is made
    del read
    for members in sets:
        yield _closed_around(_joined(tiles, members))


def _middle(x0: float, dx: float, count: int) -> float:
    """The coordinate halfway between a grid's first and last samples along one axis."""
    return x0 + 0.5 * (count - 1) * dx


def _on_lattice(reference: Elevation, tile: Elevation) -> tuple[float, int, int] | None:
    """(x0, row, column): where ``tile``'s first sample lies on ``reference``'s lattice, with the
    tile's x0 in the reference's convention (a geographic tile's longitudes moved by whole turns to
    within 180 deg of the reference's first sample); None when the lattices differ (another CRS,
    another spacing, or samples a fraction of a sample apart)."""
    if tile.epsg != reference.epsg:
        return None
    if not (
        abs(tile.dx - reference.dx) <= _SPACING_TOLERANCE * reference.dx
        and abs(tile.dy - reference.dy) <= _SPACING_TOLERANCE * reference.dy
    ):
        return None
    x0 = tile.x0
    if tile.epsg == _EPSG_WGS84:
        x0 -= 360.0 * math.floor((x0 - reference.x0 + 180.0) / 360.0)
    column, row = (x0 - reference.x0) / reference.dx, (reference.y0 - tile.y0) / reference.dy
    if abs(column - round(column)) > _LATTICE_TOLERANCE or abs(row - round(row)) > _LATTICE_TOLERANCE:
        return None
    return x0, round(row), round(column)


def _tile_sets(paths: list[str], tiles: list[Elevation]) -> list[list[int]]:
    """Which tiles make one grid (indices, each set in file order, the sets in the order of their
    first files): the touching tiles of one lattice (:func:`_touching`) whose grid holds at most
    _MOSAIC_FILL times their samples; every other tile alone. A SceneWarning names the tiles left
    alone between which a crack may show. Geographic tiles are moved by whole turns onto their
    lattice's convention (in ``tiles``)."""
    from refracta._render import SceneWarning

    # The lattices, each tile on the first it lies on.
    lattices: list[list[int]] = []
    for i, tile in enumerate(tiles):
        for lattice in lattices:
            place = _on_lattice(tiles[lattice[0]], tile)
            if place is not None:
                tiles[i] = replace(tile, x0=place[0])
                lattice.append(i)
                break
        else:
            lattices.append([i])
    # The touching tiles of each lattice, joined unless too sparse.
    sets: list[list[int]] = []
    lattice_of: list[int] = []  # each set's lattice
    for k, lattice in enumerate(lattices):
        for touching in _touching([tiles[i] for i in lattice]):
            members = [lattice[m] for m in touching]
            grid = _mosaic_frame([tiles[i] for i in members])[0]
            samples = sum(tiles[i].heights.size for i in members)
            if grid.heights.shape[0] * grid.heights.shape[1] <= _MOSAIC_FILL * samples:
                sets.append(members)
                lattice_of.append(k)
                continue
            warnings.warn(
                f"add_terrain: the tiles {[paths[i] for i in members]} touch on one grid but are too sparse to join: "
                f"their grid would hold {grid.heights.shape[0] * grid.heights.shape[1]} samples, over "
                f"{_MOSAIC_FILL:g} times their {samples}; they are added as separate grids and a crack may show "
                "between them",
                SceneWarning,
                stacklevel=4,
            )
            sets.extend([i] for i in members)
            lattice_of.extend([k] * len(members))
    # Grids of different lattices meeting edge to edge: a crack may show between them.
    frames = [_mosaic_frame([tiles[i] for i in members])[0] for members in sets]
    names = [" + ".join(repr(paths[i]) for i in members) for members in sets]
    cracks = [
        f"{names[a]} and {names[b]}"
        for a in range(len(sets))
        for b in range(a + 1, len(sets))
        if lattice_of[a] != lattice_of[b] and _meet_edge_to_edge(frames[a], frames[b])
    ]
    if cracks:
        warnings.warn(
            f"add_terrain: tiles on different grids (another spacing, or shifted by a fraction of a sample) meet "
            f"edge to edge: {'; '.join(cracks)}; they cannot be joined and a crack may show between them "
            "(resample them onto one grid to join them)",
            SceneWarning,
            stacklevel=4,
        )
    return sorted(sets, key=min)


def _touching(tiles: list[Elevation]) -> list[list[int]]:
    """The sets of tiles of one lattice connected through touching ones (indices in order): two
    touch when their samples overlap, share an edge (SRTM tiles) or lie one spacing apart
    (pixel-is-area tiles), also across a corner."""
    first = np.array(_mosaic_frame(tiles)[1])
    last = first + np.array([tile.heights.shape[:2] for tile in tiles]) - 1
    # At most one spacing between them along rows and along columns.
    touch = np.all((first[:, None, :] <= last[None, :, :] + 1) & (first[None, :, :] <= last[:, None, :] + 1), axis=2)
    unseen = set(range(len(tiles)))
    sets = []
    for start in range(len(tiles)):
        if start not in unseen:
            continue
        unseen.discard(start)
        members, frontier = [start], [start]
        while frontier:
            for j in np.flatnonzero(touch[frontier.pop()]):
                if int(j) in unseen:
                    unseen.discard(int(j))
                    members.append(int(j))
                    frontier.append(int(j))
        sets.append(sorted(members))
    return sets


def _mosaic_frame(tiles: Sequence[Elevation]) -> tuple[Elevation, list[tuple[int, int]]]:
    """The grid over tiles of one lattice (their longitudes in one convention: _tile_sets), as a
    shape-only Elevation (heights (rows, cols, 0)), and each tile's first sample (row, column) in it."""
    reference = tiles[0]
    offsets = [
        (round((reference.y0 - tile.y0) / reference.dy), round((tile.x0 - reference.x0) / reference.dx))
        for tile in tiles
    ]
    top, left = min(r for r, _ in offsets), min(c for _, c in offsets)
    rows = max(r + tile.heights.shape[0] for tile, (r, _) in zip(tiles, offsets)) - top
    cols = max(c + tile.heights.shape[1] for tile, (_, c) in zip(tiles, offsets)) - left
    grid = Elevation(
        np.empty((rows, cols, 0)),
        reference.x0 + left * reference.dx,
        reference.y0 - top * reference.dy,
        reference.dx,
        reference.dy,
        reference.epsg,
    )
    return grid, [(r - top, c - left) for r, c in offsets]


def _joined(tiles: list[Elevation | None], members: list[int]) -> Elevation:
    """One grid of the tiles ``members`` of one lattice: NaN where none covers, the first tile's
    sample where they overlap (neighbouring SRTM tiles share their edge samples, which agree). The
    tiles leave ``tiles``: their heights go when the grid is made (one grid's at a time)."""
    parts = []
    for i in members:
        tile, tiles[i] = tiles[i], None
        assert tile is not None  # _tile_sets puts each tile in one set
        parts.append(tile)
    if len(parts) == 1:
        return parts[0]
    frame, corners = _mosaic_frame(parts)
    heights = np.full(frame.heights.shape[:2], np.nan)
    for tile, (r, c) in zip(parts, corners):
        window = heights[r : r + tile.heights.shape[0], c : c + tile.heights.shape[1]]
        np.copyto(window, tile.heights, where=np.isnan(window))
    return replace(frame, heights=heights)


def _closed_around(grid: Elevation) -> Elevation:
    """A geographic grid all around the Earth (columns x dx = 360 deg, as a global pixel-is-area
    grid's) with its first column repeated after its last, at its longitudes + 360 deg: the cells
    between them close the seam where its columns wrap (the antimeridian, or 0 deg in the [0, 360]
    convention). Any other grid as it is. Nothing is added at the poles."""
    cols = grid.heights.shape[1]
    if grid.epsg != _EPSG_WGS84 or abs(cols * grid.dx - 360.0) > _LATTICE_TOLERANCE * grid.dx:
        return grid
    return replace(grid, heights=np.concatenate([grid.heights, grid.heights[:, :1]], axis=1))


def _meet_edge_to_edge(a: Elevation, b: Elevation) -> bool:
    """Whether grids ``a`` and ``b`` (shape-only is enough) of one CRS meet edge to edge: their
    pixels touch (at most half a spacing of each between their outer samples) but no area lies
    under the samples of both, so their triangles may leave a crack between them. Grids in two
    CRSs are not compared."""
    if a.epsg != b.epsg:
        return False
    (rows_a, cols_a), (rows_b, cols_b) = a.heights.shape[:2], b.heights.shape[:2]
    shift = 0.0
    if a.epsg == _EPSG_WGS84:  # b's longitudes in a's convention
        shift = 360.0 * round((_middle(a.x0, a.dx, cols_a) - _middle(b.x0, b.dx, cols_b)) / 360.0)
    gap_x = max(a.x0, b.x0 + shift) - min(a.x0 + (cols_a - 1) * a.dx, b.x0 + shift + (cols_b - 1) * b.dx)
    gap_y = max(a.y0 - (rows_a - 1) * a.dy, b.y0 - (rows_b - 1) * b.dy) - min(a.y0, b.y0)
    slack_x, slack_y = _LATTICE_TOLERANCE * min(a.dx, b.dx), _LATTICE_TOLERANCE * min(a.dy, b.dy)
    touch = gap_x <= 0.5 * (a.dx + b.dx) + slack_x and gap_y <= 0.5 * (a.dy + b.dy) + slack_y
    overlap = gap_x < -slack_x and gap_y < -slack_y
    return touch and not overlap


def _water(scene, material, level, earth_radius: float | None, lower, upper) -> int:
    """A rectangle at the flat height of ``level`` over the terrain's extent (x, z)."""
    if not is_number(level):
        raise ValueError(f"add_terrain: water_level must be a number [m] (got {level!r})")
    level = float(level)
    if not (math.isfinite(level) and abs(level) <= _FARTHEST_HEIGHT):
        raise ValueError(f"add_terrain: water_level must be finite, within {_FARTHEST_HEIGHT:g} m [m] (got {level!r})")
    y = level
    if earth_radius is not None and math.isfinite(earth_radius):
        y = float(_flat_height(np.array([level]), earth_radius)[0])
    x0, z0, x1, z1 = lower[0], lower[1], upper[0], upper[1]
    vertices = np.array([[x0, y, z0], [x1, y, z0], [x1, y, z1], [x0, y, z1]], dtype=np.float64)
    return scene.add_mesh(vertices, np.array([[0, 2, 1], [0, 3, 2]]), material=material)


def add_terrain(
    self,
    heights,
    origin=None,
    spacing=None,
    material=None,
    *,
    frame=None,
    earth_radius=None,
    orthophoto=None,
    water_level=None,
    water=None,
) -> TerrainGeometry:
    """Add terrain from elevation data to the Scene ``self`` (bound as ``Scene.add_terrain``); see the
    module's docstring.

    heights: a (rows, cols) array of heights [m] (NaN: a hole), with ``origin`` (x0, z0) [m] and
    ``spacing`` (dx, dz) [m] > 0 (rows along +z, columns along +x) and, for a curved Earth,
    ``earth_radius`` [m] (or a CurvedEarth); or the path of an SRTM .hgt tile or a GeoTIFF, or a list of them, with
    ``frame`` a :class:`refracta.geo.LocalFrame` placing them.
    material: a refracta.shading material, or None for TerrainShading (elevation, slope, snow line).
    orthophoto: an image file draped over the terrain (a georeferenced GeoTIFF for the file forms).
    water_level: a true height [m]: a water surface (``water``, default refracta.shading.Water)
    over the terrain's extent at that height.
    Returns a :class:`TerrainGeometry` (the geometry ids). Bad input raises ValueError naming the
    argument; a missing file refracta.IoError (ElevationFileNotFoundError, also a
    FileNotFoundError), a FIFO or folder refracta.IoError. Terrain is traced (refracta.render); render_raster
    draws only triangle meshes and does not show it.
    """
    from refracta import shading

    if isinstance(heights, bytes):  # a path as bytes (os.fsencode), not an array of them
        heights = os.fsdecode(heights)
    # The grids: positions and, for orthophotos, the uv map of each.
    grids: list[tuple[np.ndarray, Elevation | None]] = []
    if isinstance(heights, Sequence) and not isinstance(heights, str):
        names = [isinstance(p, (str, os.PathLike)) for p in heights]
        if len(heights) == 0:
            raise ValueError("add_terrain: heights is empty: give an array of heights [m] or elevation files")
        if any(names) and not all(names):
            bad = names.index(False)
            raise ValueError(
                f"add_terrain: heights[{bad}] must be an elevation file's path, as the others (got {heights[bad]!r})"
            )
    if isinstance(heights, (str, os.PathLike)) or (
        isinstance(heights, Sequence) and len(heights) > 0 and all(isinstance(p, (str, os.PathLike)) for p in heights)
    ):
        if origin is not None or spacing is not None or earth_radius is not None:
            raise ValueError(
                "add_terrain: origin, spacing and earth_radius belong to the array form; files are placed by frame"
            )
        if frame is None or not hasattr(frame, "to_scene"):
            raise ValueError("add_terrain: elevation files need frame=refracta.geo.LocalFrame(lat, lon) to place them")
        paths = [os.fspath(heights)] if isinstance(heights, (str, os.PathLike)) else [os.fspath(p) for p in heights]
        for grid in _tile_grids(paths):
            placement = replace(grid, heights=np.empty((*grid.heights.shape, 0)))  # the uvs' (the heights go)
            grids.append((_geographic_positions(grid, frame), placement))
        radius = float(frame.earth_radius)
    else:
        if frame is not None:
            raise ValueError("add_terrain: frame places elevation files; an array is placed by origin and spacing")
        if origin is None or spacing is None:
            raise ValueError("add_terrain: an array of heights needs origin=(x0, z0) and spacing=(dx, dz) [m]")
        grids.append((_array_positions(heights, origin, spacing, earth_radius), None))
        radius = math.inf if earth_radius is None else _earth_radius(earth_radius)

    if orthophoto is not None and material is None:  # named before the texture loader names it a texture
        with _named("add_terrain"):
            _missing(os.fspath(orthophoto), "orthophoto")
    if material is None:
        if orthophoto is not None:
            material = shading.Diffuse(1.0, texture=os.fspath(orthophoto))
        else:
            material = shading.TerrainShading(earth_radius=radius)
    elif orthophoto is not None:
        raise ValueError(
            "add_terrain: give material or orthophoto, not both (a textured material uses the terrain's uvs)"
        )
    ids = []
    lower, upper = np.full(3, np.inf), np.full(3, -np.inf)
    try:
        for positions, placed in grids:
            rows, cols = positions.shape[:2]
            if orthophoto is not None and placed is not None:
                with _named("add_terrain"):
                    uv = _orthophoto_uv(os.fspath(orthophoto), placed)
            else:  # the image over the grid: u along the columns, its top edge along row 0 (v = 1)
                uv = np.array([[1.0 / (cols - 1), 0.0, 0.0], [0.0, -1.0 / (rows - 1), 1.0]])
            ids.append(self._add_terrain_grid(positions, material, uv))
            lower = np.fmin(lower, np.nanmin(positions.reshape(-1, 3), axis=0))
            upper = np.fmax(upper, np.nanmax(positions.reshape(-1, 3), axis=0))
        water_id = None
        if water_level is not None:
            water_material = shading.Water() if water is None else water
            water_id = _water(self, water_material, water_level, radius, lower[[0, 2]], upper[[0, 2]])
        elif water is not None:
            raise ValueError("add_terrain: water= is the material of the water_level surface; give water_level")
    except BaseException:  # all or nothing: a later grid's or the water's error leaves none of the call's grids
        for added in ids:
            self.remove(added)
        raise
    return TerrainGeometry(ids, water_id)


_core.Scene.add_terrain = add_terrain  # type: ignore[method-assign]
