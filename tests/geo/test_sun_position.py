"""refracta.geo.sun_position and LocalFrame.sun_direction: the sun's true place at a time."""

import datetime

import numpy as np
import pytest

from refracta import geo

UTC = datetime.timezone.utc
# The obliquity of the ecliptic in 2024 (IAU: 23.4392911 deg - 0.0130042 deg per Julian century
# since J2000, T = 0.245): the sun's declination at the June solstice (2024-06-20 20:51 UTC).
OBLIQUITY_2024 = 23.4361


def highest_of_the_day(lat, lon, day):
    """The sun's highest elevation over a day (minute steps) and its azimuth then."""
    start = datetime.datetime(day.year, day.month, day.day, tzinfo=UTC)
    places = [geo.sun_position(lat, lon, start + datetime.timedelta(minutes=m)) for m in range(0, 24 * 60)]
    azimuth, elevation = max(places, key=lambda p: p[1])
    return azimuth, elevation


@pytest.mark.parametrize(("lat", "lon"), [(59.91, 10.75), (40.0, -105.0), (-33.9, 151.2)])
def test_the_solstice_sun_culminates_at_ninety_degrees_less_the_latitude_from_its_declination(lat, lon):
    # At the meridian the sun stands at 90 - |lat - declination|; near the solstice the declination
    # is the obliquity to 1e-3 deg over the day. NOAA's calculation is good to ~0.01 deg and a
    # minute's step misses the culmination by < 0.001 deg: 0.02.
    azimuth, elevation = highest_of_the_day(lat, lon, datetime.date(2024, 6, 20))
    assert elevation == pytest.approx(90.0 - abs(lat - OBLIQUITY_2024), abs=0.02)  # NOAA and the step (above)
    # Due south north of the tropic, due north south of it: within the minute's turn (< 0.5 deg here).
    assert azimuth == pytest.approx(180.0 if lat > OBLIQUITY_2024 else 0.0, abs=0.5) or azimuth > 359.5


def test_the_frames_sun_direction_is_its_sun_position_and_times_say_their_zone():
    frame = geo.LocalFrame(28.1, -15.7)
    when = datetime.datetime(2024, 6, 21, 20, 50, tzinfo=datetime.timezone(datetime.timedelta(hours=1)))
    azimuth, elevation = geo.sun_position(28.1, -15.7, "2024-06-21T19:50:00Z")  # the same instant
    assert (azimuth, elevation) == geo.sun_position(28.1, -15.7, when)
    # RFC 3339 allows a lower-case z (a trial's was refused) and a lower-case t.
    assert geo.sun_position(28.1, -15.7, "2024-06-21t19:50:00z") == (azimuth, elevation)
    np.testing.assert_array_equal(frame.sun_direction(when), frame.direction(azimuth, elevation))
    assert 290.0 < azimuth < 300.0 and 0.0 < elevation < 3.0  # a Canary Islands summer sunset, west-north-west
    for bad, message in (
        ("2024-06-21T19:50:00", "must say its time zone"),
        (datetime.datetime(2024, 6, 21, 19, 50), "must say its time zone"),
        ("midsummer", "ISO 8601"),
        (1718999400, "datetime with its time zone"),
    ):
        with pytest.raises(ValueError, match=message):
            geo.sun_position(28.1, -15.7, bad)
    # East of Greenwich in [0, 360] is the same place: only rounding differs.
    assert geo.sun_position(28.1, 344.3, when) == pytest.approx(geo.sun_position(28.1, -15.7, when), abs=1e-9)
    with pytest.raises(ValueError, match="lat"):
        geo.sun_position(95.0, 0.0, when)
