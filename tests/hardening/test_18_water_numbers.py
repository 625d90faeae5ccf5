"""The water optics refuse what is not a number, naming the argument (issues 19 and 22): py::vectorize
cast the string '550' to 550 nm and True to 1, and Water(wind_speed='5') was pybind11's TypeError listing the
whole signature."""

import numpy as np
import pytest

from refracta import shading


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: shading.water_ior("550"), r"wavelength_nm must hold real numbers \(got dtype <U3\)"),
        (lambda: shading.water_ior(550.0, "20"), r"temperature_c must hold real numbers"),
        (lambda: shading.water_ior(550.0, 20.0, ["35"]), r"salinity must hold real numbers"),
        (lambda: shading.water_ior(None), r"wavelength_nm must hold real numbers \(got dtype object\)"),
        (lambda: shading.water_density("20"), r"temperature_c must hold real numbers"),
        (lambda: shading.water_absorption("550"), r"wavelength_nm must hold real numbers"),
        (lambda: shading.water_backscattering(550.0, "35"), r"salinity must hold real numbers"),
        (lambda: shading.water_body_reflectance("550"), r"wavelength_nm must hold real numbers"),
        (lambda: shading.cox_munk_mean_square_slope("5"), r"wind_speed must hold real numbers"),
        (lambda: shading.fresnel_dielectric("0.5", 1.5), r"cos_i must hold real numbers"),
        (lambda: shading.fresnel_conductor(0.5, 0.2, "3"), r"k must hold real numbers"),
        # A bool is no temperature: numpy would take True as 1 deg C (as Water(temperature_c=True) refuses).
        (lambda: shading.water_ior(550.0, True), r"temperature_c must hold real numbers \(got dtype bool\)"),
        (lambda: shading.water_ior([True, False]), r"wavelength_nm must hold real numbers \(got dtype bool\)"),
        (lambda: shading.cox_munk_mean_square_slope(np.bool_(True)), r"wind_speed must hold real numbers"),
    ],
)
def test_vectorised_water_and_fresnel_functions_refuse_strings(call, message):
    with pytest.raises(ValueError, match=message):
        call()


@pytest.mark.parametrize("name", ["wind_speed", "temperature_c", "salinity"])
@pytest.mark.parametrize("value, shown", [("5", "'5'"), (True, "True"), (None, "None")])
def test_water_refuses_a_parameter_that_is_not_a_number(name, value, shown):
    with pytest.raises(ValueError, match=rf"Water: {name} must be a number \(got {shown}\)"):
        shading.Water(**{name: value})


def test_numbers_of_any_real_type_still_give_the_same_values():
    # Integers, numpy scalars and arrays are numbers: the same results as the floats.
    assert shading.water_ior(np.int64(550), 20, np.float32(35.0)) == shading.water_ior(550.0, 20.0, 35.0)
    assert isinstance(shading.water_ior(550.0), float)  # a scalar in, a float out
    pair = shading.water_ior(np.array([500.0, 600.0]))
    assert np.array_equal(pair, [shading.water_ior(500.0), shading.water_ior(600.0)])
    water = shading.Water(wind_speed=np.float64(3.0), temperature_c=np.int64(10), salinity=30)
    assert water.parameters == shading.Water(wind_speed=3.0, temperature_c=10.0, salinity=30.0).parameters
