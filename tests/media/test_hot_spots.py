"""Areal hot spots (refracta.HotSpot): footprints, parameters, the height-only part outside their
regions, gradients, and the first-order sideways deflection of a level ray (issue 10)."""

import pickle

import numpy as np
import pytest

import refracta

# Central differences with step 1e-4 m of fields whose gradients vary on >= 0.1 m: truncation
# ~(1e-4 / 0.1)^2 = 1e-6 relative, round-off 1e-16 / 1e-4 = 1e-12 absolute.
GRADIENT_RELATIVE = 1e-5
GRADIENT_ABSOLUTE = 1e-11  # round-off 1e-16 / 1e-4 = 1e-12 (comment above), with 10x margin
# The column table under a spot against the exact column (column_table.h), for the 10 K, 0.1 m road layer:
TABLE_N = 1e-15  # its ~1e-16 in n: a few ulps of n ~ 1.0003 (2.2e-16 each)
TABLE_GRADIENT = 1e-12  # its ~4e-13 1/m in dn/dh, with 2.5x margin


def road(*spots, **params):
    return refracta.PhysicalAtmosphere(
        surface_dt=params.pop("surface_dt", 10.0), surface_depth=0.1, hot_spots=list(spots), **params
    )


def test_spot_parameters_are_named_and_read_back():
    field = road(
        refracta.HotSpot(100.0, -3.0, 8.0, 15.0, footprint="compact"), refracta.HotSpot(40.0, 5.0, 2.0, -4.0, depth=0.3)
    )
    names = field.param_names
    assert names[-10:] == [f"hot_spot{i}_{k}" for i in (0, 1) for k in ("x", "z", "radius", "dt", "depth")]
    assert field.params["hot_spot1_depth"] == 0.3
    assert field.params["hot_spot0_depth"] == 0.1  # None: the atmosphere's surface_depth
    moved = field.with_params(hot_spot0_x=120.0, hot_spot0_radius=4.0)
    spot = moved.hot_spots[0]
    assert (spot.x, spot.z, spot.radius, spot.dt, spot.footprint) == (120.0, -3.0, 4.0, 15.0, "compact")
    assert pickle.loads(pickle.dumps(moved)).params == moved.params
    assert pickle.loads(pickle.dumps(moved)).hot_spots == moved.hot_spots
    assert not field.height_only
    assert refracta.PhysicalAtmosphere(surface_dt=10.0).height_only


@pytest.mark.parametrize("model", [refracta.PhysicalAtmosphere, refracta.LogisticProfile])
def test_a_spot_search_box_follows_the_spot_however_the_field_was_made(model):
    # The bounds are centred on the spot (moves of 20 radii, radii 20-fold, dt down to a cold
    # spot's): a field from with_params has the bounds of one made with those values.
    made = model(hot_spots=[refracta.HotSpot(60.0, 5.0, 2.0, -0.5, footprint="compact")])
    moved = model(hot_spots=[refracta.HotSpot(30.0, 0.0, 10.0, 1.0, footprint="compact")]).with_params(
        hot_spot0_x=60.0, hot_spot0_z=5.0, hot_spot0_radius=2.0, hot_spot0_dt=-0.5
    )
    assert moved.params == made.params
    assert moved.bounds == made.bounds
    assert moved.bounds["hot_spot0_radius"] == (0.1, 40.0) and moved.bounds["hot_spot0_dt"][0] <= -0.5
    assert pickle.loads(pickle.dumps(moved)).bounds == made.bounds


def test_temperature_excess_follows_the_footprint():
    # n depends on T alone at one height: n(T_column + dt e^(-h/d) F(r)) against the spot-free
    # air at that temperature (a spot-free field whose surface layer carries the same excess).
    spot = refracta.HotSpot(0.0, 0.0, 5.0, 6.0, depth=0.2)
    field = road(spot, surface_dt=0.0)
    h = 0.1
    for r in (0.0, 2.0, 5.0, 9.0):
        F = np.exp(-(r**2) / (2 * 25.0))
        # Same excess at this height from a surface layer: dt_s e^(-h/0.2) = 6 F e^(-h/0.2).
        layered = refracta.PhysicalAtmosphere(surface_dt=6.0 * F, surface_depth=0.2)
        # The layer also lowers its column's pressure at h (by ~2e-7: hydrostatic), the spot does
        # not (the pressure stays the column's); n - 1 is proportional to P up to Edlen's
        # compressibility term (6e-3 of it: 1e-9 of n - 1, 3e-13 in n).
        pressure_ratio = field.pressure(h) / layered.pressure(h)
        expected = 1.0 + (layered.ior([0.0, h, 0.0]) - 1.0) * pressure_ratio
        # Edlen's compressibility term: 3e-13 in n (comment above).
        assert field.ior([r, h, 0.0]) == pytest.approx(expected, abs=1e-12)


def test_compact_spot_is_exactly_the_height_only_air_outside_its_radius():
    field = road(refracta.HotSpot(50.0, 0.0, 6.0, 20.0, footprint="compact"))
    part = field.height_only_part
    assert part.height_only and part.params == {k: v for k, v in field.params.items() if not k.startswith("hot_spot")}
    outside = np.array([[56.0001, 0.05, 0.0], [50.0, 0.02, -6.5], [80.0, 1.0, 3.0]])
    np.testing.assert_array_equal(field.ior(outside), part.ior(outside))
    np.testing.assert_array_equal(field.grad_ior(outside), part.grad_ior(outside))
    inside = np.array([[50.0, 0.05, 0.0], [53.0, 0.05, 2.0]])
    assert np.all(field.ior(inside) < part.ior(inside))  # hotter: lower index


def test_the_column_table_under_a_spot_is_the_column():
    """Where a spot heats the air the column's pressure and temperature come from a table
    (media/column_table.h); a gaussian spot 37 radii away adds ~1e-300 K, so the field there is the
    column's through the table and its height-only part is the column evaluated exactly. The
    table's error (cubic Hermite at a 128th of the 0.1 m layer, 10 K): ~1e-10 K in T, ~1e-16 in n;
    its slope ~4e-9 of the layer's 100 K/m, ~4e-13 1/m in dn/dh."""
    field = road(refracta.HotSpot(0.0, 0.0, 1.0, 10.0))
    exact = field.height_only_part
    h = np.concatenate([np.linspace(-0.1, 1.5, 801), [0.0, 1e-6, 0.0123456]])
    points = np.stack([np.full_like(h, 37.0), h, np.zeros_like(h)], axis=1)
    tabulated, column = field.ior(points), exact.ior(points)
    assert np.any(tabulated != column)  # the table is in use (its rounding differs from the column's)
    np.testing.assert_allclose(tabulated, column, rtol=0, atol=TABLE_N)
    np.testing.assert_allclose(field.grad_ior(points), exact.grad_ior(points), rtol=0, atol=TABLE_GRADIENT)


def test_regions_bound_where_the_field_differs_from_its_height_only_part():
    spot = refracta.HotSpot(0.0, 0.0, 3.0, 10.0, depth=0.1)
    field = road(spot)
    (region,) = field.local_regions
    # Default rel 1e-6: the same closed forms in C++ and here, rounding only.
    assert region["radius"] == pytest.approx(spot.reach) and spot.reach == pytest.approx(3.0 * np.sqrt(2 * np.log(1e6)))
    assert region["top"] == pytest.approx(0.1 * np.log(1e6))  # default rel 1e-6: as above
    # At the region's border the spot's temperature excess is 1e-6 of its peak; its change of n
    # too, up to n's sensitivity to T there against at the peak (~ (n - 1) / T^2: a 10 K step from
    # 298 K under the spot's peak on the 10 K road vs 288 K at the top, 298 * 308 / 288^2 = 1.11).
    peak = field.height_only_part.ior([0, 0, 0]) - field.ior([0, 0, 0])
    for p in ([region["radius"], 0.0, 0.0], [0.0, region["top"], 0.0]):
        change = field.height_only_part.ior(p) - field.ior(p)
        assert 0 < change <= 1.12e-6 * peak


@pytest.mark.parametrize("footprint", ["gaussian", "compact"])
@pytest.mark.parametrize("model", ["physical", "logistic"])
def test_gradient_matches_central_differences(footprint, model):
    if model == "physical":
        field = road(
            refracta.HotSpot(1.0, -0.5, 2.0, 12.0, depth=0.15, footprint=footprint),
            refracta.HotSpot(-1.0, 1.0, 1.5, -5.0, footprint=footprint),
        )
    else:
        field = refracta.LogisticProfile(hot_spots=[refracta.HotSpot(1.0, -0.5, 2.0, 0.8, footprint=footprint)])
    rng = np.random.default_rng(4)
    step = 1e-4
    for p in rng.uniform([-2.5, -0.2, -2.5], [2.5, 0.6, 2.5], (20, 3)):
        fd = [(field.ior(p + step * e) - field.ior(p - step * e)) / (2 * step) for e in np.eye(3)]
        np.testing.assert_allclose(field.grad_ior(p), fd, rtol=GRADIENT_RELATIVE, atol=GRADIENT_ABSOLUTE)


def test_logistic_spot_localises_the_hot_term():
    plain = refracta.LogisticProfile()
    spotted = refracta.LogisticProfile(hot_spots=[refracta.HotSpot(0.0, 0.0, 1.0, 1.0, footprint="compact")])
    h = np.linspace(-2.0, 5.0, 15)
    centre = np.stack([np.zeros_like(h), h, np.zeros_like(h)], axis=1)
    # Strength 1 at the centre (F = 1): the profile's own hot term.
    np.testing.assert_allclose(spotted.ior(centre), plain.ior(centre), rtol=0, atol=1e-15)
    # Outside the spot the hot term is at its far value n_hot: the hot layer is gone.
    far = centre + [5.0, 0.0, 0.0]
    no_layer = spotted.height_only_part
    np.testing.assert_array_equal(spotted.ior(far), no_layer.ior(far))
    k = plain.params
    w = 0.3 * k["a_hot"]
    scale = 0.003 * k["k_s"] / (abs(k["n_bg"]) + abs(k["n_inv"]) + abs(k["n_hot"]))
    hot_deficit = scale * k["n_hot"] / (1 + np.exp(h / w))  # n_hot sigma(-h/w)
    # n ~ 1.03: the difference of two n carries 2e-16 absolute round-off.
    np.testing.assert_allclose(no_layer.ior(centre) - plain.ior(centre), hot_deficit, rtol=1e-9, atol=5e-16)


# First order in the spot's change of n (Born): a straight path, so the deflection is the integral
# of grad_z n / n; the neglected terms are the path's own bending (~1e-5 rad over 60 m moves it
# 0.3 mm of 10 m: 3e-5) and n - 1's nonlinearity in T (dt / T = 0.3 % for 1 K).
DEFLECTION_FIRST_ORDER = 0.01


@pytest.mark.parametrize("offset", [0.0, 3.0, 10.0, 16.0])
def test_level_ray_turns_away_from_a_gaussian_spot(offset):
    # theta(b) = (delta / n) sqrt(2 pi) (b / rho) e^(-b^2 / 2 rho^2), delta = (n - 1) dt e^(-h/depth) / T
    # (issue 10). A deep layer (depth 2 m) keeps the ray's height, and so delta, constant.
    rho, dt, depth, h, T = 10.0, 1.0, 2.0, 1.0, 288.15 - 0.0065 * 1.0
    spot = refracta.HotSpot(100.0, 0.0, rho, dt, depth=depth)
    field = refracta.PhysicalAtmosphere(hot_spots=[spot])
    start = np.array([0.0, h, offset])
    path = refracta.trace_ray(field, start, [1.0, 0.0, 0.0], tol=1e-12, max_length=200.0)
    direction = path.directions[-1] / np.linalg.norm(path.directions[-1])
    sideways = np.arctan2(direction[2], direction[0])
    n = field.height_only_part.ior(start)
    delta = (n - 1) * dt * np.exp(-h / depth) / T
    expected = delta / n * np.sqrt(2 * np.pi) * offset / rho * np.exp(-(offset**2) / (2 * rho**2))
    if offset == 0.0:
        assert abs(sideways) < 1e-15  # through the centre: stays in its vertical plane
        assert np.max(np.abs(path.points[:, 2])) < 1e-12
    else:
        assert sideways > 0  # away from the centre
        assert sideways == pytest.approx(expected, rel=DEFLECTION_FIRST_ORDER)


@pytest.mark.parametrize(
    "bad, match",
    [
        (dict(radius=0.0), "radius must be >= 0.001"),
        (dict(radius=-1.0), "radius must be >= 0.001"),
        (dict(radius=1e-300), "radius must be >= 0.001"),  # 1 / radius^2 overflowed: every ior NaN
        (dict(depth=0.0), r"depth must be in \[0.0001, 10000\]"),
        (dict(depth=-0.1), r"depth must be in \[0.0001, 10000\]"),
        (dict(depth=1e300), r"depth must be in \[0.0001, 10000\]"),
        (dict(x=float("nan")), "x must be finite"),
        (dict(z=float("inf")), "z must be finite"),
        (dict(dt=float("nan")), "dt must be finite"),
        (dict(footprint="square"), "footprint must be 'gaussian' or 'compact'"),
    ],
)
def test_bad_hot_spots_are_refused(bad, match):
    args = dict(x=0.0, z=0.0, radius=1.0, dt=5.0)
    args.update(bad)
    with pytest.raises(ValueError, match=match):
        refracta.HotSpot(**args)


def test_bad_spot_parameters_and_arguments_are_refused():
    field = road(refracta.HotSpot(0.0, 0.0, 1.0, 5.0))
    with pytest.raises(ValueError, match="hot_spot0_radius must be >= 0.001"):
        field.with_params(hot_spot0_radius=0.0)
    with pytest.raises(ValueError, match=r"hot_spot0_depth must be in \[0.0001, 10000\]"):
        field.with_params(hot_spot0_depth=-1.0)
    with pytest.raises(ValueError, match="hot_spots must be a HotSpot or a list"):
        refracta.PhysicalAtmosphere(hot_spots=3)
    with pytest.raises(ValueError, match=r"hot_spots\[1\] must be a refracta.HotSpot"):
        refracta.PhysicalAtmosphere(hot_spots=[refracta.HotSpot(0, 0, 1, 1), (0, 0, 1, 1)])
    with pytest.raises(ValueError, match="leave depth None"):
        refracta.LogisticProfile(hot_spots=[refracta.HotSpot(0, 0, 1, 1, depth=0.2)])
    with pytest.raises(ValueError, match="takes no hot_spots"):
        refracta.LinearSquaredProfile(hot_spots=[refracta.HotSpot(0, 0, 1, 1)])


@pytest.mark.parametrize(
    "make, match",
    [
        # n - 1 was -7e-7 (n < 1) at 1e6 K: Edlen's density factor turns negative above ~1e5 K.
        (
            lambda: refracta.PhysicalAtmosphere(surface_dt=1e6),
            r"temperature is 2000294.6\d* K .* must stay in \(0, 10000\] K",
        ),
        (lambda: refracta.PhysicalAtmosphere(t_ground=-400.0), r"t_ground must be in \[100, 10000\] K, in kelvin"),
        (
            lambda: refracta.PhysicalAtmosphere(hot_spots=[refracta.HotSpot(10, 0, 5, 1e6)]),
            r"hot_spot0_dt must be in \[-150, 500\] K",
        ),
        (
            lambda: refracta.PhysicalAtmosphere(hot_spots=[refracta.HotSpot(10, 0, 5, -600.0)]),
            "hot_spot0_dt must be in",
        ),
    ],
)
def test_air_too_hot_or_cold_for_the_index_formula_is_refused(make, match):
    with pytest.raises(ValueError, match=match):
        make()


# rk45 at its default tolerance against rk4 in 0.1 m steps (error ~ step^4: far below either's
# figure here): they agreed to 3e-8 of the spot's deflection and 4e-9 m in position when measured.
ADAPTIVE_AGAINST_FIXED = 1e-6
# A pair's miss on the fixed-step path, whose node nearest x = 2000 m is its source: the default
# tol (1e-6 m) of both traces, with margin; the spot itself moves the path by 2.6-23 cm there.
PAIR_ON_ITS_PATH = 1e-6


@pytest.mark.parametrize("footprint", ["gaussian", "compact"])
@pytest.mark.parametrize("spot_x", [300.0, 1000.0])
def test_adaptive_steps_do_not_step_over_a_spot_far_along_a_calm_path(footprint, spot_x):
    # In the calm air before it rk45 grows its steps to tens or hundreds of metres and once
    # stepped over a 10 m spot whole: the spot changed no traced path and editing its dt had no
    # gradient (a trial), though the renderer drew it.
    spot = refracta.HotSpot(spot_x, 0.0, 10.0, 20.0, depth=2.0, footprint=footprint)
    field = refracta.PhysicalAtmosphere(hot_spots=[spot])
    start = [0.0, 1.0, 3.0]
    adaptive = refracta.trace_ray(field, start, [1.0, 0.0, 0.0], max_length=3000.0)
    fixed = refracta.trace_ray(field, start, [1.0, 0.0, 0.0], max_length=3000.0, trace="rk4", step=0.1)

    def sideways(path):
        return np.arctan2(path.directions[-1][2], path.directions[-1][0])

    assert sideways(fixed) > 5e-6  # the spot turns the ray away from its centre by ~1e-5 rad
    assert sideways(adaptive) == pytest.approx(sideways(fixed), rel=ADAPTIVE_AGAINST_FIXED)

    source = fixed.points[np.argmin(np.abs(fixed.points[:, 0] - 2000.0))]
    pair = refracta.edit.PointPair(destination=(2000.0, 1.0, 3.0), source=tuple(source))
    assert refracta.edit.distances(field, start, [pair])[0] < PAIR_ON_ITS_PATH
    assert refracta.edit.distances(field.height_only_part, start, [pair])[0] > 0.02  # the spot's own effect
    _, jacobian, _ = refracta.edit.jacobian(field, start, [pair], free=["hot_spot0_dt"])
    assert np.abs(jacobian).max() > 1e-4  # m per K: the spot's dt moves the path
