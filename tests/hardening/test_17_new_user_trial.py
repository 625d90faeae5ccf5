"""Bad input a new-user trial found accepted silently, or refused without naming the argument: each
now raises ValueError naming it."""

import numpy as np
import pytest

import refracta


@pytest.mark.parametrize(
    "make, message",
    [
        # A bool went through float(): surface_dt=True was a 1 K warmer surface.
        (
            lambda: refracta.PhysicalAtmosphere(surface_dt=True),
            r"PhysicalAtmosphere: surface_dt must be a number \(got True\)",
        ),
        (
            lambda: refracta.PhysicalAtmosphere(surface_dt=np.bool_(True)),
            r"surface_dt must be a number \(got (np\.)?True_?\)",
        ),
        (
            lambda: refracta.LogisticProfile(True),
            r"LogisticProfile: positional parameter 1 must be a number \(got True\)",
        ),
        (lambda: refracta.LogisticProfile(3.0, False), r"positional parameter 2 must be a number \(got False\)"),
        (
            lambda: refracta.LogisticProfile().with_params(k_s=True),
            r"LogisticProfile: k_s must be a number \(got True\)",
        ),
        # Strings say what they got, as bools do.
        (lambda: refracta.LogisticProfile(k_s="a"), r"LogisticProfile: k_s must be a number \(got 'a'\)"),
        (lambda: refracta.PhysicalAtmosphere(surface_dt=None), r"surface_dt must be a number \(got None\)"),
    ],
)
def test_model_parameters_refuse_bools_and_strings_naming_the_parameter(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_model_parameters_still_take_numpy_and_integer_numbers():
    # Integers and numpy scalars are numbers: the same model as the float.
    a = refracta.PhysicalAtmosphere(surface_dt=np.float32(2.0), surface_depth=np.int64(3))
    b = refracta.PhysicalAtmosphere(surface_dt=2.0, surface_depth=3.0)
    assert a.params == b.params


def test_a_focus_distance_without_f_number_is_refused():
    # Without f_number the camera is a pinhole: the focus distance was dropped without a word.
    with pytest.raises(ValueError, match=r"focus_distance needs f_number \(a pinhole has no focus\)"):
        refracta.Camera.photographic((0, 2, 0), (100, 2, 0), 50.0, focus_distance=5.0)
    with pytest.raises(ValueError, match=r"focus_distance needs f_number"):
        refracta.Camera.eye_level((0, 0, 0), (100, 0, 0), focus_distance=5.0)
    # With f_number it is the lens's focus (unchanged).
    camera = refracta.Camera.photographic((0, 2, 0), (100, 2, 0), 50.0, f_number=2.0, focus_distance=5.0)
    assert camera.focus_distance == 5.0 and camera.aperture_diameter == pytest.approx(0.025, rel=1e-15)  # f / N


def test_an_image_that_is_not_numbers_names_the_image():
    # A path given where the pixels belong: numpy's "could not convert string to float" named nothing.
    with pytest.raises(ValueError, match=r"image must hold real numbers \(got dtype <U9\)"):
        refracta.io.to_display("image.png")
    with pytest.raises(ValueError, match=r"image must hold real numbers"):
        refracta.io.exposure_of(np.array([["a", "b"]]))
    # Integer and bool pixels remain images.
    assert refracta.io.to_display(np.ones((2, 2), np.int32), exposure=0.5, tonemap="linear").shape == (2, 2, 1)


@pytest.mark.parametrize(
    "value, message",
    [
        (float("nan"), r"examples.green_flash: sun_elevation must be finite \(got nan\)"),
        (float("inf"), r"sun_elevation must be finite \(got inf\)"),
        (True, r"examples.green_flash: sun_elevation must be a number \(got True\)"),
        ("-0.8", r"sun_elevation must be a number \(got '-0.8'\)"),
    ],
)
def test_green_flash_names_a_bad_sun_elevation(value, message):
    with pytest.raises(ValueError, match=message):
        refracta.examples.green_flash(16, 16, sun_elevation=value)
