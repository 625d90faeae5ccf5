"""refracta.geo's geodesy against pyproj's Geod (WGS84) and the ellipsoid's principal radii (issue 20)."""

import math

import numpy as np
import pyproj
import pytest

from refracta import geo

GEOD = pyproj.Geod(ellps="WGS84")

# (lat1, lon1, lat2, lon2): 95 km across the Alps, London-Sydney (17000 km), across the antimeridian
# (Fiji), near the north pole across it, from the south pole, and almost antipodal on the equator.
PAIRS = [
    (47.3769, 8.5417, 46.9480, 7.4474),
    (51.5074, -0.1278, -33.8688, 151.2093),
    (-17.8, 179.9, -16.5, -179.2),
    (89.9, 0.0, 89.9, 180.0),
    (-90.0, 0.0, -60.0, 45.0),
    (0.0, 0.0, 0.5, 179.5),
]


@pytest.mark.parametrize("lat1, lon1, lat2, lon2", PAIRS)
def test_inverse_and_forward_are_pyprojs_geodesics(lat1, lon1, lat2, lon2):
    az12, az21, dist = GEOD.inv(lon1, lat1, lon2, lat2)
    distance, forward_azimuth, back_azimuth = geo.inverse(lat1, lon1, lat2, lon2)
    # The same algorithm (Karney's, in PROJ) on the same numbers: equal to rounding.
    assert distance == pytest.approx(dist, rel=1e-12, abs=1e-9)  # rounding only: the same computation
    assert forward_azimuth == pytest.approx(az12, abs=1e-9)  # rounding only: the same computation
    assert back_azimuth == pytest.approx(az21, abs=1e-9)  # rounding only: the same computation
    lat, lon, back = geo.forward(lat1, lon1, forward_azimuth, distance)
    # Forward along the inverse's geodesic ends at point 2: Karney's algorithm is accurate to 15 nm,
    # 1e-9 deg of latitude is 0.1 mm.
    assert lat == pytest.approx(lat2, abs=1e-9)  # 0.1 mm: well above Karney's 15 nm round trip
    if abs(lat2) < 90.0:
        assert math.remainder(lon - lon2, 360.0) == pytest.approx(0.0, abs=1e-9)  # as latitude, mod 360
    assert math.remainder(back - back_azimuth, 360.0) == pytest.approx(0.0, abs=1e-7)  # 15 nm over 1e7 m of arc


def test_arrays_broadcast():
    lat2 = np.array([46.0, 47.0, 48.0])
    distance, azimuth, _ = geo.inverse(47.0, 8.0, lat2, 9.0)
    assert distance.shape == (3,)
    expected = GEOD.inv(np.full(3, 8.0), np.full(3, 47.0), np.full(3, 9.0), lat2)[2]
    np.testing.assert_allclose(distance, expected, rtol=1e-12)  # rounding only: the same computation
    assert azimuth[0] > 90.0 and azimuth[2] < 90.0  # south-east, then north-east


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: geo.inverse(91.0, 0.0, 0.0, 0.0), "lat1"),
        (lambda: geo.inverse(0.0, 0.0, -90.5, 0.0), "lat2"),
        (lambda: geo.inverse(0.0, math.nan, 0.0, 0.0), "lon1"),
        (lambda: geo.inverse(0.0, 0.0, 0.0, [1.0, math.inf]), "lon2"),
        (lambda: geo.forward(math.nan, 0.0, 0.0, 1.0), "lat"),
        (lambda: geo.forward(0.0, 0.0, 0.0, -1.0), "distance"),
        (lambda: geo.forward(0.0, 0.0, math.nan, 1.0), "azimuth"),
        (lambda: geo.radius_of_curvature(100.0, 0.0), "lat"),
        (lambda: geo.LocalFrame(90.0, 0.0), "pole"),
        (lambda: geo.LocalFrame(-91.0, 0.0), "lat"),
    ],
)
def test_bad_input_is_a_value_error_naming_the_argument(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_principal_radii_are_the_curvatures_of_pyprojs_geodesics():
    # M is dS/dlat along a meridian, N cos(lat) dS/dlon along a parallel: central differences of
    # pyproj's geodesic lengths over +-1e-4 deg (11 m), independent of the formulas in geo.
    delta = 1e-4
    for lat in (0.0, 30.0, 47.0, 75.0):
        m, n = geo.principal_radii(lat)
        meridian = GEOD.inv(8.0, lat - delta, 8.0, lat + delta)[2] / math.radians(2 * delta)
        parallel = (
            GEOD.inv(8.0 - delta, lat, 8.0 + delta, lat)[2] / math.radians(2 * delta) / math.cos(math.radians(lat))
        )
        # Differences over 11 m: Karney's 15 nm error is 1.4e-9 of them; the truncation (delta^2
        # e^2, and the geodesic's sagging off the parallel, (delta sin lat)^2 / 24) is below 1e-12.
        assert m == pytest.approx(meridian, rel=1e-8)  # 15 nm / 11 m: pyproj's own accuracy
        assert n == pytest.approx(parallel, rel=1e-8)  # 15 nm / 11 m: pyproj's own accuracy


def test_euler_radius_is_m_north_and_n_east_and_between_them():
    a, b = GEOD.a, GEOD.b
    # WGS84's published values: M = b^2 / a and N = a at the equator, a^2 / b at the poles.
    assert geo.radius_of_curvature(0.0, 0.0) == pytest.approx(b * b / a, rel=1e-14)  # rounding only
    assert geo.radius_of_curvature(0.0, 90.0) == pytest.approx(a, rel=1e-14)  # rounding only
    assert geo.radius_of_curvature(90.0, 37.0) == pytest.approx(a * a / b, rel=1e-14)  # rounding only
    for lat in (10.0, 47.0, -60.0):
        m, n = geo.principal_radii(lat)
        assert geo.radius_of_curvature(lat, 0.0) == pytest.approx(m, rel=1e-15)  # cos^2 = 1 exactly
        assert geo.radius_of_curvature(lat, 90.0) == pytest.approx(n, rel=1e-14)  # cos^2(90 deg) ~ 4e-33
        assert geo.radius_of_curvature(lat, 180.0) == pytest.approx(m, rel=1e-14)  # north and south alike
        radii = geo.radius_of_curvature(lat, np.arange(0.0, 180.0, 5.0))
        assert np.all(np.diff(radii[:19]) > 0)  # rising from north to east
        # Between M and N (up to rounding: at 90 deg the formula's N differs from N by an ulp).
        assert np.all(radii >= m * (1 - 1e-14)) and np.all(radii <= n * (1 + 1e-14))  # an ulp of rounding
        # 45 deg: the harmonic mean of M and N (Euler with cos^2 = sin^2 = 1/2).
        assert geo.radius_of_curvature(lat, 45.0) == pytest.approx(2 * m * n / (m + n), rel=1e-14)  # rounding only
