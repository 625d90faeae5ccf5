"""What a geodesist's trial at the edges (below sea level, 30 km up, the poles, 450 km sight
lines, lab-scale mirages) found: unit slips accepted, and readouts that traced every bisection
ray to max_length."""

import numpy as np
import pytest

import refracta
from refracta import geo


@pytest.mark.parametrize(
    "slip",
    [
        lambda: refracta.CurvedEarth(refracta.PhysicalAtmosphere(), 6371.0),
        lambda: geo.LocalFrame(45.0, 7.0, earth_radius=6371.0),
        lambda: refracta.refraction_coefficient(refracta.PhysicalAtmosphere(), 2.0, 1000.0, earth_radius=6371.0),
    ],
)
def test_an_earth_radius_in_km_is_refused(slip):
    # A 6.4 km Earth gave k = -0.0105 (0.170 for the real one) and put a 100 m hill at 99.22 m.
    with pytest.raises(ValueError, match=r"at least 100000 m \(in metres"):
        slip()


@pytest.mark.parametrize(
    "slip",
    [
        lambda: refracta.TemperatureProfile([0.0, 10.0, 100.0], [15.0, 14.9, 14.3]),
        lambda: refracta.PhysicalAtmosphere(t_ground=15.0, lapse_rate=0.0),
    ],
)
def test_temperatures_in_celsius_are_refused(slip):
    # A 15 "K" sounding gave n - 1 = 5.3e-3, 19 times the real 2.78e-4, without a word; t_ground=15
    # was refused only with lapse_rate > 0, as air below 0 K 2.5 km up.
    with pytest.raises(ValueError, match="in kelvin"):
        slip()


def test_hidden_heights_do_not_depend_on_how_far_the_bisection_traces():
    # The bisection's rays end where they rise above the air's top (86 km, reached ~1000 km out):
    # at max_length 2000 km they do, at 200 km they never get there and run to max_length as
    # before. Both must find the same grazing ray (no ray that misses the ground within 20 km of a
    # 30 m eye comes back down in standard air), so the same hidden heights at 20 and 60 km.
    earth = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), 6371000.0)
    scene = refracta.Scene()
    scene.add_ground(0.0, 4e5)
    scene.set_sky((0.5, 0.6, 0.8))
    for x in (20000.0, 60000.0):
        scene.add_box((x, 50.0, 0.0), (10.0, 100.0, 400.0))
    camera = refracta.Camera((0.0, 30.0, 0.0), (1.0, 30.0, 0.0), vfov=0.5, width=16, height=8)
    short, long = (
        refracta.render(scene, camera, earth, max_length=length, aovs=["hidden_height"], progress=False)[1]
        for length in (2e5, 2e6)
    )
    # The same rays to the boxes (within max_length either way): the same readouts.
    np.testing.assert_array_equal(np.isnan(short["hidden_height"]), np.isnan(long["hidden_height"]))
    assert np.isfinite(short["hidden_height"]).any()
    # The same grazing ray: equal to round-off (assert_allclose's default 1e-7 relative).
    np.testing.assert_allclose(short["hidden_height"], long["hidden_height"], equal_nan=True)
