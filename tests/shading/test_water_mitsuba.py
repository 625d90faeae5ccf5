"""The Water surface's interface against Mitsuba 3's roughdielectric with distribution='beckmann' (an
independent renderer, scalar_rgb variant), same alpha (Cox-Munk: alpha^2 = 0.003 + 5.12e-3 U) and
the same index per RGB channel (Water.ior at 630, 532, 465 nm; Mitsuba's index is one number, so
each channel is compared with its own Mitsuba BSDF).

Conventions (SHADING.md section 0, test_06_mitsuba.py): Mitsuba's si.wi is refracta's wo and its
eval returns f |cos theta_i|. Masking: refracta uses the exact Beckmann Lambda, height-correlated
(beckmann.h); Mitsuba the separable G1(wo) G1(wi) with Walter et al. 2007's rational approximation
of G1. Values are compared after multiplying refracta's by Mitsuba's G1 G1 over refracta's G2,
which isolates D, F and the transmission Jacobian. Measured: 1.1e-5 worst relative difference
with the correction; without it up to 4.3 % (U = 12 m/s, from below, grazing pairs). Albedo (the
integral of f |cos| over the sphere, radiance transport) at 0, 45, 75, 88 degrees, U = 12 m/s:
Mitsuba's own sampler against refracta's, refracta's weights carrying the same masking correction;
measured 0.05, 0.02, 0.25, 0.48 % apart (1.5 combined standard errors at most); without the
correction refracta's albedo is up to 2.2 % higher at 88 degrees (height-correlated masking loses
less light)."""

import numpy as np
import pytest

from refracta import shading

from .conftest import direction

mi = pytest.importorskip("mitsuba")

RGB_NM = (630.0, 532.0, 465.0)  # refracta's representative wavelengths of R, G, B (thin_film.h)
FLOAT32_TOLERANCE = 5e-5  # Mitsuba's scalar_rgb is single precision: exp(-tan^2/alpha^2) and the
# transmission Jacobian lose a few ulps each (measured worst 1.1e-5)
VALUE_FLOOR = 1e-4  # below this f |cos| the relative difference is float32 noise
WINDS = (0.0, 5.0, 12.0)  # [m/s]: alpha = 0.055, 0.169, 0.254
ALBEDO_SAMPLES = 20_000
NOISE_SIGMAS = 5.0  # albedo: both estimates are Monte Carlo; 5 combined standard errors


@pytest.fixture(scope="module", autouse=True)
def scalar_rgb():
    mi.set_variant("scalar_rgb")


def mitsuba_bsdf(water, channel):
    return mi.load_dict(
        {
            "type": "roughdielectric",
            "distribution": "beckmann",
            "alpha": water.roughness,
            "int_ior": float(water.ior(RGB_NM[channel])),
            "ext_ior": 1.0,
        }
    )


def local_interaction():
    si = mi.SurfaceInteraction3f()
    si.sh_frame = mi.Frame3f(mi.Vector3f(0, 0, 1))
    si.n = mi.Vector3f(0, 0, 1)
    return si


def mitsuba_eval(bsdf, wo, wi, channel):
    si = local_interaction()
    out = []
    for o, i in zip(wo, wi):
        si.wi = mi.Vector3f(*o)
        out.append(bsdf.eval(mi.BSDFContext(), si, mi.Vector3f(*i))[channel])
    return np.array(out)


def mitsuba_g1(alpha, w):
    """Mitsuba 3's Beckmann G1 (render/microfacet.h): Walter et al. 2007's rational approximation."""
    cos2 = w[:, 2] ** 2
    tan = np.sqrt(np.maximum(0.0, 1.0 - cos2) / cos2)
    with np.errstate(divide="ignore"):
        a = np.minimum(1.0 / (alpha * tan), 1e6)  # normal incidence: a = inf, G1 = 1 (the a >= 1.6 branch)
    return np.where(a >= 1.6, 1.0, (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a))


def masking_correction(water, wo, wi):
    """Mitsuba's G1(wo) G1(wi) over refracta's height-correlated G2 (both depend on |cos| only)."""
    b = shading.Beckmann(water.roughness)
    return mitsuba_g1(water.roughness, wo) * mitsuba_g1(water.roughness, wi) / b.G(wo, np.abs(wi))


def lobe_pairs(water, below=False, n=240, seed=7):
    """Random wo (|z| >= 0.1) and wi drawn from refracta's own sampler: pairs inside the lobes,
    reflected and transmitted alike."""
    rng = np.random.default_rng(seed)
    wo = rng.normal(size=(n, 3))
    wo[:, 2] = (np.abs(wo[:, 2]) + 0.1) * (-1 if below else 1)
    wo /= np.linalg.norm(wo, axis=1, keepdims=True)
    s = water.sample(wo, rng.random((n, 3)))
    return wo[s.valid], s.wi[s.valid]


@pytest.mark.parametrize("wind", WINDS)
@pytest.mark.parametrize("below", [False, True])
def test_01_interface_values_match_roughdielectric_beckmann(wind, below):
    water = shading.Water(wind, body=False)
    wo, wi = lobe_pairs(water, below)
    transmitted = wo[:, 2] * wi[:, 2] < 0
    assert transmitted.sum() > 20 and (~transmitted).sum() > 5  # both lobes are exercised
    ours = water.f(wo, wi) * np.abs(wi[:, 2:3]) * masking_correction(water, wo, wi)[:, None]
    for c in range(3):
        theirs = mitsuba_eval(mitsuba_bsdf(water, c), wo, wi, c)
        mask = theirs > VALUE_FLOOR
        assert mask.sum() > 50
        assert np.max(np.abs(ours[mask, c] - theirs[mask]) / theirs[mask]) < FLOAT32_TOLERANCE, (c, wind, below)


def test_02_channels_use_their_own_index():
    # Per RGB channel the transmitted lobe moves with the index (n(465) > n(630)): with Mitsuba
    # at the green channel's index, the red and blue channels differ, by more than float32 noise.
    water = shading.Water(5.0, body=False)
    wo, wi = lobe_pairs(water)
    ours = water.f(wo, wi) * np.abs(wi[:, 2:3]) * masking_correction(water, wo, wi)[:, None]
    theirs = mitsuba_eval(mitsuba_bsdf(water, 1), wo, wi, 1)
    mask = theirs > VALUE_FLOOR
    for c in (0, 2):
        assert np.max(np.abs(ours[mask, c] - theirs[mask]) / theirs[mask]) > 100 * FLOAT32_TOLERANCE


def mitsuba_albedo(bsdf, wo, channel, seed=3):
    rng = np.random.default_rng(seed)
    si = local_interaction()
    si.wi = mi.Vector3f(*wo)
    w = np.empty(ALBEDO_SAMPLES)
    for k, u in enumerate(rng.random((ALBEDO_SAMPLES, 3))):
        _, weight = bsdf.sample(mi.BSDFContext(), si, float(u[0]), mi.Point2f(float(u[1]), float(u[2])))
        w[k] = weight[channel]
    return w.mean(), w.std() / np.sqrt(ALBEDO_SAMPLES)


def refracta_albedo(water, wo, channel, corrected, samples=200_000, seed=4):
    u = np.random.default_rng(seed).random((samples, 3))
    s = water.sample(np.tile(wo, (samples, 1)), u)
    w = s.weight[:, channel].copy()
    if corrected:
        v = s.valid
        w[v] *= masking_correction(water, np.tile(wo, (v.sum(), 1)), s.wi[v])
    return w.mean(), w.std() / np.sqrt(samples)


@pytest.mark.slow
@pytest.mark.parametrize("theta", [0.0, 45.0, 75.0, 88.0])
def test_03_albedo_matches_roughdielectric_beckmann(theta):
    water = shading.Water(12.0, body=False)
    wo = direction(theta)
    theirs, err_theirs = mitsuba_albedo(mitsuba_bsdf(water, 1), wo, 1)
    ours, err_ours = refracta_albedo(water, wo, 1, corrected=True)
    assert ours == pytest.approx(theirs, abs=NOISE_SIGMAS * np.hypot(err_ours, err_theirs))
    # Unchanged, refracta's masking keeps at least as much light (height-correlated G2 >= G1 G1).
    raw, err_raw = refracta_albedo(water, wo, 1, corrected=False)
    assert raw >= theirs - NOISE_SIGMAS * np.hypot(err_raw, err_theirs)
