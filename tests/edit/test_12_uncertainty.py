"""EditResult.uncertainty: how far reading the destinations off a picture with a given error moves
the solved parameters (a photo-fitting trial: 'unique' said nothing of it)."""

import numpy as np
import pytest

from refracta import examples
from refracta.edit import PointPair, solve


@pytest.fixture(scope="module")
def edit():
    """README's two-pair edit of the hot road, met to a thousandth of a pixel, and a re-solve."""
    road = examples.hot_road(320, 120)
    bottom = road.camera.pick(road.scene, 178.0, 52.28)
    top = road.camera.pick(road.scene, 178.0, 45.34)

    def run(destinations):
        pairs = [PointPair(destinations[0], bottom), PointPair(destinations[1], top)]
        result = solve(
            road.field, road.camera, pairs, free=["surface_dt", "surface_depth"], stop_height=0.0, pixel_tolerance=1e-3
        )
        assert result.success
        return result, np.array([result.field.params[name] for name in result.free])

    return run, [(178.0, 52.51), (178.0, 45.33)]


def test_the_spread_matches_re_solving_with_moved_destinations(edit):
    run, destinations = edit
    result, solved = run(destinations)
    sigma = result.uncertainty(1.0)
    # Independent: each destination coordinate moved by 0.002 px and the edit solved again; the
    # spread for 1 px of independent error per coordinate is the root sum of squares of the slopes.
    step = 0.002
    slopes = []
    for pair in range(2):
        for axis in range(2):
            moved = [list(d) for d in destinations]
            moved[pair][axis] += step
            slopes.append((run([tuple(d) for d in moved])[1] - solved) / step)
    spread = np.sqrt(np.sum(np.square(slopes), axis=0))
    # Measured 966 vs 860 K and 2.59 vs 2.51 m per pixel: the formula takes the miss's error as
    # isotropic across the path (the re-solve moves it along the image's axes) and the slopes are
    # finite differences of an ill-conditioned edit (condition 74): 25 %.
    np.testing.assert_allclose([sigma["surface_dt"], sigma["surface_depth"]], spread, rtol=0.25)
    half = result.uncertainty(0.5)
    # Linear in the reading error: the covariance scales with its square (1e-12: round-off only).
    assert half["surface_dt"] == pytest.approx(0.5 * sigma["surface_dt"], rel=1e-12)


def test_bad_pixel_sigma_is_refused(edit):
    result, _ = edit[0](edit[1])
    with pytest.raises(ValueError, match="pixel_sigma must be > 0"):
        result.uncertainty(0.0)


def test_a_report_notes_paths_that_run_below_the_ground_unstopped():
    # A photo-fitting trial: a source 30 m under the sea, stop_height None (the default), was met
    # through the sea ('success', inversion base -3.8 m) without a word.
    import refracta

    ship = examples.cold_sea(160, 60)
    air = refracta.CurvedEarth(
        refracta.PhysicalAtmosphere(t_ground=278.15, inversion_dt=10, inversion_base=20, inversion_thickness=10)
    )
    pairs = [PointPair((80.5, 50.0), (10000.0, -30.0, 0.0))]
    result = solve(air, ship.camera, pairs, free=["inversion_dt", "inversion_base"], pixel_tolerance=0.7)
    assert result.success  # met through the sea: the report says where the path went
    assert "note: stop_height is None, so no ground stops the paths: pair 0's dips to -" in result.report()
    grounded = solve(
        air, ship.camera, pairs, free=["inversion_dt", "inversion_base"], pixel_tolerance=0.7, stop_height=0.0
    )
    assert not grounded.success and "note: stop_height" not in grounded.report()
