"""The BSDF library: materials, Fresnel functions and the GGX distribution (pbrt-v4's models;
Mitsuba 3 as the reference).

Every material is a ``refracta._core.Material`` subclass, so any of them can be given where a scene
takes ``material=``. Evaluate a material in its local shading frame (z = shading normal, x = the
surface tangent along which ``alpha_u`` acts) with float64 unit directions of shape (N, 3) or (3,):

- ``f(wo, wi)`` -> (N, 3) linear RGB BSDF values without the cosine [1/sr] (delta lobes give 0);
- ``pdf(wo, wi)`` -> (N,) density [1/sr] of ``sample`` producing wi, lobe probabilities included;
- ``sample(wo, u)`` with u (N, 3) uniform in [0, 1) (u[:, 0] picks the lobe, u[:, 1:] the
  direction) -> a ``BsdfSample`` of read-only arrays ``wi`` (N, 3), ``weight`` (N, 3) =
  ``f |cos theta_i| / pdf`` (delta lobes: albedo over the lobe's probability), ``f``, ``pdf`` (N,),
  ``flags`` (N,) (1 reflection, 2 transmission, 4 diffuse, 8 glossy, 16 specular), ``is_delta``,
  ``eta`` (relative index crossed, 1 for reflection), ``valid`` (False where no direction came
  out), ``terminated`` (``s["wi"]``, the former dict's access, is deprecated).

``wo`` points toward the viewer and ``wi`` toward the light, both away from the surface (pbrt-v4's
names; Mitsuba 3's ``si.wi`` is refracta's ``wo``). Keywords of the three methods:
``wavelengths=`` (4,) or (N, 4) [nm] for spectral evaluation (values per wavelength, shape (N, 4)),
``eta_outside=1.0`` (index of the medium on the normal's side), ``mode='radiance'|'importance'``
(refraction scales radiance by (eta_i / eta_t)^2, importance not). Non-unit or NaN directions raise
ValueError. Reflectances above 1 are refused (ValueError) because they would create energy. Two
models reflect somewhat more than arrives at some parameters all the same, as their published
forms do: ``Principled`` (Burley 2012: its sheen, clearcoat and diffuse retro-reflection are
added, not balanced; albedo 1.04 at normal incidence and up to 1.7 at grazing with every lobe at
full strength) and ``BlinnPhong`` (its lobe's (ns + 8) / (8 pi) normalisation is approximate: with
ks = 1 it reflects 1.02-1.075 at normal incidence for ns from 1 to 100 (most near ns 8-10), and
with kd + ks = 1 in between by ks's share: 1.05 at kd 0.3, ks 0.7 and 1.07 at kd 0.1, ks 0.9, ns 8);
use ``Diffuse``, ``Plastic`` or the microfacet models where energy must balance.

Materials (colours are a number or an (r, g, b) triple; ``texture=`` an image file whose linear
RGB multiplies the colour at the surface's uvs, registered in each scene the material joins):

- ``Diffuse(reflectance=0.5, texture=None)``
- ``BlinnPhong(kd=0.5, ks=0.0, ns=1.0, texture=None, alpha=1.0)``
- ``Conductor(eta=None, k=None)``: eta and k unset = a perfect mirror (F = 1)
- ``RoughConductor(alpha=None, alpha_u=None, alpha_v=None, eta=None, k=None)``
- ``Dielectric(ior=1.5 | 'bk7', sellmeier=None, priority=0)``
- ``RoughDielectric(alpha, ior=1.5, sellmeier=None, priority=0, alpha_u=None, alpha_v=None)``
- ``ThinDielectric(ior=1.5)``
- ``Plastic(reflectance=0.5, ior=1.5, alpha=0.0, texture=None)``: alpha = 0 smooth, > 0 rough (GGX)
- ``Principled(base_color=0.5, metallic=0, roughness=0.5, anisotropic=0, specular=0.5,
  specular_tint=0, sheen=0, sheen_tint=0.5, clearcoat=0, clearcoat_gloss=1, texture=None)``
- ``ThinFilm(thickness, film_ior=1.33, eta=1.5, k=0.0, alpha=0.1)``: thin-film iridescence
  (thickness [nm]) over a GGX base of complex index eta + i k; alpha = 0 is a smooth mirror.

- ``Water(wind_speed=5.0, temperature_c=20.0, salinity=35.0, body=True, priority=0,
  resolved_slope_variance=0.0)``: the sea, below.
- ``TerrainShading(snow_line=3000, tree_line=2000, rock_slope=35, earth_radius=inf, *, vegetation,
  rock, snow)``: terrain coloured by elevation, slope and snow line (Scene.add_terrain's default).

Water: ``water_ior(wavelength_nm, temperature_c=20.0, salinity=0.0)`` (IAPWS R9-97 with Tanaka et
al.'s density and Quan & Fry's salinity terms; n = 1.33335 at 589.3 nm and 20 C, relative to
vacuum) gives a ``Dielectric`` its index, e.g. ``Dielectric(water_ior(550.0, 15.0, 35.0))``.

``Water`` is a wind-roughened sea surface over deep water. Defaults: a gentle breeze of 5 m/s
(Beaufort 3; wind measured 12.5 m above the sea), 20 C and 35 g/kg (the open ocean's salinity).

- The interface is a rough dielectric (Walter et al. 2007; pbrt-v4's DielectricBxDF, Mitsuba 3's
  ``roughdielectric``) with the Beckmann distribution D = exp(-tan^2 theta / alpha^2) /
  (pi alpha^2 cos^4 theta), whose slopes are Gaussian with total mean-square slope alpha^2 (Heitz
  2014, JCGT 3(2): variance alpha^2 / 2 per axis), set to Cox & Munk 1954's (JOSA 44(11), 838-850) clean-sea statistics
  ``cox_munk_mean_square_slope(U) = 0.003 + 5.12e-3 U``: alpha = 0.055 in a calm, 0.17 at 5 m/s,
  0.23 at 10 m/s, so sun glitter widens with wind. Its index is ``water_ior(lambda, temperature_c,
  salinity)`` over the outside medium's: per wavelength in spectral rendering, at 630, 532 and
  465 nm per RGB channel (directions sampled at 550 nm).
- ``body=True``: under the surface, optically deep pure sea water absorbs (``water_absorption``:
  Pope & Fry 1997, Smith & Baker 1981, Kou et al. 1993) and backscatters (``water_backscattering``:
  Morel 1974's b_w(500) (lambda / 500)^-4.32, half of it backward) the light refracted in, and
  returns the irradiance reflectance ``water_body_reflectance`` R = 0.33 b_b / (a + b_b) (Morel &
  Prieur 1977, Gordon et al. 1975), isotropically, through the same rough interface:
  f_body = T(cos_i) T(cos_o) R / (pi eta^2 (1 - R Fbar_int)) (the Plastic layer with the water as its
  base), T(mu) = ``Water.transmittance(mu)`` the rough interface's directional transmittance (its
  transmission lobe integrated, tabulated) and Fbar_int = ``Water.internal_reflectance()`` =
  1 - 2 int T mu dmu / eta^2. Energy: reflection + body <= reflection + T <= 1. Reflection-only,
  two-sided; no path continues under the surface. Left out: chlorophyll and dissolved matter (real
  seas are greener and darker), the upwelling light's angular shape, foam, the sea floor.
- ``body=False``: the bare interface, which also transmits, bounding a medium of the water's index
  (nested dielectrics by ``priority``); nothing absorbs in it.
- Waves larger than a pixel are geometry: ``Scene.add_sea`` displaces the sea near the camera by a
  ``refracta.OceanWaves`` field (Tessendorf 2001's FFT synthesis of the Phillips spectrum, scaled to
  Pierson & Moskowitz 1964's significant wave height) and shades it with copies of the Water whose
  ``resolved_slope_variance`` is the mean-square slope the mesh shows, so that the microfacets keep
  alpha^2 = Cox & Munk's total - resolved and the two add up to Cox & Munk's total.

``Beckmann(alpha)`` exposes the distribution (D, G1, height-correlated G).

Roughness ``alpha`` is the GGX parameter (>= 0; values below 1e-4 are raised to 1e-4).
Measured BRDFs (MERL) are not provided: no MERL data set is installable from the registries.

Example::

    import numpy as np
    from refracta.shading import RoughConductor
    m = RoughConductor(alpha=0.2, eta=(0.2, 0.92, 1.1), k=(3.9, 2.45, 2.14))  # gold-like
    wo = np.array([0.0, 0.6, 0.8])
    s = m.sample(np.tile(wo, (4, 1)), np.random.default_rng(1).random((4, 3)))
"""

from ._core import (
    Beckmann,
    BlinnPhong,
    BsdfSample,
    Conductor,
    Dielectric,
    Diffuse,
    Ior,
    Material,
    Plastic,
    Principled,
    RoughConductor,
    RoughDielectric,
    TerrainShading,
    ThinDielectric,
    ThinFilm,
    TrowbridgeReitz,
    Water,
    cox_munk_mean_square_slope,
    fresnel_conductor,
    fresnel_dielectric,
    fresnel_diffuse_reflectance,
    thin_film_reflectance,
    water_absorption,
    water_backscattering,
    water_body_reflectance,
    water_density,
    water_ior,
)

__all__ = [
    "Material",
    "BsdfSample",
    "Diffuse",
    "BlinnPhong",
    "Conductor",
    "RoughConductor",
    "Dielectric",
    "RoughDielectric",
    "ThinDielectric",
    "Plastic",
    "Principled",
    "ThinFilm",
    "Water",
    "TerrainShading",
    "Ior",
    "TrowbridgeReitz",
    "Beckmann",
    "fresnel_dielectric",
    "fresnel_conductor",
    "fresnel_diffuse_reflectance",
    "thin_film_reflectance",
    "water_ior",
    "water_density",
    "water_absorption",
    "water_backscattering",
    "water_body_reflectance",
    "cox_munk_mean_square_slope",
]
