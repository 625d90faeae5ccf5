"""A hot-spot trial's findings: spots that overlap heat or cool the air together (checked against
the column's own bounds), the order of the model's checks, a spot's depth once the field is made,
and HotSpot as a value (hashable, its pickle state checked)."""

import pytest

import refracta

HotSpot = refracta.HotSpot


def test_overlapping_spots_are_checked_together_against_absolute_zero():
    # -150 K over 140 K air: -10 K on the ground (the trial's n = 0.992, with no error before).
    with pytest.raises(ValueError, match=r"the hot spots make the air -?\d.* K at h = .* must stay in \(0, 10000\] K"):
        refracta.PhysicalAtmosphere(t_ground=140.0, hot_spots=[HotSpot(0.0, 0.0, 10.0, -150.0)])
    # Each -100 K spot alone leaves the air above 0 K everywhere modelled (294.7 K at -1000 m, less
    # twice 100 K below the ground); two on one place reach -105 K there.
    refracta.PhysicalAtmosphere(hot_spots=[HotSpot(0.0, 0.0, 10.0, -100.0)])
    with pytest.raises(ValueError, match="the hot spots make the air"):
        refracta.PhysicalAtmosphere(hot_spots=[HotSpot(0.0, 0.0, 10.0, -100.0)] * 2)
    # Apart (1 km, their 10 m gaussians reach 53 m) they never add: each cools its own patch.
    refracta.PhysicalAtmosphere(hot_spots=[HotSpot(0.0, 0.0, 10.0, -100.0), HotSpot(1000.0, 0.0, 10.0, -100.0)])
    # Thirty 500 K spots add to 15 000 K on the ground: past the air formula's 10 000 K.
    with pytest.raises(ValueError, match=r"must stay in \(0, 10000\] K"):
        refracta.PhysicalAtmosphere(hot_spots=[HotSpot(0.0, 0.0, 10.0, 500.0)] * 30)


def test_humid_air_over_overlapping_spots_counts_their_sum():
    # 300 K air at 100 %: one +40 K spot leaves the warmest air at 340 K (27 kPa of vapour); two on
    # one place make it 380 K, whose 129 kPa of saturated vapour exceeds the air's 101 kPa.
    refracta.PhysicalAtmosphere(t_ground=300.0, humidity=1.0, hot_spots=[HotSpot(0.0, 0.0, 5.0, 40.0)])
    with pytest.raises(ValueError, match=r"warmest 380 K .*the water would boil"):
        refracta.PhysicalAtmosphere(t_ground=300.0, humidity=1.0, hot_spots=[HotSpot(0.0, 0.0, 5.0, 40.0)] * 2)
    puddles = [HotSpot(0.0, 0.0, 5.0, 40.0), HotSpot(5000.0, 0.0, 5.0, 40.0)]  # 5 km apart
    refracta.PhysicalAtmosphere(t_ground=300.0, humidity=1.0, hot_spots=puddles)


def test_surface_depth_is_named_before_the_spots_that_take_it():
    # A spot without a depth takes surface_depth's: the message names the parameter the user gave.
    with pytest.raises(ValueError, match=r"surface_depth must be in \[0.0001, 10000\] m \(got -0.2\)"):
        refracta.PhysicalAtmosphere(surface_depth=-0.2, hot_spots=[HotSpot(0.0, 0.0, 10.0, 5.0)])


def test_a_spot_depth_is_its_own_parameter_once_the_field_is_made():
    # Documented: depth None is surface_depth as the field is made; with_params(surface_depth=...)
    # leaves the spot where it was, and setting both moves both.
    air = refracta.PhysicalAtmosphere(surface_dt=5.0, surface_depth=0.15, hot_spots=[HotSpot(0.0, 0.0, 5.0, 10.0)])
    assert air.params["hot_spot0_depth"] == 0.15
    assert air.with_params(surface_depth=0.3).params["hot_spot0_depth"] == 0.15
    both = air.with_params(surface_depth=0.3, hot_spot0_depth=0.3)
    fresh = refracta.PhysicalAtmosphere(surface_dt=5.0, surface_depth=0.3, hot_spots=[HotSpot(0.0, 0.0, 5.0, 10.0)])
    assert both.params == fresh.params
    assert both.ior([0.0, 0.2, 0.0]) == fresh.ior([0.0, 0.2, 0.0])


def test_hot_spots_are_hashable_values():
    same = {HotSpot(1.0, 2.0, 3.0, 4.0), HotSpot(1.0, 2.0, 3.0, 4.0), HotSpot(1.0, 2.0, 3.0, 4.0, depth=0.2)}
    assert len(same) == 2
    assert hash(HotSpot(1.0, 2.0, 3.0, 4.0, footprint="compact")) != hash(HotSpot(1.0, 2.0, 3.0, 4.0))
    assert {HotSpot(0.0, 0.0, 1.0, 1.0): "spot"}[HotSpot(0.0, 0.0, 1.0, 1.0)] == "spot"


def test_a_pickle_state_of_the_wrong_types_names_the_class():
    spot = HotSpot.__new__(HotSpot)  # as pickle makes it, before __setstate__
    with pytest.raises(ValueError, match=r"HotSpot: bad pickle state \(an item of the wrong type among .*str"):
        spot.__setstate__((1.0, 2.0, 3.0, 4.0, 0.1, "compact"))
