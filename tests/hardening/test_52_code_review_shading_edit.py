"""Defects found by a read-through of the C++ shading, edit and binding code on 7 December: a
material evaluated on zero rows of wavelengths crashed; a tabulated sun of 1e300 per nm rendered
inf; an index-matched rough dielectric dropped ~97 % of its light; a Sellmeier pole between whole
nanometres passed; fresnel_conductor at grazing incidence and eta 1 was NaN; the in-scatter
reference took any number of steps."""

import subprocess
import sys

import numpy as np
import pytest

import refracta
from refracta import shading


def test_materials_evaluate_zero_rows_of_wavelengths_to_nothing():
    # In a child: the build before read row 0 of the empty (0, 4) array and died of SIGSEGV.
    code = """
import numpy as np
from refracta import shading
print(shading.Diffuse().f(np.zeros((0, 3)), np.zeros((0, 3)), wavelengths=np.zeros((0, 4))).shape,
      shading.Plastic().pdf(np.zeros((0, 3)), np.zeros((0, 3)), wavelengths=np.zeros((0, 4))).shape)
"""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["(0,", "4)", "(0,)"]


def test_a_tabulated_light_is_capped_as_an_rgb_one():
    scene = refracta.Scene()
    with pytest.raises(ValueError, match=r"tabulated: values must be finite and in \[0, 1e\+30\] \(got 1e\+300"):
        scene.set_sun([0, 1, 0], radiance=[1e300, 1e300], wavelengths=[400.0, 700.0])


def test_an_index_matched_rough_dielectric_lets_all_light_straight_through():
    # ior 1.5 inside glass of 1.5: no interface at all. Every sample goes on along -wo with weight 1
    # (it is the smooth interface's exact pass-through); 2.9 % of them were valid before.
    u = np.random.default_rng(0).random((2000, 3))
    wo = np.array([0.0, 0.6, 0.8])
    sample = shading.RoughDielectric(alpha=0.3, ior=1.5).sample(wo, u, eta_outside=1.5)
    assert np.all(sample.valid) and np.all(sample.is_delta)
    np.testing.assert_array_equal(sample.weight, 1.0)
    np.testing.assert_allclose(sample.wi, np.tile(-wo, (2000, 1)), atol=1e-15)  # tolerance: round-off of a unit vector
    # Beside it, a hair off index matching, the rough lobe's samples are all valid (the trial: 100 %,
    # mean weight 0.988): only the exact match was lost.
    near = shading.RoughDielectric(alpha=0.3, ior=1.5).sample(wo, u, eta_outside=1.4999)
    assert np.mean(near.valid) > 0.99  # tolerance: a sample or two may fall outside the lobe


def test_a_sellmeier_pole_between_whole_nanometres_is_refused():
    with pytest.raises(ValueError, match=r"sellmeier term 1 has its pole at 600.5 nm"):
        shading.Ior(sellmeier=(1e-4, 0, 0, 0.6005**2, 0, 0))
    assert shading.Ior("bk7").at([550.0])[0] == pytest.approx(1.51852, abs=1e-5)  # Schott N-BK7 at 550 nm


def test_conductor_fresnel_is_one_at_grazing_incidence():
    assert shading.fresnel_conductor(0.0, 1.0, 0.0) == 1.0
    assert shading.fresnel_conductor(0.0, 0.2, 3.0) == 1.0


def test_the_in_scatter_reference_takes_at_most_a_million_steps():
    air = refracta.spectrum.AerialPerspective(refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0)))
    with pytest.raises(ValueError, match=r"steps must be in \[1, 1000000\] \(got 2147483647\)"):
        air.inscatter_reference((0, 0, 0), (100, 0, 0), 550.0, steps=2**31 - 1)
