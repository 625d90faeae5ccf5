"""Fresnel reflectance against shared/SHADING.md section 1, independent closed forms, Sellmeier
BK7 and the thin-film limits."""

import numpy as np
import pytest

from refracta import shading

# The table of SHADING.md gives six digits.
TABLE_TOLERANCE = 5e-7
# Two algebraic forms of one formula in double precision.
FORMULA_TOLERANCE = 1e-12
# 32-point Gauss-Legendre with the square-root substitution (fresnel.cpp).
HEMISPHERICAL_TOLERANCE = 1e-6
# SHADING.md section 7 lists BK7 to 6 decimals.
SELLMEIER_TOLERANCE = 1e-6


def test_dielectric_values_of_the_table():
    angles = np.radians([0.0, 30.0, 45.0, 60.0, 80.0])
    expected = [0.04, 0.041523, 0.050240, 0.089187, 0.387704]
    np.testing.assert_allclose(shading.fresnel_dielectric(np.cos(angles), 1.5), expected, atol=TABLE_TOLERANCE)


def test_brewster_angle_and_total_internal_reflection():
    # At Brewster's angle r_p = 0, so F = r_s^2 / 2 with r_s = cos(theta_i + theta_t) ... checked via the closed form.
    brewster = np.arctan(1.5)
    # The literal's last digit (arctan 1.5 = 56.30993 deg).
    assert np.degrees(brewster) == pytest.approx(56.3099, abs=1e-4)
    ci = np.cos(brewster)
    ct = np.sqrt(1 - (1 - ci**2) / 1.5**2)
    r_s = (ci - 1.5 * ct) / (ci + 1.5 * ct)
    assert shading.fresnel_dielectric(ci, 1.5) == pytest.approx(0.5 * r_s**2, abs=FORMULA_TOLERANCE)
    critical = np.degrees(np.arcsin(1 / 1.5))
    assert critical == pytest.approx(41.8103, abs=1e-4)  # the literal's last digit (arcsin(1/1.5) = 41.81031 deg)
    inside = -np.cos(np.radians([critical + 0.01, 60.0, 89.0]))
    np.testing.assert_array_equal(shading.fresnel_dielectric(inside, 1.5), 1.0)
    assert shading.fresnel_dielectric(-np.cos(np.radians(30.0)), 1.5) == pytest.approx(0.055190, abs=TABLE_TOLERANCE)
    assert shading.fresnel_dielectric(-np.cos(np.radians(critical - 0.5)), 1.5) < 1.0


def test_hemispherical_reflectance():
    assert shading.fresnel_diffuse_reflectance(1.5) == pytest.approx(0.091778, abs=TABLE_TOLERANCE)
    assert shading.fresnel_diffuse_reflectance(1 / 1.5) == pytest.approx(0.596346, abs=TABLE_TOLERANCE)
    # Independent: 2 int F mu dmu by a fine midpoint rule, and the exact inside/outside relation.
    for eta in (1.33, 1.5, 2.4, 1 / 1.33, 1 / 2.0):
        mu = (np.arange(200_000) + 0.5) / 200_000
        reference = np.sum(2 * shading.fresnel_dielectric(mu, eta) * mu) / 200_000
        assert shading.fresnel_diffuse_reflectance(eta) == pytest.approx(reference, abs=HEMISPHERICAL_TOLERANCE)
        if eta > 1:
            inside = 1 - (1 - shading.fresnel_diffuse_reflectance(eta)) / eta**2
            assert shading.fresnel_diffuse_reflectance(1 / eta) == pytest.approx(inside, abs=HEMISPHERICAL_TOLERANCE)


def test_conductor_with_k_zero_is_the_dielectric():
    cos = np.linspace(0.0, 1.0, 101)
    for eta in (1.2, 1.5, 3.0):
        np.testing.assert_allclose(
            shading.fresnel_conductor(cos, eta, 0.0), shading.fresnel_dielectric(cos, eta), atol=FORMULA_TOLERANCE
        )


def conductor_closed_form(cos_i, eta, k):
    """The real-arithmetic form of the conductor Fresnel equations (pbrt-v3 FrConductor,
    Mitsuba's fresnel_conductor): a^2 + b^2 = sqrt((eta^2 - k^2 - sin^2)^2 + 4 eta^2 k^2)."""
    c2 = cos_i**2
    s2 = 1 - c2
    t0 = eta**2 - k**2 - s2
    a2b2 = np.sqrt(t0**2 + 4 * eta**2 * k**2)
    a = np.sqrt(0.5 * (a2b2 + t0))
    rs = (a2b2 + c2 - 2 * a * cos_i) / (a2b2 + c2 + 2 * a * cos_i)
    rp = rs * (c2 * a2b2 + s2**2 - 2 * a * cos_i * s2) / (c2 * a2b2 + s2**2 + 2 * a * cos_i * s2)
    return 0.5 * (rs + rp)


@pytest.mark.parametrize("eta, k", [(0.2, 3.9), (1.1, 2.1), (2.9, 3.1), (0.05, 0.5)])
def test_conductor_against_the_closed_form(eta, k):
    cos = np.cos(np.radians([0.0, 20.0, 45.0, 70.0, 85.0, 89.9]))
    # The same complex closed form, rearranged in C++: double rounding.
    np.testing.assert_allclose(shading.fresnel_conductor(cos, eta, k), conductor_closed_form(cos, eta, k), rtol=1e-10)


def test_bk7_sellmeier():
    bk7 = shading.Ior("bk7")
    assert bk7.dispersive
    np.testing.assert_allclose(bk7.at([587.6, 486.1, 656.3]), [1.516798, 1.522379, 1.514321], atol=SELLMEIER_TOLERANCE)
    assert shading.Ior(1.33).at(400.0) == 1.33
    assert shading.Dielectric("bk7").interior_ior(587.6) == pytest.approx(1.516798, abs=SELLMEIER_TOLERANCE)
    # The same Sellmeier formula evaluated twice: bit-identical up to approx's 1e-6 default.
    assert shading.Dielectric("bk7").interior_ior() == pytest.approx(bk7.at(550.0))
    assert shading.ThinDielectric(1.5).interior_ior() is None


def test_thin_film_limits():
    cos = np.cos(np.radians([0.0, 30.0, 60.0, 80.0]))
    # No film (d = 0) and an index-matched film are the base's own Fresnel reflectance.
    for eta, k in [(1.5, 0.0), (0.2, 3.9)]:
        base = shading.fresnel_conductor(cos, eta, k)
        # A zero-thickness film is the bare interface: rounding only.
        film = shading.thin_film_reflectance(cos, 1.0, 1.38, eta, k, thickness=0.0, wavelength=550.0)
        # A zero-thickness film: rounding only.
        np.testing.assert_allclose(film, base, atol=1e-12)
        # A film of the ambient index is the bare interface: rounding only.
        film = shading.thin_film_reflectance(cos, 1.0, 1.0, eta, k, thickness=300.0, wavelength=550.0)
        # A film of the ambient index: rounding only.
        np.testing.assert_allclose(film, base, atol=1e-12)
    # A quarter-wave coating of index sqrt(n3) is a perfect antireflection layer at normal incidence.
    n3, lam = 1.9, 550.0
    n2 = np.sqrt(n3)
    # Exactly 0 in exact arithmetic: double rounding.
    quarter_wave = shading.thin_film_reflectance(1.0, 1.0, n2, n3, 0.0, thickness=lam / (4 * n2), wavelength=lam)
    # Exactly 0 in exact arithmetic: double rounding.
    assert quarter_wave == pytest.approx(0.0, abs=1e-14)
    # A half-wave layer is absent at normal incidence.
    half_wave = shading.thin_film_reflectance(1.0, 1.0, 1.33, 1.5, 0.0, thickness=lam / (2 * 1.33), wavelength=lam)
    # A half-wave layer in exact arithmetic: double rounding.
    assert half_wave == pytest.approx(0.04, abs=1e-12)
    # Normal incidence closed form (Born & Wolf 1.6 eq. 57):
    # R = (r12^2 + r23^2 + 2 r12 r23 cos d) / (1 + r12^2 r23^2 + 2 r12 r23 cos d).
    n2, d = 1.33, 380.0
    r12, r23 = (1 - n2) / (1 + n2), (n2 - 1.5) / (n2 + 1.5)
    delta = 4 * np.pi * n2 * d / lam
    expected = (r12**2 + r23**2 + 2 * r12 * r23 * np.cos(delta)) / (1 + r12**2 * r23**2 + 2 * r12 * r23 * np.cos(delta))
    # Airy's closed form in double on both sides: rounding.
    airy = shading.thin_film_reflectance(1.0, 1.0, n2, 1.5, 0.0, thickness=d, wavelength=lam)
    # Airy's closed form in double on both sides: rounding.
    assert airy == pytest.approx(expected, abs=1e-12)
