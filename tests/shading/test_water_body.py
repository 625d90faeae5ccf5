"""The water body's optics (water.h) and how the Water material uses them: pure-water absorption at
Pope & Fry's tabulated values, Morel's backscattering law, the irradiance reflectance R = 0.33 b_b /
(a + b_b), the body term's closed form per wavelength, the index per wavelength and per RGB channel,
the Beckmann distribution's normalisation and slope variance; scene files; bad input."""

import pickle

import numpy as np
import pytest

import refracta
from refracta import shading

from .conftest import direction

EXACT = 1e-12  # table nodes and closed forms evaluated the same way in C++ and here
# The material's index and internal-reflectance tables are linear between 1 nm nodes: the index's
# second derivative (~1e-7 per nm^2 in the visible) bounds the error by ~1e-8.
TABLE_TOLERANCE = 1e-7
# Pope & Fry 1997, Table 3 (and Smith & Baker 1981 at 360 nm) [1/m].
POPE_FRY = {
    360.0: 0.0379,
    380.0: 0.01137,
    400.0: 0.00663,
    440.0: 0.00635,
    500.0: 0.0204,
    550.0: 0.0565,
    600.0: 0.2224,
    650.0: 0.340,
    700.0: 0.624,
    725.0: 1.489,
}
INTEGER_NM = np.array([450.0, 500.0, 550.0, 600.0])  # the 1 nm tables are exact at integer wavelengths
SIGMAS = 5.0


def test_01_absorption_is_pope_and_fry():
    for wavelength, a in POPE_FRY.items():
        assert shading.water_absorption(wavelength) == pytest.approx(a, rel=EXACT)
    # linear between 5 nm nodes
    assert shading.water_absorption(442.5) == pytest.approx(0.5 * (0.00635 + 0.00751), rel=EXACT)


def test_02_backscattering_follows_morel():
    # Morel 1974: b_w(500) = 0.00222 1/m for pure water, half backward; lambda^-4.32; sea water +30 %.
    assert shading.water_backscattering(500.0) == pytest.approx(0.00111, rel=EXACT)
    assert shading.water_backscattering(400.0) / shading.water_backscattering(500.0) == pytest.approx(
        0.8**-4.32, rel=EXACT
    )
    assert shading.water_backscattering(500.0, 37.0) == pytest.approx(1.3 * 0.00111, rel=EXACT)


def test_03_body_reflectance_and_the_colour_of_the_sea():
    wavelengths = np.arange(360.0, 831.0, 10.0)
    a = shading.water_absorption(wavelengths)
    bb = shading.water_backscattering(wavelengths, 35.0)
    np.testing.assert_allclose(shading.water_body_reflectance(wavelengths, 35.0), 0.33 * bb / (a + bb), rtol=EXACT)
    r = shading.water_body_reflectance(np.array([420.0, 550.0, 650.0]), 35.0)
    np.testing.assert_allclose(r, [0.132, 0.0054, 4.4e-4], rtol=0.02)  # the docstring's figures
    # The sea under a white sky is blue: the water-leaving light (body term, RGB) is bluest.
    deep, bare = shading.Water(), shading.Water(body=False)
    wo, wi = direction(20.0), direction(40.0, 200.0)
    body = (deep.f(wo, wi) - bare.f(wo, wi))[0]
    assert body[2] > 5 * body[1] > 5 * body[0] > 0


def test_04_body_term_closed_form_per_wavelength():
    deep, bare = (
        shading.Water(3.0, temperature_c=10.0, salinity=30.0),
        shading.Water(3.0, temperature_c=10.0, salinity=30.0, body=False),
    )
    rng = np.random.default_rng(2)
    wo, wi = rng.normal(size=(50, 3)), rng.normal(size=(50, 3))
    wo[:, 2], wi[:, 2] = np.abs(wo[:, 2]) + 0.05, np.abs(wi[:, 2]) + 0.05
    wo /= np.linalg.norm(wo, axis=1, keepdims=True)
    wi /= np.linalg.norm(wi, axis=1, keepdims=True)
    body = deep.f(wo, wi, wavelengths=INTEGER_NM) - bare.f(wo, wi, wavelengths=INTEGER_NM)
    eta = shading.water_ior(INTEGER_NM, 10.0, 30.0)
    r = shading.water_body_reflectance(INTEGER_NM, 30.0)
    fdr = np.array([deep.internal_reflectance(x) for x in INTEGER_NM])
    t = np.stack([deep.transmittance(wi[:, 2], x) * deep.transmittance(wo[:, 2], x) for x in INTEGER_NM], 1)
    np.testing.assert_allclose(body, t * r / (np.pi * eta**2 * (1 - r * fdr)), rtol=TABLE_TOLERANCE)


def test_05_index_per_wavelength_and_channel():
    water = shading.Water(temperature_c=12.0, salinity=33.0)
    wavelengths = np.random.default_rng(4).uniform(360.0, 830.0, 200)
    np.testing.assert_allclose(water.ior(wavelengths), shading.water_ior(wavelengths, 12.0, 33.0), atol=TABLE_TOLERANCE)
    # RGB: each channel's reflection uses its own index (630, 532, 465 nm): at normal incidence
    # the mirror-like lobe's channels are in the ratio of F0 = ((n - 1) / (n + 1))^2.
    bare = shading.Water(0.0, 12.0, 33.0, body=False)
    f = bare.f(np.array([0.0, 0.0, 1.0]), np.array([0.0, 0.0, 1.0]))[0]
    n = shading.water_ior(np.array([630.0, 532.0, 465.0]), 12.0, 33.0)
    f0 = ((n - 1) / (n + 1)) ** 2
    np.testing.assert_allclose(f / f[1], f0 / f0[1], rtol=1e-9)  # Schlick's F0 ratios in double on both sides: rounding
    # Spectral: per wavelength likewise, no wavelength terminated (the rough lobe covers dispersion).
    s = bare.sample(np.array([0.0, 0.6, 0.8]), np.array([0.99, 0.3, 0.6]), wavelengths=INTEGER_NM)
    assert s.valid[0] and not s.terminated[0] and np.all(s.weight[0] > 0)


def test_06_beckmann_is_normalised_with_slope_variance_alpha_squared():
    for alpha in (0.055, 0.17, 0.3):
        b = shading.Beckmann(alpha)
        dt = np.pi / 2 / 20000
        t = (np.arange(20000) + 0.5) * dt  # midpoints in theta; D is isotropic, so phi gives 2 pi
        m = np.stack([np.sin(t), np.zeros_like(t), np.cos(t)], 1)
        weight = b.D(m) * np.cos(t) * np.sin(t) * 2 * np.pi * dt
        assert np.sum(weight) == pytest.approx(1.0, rel=1e-6)  # int D cos dm = 1
        assert np.sum(np.tan(t) ** 2 * weight) == pytest.approx(alpha**2, rel=1e-6)  # <p^2 + q^2> = alpha^2


def test_07_pickles_and_describes():
    water = shading.Water(7.5, 14.0, 31.0, body=False, priority=3)
    again = pickle.loads(pickle.dumps(water))
    assert (
        again.parameters
        == water.parameters
        == dict(wind_speed=7.5, temperature_c=14.0, salinity=31.0, body=False, priority=3, resolved_slope_variance=0.0)
    )
    assert repr(again) == "Water(wind_speed=7.5, temperature_c=14, salinity=31, body=False, priority=3)"
    assert again.priority == 3


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(wind_speed=-1.0), "wind_speed"),
        (dict(wind_speed=float("nan")), "wind_speed"),
        (dict(wind_speed=31.0), "wind_speed"),
        (dict(wind_speed=float("inf")), "wind_speed"),
        (dict(salinity=-0.1), "salinity"),
        (dict(salinity=float("nan")), "salinity"),
        (dict(salinity=41.0), "salinity"),
        (dict(temperature_c=-2.5), "temperature_c"),
        (dict(temperature_c=41.0), "temperature_c"),
        (dict(temperature_c=float("nan")), "temperature_c"),
    ],
)
def test_08_bad_input_names_the_argument(kwargs, name):
    with pytest.raises(ValueError, match=name):
        shading.Water(**kwargs)


def test_09_bad_input_of_the_optics_functions():
    with pytest.raises(ValueError, match="wind_speed"):
        shading.cox_munk_mean_square_slope(-0.5)
    with pytest.raises(ValueError, match="wavelength"):
        shading.water_absorption(300.0)
    with pytest.raises(ValueError, match="salinity"):
        shading.water_backscattering(500.0, float("nan"))
    with pytest.raises(ValueError, match="wavelength"):
        shading.water_body_reflectance(900.0)
    with pytest.raises(ValueError, match="wavelength_nm"):
        shading.Water().ior(100.0)


CAMERA = "[camera]\nposition = [0, 10, 0]\nlook_at = [10, 0, 0]\nsize = [8, 4]\n"


def test_10_scene_files_take_water(tmp_path):
    path = tmp_path / "sea.toml"
    path.write_text(
        CAMERA + "[[materials]]\nname = 'sea'\ntype = 'water'\nwind_speed = 8.0\nsalinity = 30\n"
        "body = false\n[[objects]]\ntype = 'ground'\nmaterial = 'sea'\n"
    )
    scene, _, _ = refracta.load_scene(path)
    assert repr(scene.material(0)) == "Water(wind_speed=8, temperature_c=20, salinity=30, body=False)"  # the ground
    path.write_text(CAMERA + "[[materials]]\nname = 'sea'\ntype = 'water'\nbody = 1\n")
    with pytest.raises(ValueError, match="body: must be true or false"):
        refracta.load_scene(path)
    path.write_text(CAMERA + "[[materials]]\nname = 'sea'\ntype = 'water'\nwind_speed = -3\n")
    with pytest.raises(ValueError, match="wind_speed"):
        refracta.load_scene(path)
