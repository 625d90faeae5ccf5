"""BSDF values against Mitsuba 3 (an independent renderer, scalar_rgb variant) on fixed random
direction pairs. Conventions (SHADING.md section 0): Mitsuba's si.wi is refracta's wo, its eval
returns f |cos theta_i|, so f(wo, wi) |wi.z| is compared. Mitsuba uses the separable Smith
G1(wo) G1(wi); refracta the height-correlated G2 (microfacet.h): microfacet values are compared
after multiplying refracta's by G1(wo) G1(wi) / G2, which isolates D and F. Mitsuba computes in
float32, hence the tolerances."""

import numpy as np
import pytest

from refracta import shading

mi = pytest.importorskip("mitsuba")

FLOAT32_TOLERANCE = 2e-5  # Mitsuba's scalar_rgb variant is single precision (relative)
# Mitsuba's plastic uses a polynomial fit of the internal diffuse reflectance (0.596811 for eta 1.5;
# exact 0.596346), changing R / (1 - R Fbar) by up to 1.3e-3 relative at R = 0.6.
FIT_TOLERANCE = 2e-3
VALUE_FLOOR = 1e-4  # below this f |cos| the relative difference is float32 noise


@pytest.fixture(scope="module", autouse=True)
def scalar_rgb():
    mi.set_variant("scalar_rgb")


def pairs(n=300, seed=3, transmit=False):
    rng = np.random.default_rng(seed)
    a, b = rng.normal(size=(n, 3)), rng.normal(size=(n, 3))
    a[:, 2], b[:, 2] = np.abs(a[:, 2]) + 0.1, np.abs(b[:, 2]) + 0.1
    if transmit:
        b[:, 2] = -b[:, 2]
    return a / np.linalg.norm(a, axis=1, keepdims=True), b / np.linalg.norm(b, axis=1, keepdims=True)


def mitsuba_eval(spec, wo, wi):
    bsdf = mi.load_dict(spec)
    si = mi.SurfaceInteraction3f()
    si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
    si.n = mi.Vector3f(0, 0, 1)
    out = []
    for o, i in zip(wo, wi):
        si.wi = mi.Vector3f(*o)
        v = bsdf.eval(mi.BSDFContext(), si, mi.Vector3f(*i))
        out.append([v[0], v[1], v[2]])
    return np.array(out)


def separable_over_correlated(alpha_u, alpha_v, wo, wi):
    d = shading.TrowbridgeReitz(alpha_u, alpha_v)
    wi_up = wi * np.where(wi[:, 2:3] < 0, -1.0, 1.0)  # Lambda depends on |cos| only
    return (d.G1(wo) * d.G1(wi_up) / d.G(wo, wi_up))[:, None]


def rgb(v):
    return {"type": "rgb", "value": list(v)}


def max_relative(ours, theirs):
    mask = theirs > VALUE_FLOOR
    return np.max(np.abs(ours[mask] - theirs[mask]) / theirs[mask])


def test_diffuse():
    wo, wi = pairs()
    ours = shading.Diffuse((0.8, 0.5, 0.2)).f(wo, wi) * wi[:, 2:3]
    theirs = mitsuba_eval({"type": "diffuse", "reflectance": rgb((0.8, 0.5, 0.2))}, wo, wi)
    assert max_relative(ours, theirs) < FLOAT32_TOLERANCE


@pytest.mark.parametrize("au, av, eta, k", [(0.3, 0.3, (0.2, 0.9, 1.1), (3.9, 2.4, 2.1)), (0.1, 0.4, None, None)])
def test_rough_conductor(au, av, eta, k):
    wo, wi = pairs()
    spec = {"type": "roughconductor", "distribution": "ggx", "alpha_u": au, "alpha_v": av}
    spec.update({"eta": rgb(eta), "k": rgb(k)} if eta else {"material": "none"})
    ours = shading.RoughConductor(alpha_u=au, alpha_v=av, eta=eta, k=k).f(wo, wi) * wi[:, 2:3]
    theirs = mitsuba_eval(spec, wo, wi)
    assert max_relative(ours * separable_over_correlated(au, av, wo, wi), theirs) < FLOAT32_TOLERANCE
    # Without the correction the masking conventions differ by this much (reported): up to ~50% at grazing.
    assert max_relative(ours, theirs) > 0.01


@pytest.mark.parametrize("transmit", [False, True])
def test_rough_dielectric(transmit):
    wo, wi = pairs(transmit=transmit)
    ours = shading.RoughDielectric(alpha=0.3, ior=1.5).f(wo, wi) * np.abs(wi[:, 2:3])
    theirs = mitsuba_eval(
        {"type": "roughdielectric", "distribution": "ggx", "alpha": 0.3, "int_ior": 1.5, "ext_ior": 1.0}, wo, wi
    )
    assert max_relative(ours * separable_over_correlated(0.3, 0.3, wo, wi), theirs) < FLOAT32_TOLERANCE


def test_smooth_dielectric_probabilities():
    # Mitsuba samples reflection with probability F (its sample's pdf); refracta's delta pdf is the same.
    bsdf = mi.load_dict({"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0})
    si = mi.SurfaceInteraction3f()
    si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
    for theta in (0.0, 30.0, 60.0, 85.0):
        wo = np.array([np.sin(np.radians(theta)), 0.0, np.cos(np.radians(theta))])
        si.wi = mi.Vector3f(*wo)
        bs, _ = bsdf.sample(mi.BSDFContext(), si, 0.0, mi.Point2f(0.5, 0.5))
        ours = shading.Dielectric(1.5).sample(wo, [0.0, 0.5, 0.5])
        assert ours.pdf[0] == pytest.approx(bs.pdf, rel=FLOAT32_TOLERANCE)
        bs_t, w_t = bsdf.sample(mi.BSDFContext(), si, 0.9999, mi.Point2f(0.5, 0.5))
        ours_t = shading.Dielectric(1.5).sample(wo, [0.9999, 0.5, 0.5])
        # Mitsuba computes in float32: ~1e-7 per component, 1e-6 with margin.
        np.testing.assert_allclose(ours_t.wi[0], [bs_t.wo[0], bs_t.wo[1], bs_t.wo[2]], atol=1e-6)
        assert ours_t.weight[0, 0] == pytest.approx(w_t[0], rel=FLOAT32_TOLERANCE)  # both 1 / eta^2 in radiance


def test_plastic():
    # Mitsuba's nonlinear=True is Weidlich & Wilkie's R / (1 - R Fbar_int) (its default divides by 1 - Fbar_int).
    wo, wi = pairs()
    ours = shading.Plastic((0.6, 0.3, 0.1)).f(wo, wi) * wi[:, 2:3]
    theirs = mitsuba_eval(
        {
            "type": "plastic",
            "diffuse_reflectance": rgb((0.6, 0.3, 0.1)),
            "int_ior": 1.5,
            "ext_ior": 1.0,
            "nonlinear": True,
        },
        wo,
        wi,
    )
    assert max_relative(ours, theirs) < FIT_TOLERANCE


def test_rough_plastic_specular_part():
    wo, wi = pairs()
    ours = shading.Plastic(0.0, alpha=0.2).f(wo, wi) * wi[:, 2:3]
    theirs = mitsuba_eval(
        {
            "type": "roughplastic",
            "distribution": "ggx",
            "alpha": 0.2,
            "diffuse_reflectance": rgb((0, 0, 0)),
            "int_ior": 1.5,
            "ext_ior": 1.0,
        },
        wo,
        wi,
    )
    assert max_relative(ours * separable_over_correlated(0.2, 0.2, wo, wi), theirs) < FLOAT32_TOLERANCE
