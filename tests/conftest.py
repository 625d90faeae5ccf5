"""Shared fixtures and tolerances of the refracta test suite."""

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")  # plots render off-screen in tests

import refracta


@pytest.fixture
def hot_road():
    """A hot road: 10 K warmer air at the surface, e-folding over 0.1 m (ORACLES.md typical layer)."""
    return refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
