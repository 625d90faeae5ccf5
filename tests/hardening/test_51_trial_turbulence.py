"""Defects found by a turbulence trial of 7 December (the physics ones in
tests/media/test_turbulence_layers.py): the public spectrum took a negative C_n^2, NaN and negative
scales; a two-number option given one number named its count; separations_within('a') raised
numpy's TypeError; a layer took a grid that was not its settings'; D_n(0) came out -3e-26."""

import numpy as np
import pytest

import refracta
from refracta import _core
from refracta import turbulence as tb


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: tb.von_karman_spectrum(1.0, cn2=-1.0), r"cn2 must be finite and >= 0 \(got -1\)"),
        (lambda: tb.von_karman_spectrum(np.array([1.0, np.nan])), r"kappa must be finite and >= 0 \(got nan\)"),
        (lambda: tb.von_karman_spectrum(1.0, inner_scale=-1.0), r"inner_scale must be finite and >= 0 m"),
        (lambda: tb.von_karman_spectrum(1.0, outer_scale=0.0), r"outer_scale must be > 0 m"),
        (lambda: refracta.Turbulence(wind=5), r"wind must be two numbers \(x, z\) \(got 5\)"),
        (lambda: refracta.Turbulence(wind=(1, 2, 3)), r"wind must be two numbers \(x, z\) \(got 3 numbers: 1, 2, 3\)"),
        (lambda: refracta.Turbulence(cells=16).separations_within("a"), r"tolerance must be > 0 and finite"),
        (
            lambda: _core.TurbulenceLayer.of(
                refracta.Turbulence(cells=32).settings, refracta.Turbulence(cells=16).grid, 0
            ),
            r"the grid \(16\^3 cells of 0.05 m\) is not the settings' \(32\^3 of 0.05 m\)",
        ),
    ],
)
def test_bad_turbulence_inputs_are_named(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def test_the_spectrum_of_good_numbers_is_unchanged():
    # 5 / (18 pi Gamma(1/3)) kappa^(-11/3) at kappa = 1 and 2 (Kolmogorov, no scales).
    np.testing.assert_allclose(
        tb.von_karman_spectrum(np.array([1.0, 2.0])), 0.0330054 * np.array([1.0, 2.0 ** (-11 / 3)]), rtol=1e-6
    )  # tolerance: the constant's printed digits


def test_the_structure_function_is_a_variance_at_zero():
    assert refracta.Turbulence(cells=16).structure_function(0.0)[0] == 0.0
