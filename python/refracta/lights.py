"""Lights for refracta's integrators, and for users' own.

Every light derives from :class:`Light` and offers, in RGB rendering and vectorised over N points:

- ``sample_li(points (N, 3), normals (N, 3) or None, u (N, 2) in [0, 1))`` ->
  ``(wi (N, 3) unit toward the light, L (N, 3) RGB radiance arriving [W/(m^2 sr)], pdf (N,) per
  steradian (delta lights: 1), distance (N,) [m] (infinite lights: inf))``; points the light cannot
  reach get ``pdf = 0`` and zeros;
- ``pdf_li(points, normals, wi, p_light=None, n_light=None)``: the density of ``sample_li``
  (0 for delta lights; area lights need the hit point and its normal);
- ``Le(dirs)`` for infinite lights (sun, environments): radiance seen looking along ``dirs``;
- ``L(points, normals, dirs)`` for area lights: radiance leaving the light's points (front normals)
  toward ``dirs``;
- ``power``: emitted power [W] as luminance Y (infinite lights: through the disc of the scene
  radius given to ``preprocess(centre, radius)``, 1 m until then).

Units: metres, radiance W/(m^2 sr), intensity W/sr, angles in degrees. y is up. Colours are a
number (grey) or linear-sRGB triples; in spectral rendering they are RGB x D65 (illuminants).

Lights:

- ``PointLight(position, intensity)``: E = I cos(theta) / r^2; power 4 pi I.
- ``SpotLight(position, direction, angle, intensity, inner_angle=None)``: a cone of full ``angle``;
  hard edge, or a smoothstep falloff from ``inner_angle`` to ``angle`` (pbrt-v4).
- ``SunLight(direction, radiance, angular_diameter=0.53, limb_darkening=0)``: a disc at infinity
  toward ``direction`` with mean radiance ``radiance``; I(mu) = 1 - u (1 - mu).
- ``AreaLight(vertices, triangles, emission, two_sided=False)``: an emissive triangle mesh,
  emitting from the counter-clockwise front ((v1 - v0) x (v2 - v0)); sampled by area.
- ``SphereLight(centre, radius, emission)``: an outward-emitting sphere, sampled by its cone (in a
  scene, ``Scene.add_sphere(..., emission=)`` makes one with the sphere the rays see).
- ``EnvironmentLight(image, scale=1, rotation=None)``: an equirectangular map (H, W, 3), Mitsuba 3's
  orientation: u = atan2(d.x, -d.z) / (2 pi) wrapped to [0, 1), v = acos(d.y) / pi, d in the map's
  frame (d = rotation^T world); column i at u = (i + 1/2) / W, row j at v = j / (H - 1), bilinear;
  ``rotation`` is degrees about +y or a 3 x 3 matrix (map -> world). Importance-sampled by
  luminance x sin(theta).
- ``ConstantEnvironment(radiance, sampling="cosine")``: uniform radiance; E = pi L.
- ``ScaledLight(light, scale)``: a sky or an environment times ``scale`` (the sun: scale its radiance)
  (``Scene.set_physical_sky(..., scale=)`` puts one in ``Scene.lights``); ``light`` and ``scale``.
- ``LightSampler(lights, strategy="power")``: ``sample(u) -> (index, probability)``, ``pmf(i)``.

Example::

    import numpy as np
    from refracta.lights import PointLight
    light = PointLight([0, 2, 0], intensity=10.0)
    wi, L, pdf, r = light.sample_li(np.zeros((1, 3)), None, np.full((1, 2), 0.5))
    # wi = (0, 1, 0), L = 10 / 2^2 = 2.5, pdf = 1, r = 2
"""

from refracta._core import (
    AreaLight,
    ConstantEnvironment,
    EnvironmentLight,
    Light,
    LightSampler,
    PointLight,
    ScaledLight,
    SphereLight,
    SpotLight,
    SunLight,
)

__all__ = [
    "AreaLight",
    "ConstantEnvironment",
    "EnvironmentLight",
    "Light",
    "LightSampler",
    "PointLight",
    "ScaledLight",
    "SphereLight",
    "SpotLight",
    "SunLight",
]
