"""Sun glitter widens with wind as Cox & Munk 1954 say: the sea's slope distribution recovered from
the glitter the way they recovered it from their photographs has the total mean-square slope
sigma^2 = 0.003 + 5.12e-3 U that the Water material is given.

Cox & Munk's inversion: a facet tilted by beta (slopes p, q) mirrors the sun of irradiance E toward
the viewer with radiance L = E F(wo.h) P(p, q) / (4 cos_o cos^4 beta) (their eq. for the glitter
radiance), so P = 4 cos_o cos^4 beta L / (E F). Here L is first the BSDF itself (sun at the zenith,
L = f E cos_i), then a render: a camera 10 m above the water looking straight down, the sun at the
zenith, the glitter's radiance per pixel; ln P fitted by a line in p^2 + q^2 gives -1 / sigma^2.
The same scene rendered by Mitsuba 3 (roughdielectric beckmann, a directional sun of the same
irradiance) gives the same glitter."""

import numpy as np
import pytest

import refracta
from refracta import lights, shading

WINDS = (0.0, 2.0, 5.0, 10.0, 15.0)  # [m/s]
# BSDF inversion on a slope grid: exact but for Smith masking G2 < 1 on the steepest facets the
# grid reaches (viewed at up to 84 degrees at 15 m/s): measured -7.4e-4 at 15 m/s, 1.6e-5 at 10.
MASKING_TOLERANCE = 2e-3
# The render's fit: each pixel averages the lobe over its footprint and the sun's 0.53-degree disc
# widens the lobe by ~(0.0046 / 2)^2 in slope^2 (1e-3 of sigma^2 at 2 m/s); pixel noise at 4 spp
# of direct sun sampling. Measured 0.17 %, 0.05 %, 0.015 % at 2, 5, 10 m/s.
RENDER_TOLERANCE = 1e-2
# The fitted P integrates to 1 when the render's radiance is the sun's: E = 1e4 W/(m^2 sr) x the disc's
# solid angle = 0.6720 W/m^2; measured 0.6712-0.6720 (footprint averaging, the fit's range).
IRRADIANCE_TOLERANCE = 1e-2
SUN_RADIANCE = 1.0e4
SUN_DIAMETER = 0.53  # [deg]


def test_01_cox_munk_slopes_and_alpha():
    for u in WINDS:
        water = shading.Water(u)
        # The same linear formula in double: rounding.
        assert water.mean_square_slope == pytest.approx(0.003 + 5.12e-3 * u, rel=1e-12)
        assert water.roughness == pytest.approx(np.sqrt(0.003 + 5.12e-3 * u), rel=1e-12)  # as above
    np.testing.assert_allclose(shading.cox_munk_mean_square_slope(np.array(WINDS)), 0.003 + 5.12e-3 * np.array(WINDS))


def bsdf_glitter_moment(wind, n=801):
    """Second moment <p^2 + q^2> of the slope density recovered from f(wo, wi = zenith sun)."""
    water = shading.Water(wind, body=False)
    sigma2 = shading.cox_munk_mean_square_slope(wind)
    limit = min(6.0 * np.sqrt(sigma2), 0.95)  # 6 sigma, or up to the viewer's horizon
    p = np.linspace(-limit, limit, n)
    pp, qq = (a.ravel() for a in np.meshgrid(p, p))
    h = np.stack([-pp, -qq, np.ones_like(pp)], 1)
    h /= np.linalg.norm(h, axis=1, keepdims=True)
    wi = np.array([0.0, 0.0, 1.0])
    wo = -wi + 2.0 * h[:, 2:3] * h  # the direction the facet h mirrors the sun into
    ok = wo[:, 2] > 1e-3
    f = water.f(wo[ok], wi)[:, 1]
    fresnel = shading.fresnel_dielectric(np.sum(wo[ok] * h[ok], 1), water.ior(532.0))  # green channel's index
    density = 4.0 * wo[ok, 2] * h[ok, 2] ** 4 * f / fresnel
    r2 = pp[ok] ** 2 + qq[ok] ** 2
    return np.sum(r2 * density) / np.sum(density), np.sum(density) * (p[1] - p[0]) ** 2


@pytest.mark.parametrize("wind", WINDS)
def test_02_bsdf_glitter_has_cox_munk_mean_square_slope(wind):
    moment, total = bsdf_glitter_moment(wind)
    sigma2 = 0.003 + 5.12e-3 * wind
    assert moment == pytest.approx(sigma2, rel=MASKING_TOLERANCE)
    assert total == pytest.approx(1.0, abs=MASKING_TOLERANCE)  # a normalised slope density


def render_glitter(wind, size=96, spp=4):
    scene = refracta.Scene()
    scene.add_ground(0.0, 2000.0, material=shading.Water(wind, body=False))
    scene.add_light(lights.SunLight((0.0, 1.0, 0.0), SUN_RADIANCE, angular_diameter=SUN_DIAMETER))
    camera = refracta.Camera((0.0, 10.0, 0.0), (0.0, 0.0, 0.0), up=(0.0, 0.0, 1.0), vfov=100.0, width=size, height=size)
    image = refracta.render(scene, camera, transport="direct", spp=spp, progress=False)
    u, v = np.meshgrid(np.arange(size) + 0.5, np.arange(size) + 0.5)
    d = np.array([camera.ray(a, b)[1] for a, b in zip(u.ravel(), v.ravel())])
    return image[..., 1].ravel(), -d


def fit_glitter(wind, image=None):
    """(sigma^2, E) from ln P = ln(E / (pi sigma^2)) - (p^2 + q^2) / sigma^2 over the glitter's pixels
    of refracta's render (or of `image`, green channel (N,), seen through the same camera)."""
    radiance, wo = render_glitter(wind)
    if image is not None:
        radiance = image
    wi = np.array([0.0, 1.0, 0.0])  # the sun at the zenith (y up)
    h = (wo + wi) / np.linalg.norm(wo + wi, axis=1, keepdims=True)
    cos_beta = h[:, 1]
    r2 = (1.0 - cos_beta**2) / cos_beta**2
    fresnel = shading.fresnel_dielectric(np.sum(wo * h, 1), shading.Water(wind).ior(532.0))
    density = radiance * 4.0 * wo[:, 1] * cos_beta**4 / fresnel
    ok = density > 1e-3 * density.max()  # the glitter, down to 1e-3 of its peak (r up to ~2.6 sigma)
    c0, c1 = np.linalg.lstsq(np.stack([np.ones(ok.sum()), r2[ok]], 1), np.log(density[ok]), rcond=None)[0]
    sigma2 = -1.0 / c1
    return sigma2, np.exp(c0) * np.pi * sigma2


@pytest.mark.parametrize("wind", [2.0, 5.0, 10.0])
def test_03_rendered_glitter_widens_as_cox_munk(wind):
    sigma2, irradiance = fit_glitter(wind)
    assert sigma2 == pytest.approx(0.003 + 5.12e-3 * wind, rel=RENDER_TOLERANCE)
    sun_irradiance = SUN_RADIANCE * np.pi * np.radians(SUN_DIAMETER / 2) ** 2
    assert irradiance == pytest.approx(sun_irradiance, rel=IRRADIANCE_TOLERANCE)


def test_04_glitter_is_wider_in_more_wind():
    widths = [fit_glitter(u)[0] for u in (2.0, 5.0, 10.0)]
    assert widths[0] < widths[1] < widths[2]
    # and by Cox & Munk's slope: 5.12e-3 per m/s between 2 and 10 m/s
    assert (widths[2] - widths[0]) / 8.0 == pytest.approx(5.12e-3, rel=2 * RENDER_TOLERANCE)


# Mitsuba's render of the same glitter at 64 spp: the total within 0.1 %. Its 4-spp total spreads
# 0.08 % (sd over 6 seeds at 2 m/s), ours 0.025 %; at 64 spp Mitsuba's 0.024 %, and the sun's disc
# against Mitsuba's directional (delta) sun moves ours 0.02 % (64-spp means): 0.1 % is ~3 sd.
# Per pixel, the mean absolute difference is 4 spp noise plus the disc, measured 2.4 %, 1.5 %,
# 1.0 % of the total at 2, 5, 10 m/s with both at 4 spp (an upper bound with Mitsuba at 64).
MITSUBA_TOTAL_TOLERANCE = 1e-3
MITSUBA_PIXEL_TOLERANCE = 5e-2


@pytest.mark.parametrize("wind", [2.0, 5.0, 10.0])
def test_05_mitsuba_renders_the_same_glitter(wind):
    mi = pytest.importorskip("mitsuba")
    mi.set_variant("scalar_rgb")
    size = 96
    water = shading.Water(wind, body=False)
    irradiance = SUN_RADIANCE * np.pi * np.radians(SUN_DIAMETER / 2) ** 2
    scene = mi.load_dict(
        {
            "type": "scene",
            "integrator": {"type": "direct", "emitter_samples": 1, "bsdf_samples": 0},
            "sensor": {
                "type": "perspective",
                "fov": 100.0,
                "fov_axis": "y",
                "to_world": mi.ScalarTransform4f().look_at(origin=[0, 10, 0], target=[0, 0, 0], up=[0, 0, 1]),
                "film": {"type": "hdrfilm", "width": size, "height": size, "rfilter": {"type": "box"}},
                "sampler": {"type": "independent", "sample_count": 64},
            },
            "sea": {
                "type": "rectangle",
                "to_world": mi.ScalarTransform4f().rotate([1, 0, 0], -90).scale(1000.0),
                "bsdf": {
                    "type": "roughdielectric",
                    "distribution": "beckmann",
                    "alpha": water.roughness,
                    "int_ior": float(water.ior(532.0)),
                    "ext_ior": 1.0,
                },
            },
            "sun": {
                "type": "directional",
                "direction": [0, -1, 0],
                "irradiance": {"type": "rgb", "value": [irradiance] * 3},
            },
        }
    )
    theirs = np.array(mi.render(scene))[..., 1]
    ours = render_glitter(wind, size)[0].reshape(size, size)
    assert theirs.sum() == pytest.approx(ours.sum(), rel=MITSUBA_TOTAL_TOLERANCE)
    assert np.abs(theirs - ours).sum() < MITSUBA_PIXEL_TOLERANCE * ours.sum()
    sigma2, _ = fit_glitter(wind, theirs.ravel())
    assert sigma2 == pytest.approx(0.003 + 5.12e-3 * wind, rel=RENDER_TOLERANCE)
