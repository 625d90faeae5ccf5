"""Regression tests for what the property suites (test_12, test_13) found, pinned as plain
examples so they hold whatever examples Hypothesis draws."""

import numpy as np
import pytest

import refracta
from refracta import moments


@pytest.mark.parametrize("method", ["rk45", "stratified"])
def test_a_tolerance_below_position_round_off_is_refused(method):
    # rk45 with tol 1e-300 divided by an underflowed allowance: NaN states, reported as
    # "height -nan m is outside the modelled range"; stratified split 1 m into 10 million nodes.
    field = refracta.PhysicalAtmosphere()
    with pytest.raises(ValueError, match=rf"{method}: tol must be at least 1e-15 x max_length = 1e-12 m"):
        refracta.trace_ray(field, [0, 1, 0], [1, 0.1, 0], trace=method, tol=1e-300, max_length=1000.0)
    path = refracta.trace_ray(field, [0, 1, 0], [1, 0.1, 0], trace=method, tol=1e-12, max_length=1000.0)
    assert np.isfinite(path.points).all()


def test_moments_far_outside_the_unit_range_are_refused():
    # fp32 storage of b2 = 1e300 overflowed and the Hamburger 4MSM shadow came out NaN.
    with pytest.raises(ValueError, match=r"moments must lie in \[-1.5, 1.5\]"):
        moments.shadow_intensity([0.0, 1e300, 0.0, 0.0], 1.0, storage="fp32")
    with pytest.raises(ValueError, match="overflow"):
        moments.power_moments([0.0, 1e300])
    with pytest.raises(ValueError, match="finite"):
        moments.power_moments([0.0, np.inf])


def test_a_texture_header_claiming_more_than_memory_is_refused_before_reading(tmp_path):
    # A 99999999 x 99999999 PFM header (and 48 bytes of data) was std::bad_alloc (MemoryError).
    path = tmp_path / "huge.pfm"
    path.write_bytes(b"PF\n99999999 99999999\n-1.0\n" + bytes(48))
    with pytest.raises(refracta.IoError, match="needs at least"):
        refracta.Scene().add_ground(texture=str(path))
