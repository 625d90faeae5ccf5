"""The sun over a spherical Earth (render/sun_exit_map.h): its light samples launch along the paths
that leave toward them, so surfaces get the sun's whole refracted disc from light sampling.

Before, a sample launched along its own direction left bent down by the refraction; the crescent of
the disc's launches it missed was left to BSDF samples alone, at full weight: a Lambertian ground
under a 15 deg sun was 10 % too dark (BSDF samples hardly ever find a 0.27 deg disc), and a glossy
sea sparkled with fireflies hundreds of times its neighbours."""

import numpy as np
import pytest

import refracta
from refracta import lights, shading

SUN_RADIANCE = 1e4  # [W/(m^2 sr)] a grey sun, no sky: the only light
ALBEDO = 0.5
SUN_RADIUS = np.radians(0.53 / 2.0)  # SunLight's default disc
# Shadow rays long enough to leave the standard atmosphere (86 km) at 5 deg: the path the reference
# (astronomical_refraction, to the atmosphere's top) follows.
REACH = 1.5e6  # [m]


def sunlit_scene(material, elevation_deg, half_size=5000.0):
    scene = refracta.Scene()
    scene.add_ground(0.0, half_size, material=material)
    e = np.radians(elevation_deg)
    scene.add_light(lights.SunLight((np.cos(e), np.sin(e), 0.0), SUN_RADIANCE))
    return scene


def refracted_irradiance(elevation_deg):
    """E = L * integral over launch directions whose paths leave inside the sun's disc of cos(zenith)
    d omega, the exit of a launch at apparent elevation e from astronomical_refraction (a ray traced
    from the ground to the atmosphere's top in true heights over the sphere: not the renderer's
    caster), the azimuth kept."""
    sun = np.radians(elevation_deg)
    # Refraction is smooth in elevation: traced on a coarse grid, interpolated for the quadrature.
    nodes = np.linspace(sun - 2 * SUN_RADIUS, sun + 2 * SUN_RADIUS + np.radians(0.3), 33)
    refraction = np.radians(refracta.astronomical_refraction(refracta.PhysicalAtmosphere(), np.degrees(nodes)) / 60.0)
    launch = np.linspace(nodes[0], nodes[-1], 20001)
    exit_elevation = launch - np.interp(launch, nodes, refraction)
    # The azimuth half-width of the disc at that exit elevation (spherical law of cosines).
    cos_half = (np.cos(SUN_RADIUS) - np.sin(exit_elevation) * np.sin(sun)) / (np.cos(exit_elevation) * np.cos(sun))
    half_width = np.arccos(np.clip(cos_half, -1.0, 1.0))
    integrand = 2.0 * half_width * np.sin(launch) * np.cos(launch)
    return SUN_RADIANCE * float(np.sum(0.5 * (integrand[1:] + integrand[:-1]) * np.diff(launch)))


@pytest.mark.parametrize("elevation_deg", [1.0, 2.0, 5.0, 15.0])
def test_a_lambertian_ground_gets_the_whole_refracted_sun(elevation_deg):
    scene = sunlit_scene(shading.Diffuse(ALBEDO), elevation_deg)
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere())
    camera = refracta.Camera((0.0, 3.0, 0.0), (3.0, 0.0, 0.0), vfov=20.0, width=16, height=16)  # ground only
    image = refracta.render(scene, camera, field, transport="direct", spp=4, seed=0, max_length=REACH, progress=False)
    expected = ALBEDO / np.pi * refracted_irradiance(elevation_deg)
    # Measured within 0.01 % at 5 and 15 deg, +0.04 % at 1 deg, +0.08 % at 2 deg (the disc's edge
    # through the map's interpolation; every pixel's point within 5 m of the origin, whose frame the
    # reference's is). The view's 16 px across 20 deg are coarse pixels (0.022 rad): shadow rays
    # standing for them strayed enough to put a 1 deg sun's light 2 % high until their tolerance
    # was capped (Caster::kMaxSecondarySpread).
    # 0.3 % allows for the n^2 of basic radiance (L / n^2 conserved: 0.06 % between the ground and
    # the top, which the renderer leaves out over a sphere). The refraction's own effect on E is
    # +6.6 % at 2 deg, +0.6 % at 5 deg (the disc lifted, against its flattening); the missing
    # crescent was -10 % at 15 deg and -12 % at 5 deg.
    assert image[..., 0].mean() == pytest.approx(expected, rel=3e-3)  # reason: comment above


@pytest.mark.parametrize("across_km", [20.0, 60.0])
def test_points_off_the_origins_axis_get_the_whole_refracted_sun(across_km):
    # A ground point 20-60 km across the sun's azimuth from the flat frame's origin: its paths turn
    # in azimuth as well (CurvedEarth's frame turns with the end point, ~0.06 deg at 60 km), which a
    # map of elevations alone missed (-2.2 % at 20 km, -7.5 % at 60 km with a 3 deg sun); the
    # launch is solved in elevation and azimuth. The sun's elevation there is the origin's (the
    # offset is across its azimuth), so the same reference holds. Measured +0.01 %; the tolerance
    # as above.
    elevation_deg = 3.0
    scene = sunlit_scene(shading.Diffuse(ALBEDO), elevation_deg, half_size=150e3)  # reaching the point
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere())
    z = across_km * 1e3
    camera = refracta.Camera((0.0, 3.0, z), (3.0, 0.0, z), vfov=1.0, width=16, height=16)
    image = refracta.render(scene, camera, field, transport="direct", spp=4, seed=0, max_length=REACH, progress=False)
    expected = ALBEDO / np.pi * refracted_irradiance(elevation_deg)
    assert image[..., 0].mean() == pytest.approx(expected, rel=3e-3)  # reason: comment above


def test_the_sea_under_a_low_sun_has_no_fireflies():
    # A sea of light air (2 m/s) under a 10 deg sun: its glitter from 10 m up, 16 spp, three seeds.
    # The crescent of the disc left to BSDF samples made pixels 400x the median in one seed of
    # three (16 % of the image's light above 3x its 5 x 5 neighbourhood's median) and the other two
    # 11 % dark; now the seeds' means agree within 0.02 % (measured) and no pixel stands out.
    from scipy.ndimage import median_filter

    e = 10.0
    scene = sunlit_scene(shading.Water(wind_speed=2.0), e)
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere())
    camera = refracta.Camera((0.0, 10.0, 0.0), (10.0 / np.tan(np.radians(e)), 0.0, 0.0), vfov=12.0, width=48, height=48)
    means = []
    for seed in range(3):
        image = refracta.render(
            scene, camera, field, transport="direct", spp=16, seed=seed, max_length=40000.0, progress=False
        )
        luminance = image.mean(axis=2)
        neighbourhood = median_filter(luminance, size=5)
        outstanding = np.maximum(luminance - 3.0 * neighbourhood, 0.0).sum() / luminance.sum()
        assert outstanding < 1e-3  # reason: 0.00 % measured each seed; 16 % with a firefly
        means.append(luminance.mean())
    assert np.ptp(means) / np.mean(means) < 2e-3  # reason: 0.014 % measured; 18 % before
