"""The setting sun through the standard atmosphere over a spherical Earth (issue 10): camera rays
leave the air ~1000 km away, turned into the world frame by their central angle, and see a disc
squashed by refraction -- the same squashing astronomical_refraction computes -- with a blue
upper rim and a red lower one where the air disperses."""

import numpy as np
import pytest

import refracta

EYE = 1.0  # [m] above the sea
LOWER_LIMB = 0.1  # [deg] apparent elevation of the disc's lower limb
AIR = refracta.PhysicalAtmosphere()


def sun_scene(lower_limb=LOWER_LIMB):
    """A 32' sun (0.53 deg) placed so that its lower limb appears at `lower_limb`, over a dark sea."""
    refraction = refracta.astronomical_refraction(AIR, lower_limb, eye_height=EYE) / 60.0
    centre = np.radians(lower_limb - refraction + 0.265)
    scene = refracta.Scene()
    scene.set_sun([np.cos(centre), np.sin(centre), 0.0], (1000.0, 1000.0, 1000.0), angular_diameter=0.53)
    scene.add_ground(0.0, 1e5, material=refracta.shading.Diffuse(0.0))
    return scene, np.degrees(centre)


def expected_upper_limb(true_centre):
    from scipy.optimize import brentq

    true_upper = true_centre + 0.265
    return brentq(
        lambda e: e - refracta.astronomical_refraction(AIR, e, eye_height=EYE) / 60.0 - true_upper,
        LOWER_LIMB,
        LOWER_LIMB + 1.0,
        xtol=1e-9,
    )


def test_the_rendered_disc_is_squashed_as_refraction_says():
    scene, true_centre = sun_scene()
    upper = expected_upper_limb(true_centre)
    assert (upper - LOWER_LIMB) * 60 == pytest.approx(27.2, abs=0.3)  # vs 31.8' across
    # 1' per pixel: the camera's rows span apparent elevations around the disc.
    middle = np.radians(0.5 * (LOWER_LIMB + upper))
    camera = refracta.Camera([0, EYE, 0], [np.cos(middle), EYE + np.sin(middle), 0], vfov=1.0, width=80, height=60)
    image = refracta.render(
        scene, camera, refracta.CurvedEarth(AIR), max_length=1.5e6, transport="path", max_depth=0, progress=False
    )
    lit = image[..., 1] > 0
    rows, columns = np.nonzero(lit.any(axis=1))[0], np.nonzero(lit.any(axis=0))[0]
    elevation = lambda v: np.degrees(np.arcsin(camera.ray(40.0, v)[1][1]))  # noqa: E731
    # Edges to the pixel (one pixel = 1'): the lowest and highest lit rows' centres lie within
    # half a pixel inside the limbs.
    half_pixel = 0.5 / 60.0
    # Half a pixel (comment above); 1e-6 deg for rounding.
    assert elevation(rows.max() + 0.5) == pytest.approx(LOWER_LIMB, abs=half_pixel + 1e-6)
    assert elevation(rows.min() + 0.5) == pytest.approx(upper, abs=half_pixel + 1e-6)  # as above
    assert columns.size == pytest.approx(31.8, abs=1.0)  # the width is not refracted


@pytest.mark.slow
def test_dispersion_colours_the_rims():
    # Spectral rays (each sample bends at its hero wavelength): blue is lifted ~30" more than red,
    # so the top rim is bluer than the disc's middle and the bottom rim redder. 0.1' pixels.
    scene, true_centre = sun_scene()
    upper = expected_upper_limb(true_centre)
    colours = []
    for limb in (upper, LOWER_LIMB):
        look = np.radians(limb)
        camera = refracta.Camera([0, EYE, 0], [np.cos(look), EYE + np.sin(look), 0], vfov=4.0 / 60, width=8, height=40)
        image = refracta.render(
            scene,
            camera,
            refracta.CurvedEarth(AIR),
            max_length=1.5e6,
            transport="path",
            max_depth=0,
            spectral=True,
            spp=32,
            progress=False,
        )
        column = image[:, :, :].mean(axis=1)
        lit = np.nonzero(column.sum(axis=1) > 0.05 * column.sum(axis=1).max())[0]
        edge = lit.min() if limb == upper else lit.max()  # the outermost lit row
        inner = lit.max() if limb == upper else lit.min()  # the disc side of the crop
        colours.append((column[edge], column[inner]))
    (top_edge, top_inner), (bottom_edge, bottom_inner) = colours
    blue_over_red = lambda c: c[2] / max(c[0], 1e-12)  # noqa: E731
    assert blue_over_red(top_edge) > 1.2 * blue_over_red(top_inner)
    assert blue_over_red(bottom_edge) < blue_over_red(bottom_inner) / 1.2


@pytest.mark.slow
def test_the_last_gleam_over_a_warm_sea_is_green():
    # examples.green_flash: the sea 3 K warmer than the air folds the image of the sky at 0.025 deg
    # below the horizontal (true -0.512 deg): the sun sets into that fold, and as its rim reaches
    # it the longer wavelengths go first (each wavelength's air lifts the sun by its own amount,
    # blue-green most; the setting sun's own blue is extinguished by the horizontal air column:
    # the physical sky's sun at the horizon, 0.2 % at 450 nm of 700 nm's). Its last gleam is green.
    from refracta import examples

    def colour(sun_elevation, vfov, look):
        example = examples.green_flash(24, 24, sun_elevation)
        eye = example.camera.position
        camera = refracta.Camera(
            eye, eye + [np.cos(np.radians(look)), np.sin(np.radians(look)), 0.0], vfov=vfov, width=24, height=24
        )
        image = refracta.render(
            example.scene, camera, example.field, max_length=example.max_length, spectral=True, spp=16, progress=False
        )
        lit = image.sum(axis=2) > 0.05 * image.sum(axis=2).max()
        return image[lit].mean(axis=0)

    def green_share(rgb):  # linear sRGB; a near-monochromatic gleam lies outside the gamut (R < 0)
        return rgb[1] / np.abs(rgb).sum()

    disc = colour(-0.65, 0.7, -0.05)
    gleam = colour(-0.776, 0.08, -0.02)
    assert disc[0] > disc[1] > disc[2]  # the setting sun: red (its blue extinguished by ~38 air masses)
    assert green_share(disc) < 0.3
    assert gleam[1] > gleam[0] and gleam[1] > gleam[2]  # its last gleam: green
    assert green_share(gleam) > 0.6
