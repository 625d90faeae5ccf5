"""Bad input a second new-user trial (4 December) found accepted silently (integer wraparound, float
indices truncated, a curved Earth flattened twice) or refused with a misleading message: each now
raises ValueError naming the argument and its value."""

import numpy as np
import pytest

import refracta
from refracta import examples, shading


def sky_scene():
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    return scene


@pytest.mark.parametrize(
    "make, message",
    [
        # 2**32 + 16 cells wrapped to a 16^3 grid in the int the grid is indexed by.
        (
            lambda: refracta.Turbulence(1e-10, cells=2**32 + 16, spacing=0.1),
            r"cells must be a whole number in \[8, 65536\] \(got 4294967312\)",
        ),
        (
            lambda: refracta.Turbulence(1e-10, size=1e9, spacing=0.1),
            r"size / spacing must be at most 65536 cells \(got size=1000000000, spacing=0.1\)",
        ),
        # The byte count printed through an int64_t wrapped negative.
        (
            lambda: refracta.render(
                sky_scene(), refracta.Camera((0, 1, 0), (1, 1, 0), width=10**9, height=10**9), None
            ),
            r"needs at least 24000000000000000000 bytes \(24000000000 GB\)",
        ),
        # Float indices were truncated: 1.7 made vertex 1.
        (
            lambda: refracta.Scene().add_mesh(np.eye(3), np.array([[0.0, 1.7, 2.0]])),
            r"triangles must hold whole vertex indices \(got 1.7\)",
        ),
        (lambda: examples.sun_direction(float("nan"), 0.0), r"elevation must be in \[-90, 90\] deg \(got nan\)"),
        (lambda: examples.sun_direction(100.0, 0.0), r"elevation must be in \[-90, 90\] deg \(got 100"),
        (lambda: examples.sun_direction(10.0, float("inf")), r"azimuth must be finite \(got inf\)"),
        # The Earth's curvature applied twice.
        (
            lambda: refracta.CurvedEarth(refracta.CurvedEarth(refracta.PhysicalAtmosphere())),
            r"CurvedEarth: the base field is already over a curved Earth",
        ),
        # The refusal named an OceanWaves the caller never made.
        (
            lambda: refracta.Scene().add_sea(material=shading.Water(wind_speed=0.0)),
            r"add_sea: the Water material's wind_speed is 0 m/s: calm water has no waves",
        ),
        # A thin lens cannot focus nearer than its focal length.
        (
            lambda: refracta.Camera.photographic((0, 1, 0), (1, 1, 0), 50.0, f_number=2.0, focus_distance=0.02),
            r"focus_distance must exceed the focal length \(0.05 m\) \(got 0.02\)",
        ),
        # RenderOptions.march is parsed as a trace method; its error said 'trace'.
        (lambda: setattr(refracta.RenderOptions(), "march", "foo"), r"^march must be"),
    ],
)
def test_refused_with_a_message_naming_the_argument(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_whole_float_indices_still_make_a_mesh():
    # np.array([[0.0, 1.0, 2.0]]) is a triangle: only fractional indices are refused.
    scene = refracta.Scene()
    assert scene.add_mesh(np.eye(3), np.array([[0.0, 1.0, 2.0]])) == 0
    assert scene.add_mesh(np.eye(3), [[0, 1, 2]]) == 1
    assert scene.geometry_count == 2
