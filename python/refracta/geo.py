"""refracta.geo: places on the real Earth (WGS84, through pyproj) and the scene frame around an observer.

Conventions (issue 20, shared by refracta.geo, the terrain loader and the per-pixel readouts):

- Angles in degrees, distances and heights in metres. Latitude in [-90, 90] (outside, or NaN:
  ValueError naming the argument); longitude in [-360, 360] (either convention, [-180, 180] or
  [0, 360]; wrapped by pyproj).
- Azimuth: degrees clockwise from north (0 north, 90 east). Elevation: degrees above the local
  horizontal.
- Scene frame of an observer at (lat0, lon0): x east, y up, z SOUTH (right-handed; north is -z), so
  a horizontal direction at azimuth a is (sin a, 0, -cos a).
- Horizontal placement: azimuthal equidistant about the origin (PROJ ``+proj=aeqd`` on WGS84): a
  point at geodesic distance d and forward azimuth a from the origin lands at x = d sin a,
  z = -d cos a -- CurvedEarth's flat frame, x' = R phi along every azimuth.
- Vertical placement: a height h [m] above the ellipsoid (taken as sea level: the geoid's
  undulation, up to about 100 m, is not applied -- give every height above the same surface) lands
  at CurvedEarth's flat height y' = R ln(1 + h / R) (CurvedEarth.flat_height, the conformal
  Earth-flattening transform), R the Earth radius of the scene's CurvedEarth field. For a
  flat-Earth scene (no CurvedEarth) pass ``earth_radius=math.inf``: then y = h.
- The Earth radius for CurvedEarth: the radius of curvature of the ellipsoid along the view azimuth
  (Euler's formula, :func:`radius_of_curvature`), e.g.
  ``CurvedEarth(base, radius=geo.radius_of_curvature(lat0, azimuth))``.

Geodesics are pyproj's (Karney's algorithm, accurate to nanometres): :func:`inverse` and
:func:`forward` are ``pyproj.Geod(ellps="WGS84").inv`` / ``.fwd`` with checked arguments. The sun's
place at a time (:func:`sun_position`, ``LocalFrame.sun_direction``) is the astral package's NOAA
solar-position calculation.
"""

from __future__ import annotations

import datetime
import math
import re
import warnings
from typing import Any

import numpy as np
import pyproj

from refracta import _core
from refracta._checks import ReadOnly, finite_pair, is_number, is_seed, no_unknown_keywords
from refracta._refraction_coefficient import straight_elevation

__all__ = ["LocalFrame", "forward", "inverse", "principal_radii", "radius_of_curvature", "sun_position"]

_GEOD = pyproj.Geod(ellps="WGS84")
# Geographic coordinates on the WGS84 ellipsoid itself (no datum shift between the two CRSs).
_LONLAT = pyproj.CRS.from_proj4("+proj=longlat +ellps=WGS84 +no_defs")


def _checked(value, name: str, low: float = -math.inf, high: float = math.inf) -> np.ndarray:
    """value as a float64 array, every element finite and in [low, high], else ValueError naming it
    (strings and booleans too: numpy would read "46.5" and True as numbers)."""
    if value is None or np.asarray(value).dtype.kind in "bUSO":  # numpy reads None as NaN
        raise ValueError(f"{name} must be a number or an array of numbers (got {value!r})")
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name} must be a number or an array of numbers (got {value!r})") from error
    bad = ~np.isfinite(array) | (array < low) | (array > high)
    if np.any(bad):
        where = float(array[bad].flat[0])
        span = f" in [{low:g}, {high:g}]" if math.isfinite(low) or math.isfinite(high) else ""
        raise ValueError(f"{name} must be finite{span} (got {where!r})")
    return array


def _value_kind(value) -> str:
    """numpy's dtype kind of `value` ('O' for None, which numpy would read as NaN)."""
    return "O" if value is None else np.asarray(value).dtype.kind


def _number(value, name: str, low: float = -math.inf, high: float = math.inf) -> float:
    """One number (_checked's rules), else ValueError naming it."""
    array = _checked(value, name, low, high)
    if array.ndim != 0:
        raise ValueError(f"{name} must be one number (got an array of shape {array.shape})")
    return float(array)


# [m] a geodesic longer than once around the Earth (its equator: 40 075 km) is no place.
_ONCE_AROUND = 4.01e7


def _latitude(value, name: str) -> np.ndarray:
    return _checked(value, name, -90.0, 90.0)


def _longitude(value, name: str) -> np.ndarray:
    return _checked(value, name, -360.0, 360.0)  # east of Greenwich, either convention ([-180, 180] or [0, 360])


# [deg] An azimuth or a roll within a turn either way: 1e300 deg was taken for 0 (its sine and
# cosine are rounding noise).
_TURN = (-360.0, 360.0)


def _angle(value, name: str) -> np.ndarray:
    return _checked(value, name, *_TURN)


# [m] The scene's reach (C++ kSceneReach): an origin or an eye beyond it is no place on Earth.
_REACH = float(_core._SCENE_REACH)
# How a bad (lat, lon) given as position= is named.
_POSITION_NAMES = ("position[0] (lat)", "position[1] (lon)")


def _broadcast(**arrays: np.ndarray) -> tuple[np.ndarray, ...]:
    """The arrays broadcast together, else ValueError naming them and their shapes."""
    try:
        return tuple(np.broadcast_arrays(*arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{name} {np.shape(a)}" for name, a in arrays.items())
        raise ValueError(f"the arrays do not broadcast together: {shapes}") from None


def _scalar_or_array(array: np.ndarray):
    """A 0-d result as a Python float, else the array."""
    return float(array) if np.ndim(array) == 0 else array


def inverse(lat1, lon1, lat2, lon2):
    """The geodesic between two points on the WGS84 ellipsoid (pyproj ``Geod.inv``).

    lat1, lon1, lat2, lon2 [deg] (arrays broadcast). Returns (distance [m], forward azimuth at point 1
    [deg], back azimuth at point 2 [deg], i.e. the azimuth from point 2 back toward point 1), azimuths
    clockwise from north in (-180, 180]. At a pole, azimuths are measured from the meridian of the
    longitude given there. Latitudes outside [-90, 90] or non-finite values: ValueError.
    """
    la1, lo1 = _latitude(lat1, "lat1"), _longitude(lon1, "lon1")
    la2, lo2 = _latitude(lat2, "lat2"), _longitude(lon2, "lon2")
    la1, lo1, la2, lo2 = _broadcast(lat1=la1, lon1=lo1, lat2=la2, lon2=lo2)
    az12, az21, dist = _GEOD.inv(lo1, la1, lo2, la2)
    return _scalar_or_array(np.asarray(dist)), _scalar_or_array(np.asarray(az12)), _scalar_or_array(np.asarray(az21))


def forward(lat, lon, azimuth, distance):
    """The point reached along the geodesic from (lat, lon) at ``azimuth`` after ``distance``.

    lat, lon, azimuth [deg], distance [m] (>= 0; arrays broadcast), pyproj ``Geod.fwd``. Returns
    (lat2, lon2 [deg], back azimuth at the end point [deg]). From a pole the azimuth is measured from
    the meridian of ``lon``. Bad input (latitude outside [-90, 90], negative or non-finite): ValueError.
    """
    la, lo = _latitude(lat, "lat"), _longitude(lon, "lon")
    az, d = _angle(azimuth, "azimuth"), _checked(distance, "distance", 0.0, _ONCE_AROUND)
    la, lo, az, d = _broadcast(lat=la, lon=lo, azimuth=az, distance=d)
    lon2, lat2, back = _GEOD.fwd(lo, la, az, d)
    return _scalar_or_array(np.asarray(lat2)), _scalar_or_array(np.asarray(lon2)), _scalar_or_array(np.asarray(back))


def _utc(when) -> datetime.datetime:
    """A time as an aware UTC datetime: a datetime with its time zone, or an ISO 8601 string with
    its offset ("2024-06-21T19:50:00Z", "...+01:00"); a time without a zone is ambiguous: ValueError."""
    if isinstance(when, str):
        try:
            # RFC 3339 (section 5.6) allows a lower-case "z" for UTC, which fromisoformat refuses.
            when = datetime.datetime.fromisoformat(re.sub(r"[zZ]$", "+00:00", when.strip()))
        except ValueError as error:  # its reason: "day is out of range for month", "second must be in 0..59"
            raise ValueError(
                f"when must be an ISO 8601 time such as '2024-06-21T19:50:00Z' (got {when!r}: {error})"
            ) from None
    if not isinstance(when, datetime.datetime):
        raise ValueError(f"when must be a datetime with its time zone or an ISO 8601 string (got {when!r})")
    if when.tzinfo is None or when.utcoffset() is None:
        raise ValueError(
            f"when must say its time zone (got {when.isoformat()}): e.g. datetime(..., tzinfo=timezone.utc) or '...Z'"
        )
    try:
        utc = when.astimezone(datetime.timezone.utc)
    except OverflowError:  # 0001-01-01T00:00+05:00 is in year 0 in UTC
        raise ValueError(f"when is outside the years 1-9999 in UTC (got {when.isoformat()})") from None
    if not _NOAA_YEARS[0] <= utc.year <= _NOAA_YEARS[1]:
        warnings.warn(
            f"when: {utc.year} is outside {_NOAA_YEARS[0]}-{_NOAA_YEARS[1]}, where NOAA's solar position holds "
            "to about 0.01 deg; its error grows with the years beyond",
            RuntimeWarning,
            stacklevel=3,
        )
    return utc


# The years NOAA's solar-position calculation (astral's) is accurate to about 0.01 deg over.
_NOAA_YEARS = (1800, 2100)


def sun_position(lat, lon, when) -> tuple[float, float]:
    """The sun's (azimuth [deg clockwise from north], elevation [deg]) seen from (lat, lon) [deg] at
    `when` (a datetime with its time zone, or an ISO 8601 string with its offset): its true place,
    without the air's refraction -- a render through air refracts it (astronomical_refraction
    gives how much: 33 arcmin at the horizon). NOAA's solar-position calculation (the astral
    package; about 0.01 deg for 1800-2100). Give ``LocalFrame.sun_direction`` its scene vector."""
    import astral  # here: a small package, loaded when first asked for the sun's place
    import astral.sun

    east = _number(lon, "lon", -360.0, 360.0)
    north = _number(lat, "lat", -90.0, 90.0)
    # astral takes [-180, 180] and does not wrap: 344.3 E put the sun of -15.7 below the horizon.
    observer = astral.Observer(latitude=north, longitude=(east + 180.0) % 360.0 - 180.0)
    utc = _utc(when)
    if abs(north) > _ASTRAL_LATITUDE:
        return _polar_sun_position(north, east, utc)
    return float(astral.sun.azimuth(observer, utc)), float(astral.sun.elevation(observer, utc, with_refraction=False))


# astral's zenith_and_azimuth computes at most 89.8 deg from the equator: at a pole the sun stood
# 0.2 deg off its declination (a trial). Beyond it the same NOAA declination and equation of time,
# turned to the place by its hour angle.
_ASTRAL_LATITUDE = 89.8


def _polar_sun_position(lat: float, lon: float, utc) -> tuple[float, float]:
    """sun_position's (azimuth, elevation) [deg] for |lat| > 89.8: NOAA's declination d and
    equation of time (astral), the hour angle H from the true solar time, and
    sin(elevation) = sin(lat) sin(d) + cos(lat) cos(d) cos(H); azimuth clockwise from north along
    the meridian of `lon` (at a pole itself every direction is south or north)."""
    import astral.sun

    century = astral.sun.julianday_to_juliancentury(astral.sun.julianday(utc))
    declination = math.radians(astral.sun.sun_declination(century))
    minutes = utc.hour * 60.0 + utc.minute + (utc.second + utc.microsecond * 1e-6) / 60.0
    hour_angle = math.radians((minutes + astral.sun.eq_of_time(century) + 4.0 * lon) / 4.0 - 180.0)
    phi = math.radians(lat)
    sin_d, cos_d, cos_h = math.sin(declination), math.cos(declination), math.cos(hour_angle)
    sin_elevation = math.sin(phi) * sin_d + math.cos(phi) * cos_d * cos_h
    elevation = math.degrees(math.asin(max(-1.0, min(1.0, sin_elevation))))
    east, north = -cos_d * math.sin(hour_angle), math.cos(phi) * sin_d - math.sin(phi) * cos_d * cos_h
    return math.degrees(math.atan2(east, north)) % 360.0, elevation


def principal_radii(lat):
    """(M, N) [m] at geodetic latitude ``lat`` [deg] on WGS84: the meridional radius of curvature
    M = a (1 - e^2) / (1 - e^2 sin^2 lat)^(3/2) and the prime-vertical one N = a / sqrt(1 - e^2 sin^2 lat)
    (a the semi-major axis, e^2 the first eccentricity squared, from pyproj's ellipsoid)."""
    s = np.sin(np.radians(_latitude(lat, "lat")))
    w2 = 1.0 - _GEOD.es * s * s
    m = _GEOD.a * (1.0 - _GEOD.es) / w2**1.5
    n = _GEOD.a / np.sqrt(w2)
    return _scalar_or_array(m), _scalar_or_array(n)


def radius_of_curvature(lat, azimuth):
    """The radius of curvature [m] of the WGS84 ellipsoid's normal section along ``azimuth`` [deg] at
    latitude ``lat`` [deg] (Euler's formula): 1/R = cos^2(azimuth)/M + sin^2(azimuth)/N, with M and N
    from :func:`principal_radii`. The Earth radius to give CurvedEarth for a view along that azimuth
    (6335.4 km north-south at the equator, 6378.1 km east-west; 6399.6 km at the poles)."""
    la, az = _broadcast(lat=_latitude(lat, "lat"), azimuth=_angle(azimuth, "azimuth"))
    m, n = principal_radii(la)
    a = np.radians(az)
    return _scalar_or_array(1.0 / (np.cos(a) ** 2 / m + np.sin(a) ** 2 / n))


def _flattening(earth_radius) -> tuple[float, Any]:
    """(R, a CurvedEarth whose flat_height / true_height map heights) for LocalFrame's earth_radius:
    None -> sqrt(M N) is filled in by the caller; a CurvedEarth -> itself; inf -> (inf, None): flat."""
    if isinstance(earth_radius, _core.CurvedEarth):
        return float(earth_radius.radius), earth_radius
    if not is_number(earth_radius):  # not True (a 1 m Earth), not "6e6"
        raise ValueError(f"earth_radius must be a number [m], math.inf or a CurvedEarth (got {earth_radius!r})")
    radius = float(earth_radius)
    if radius == math.inf:
        return radius, None
    if not (radius > 0.0 and math.isfinite(radius)):
        raise ValueError(f"earth_radius must be > 0 [m] (got {radius!r})")
    # Any height-only base serves: only the mapping of heights (which depends on R alone) is used.
    return radius, _core.CurvedEarth(_core.PhysicalAtmosphere(), radius)


def _within_reach(points: np.ndarray, name: str) -> None:
    """ValueError naming `name` for scene points beyond the scene's reach: coordinates end 1e7 m
    from the origin (single-precision geometry), half way to the antipode, where the azimuthal
    equidistant projection folds back on itself; heights end there too (C++'s box: |x|, |y|, |z|)."""
    reach = float(_core._SCENE_REACH)
    far = np.maximum(np.abs(points[..., 0]), np.abs(points[..., 2]))
    if np.any(far > reach):
        raise ValueError(
            f"{name}: {float(np.max(far)):.4g} m from the frame's origin, beyond the scene's reach of {reach:g} m "
            "(put the frame's origin nearer)"
        )
    high = np.abs(points[..., 1])
    if np.any(high > reach):
        highest = float(np.max(high))
        raise ValueError(f"{name}: a scene height of {highest:.4g} m, beyond the scene's reach of {reach:g} m")


class LocalFrame(ReadOnly):
    """The scene frame around an observer at (lat, lon) on WGS84 (see the module's conventions).

    lat, lon [deg]: the origin (not at a pole: north, and so the frame's -z, is undefined there).
    height [m]: the height of the ground at the origin above the ellipsoid (``origin_ground``
    places it); scene heights are always measured from the ellipsoid (y = 0 is sea level).
    earth_radius: the R of the flat heights y' = R ln(1 + h / R) -- a number [m], the scene's
    CurvedEarth field (its radius), ``math.inf`` for a flat-Earth scene (y = h), or None: the
    Gaussian mean radius sqrt(M N) at lat (the mean of Euler's radius over all azimuths). For a
    scene viewed along one azimuth give ``geo.radius_of_curvature(lat, azimuth)`` and the same R to
    CurvedEarth.

    Horizontal positions are PROJ's azimuthal equidistant projection about (lat, lon) on WGS84
    (``+proj=aeqd``): exact geodesic distance and azimuth from the origin, to nanometres over
    thousands of km (it is singular at the antipode). Only from the origin: a camera D from it sees
    a target s beyond it about D s / (3 R^2) rad to the side (0.0068 deg for 150 km and 100 km)
    and reads its distance up to ~D^2 / (6 R^2) of itself long (``camera(position=...)`` warns
    past half a pixel); for such views make a frame at the camera.
    """

    def __init__(self, lat, lon, height=0.0, earth_radius=None):
        self._lat = _number(lat, "lat", -90.0, 90.0)
        if abs(self.lat) == 90.0:
            raise ValueError(
                f"lat must not be a pole (got {self.lat!r}): north, and so the scene's -z, is undefined there"
            )
        self._lon = _number(lon, "lon", -360.0, 360.0)  # as every function of this module takes it
        self._height = _number(height, "height", -_REACH, _REACH)
        if earth_radius is None:
            m, n = principal_radii(self.lat)
            earth_radius = math.sqrt(m * n)
        self._earth_radius, self._curved = _flattening(earth_radius)
        aeqd = pyproj.CRS.from_proj4(
            f"+proj=aeqd +lat_0={self.lat!r} +lon_0={self.lon!r} +ellps=WGS84 +units=m +no_defs"
        )
        self._to_plane = pyproj.Transformer.from_crs(_LONLAT, aeqd, always_xy=True)
        self._to_lonlat = pyproj.Transformer.from_crs(aeqd, _LONLAT, always_xy=True)

    # Read-only: the projection is made once, about the origin (a trial set lat = 45: the repr said
    # 45, to_scene projected about 28).
    _remake = "the frame's projection is made about its origin; make another LocalFrame(lat, lon, height, earth_radius)"

    lat = property(lambda self: self._lat, doc="[deg] the origin's latitude")
    lon = property(lambda self: self._lon, doc="[deg] the origin's longitude")
    height = property(lambda self: self._height, doc="[m] the ground's height at the origin above the ellipsoid")
    earth_radius = property(lambda self: self._earth_radius, doc="[m] R of the flat heights (inf: a flat Earth)")

    def __repr__(self) -> str:
        where = f"lat={self.lat!r}, lon={self.lon!r}, height={self.height!r}"
        return f"LocalFrame({where}, earth_radius={self.earth_radius!r})"

    def flat_height(self, height):
        """Scene y [m] of heights [m] above the ellipsoid: CurvedEarth.flat_height (or y = h when flat)."""
        h = _checked(height, "height")
        if self._curved is None:
            return _scalar_or_array(h)
        # The binding maps scalars and 1-D arrays: any shape goes through flat.
        return _scalar_or_array(np.asarray(self._curved.flat_height(h.ravel()), dtype=np.float64).reshape(h.shape))

    def true_height(self, y):
        """Height [m] above the ellipsoid of scene heights y [m]: CurvedEarth.true_height (or h = y when flat)."""
        flat = _checked(y, "y")
        if self._curved is None:
            return _scalar_or_array(flat)
        return _scalar_or_array(
            np.asarray(self._curved.true_height(flat.ravel()), dtype=np.float64).reshape(flat.shape)
        )

    def to_scene(self, lat, lon, height) -> np.ndarray:
        """Scene points (..., 3) float64 [m] of geographic points (lat, lon [deg], height [m] above the
        ellipsoid; arrays broadcast): x east and z south of the origin by the azimuthal equidistant
        projection, y the flat height (module conventions). ValueError for a point beyond the scene's
        reach, 1e7 m from the origin (half way to the antipode)."""
        return self._scene_points(lat, lon, height, "to_scene: the points")

    def _scene_points(self, lat, lon, height, what: str, names=("lat", "lon")) -> np.ndarray:
        """to_scene, its refusal naming `what`, a bad lat or lon by `names`."""
        la, lo = _latitude(lat, names[0]), _longitude(lon, names[1])
        h = _checked(height, "height")
        la, lo, h = _broadcast(lat=la, lon=lo, height=h)
        east, north = self._to_plane.transform(lo, la, errcheck=True)
        y = np.asarray(self.flat_height(h), dtype=np.float64)
        points = np.stack(
            [np.asarray(east, dtype=np.float64), np.broadcast_to(y, la.shape), -np.asarray(north)], axis=-1
        )
        _within_reach(points, what)  # as to_geographic refuses them
        return points

    def to_geographic(self, points):
        """(lat [deg], lon [deg], height [m] above the ellipsoid) of scene points (..., 3): the inverse of
        to_scene (a round trip is exact to well under a millimetre). Longitudes in [-180, 180]. A point
        holding NaN -- a sky pixel of render's 'position' readout -- gives NaN for all three, so a
        readout image converts whole."""
        if _value_kind(points) not in "iuf":
            _checked(points, "points")  # its message for strings, booleans, None and the like
        p = np.asarray(points, dtype=np.float64)
        if p.ndim == 0 or p.shape[-1] != 3:
            raise ValueError(f"points must have shape (..., 3) (got {p.shape})")
        missing = np.asarray(np.isnan(p).any(axis=-1))
        p = _checked(np.where(missing[..., None], 0.0, p), "points")
        _within_reach(p, "points")
        lon, lat = self._to_lonlat.transform(p[..., 0], -p[..., 2], errcheck=True)
        lat, lon, height = (
            np.where(missing, np.nan, np.asarray(v, dtype=np.float64)) for v in (lat, lon, self.true_height(p[..., 1]))
        )
        return _scalar_or_array(lat), _scalar_or_array(lon), _scalar_or_array(height)

    @staticmethod
    def direction(azimuth, elevation) -> np.ndarray:
        """Unit scene vector(s) (..., 3) at ``azimuth`` (clockwise from north) and ``elevation`` [deg]
        at the origin: (cos e sin a, sin e, -cos e cos a). Away from the origin, CurvedEarth's flat
        frame keeps y as the local vertical and (sin a, 0, -cos a) as the direction of the geodesic of
        that azimuth from the origin."""
        a = np.radians(_angle(azimuth, "azimuth"))
        e = np.radians(_checked(elevation, "elevation", -90.0, 90.0))
        a, e = _broadcast(azimuth=a, elevation=e)
        return np.stack([np.cos(e) * np.sin(a), np.sin(e), -np.cos(e) * np.cos(a)], axis=-1)

    def bearing(self, azimuth, position):
        """The compass bearing [deg clockwise from the local north, in [0, 360)] at the scene point
        ``position`` (3,) of the frame azimuth(s) ``azimuth`` [deg clockwise from the frame's north,
        -z]: render's 'apparent_azimuth' readout as the bearing a compass at the camera reads,
        ``frame.bearing(aovs["apparent_azimuth"], camera.position)``, which ``camera(position=...)``
        takes back. They differ by the meridians' convergence (about 0.96 deg 100 km east of the origin
        at 47 deg) and the projection's small distortion: the geodesic of the direction's first metre."""
        a = np.radians(_angle(azimuth, "azimuth"))
        p = _checked(position, "position")
        if p.shape != (3,):
            raise ValueError(f"position must be one scene point (3,) (got shape {p.shape})")
        ahead = p + np.stack([np.sin(a), np.zeros_like(a), -np.cos(a)], axis=-1)  # 1 m along each azimuth
        lat, lon, _ = self.to_geographic(p)
        lat2, lon2, _ = self.to_geographic(ahead)
        _, forward_azimuth, _ = inverse(lat, lon, lat2, lon2)
        wrapped = np.mod(np.asarray(forward_azimuth, dtype=np.float64), 360.0)
        return _scalar_or_array(np.where(wrapped >= 360.0, 0.0, wrapped))  # -1e-15 wraps to 360.0 itself

    def _frame_azimuth(self, lat: float, lon: float, azimuth: float) -> float:
        """The frame's azimuth [deg] of the geodesic leaving (lat, lon) at the local ``azimuth``: its
        first metre projected (this includes the meridians' convergence, about 0.96 deg 100 km east
        of the origin at 47 deg, and the projection's small distortion)."""
        lat2, lon2, _ = forward(lat, lon, azimuth, 1.0)
        start, end = self.to_scene([lat, lat2], [lon, lon2], 0.0)
        return math.degrees(math.atan2(end[0] - start[0], start[2] - end[2]))

    def __reduce__(self):
        # The mapping of heights depends on R alone: a frame made from a CurvedEarth pickles as its radius.
        return LocalFrame, (self.lat, self.lon, self.height, self.earth_radius)

    def origin_ground(self) -> np.ndarray:
        """The scene point (3,) of the ground at the origin: (0, flat height of ``height``, 0)."""
        return np.array([0.0, self.flat_height(self.height), 0.0])

    def ground_height(self, scene, position=None) -> float | None:
        """The height [m] above the ellipsoid of ``scene``'s terrain (Scene.terrain_height: the highest
        terrain surface) under the origin, or under ``position`` = (lat, lon) [deg]; None where no
        terrain lies there. What :meth:`camera` adds an eye's height to:
        ``frame.camera(frame.ground_height(scene) + 1.7, azimuth, 0.0, vfov=10.0)``. (Scene heights
        are the flat frame's y: over a curved Earth they fall short of true heights by h^2 / R,
        3.9 m at 5 000 m, so the terrain's y plus an eye's height is no camera height.)"""
        if not isinstance(scene, _core.Scene):
            raise ValueError(f"ground_height: scene must be a refracta.Scene (got {type(scene).__name__})")
        if position is None:
            x, z = 0.0, 0.0
        else:
            place = finite_pair(position)
            if place is None:
                raise ValueError(f"ground_height: position must be (lat, lon) (got {position!r})")
            x, _, z = (float(v) for v in self._scene_points(place[0], place[1], 0.0, "position", _POSITION_NAMES))
        y = scene.terrain_height(x, z)
        return None if y is None else float(self.true_height(y))

    def sun_direction(self, when) -> np.ndarray:
        """The scene's unit vector (3,) toward the sun's true place at `when` (sun_position at the
        frame's origin), for Scene.set_physical_sky or set_sun: a render through a CurvedEarth air
        refracts it as a real sun near the horizon (lifted, flattened)."""
        azimuth, elevation = sun_position(self.lat, self.lon, when)
        return self.direction(azimuth, elevation)

    def aim(self, target, height, position=None) -> tuple[float, float]:
        """(azimuth, elevation) [deg] from an eye ``height`` [m] above the ellipsoid over the origin
        (or over ``position`` = (lat, lon)) toward ``target`` = (lat, lon) or (lat, lon, height [m]
        above the ellipsoid, default 0; a map's height above the geoid differs by up to ~100 m,
        0.1 deg at 60 km: give both heights above one surface): the compass bearing of the geodesic to it, and the
        elevation of the straight line to it through a sphere of the frame's earth_radius (flat
        frame: over flat ground) -- where it would show with no air; refraction lifts it (by about
        k d / 2R, 0.045 deg at 60 km for the standard k = 0.17). ``camera(target=...)`` looks there."""
        place = finite_pair(position) if position is not None else (self.lat, self.lon)
        if place is None:
            raise ValueError(f"position must be (lat, lon) (got {position!r})")
        lat, lon, target_height = self._target(target)
        lowest = -self.earth_radius if math.isfinite(self.earth_radius) else -math.inf
        distance, azimuth, _ = inverse(place[0], place[1], lat, lon)
        if not distance > 0.0:
            raise ValueError(f"target {target!r} is straight above or below the eye: it has no azimuth")
        reach = float(_core._SCENE_REACH)
        if distance > reach:  # the antipode gave a camera looking straight down
            raise ValueError(
                f"target {target!r}: {distance:.4g} m from the eye, beyond the scene's reach of {reach:g} m"
            )
        eye_height = _number(height, "height", lowest)
        elevation = straight_elevation(distance, eye_height, target_height, self.earth_radius)
        return float(azimuth), elevation

    def _target(self, target) -> tuple[float, float, float]:
        """(lat, lon, height above the ellipsoid) of a target (lat, lon[, height]), checked."""
        values = np.asarray(target, dtype=object) if isinstance(target, (tuple, list, np.ndarray)) else None
        if values is None or values.shape not in ((2,), (3,)):
            raise ValueError(f"target must be (lat, lon) or (lat, lon, height) (got {target!r})")
        lat = _number(values[0], "target's lat", -90.0, 90.0)
        lon = _number(values[1], "target's lon", -360.0, 360.0)
        # Above the Earth's centre, as to_scene takes them (a trial's -1e7 m gave an elevation of -90.13).
        lowest = -self.earth_radius if math.isfinite(self.earth_radius) else -math.inf
        return lat, lon, (_number(values[2], "target's height", lowest) if len(values) == 3 else 0.0)

    def _aim_in_frame(self, eye: np.ndarray, target, height: float) -> tuple[float, float]:
        """(frame azimuth, elevation) [deg] from the scene point ``eye``, ``height`` [m] above the
        ellipsoid, toward ``target`` as the frame places it: the straight line to its scene point in
        plan, so that a camera away from the origin centres it (the geodesic's bearing leaves the
        projection's straight line by about D s / 3R^2 there: below)."""
        lat, lon, target_height = self._target(target)
        point = self.to_scene(lat, lon, 0.0)
        run = math.hypot(point[0] - eye[0], point[2] - eye[2])
        if not run > 0.0:
            raise ValueError(f"target {target!r} is straight above or below the eye: it has no azimuth")
        azimuth = math.degrees(math.atan2(point[0] - eye[0], eye[2] - point[2]))
        return azimuth, straight_elevation(run, height, target_height, self.earth_radius)

    def _warn_far_from_origin(self, eye: np.ndarray, pixel_angle: float) -> None:
        """Warn when a camera at the scene point ``eye`` is so far from the origin that the
        projection's distortion moves a target as far again from it by more than half a pixel: the
        azimuthal equidistant plane keeps distances and bearings from its origin only, so away from
        it a target s [m] beyond a camera D [m] out shows about D s / (3 R^2) [rad] to the side and
        its distance reads up to ~D^2 / (6 R^2) of itself long (a trial: D = 150 km, s = 100 km,
        0.0068 deg and 8.5 m)."""
        offset = math.hypot(eye[0], eye[2])
        m, n = principal_radii(self.lat)  # the projection's distortion is the ellipsoid's
        radius = math.sqrt(m * n)
        shift = offset * offset / (3.0 * radius * radius)
        if shift > 0.5 * pixel_angle:
            warnings.warn(
                f"a camera {offset / 1e3:.3g} km from the frame's origin: the frame's azimuthal equidistant "
                f"plane is exact only from its origin, so a target {offset / 1e3:.3g} km beyond the camera "
                f"shows about {shift / pixel_angle:.2g} pixels to the side ({math.degrees(shift):.2g} deg) and "
                "distances read slightly long; for geometry true to the pixel make the frame at the camera: "
                "geo.LocalFrame(lat, lon) (or Camera.geographic)",
                UserWarning,
                stacklevel=3,
            )

    def camera(
        self,
        height,
        azimuth=None,
        elevation=None,
        *,
        target=None,
        vfov=None,
        focal_length_mm=None,
        sensor_mm=None,
        image_width=None,
        image_height=None,
        roll=0.0,
        position=None,
        **unknown,
    ) -> _core.Camera:
        """A camera in this frame, ``height`` [m] above the ellipsoid (the eye, not the ground) over the
        origin (or over ``position`` = (lat, lon) elsewhere in the frame), looking at ``azimuth``
        (clockwise from the local north there: a compass bearing, turned into the frame's by
        projecting the geodesic that leaves at it) and ``elevation`` [deg] above the horizontal
        (CurvedEarth's flat frame keeps y as the local vertical everywhere). Or, instead of azimuth and
        elevation, ``target`` = (lat, lon[, height]): aimed at it (``aim``: its bearing and its elevation
        with no air, so that refraction lifts it a little above the image's centre; from ``position``
        along the frame's straight line to it, which centres it there, see the class). A camera so
        far from the origin that the frame's distortion moves a target as far again by more than
        half a pixel warns.

        Give exactly one of vfov [deg] (vertical field of view; Camera(...)) or focal_length_mm with
        sensor_mm = (width, height) [mm] (Camera.photographic's lens and sensor; None: its full-frame
        default). image_width, image_height [pixels]: the image (None: the bound constructor's
        default; one alone: the other follows the default image's shape, or the sensor's, as the
        constructor does). roll
        [deg]: the camera turned clockwise about its view direction as seen from
        behind it (the image's right side dips: a level horizon in view then rises to the right of
        the image), 0 level. ValueError when both or neither of vfov and focal_length_mm are
        given, or for a non-finite angle.
        """
        from refracta._geo_camera import IMAGE_SIZE_HINT

        no_unknown_keywords("LocalFrame.camera", unknown, LocalFrame.camera, IMAGE_SIZE_HINT)
        if (vfov is None) == (focal_length_mm is None):
            raise ValueError("give exactly one of vfov and focal_length_mm")
        if target is not None:
            if azimuth is not None or elevation is not None:
                raise ValueError("give azimuth and elevation, or target, not both")
            azimuth, elevation = self.aim(target, height, position)
        elif azimuth is None or elevation is None:
            raise ValueError("give azimuth and elevation [deg], or target=(lat, lon[, height])")
        if vfov is not None and sensor_mm is not None:
            raise ValueError("sensor_mm goes with focal_length_mm; vfov gives the field of view itself")
        height = _number(height, "height", -_REACH, _REACH)
        a = _number(azimuth, "azimuth", *_TURN)
        e = _number(elevation, "elevation", -90.0, 90.0)
        r = math.radians(_number(roll, "roll", *_TURN))
        if position is None:
            eye = np.array([0.0, self.flat_height(height), 0.0])
        else:
            place = finite_pair(position)
            if place is None:
                raise ValueError(f"position must be (lat, lon) (got {position!r})")
            eye = self._scene_points(place[0], place[1], height, "position", _POSITION_NAMES)
            if target is None:
                a = self._frame_azimuth(place[0], place[1], a)
            else:
                a, e = self._aim_in_frame(eye, target, height)
        forward_ = self.direction(a, e)
        # The unrolled camera's up: the view direction turned 90 deg up in its vertical plane.
        sa, ca, se, ce = (
            math.sin(math.radians(a)),
            math.cos(math.radians(a)),
            math.sin(math.radians(e)),
            math.cos(math.radians(e)),
        )
        up0 = np.array([-se * sa, ce, se * ca])
        right = np.cross(forward_, up0)
        up = math.cos(r) * up0 + math.sin(r) * right
        size: dict[str, Any] = {}
        for name, value in (("width", image_width), ("height", image_height)):
            if value is not None:
                if not (is_seed(value) and 1 <= value <= _core.Camera.max_side):
                    raise ValueError(
                        f"image_{name} must be a whole number of pixels in [1, {_core.Camera.max_side}] (got {value!r})"
                    )
                size[name] = int(value)
        look_at = eye + forward_
        lens: dict[str, Any] = {}
        if sensor_mm is not None:
            sensor = finite_pair(sensor_mm)
            if sensor is None:
                raise ValueError(f"sensor_mm must be (width, height) [mm] (got {sensor_mm!r})")
            lens["sensor_mm"] = sensor
        if vfov is not None:
            camera = _core.Camera(eye, look_at, up=up, vfov=_number(vfov, "vfov"), **size)
        else:
            camera = _core.Camera.photographic(
                eye, look_at, _number(focal_length_mm, "focal_length_mm"), up=up, **size, **lens
            )
        if position is not None:
            self._warn_far_from_origin(eye, camera.pixel_angle)
        return camera
