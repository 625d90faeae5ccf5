"""A December 2026 bad-input trial of the newest APIs, the library's side (the Python package's:
test_37): each test fails on the code before the fix."""

import os
import pickle

import numpy as np
import pytest

import refracta
from refracta import shading, spectrum


def test_an_impossible_ozone_column_is_refused():
    # 1e10 DU blackened the sky and every render without a word; the Earth's column is 100-600 DU.
    with pytest.raises(ValueError, match=r"ozone_du must be in \[0, 10000\] Dobson units"):
        refracta.Scene().set_physical_sky((0, 1, 0), ozone_du=1e10)
    with pytest.raises(ValueError, match="ozone_du must be in"):
        spectrum.PhysicalSky((0, 1, 0), ozone_du=1e300)
    spectrum.PhysicalSky((0, 1, 0), ozone_du=600.0)  # an ozone-rich day stays an air


def test_an_aerosol_thicker_than_the_densest_fog_is_refused():
    with pytest.raises(ValueError, match=r"aerosol 1e\+300 makes the meteorological visibility"):
        spectrum.PhysicalSky((0, 1, 0), aerosol=1e300)
    with pytest.raises(ValueError, match=r"visibility must be >= 0.001 km"):
        spectrum.PhysicalSky((0, 1, 0), visibility=1e-4)
    # The least visibility itself is an air at every altitude (it came back a rounding below 1 m).
    for altitude in (0.0, 5000.0, 15000.0):
        with pytest.warns(UserWarning, match="fog"):
            spectrum.PhysicalSky((0, 1, 0), visibility=0.001, altitude=altitude, multiple_scattering=False)


def test_aerial_perspective_scale_is_bounded_as_the_sky_s():
    sky = spectrum.PhysicalSky((0, 1, 0))
    with pytest.raises(ValueError, match=r"AerialPerspective: scale must be in \[0, 1e\+30\]"):
        spectrum.AerialPerspective(sky, scale=1e300)


def test_a_wavelength_given_as_an_array_is_named():
    air = spectrum.AerialPerspective(spectrum.PhysicalSky((0, 1, 0)))
    with pytest.raises(ValueError, match="wavelength must be a number \\(not an array\\)"):
        air.along((0, 1, 0), (100, 1, 0), np.array([550.0]))
    assert air.along((0, 1, 0), (100, 1, 0), np.array(550.0)) == air.along((0, 1, 0), (100, 1, 0), 550.0)


def test_a_sensor_of_no_size_is_refused():
    # A 1e-300 mm sensor gave a 7.6e-301 deg view: every pixel's ray the same.
    with pytest.raises(ValueError, match=r"sensor_mm sides must be in \[0.1, 2000\] mm"):
        refracta.Camera.photographic((0, 1, 0), (0, 1, -10), 50.0, sensor_mm=(1e-300, 1e-300))
    with pytest.raises(ValueError, match=r"sensor_mm sides must be in"):
        refracta.Camera.photographic((0, 1, 0), (0, 1, -10), 50.0, sensor_mm=(3.2e11, 1.6e11))
    with pytest.raises(ValueError, match=r"vfov must be at least 1e-06 degrees"):
        refracta.Camera((0, 1, 0), (0, 1, -10), vfov=1e-300)


def test_a_tampered_camera_lens_is_refused_not_dropped():
    camera = refracta.Camera.photographic((0, 1, 0), (0, 1, -10), 50.0, width=8, height=4, f_number=2.0)
    state = list(camera.__getstate__())
    assert len(state) == 9 and state[7] > 0.0  # the lens's aperture diameter
    for bad in (float("nan"), -1.0):
        state[7] = bad
        copy = refracta.Camera.__new__(refracta.Camera)
        with pytest.raises(ValueError, match="aperture"):
            copy.__setstate__(tuple(state))


def test_a_tampered_constant_environment_sampling_is_refused():
    # Sampling 7 was taken as is: neither cosine nor uniform, it sampled uniformly, silently.
    light = refracta.lights.ConstantEnvironment((1.0, 1.0, 1.0), sampling="uniform")
    state = list(light.__getstate__())
    assert pickle.loads(pickle.dumps(light)).__getstate__()[1] == state[1]
    state[1] = 7
    with pytest.raises(ValueError, match=r"ConstantEnvironment: bad pickle state \(sampling 7\)"):
        refracta.lights.ConstantEnvironment.__new__(refracta.lights.ConstantEnvironment).__setstate__(tuple(state))


def test_a_tampered_hot_spot_footprint_is_refused():
    spot = refracta.HotSpot(0.0, 300.0, 50.0, 8.0, footprint="compact")
    assert pickle.loads(pickle.dumps(spot)) == spot
    state = list(spot.__getstate__())
    state[5] = -1
    copy = refracta.HotSpot.__new__(refracta.HotSpot)
    with pytest.raises(ValueError, match=r"HotSpot: bad pickle state \(footprint -1\)"):
        copy.__setstate__(tuple(state))
    state[5], state[2] = 1, -5.0  # the constructor's checks hold too: a negative radius
    with pytest.raises(ValueError, match="radius"):
        refracta.HotSpot.__new__(refracta.HotSpot).__setstate__(tuple(state))


def test_a_tampered_scene_naming_a_missing_material_is_refused():
    scene = refracta.Scene()
    scene.add_box((0, 0, -5), (1, 1, 1))
    state = list(scene.__getstate__())
    state[2] = []  # no materials, the box still naming material 0
    with pytest.raises(ValueError, match=r"Scene: bad pickle state \(material 0 of 0\)"):
        refracta.Scene.__new__(refracta.Scene).__setstate__(tuple(state))


def test_a_sea_centred_beyond_the_scene_names_the_centre():
    waves = refracta.OceanWaves(resolution=16)
    with pytest.raises(ValueError, match=r"centre must lie within the scene's reach"):
        refracta.Scene().add_sea(waves, centre=(1e300, 0.0))


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs a FIFO")
def test_a_fifo_texture_is_not_a_regular_file(tmp_path):
    fifo = tmp_path / "ground.png"
    os.mkfifo(fifo)
    for add in (
        lambda scene: scene.add_ground(0.0, texture=fifo),
        lambda scene: scene.add_billboard((0, 1, -5), 2.0, 2.0, fifo),
    ):
        with pytest.raises(refracta.IoError, match="not a regular file"):
            add(refracta.Scene())
    with pytest.raises(refracta.IoError, match="not a regular file"):
        shading.Diffuse(texture=fifo)


def test_terrain_finer_than_single_precision_resolves_is_refused():
    # 1e-4 m steps 9.9e6 m out: float32 resolves 1 m there, so all 16 samples were one point.
    with pytest.raises(ValueError, match="finer than single-precision positions resolve"):
        refracta.Scene().add_terrain(np.zeros((4, 4)), (9.9e6, 9.9e6), (1e-4, 1e-4))
    # 30 m samples 50 km out are far above float32's 4 mm there (8 units: 3 cm).
    scene = refracta.Scene()
    scene.add_terrain(np.zeros((4, 4)), (5e4, 5e4), (30.0, 30.0))
    assert scene.geometry_count == 1
