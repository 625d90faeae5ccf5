"""The sky a camera ray sees over a spherical Earth is where the ray leaves the air, not where
max_length stops it (Caster::continue_to_sky). Found by a physicist's trial: with render()'s default
max_length of 5 km a sun 0.3 deg up rendered 27' low (10 deg up: 4.8'), silently: most of a low
sun's refraction lies beyond the few kilometres a scene spans."""

import math

import numpy as np
import pytest
from scipy import optimize

import refracta

SUN_RADIUS = 16.0 / 60.0  # [deg]
WIDTH, HEIGHT, VFOV = 160, 120, 2.4  # 0.02 deg a pixel
# The disc's lower limb read off the image: the lowest row with light plus its covered fraction,
# within a fifth of a pixel of the true edge (the disc's curvature over two columns and the
# sampling at 8 spp), 0.24'. The defect was 4.8' and 27'.
LIMB_TOLERANCE = 0.2 * VFOV / HEIGHT  # [deg]


def lower_limb(base, sun_elevation, **options):
    """The apparent elevation [deg] of the sun's lower limb rendered through the height-only air
    `base` over a spherical Earth (CurvedEarth) from its ground, and the reference: the elevation
    whose astronomical refraction lifts the true lower limb to it (astronomical_refraction, checked
    against independent refraction integrals in tests/rays/test_astronomical_refraction.py)."""
    air = refracta.CurvedEarth(base)
    true_limb = sun_elevation - SUN_RADIUS
    reference = optimize.brentq(
        lambda e: e - refracta.astronomical_refraction(base, e) / 60.0 - true_limb, 0.0, 80.0, xtol=1e-9
    )
    scene = refracta.Scene()
    s = math.radians(sun_elevation)
    scene.set_sun((math.cos(s), math.sin(s), 0.0), (1.0, 1.0, 1.0), angular_diameter=2 * SUN_RADIUS)
    eye = (0.0, air.flat_height(0.0), 0.0)
    aim = math.radians(reference)
    camera = refracta.Camera(
        eye, (1e3 * math.cos(aim), eye[1] + 1e3 * math.sin(aim), 0.0), vfov=VFOV, width=WIDTH, height=HEIGHT
    )
    image = refracta.render(scene, camera, air, spp=8, progress=False, **options)
    column = image[:, WIDTH // 2 - 1 : WIDTH // 2 + 1, 1].mean(axis=1)
    column = column / column.max()
    rows = np.nonzero(column > 0.01)[0]
    assert rows[-1] < HEIGHT - 1, "the disc reaches the frame's lower edge"
    edge = rows[-1] + column[rows[-1]]  # [pixels from the top]
    focal = (HEIGHT / 2) / math.tan(math.radians(VFOV / 2))
    return reference + math.degrees(math.atan((HEIGHT / 2 - edge) / focal)), reference


@pytest.mark.parametrize("sun_elevation", [0.3, 10.0])
def test_a_sun_over_the_curved_earth_stands_where_refraction_puts_it_at_any_max_length(sun_elevation):
    for max_length in (None, 41e3, 2e6):  # render's default 5 km, the cold sea's, past the air's top
        options = {} if max_length is None else {"max_length": max_length}
        rendered, reference = lower_limb(refracta.PhysicalAtmosphere(), sun_elevation, **options)
        assert rendered == pytest.approx(reference, abs=LIMB_TOLERANCE), max_length


def test_the_sky_near_the_horizon_does_not_depend_on_max_length():
    # A sunset over a sea plane from 2 m: rays just above the horizon graze the water ~5 km out, so
    # at 5 km some are still sinking (traced on until they rise out of the air) and some sink into
    # the sea beyond (their ends unchanged). With max_length 5 km such a ray saw the sun's disc
    # 0.6 deg below where it stands. Every row as with 2000 km, to the paths' tolerance: the sky
    # seen along exits that differ by the trace's tol (1e-6 of the path) changes by far less than
    # 1e-3 of itself.
    air = refracta.CurvedEarth(refracta.PhysicalAtmosphere())
    scene = refracta.Scene()
    scene.add_ground(material=refracta.shading.Diffuse(0.05))
    s = math.radians(0.2)
    scene.set_physical_sky((math.cos(s), math.sin(s), 0.0))
    eye = (0.0, air.flat_height(2.0), 0.0)
    camera = refracta.Camera(eye, (1e3, eye[1], 0.0), vfov=1.5, width=16, height=96)
    near, far = (refracta.render(scene, camera, air, spp=1, progress=False, max_length=m) for m in (5e3, 2e6))
    rows = np.abs(near - far).mean(axis=(1, 2)) / far.mean(axis=(1, 2))
    assert rows.max() < 1e-3  # exits a trace's tol apart see skies far closer than 1e-3 (above); measured 3e-4
