"""Bad input raises ValueError naming the parameter (DESIGN.md: errors across the boundary)."""

import numpy as np
import pytest

from refracta import shading


@pytest.mark.parametrize(
    "make, name",
    [
        (lambda: shading.Diffuse(1.2), "reflectance"),
        (lambda: shading.Diffuse((0.5, np.nan, 0.5)), "reflectance"),
        (lambda: shading.Diffuse(-0.1), "reflectance"),
        (lambda: shading.Diffuse((0.5, 0.5)), "reflectance"),
        (lambda: shading.BlinnPhong(0.5, 1.5, 10), "ks"),
        (lambda: shading.BlinnPhong(0.5, 0.5, -1), "ns"),
        (lambda: shading.BlinnPhong(0.5, 0.5, 10, alpha=2.0), "alpha"),
        (lambda: shading.Conductor(eta=-1.0), "eta"),
        (lambda: shading.Conductor(k=2.0), "k"),
        (lambda: shading.RoughConductor(alpha=-0.1), "alpha_u"),
        (lambda: shading.RoughConductor(alpha=np.nan), "alpha_u"),
        (lambda: shading.RoughConductor(), "alpha"),
        (lambda: shading.RoughConductor(alpha_u=0.1), "alpha_u and alpha_v"),
        (lambda: shading.RoughConductor(alpha=0.1, alpha_u=0.2, alpha_v=0.2), "either alpha"),
        (lambda: shading.Dielectric(0.0), "ior"),
        (lambda: shading.Dielectric(-1.5), "ior"),
        (lambda: shading.Dielectric("flint"), "ior"),
        (lambda: shading.Dielectric(sellmeier=(1, 2, 3)), "sellmeier"),
        (lambda: shading.Dielectric(sellmeier=(1.0, 0.2, 1.0, 0.25, 0.02, 100.0)), "sellmeier"),
        (lambda: shading.RoughDielectric(alpha=-1.0), "alpha_u"),
        (lambda: shading.ThinDielectric(np.nan), "ior"),
        (lambda: shading.Plastic(1.5), "reflectance"),
        (lambda: shading.Plastic(0.5, ior=0.0), "ior"),
        (lambda: shading.Plastic(0.5, alpha=-0.2), "alpha_u"),
        (lambda: shading.Principled(0.5, metallic=1.5), "metallic"),
        (lambda: shading.Principled(0.5, roughness=np.nan), "roughness"),
        (lambda: shading.Principled((2.0, 0.5, 0.5)), "base_color"),
        (lambda: shading.ThinFilm(-10.0), "thickness"),
        (lambda: shading.ThinFilm(300.0, film_ior=0.0), "film_ior"),
        (lambda: shading.Diffuse(0.5, texture=-2), "texture"),
    ],
)
def test_bad_parameters(make, name):
    with pytest.raises(ValueError, match=name):
        make()


def test_bad_directions_and_numbers():
    m = shading.Diffuse(0.5)
    with pytest.raises(ValueError, match="wo"):
        m.f([0.0, 0.0, 2.0], [0.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="wi"):
        m.f([0.0, 0.0, 1.0], [np.nan, 0.0, 1.0])
    with pytest.raises(ValueError, match="wi"):
        m.pdf([0.0, 0.0, 1.0], np.zeros((3, 2)))
    with pytest.raises(ValueError, match="u"):
        m.sample([0.0, 0.0, 1.0], [0.5, 1.5, 0.5])
    with pytest.raises(ValueError, match="row counts"):
        m.f(np.tile([0.0, 0.0, 1.0], (3, 1)), np.tile([0.0, 0.0, 1.0], (2, 1)))
    with pytest.raises(ValueError, match="mode"):
        m.f([0.0, 0.0, 1.0], [0.0, 0.0, 1.0], mode="light")
    with pytest.raises(ValueError, match="eta_outside"):
        m.f([0.0, 0.0, 1.0], [0.0, 0.0, 1.0], eta_outside=0.0)
    with pytest.raises(ValueError, match="wavelengths"):
        m.f([0.0, 0.0, 1.0], [0.0, 0.0, 1.0], wavelengths=[100.0, 500.0, 600.0, 700.0])
    with pytest.raises(ValueError, match="eta"):
        shading.fresnel_dielectric(0.5, -1.0)
    with pytest.raises(ValueError, match="cos_i"):
        shading.fresnel_dielectric(1.5, 1.5)
    with pytest.raises(ValueError, match="k"):
        shading.fresnel_conductor(0.5, 1.0, -1.0)


def test_repr_describes_the_material():
    assert repr(shading.Diffuse(0.25)) == "Diffuse(reflectance=(0.25, 0.25, 0.25))"
    assert "alpha_u=0.1" in repr(shading.RoughConductor(alpha_u=0.1, alpha_v=0.2))
    assert repr(shading.Conductor()) == "Conductor(F=1)"
    assert "priority=2" in repr(shading.Dielectric(1.33, priority=2))
    assert shading.Dielectric(1.33, priority=2).priority == 2
    assert isinstance(shading.Plastic(0.5), shading.Material)
