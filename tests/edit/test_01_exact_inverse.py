"""The editing oracle of ORACLES.md: for n^2 = n0^2 + alpha y one pair fixes alpha in closed form,
alpha = 4 n(y0)^2 (h - y0 - t0 D) / (D^2 (1 + t0^2))."""

import pytest

import refracta
from refracta.edit import PointPair, solve

# The solved alpha is exact up to the trace error (tol 1e-11 m on a 1.5 m rise -> ~1e-11
# relative) and the solvers' stopping tolerances; 1e-8 is the issue's bound.
ALPHA_REL = 1e-8


def exact_alpha(n0, y0, t0, D, h):
    # n(y0)^2 = n0^2 + alpha y0 depends on alpha itself: solve the linear equation for alpha.
    k = 4.0 * (h - y0 - t0 * D) / (D**2 * (1.0 + t0**2))
    return k * n0**2 / (1.0 - k * y0)


@pytest.mark.parametrize("backend", ["ceres", "nlopt:LN_BOBYQA", "nlopt:LD_LBFGS"])
@pytest.mark.parametrize("t0, h", [(0.0, 3.0), (0.001, 1.0), (-0.002, 0.2)])
def test_one_pair_gives_the_closed_form_alpha(backend, t0, h):
    n0, y0, D = 1.000277, 1.5, 1000.0
    pair = PointPair(destination=(1.0, y0 + t0, 0.0), source=(D, h, 0.0))
    result = solve(
        refracta.LinearSquaredProfile(n0=n0), (0.0, y0, 0.0), [pair], free=["alpha"], backend=backend, tol=1e-11
    )
    expected = exact_alpha(n0, y0, t0, D, h)
    assert result.success, result.message
    assert abs(result.field.params["alpha"] - expected) < ALPHA_REL * abs(expected)
    assert result.distances[0] < 1e-8  # solved with tol=1e-11: the pair is met to 1e-8 m


def test_the_oracle_example_value():
    """ORACLES.md: n0 = 1.000277, y0 = 1.5 m, D = 1000 m, t0 = 0, h = 3.0 m -> alpha = 6.0033e-6."""
    result = solve(
        refracta.LinearSquaredProfile(),
        (0.0, 1.5, 0.0),
        [PointPair((1.0, 1.5, 0.0), (1000.0, 3.0, 0.0))],
        free="alpha",
        tol=1e-11,
    )
    assert result.field.params["alpha"] == pytest.approx(6.0033e-6, abs=1e-10)  # quoted to 5 digits
