"""Spectral rendering end to end: white under D65, RGB against spectral, the physical sky's sun and
sky in both modes, and dispersion -- of the air (the mirage boundary per wavelength) and of glass
(a BK7 prism's spectrum), each against an independent prediction."""

import numpy as np
import pytest

import refracta
from refracta import _core, shading, spectrum

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Y of linear sRGB (IEC 61966-2-1)
# Monte Carlo bounds: a mean is compared with 4.5 standard errors estimated from the image.
SIGMAS = 4.5
# The Jakob-Hanika fit's RGB -> spectrum -> RGB round trip (refracta.spectrum tests: 7e-5) for
# reflectances, twice over for a product, plus the float32 image.
ROUND_TRIP = 5e-4
# RGB sky = the table's 10 nm quadrature of the spectrum, spectral = its linear interpolant
# sampled at hero wavelengths: they differ by the quadrature error (measured 7e-4 in Y).
SKY_QUADRATURE = 2e-3


def std_error(values):
    """Standard error of the mean of independent pixel values (axis 0)."""
    values = np.asarray(values, dtype=float)
    return values.std(axis=0, ddof=1) / np.sqrt(values.shape[0])


def downward_camera(size=24, vfov=20.0):
    """A camera 1 m above the ground looking straight down: every pixel sees the ground."""
    return refracta.Camera((0.0, 1.0, 0.0), (0.0, 0.0, 1e-3), (1.0, 0.0, 0.0), vfov, size, size)


def ground_scene(albedo, environment=(1.0, 1.0, 1.0)):
    scene = refracta.Scene()
    scene.set_environment(environment)
    scene.add_ground(0.0, 200.0, material=shading.Diffuse(albedo))
    return scene


# ---------------------------------------------------------------- white, colours


def test_white_diffuse_under_a_white_environment_renders_white():
    # Environment RGB (1, 1, 1) is D65 scaled to Y = 1 (Color.illuminant); a reflectance of 1 under
    # it has the XYZ of D65 / integral(y): sRGB (1, 1, 1) by the matrix's white point (SHADING.md 7).
    scene, camera = ground_scene((1.0, 1.0, 1.0)), downward_camera()
    rgb = refracta.render(scene, camera, None, spp=4, progress=False)
    # The constant environment is sampled by cosine: f cos / pdf = 1 exactly, every sample.
    np.testing.assert_allclose(rgb, 1.0, rtol=0, atol=1e-6)
    spectral = refracta.render(scene, camera, None, spp=16, spectral=True, progress=False).reshape(-1, 3)
    mean, error = spectral.mean(axis=0), std_error(spectral)
    assert np.all(np.abs(mean - 1.0) <= SIGMAS * error + ROUND_TRIP), (mean, error)
    assert np.all(error < 0.02)  # the estimate is usefully tight (about 0.007 measured)


@pytest.mark.parametrize("albedo", [(0.8, 0.2, 0.1), (0.1, 0.6, 0.3), (0.2, 0.3, 0.9), (0.5, 0.5, 0.5)])
def test_coloured_diffuse_agrees_between_rgb_and_spectral(albedo):
    # Reflectance s(lambda) (Jakob & Hanika 2019) times the D65 environment: its sRGB is the albedo
    # itself, up to the round trip, as the RGB render gives exactly.
    scene, camera = ground_scene(albedo, environment=(0.9, 0.9, 0.9)), downward_camera(16)
    rgb = refracta.render(scene, camera, None, spp=4, progress=False).reshape(-1, 3)
    # The RGB path's white furnace: float32 pixels, a few ulps.
    np.testing.assert_allclose(rgb, np.broadcast_to(0.9 * np.array(albedo), rgb.shape), rtol=1e-6)
    spectral = refracta.render(scene, camera, None, spp=32, spectral=True, seed=3, progress=False).reshape(-1, 3)
    mean, error = spectral.mean(axis=0), std_error(spectral)
    assert np.all(np.abs(mean - rgb.mean(axis=0)) <= SIGMAS * error + ROUND_TRIP), (mean, rgb.mean(axis=0), error)


# ---------------------------------------------------------------- the physical sky in scenes


def sky_scene(elevation_deg):
    scene = refracta.Scene()
    e = np.radians(elevation_deg)
    scene.set_physical_sky((np.cos(e), np.sin(e), 0.0))
    scene.add_ground(0.0, 200.0, material=shading.Diffuse((1.0, 1.0, 1.0)))
    return scene


@pytest.mark.parametrize("elevation", [60.0, 5.0])
def test_physical_sky_rgb_and_spectral_agree_in_luminance(elevation):
    scene, camera = sky_scene(elevation), downward_camera()
    rgb = refracta.render(scene, camera, None, spp=8, progress=False).reshape(-1, 3) @ LUMINANCE
    spectral = refracta.render(scene, camera, None, spp=32, spectral=True, progress=False).reshape(-1, 3) @ LUMINANCE
    difference = abs(spectral.mean() - rgb.mean())
    bound = SIGMAS * np.hypot(std_error(spectral), std_error(rgb)) + SKY_QUADRATURE * rgb.mean()
    assert difference <= bound, (elevation, rgb.mean(), spectral.mean(), bound)


def test_physical_sky_sun_is_the_extinguished_solar_spectrum():
    # The scene's sun carries PhysicalSky.sun_radiance: its irradiance at normal incidence is
    # E T (W/m^2 nm), here as the RGB of that spectrum (Y-weighted mean, as Color.illuminant).
    e = np.radians(30.0)
    scene = refracta.Scene()
    scene.set_physical_sky((np.cos(e), np.sin(e), 0.0))
    suns = [light for light in scene.lights if "Sun" in repr(light)]
    assert len(suns) == 1 and len(scene.lights) == 2
    sky = spectrum.PhysicalSky((np.cos(e), np.sin(e), 0.0))
    lam = np.arange(360.0, 831.0, 10.0)
    expected = spectrum.spectrum_to_rgb(lam, sky.sun_radiance(lam))
    direction = np.array([[np.cos(e), np.sin(e), 0.0]])
    # The same spectrum integrated by C++ and numpy: float rounding of the sun's radiance.
    np.testing.assert_allclose(suns[0].Le(direction)[0], expected, rtol=1e-6)
    # The sun below the horizon leaves only the sky.
    scene.set_physical_sky((1.0, -0.2, 0.0))
    assert len(scene.lights) == 1


def test_a_low_sun_turns_the_ground_orange():
    camera = downward_camera(16)
    ratios, sun_ratios = {}, {}
    for elevation in (60.0, 5.0):
        rgb = refracta.render(sky_scene(elevation), camera, None, spp=8, progress=False).reshape(-1, 3).mean(axis=0)
        ratios[elevation] = rgb[0] / rgb[2]
        e = np.radians(elevation)
        sun = spectrum.PhysicalSky((np.cos(e), np.sin(e), 0.0)).sun_radiance_rgb()
        sun_ratios[elevation] = sun[0] / sun[2]
    # The sunlight reddens over ~11 air masses (Rayleigh extinction): its R/B grows several-fold.
    assert sun_ratios[5.0] > 2.0 * sun_ratios[60.0], sun_ratios
    # The white ground, lit by that sun and the sky: with the sky's multiple scattering (Hillaire
    # 2020) the bluish skylight on the horizontal ground at a 5 deg sun balances the reddened sun:
    # R/B 1.28 at both elevations measured (single scattering alone gave 1.33 and 1.66); it must not
    # turn bluer than under a high sun (8 spp noise on the mean: < 0.5 %, 3 % allowed).
    assert ratios[5.0] > 0.97 * ratios[60.0], ratios


@pytest.mark.parametrize(
    "bad",
    [
        dict(sun_direction=(0.0, 0.0, 0.0)),
        dict(aerosol=-1.0),
        dict(ground_albedo=2.0),
        dict(sun_angular_diameter=0.0),
        dict(limb_darkening=1.5),
        dict(scale=-1.0),
        dict(scale=float("nan")),
    ],
)
def test_set_physical_sky_rejects_bad_input(bad):
    arguments = dict(sun_direction=(0.0, 1.0, 0.0))
    arguments.update(bad)
    with pytest.raises(ValueError):
        refracta.Scene().set_physical_sky(**arguments)


def test_physical_sky_scale_multiplies_sky_and_sun():
    camera = downward_camera(8)
    base = refracta.render(sky_scene(40.0), camera, None, spp=4, progress=False)
    scene = refracta.Scene()
    e = np.radians(40.0)
    scene.set_physical_sky((np.cos(e), np.sin(e), 0.0), scale=0.25)
    scene.add_ground(0.0, 200.0, material=shading.Diffuse((1.0, 1.0, 1.0)))
    scaled = refracta.render(scene, camera, None, spp=4, progress=False)
    np.testing.assert_allclose(scaled, 0.25 * base, rtol=1e-5)  # same seeds, same samples


# ---------------------------------------------------------------- dispersion of the air

EYE = 1.4
# Bisection of the critical depression and the stratified tracer: 1e-12 rad.
ANGLE_TOL = 1e-11


def hot_road():
    return refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)


def critical_depression_bouguer(field):
    """theta_c = arccos(n(0) / n(eye)) (Bouguer's invariant: the ray that grazes the ground)."""
    n_ground, n_eye = field.ior(np.array([[0.0, 0.0, 0.0], [0.0, EYE, 0.0]]))
    return np.arccos(n_ground / n_eye)


def critical_depression_traced(field):
    """The depression below which rays from the eye reach the ground, by bisection on trace_ray."""

    def reaches_ground(depression):
        path = refracta.trace_ray(
            field,
            (0.0, EYE, 0.0),
            (np.cos(depression), -np.sin(depression), 0.0),
            trace="stratified",
            tol=1e-8,
            max_length=3000.0,
            stop_height=0.0,
        )
        return path.stop == "stop_height"

    lo, hi = 1e-3, 1e-2
    assert not reaches_ground(lo) and reaches_ground(hi)
    while hi - lo > 1e-13:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if reaches_ground(mid) else (mid, hi)
    return 0.5 * (lo + hi)


def test_dispersion_scale_is_the_ciddor_k_ratio():
    # ORACLES.md: K = 7.978e-5 (450 nm), 7.901e-5 (550), 7.858e-5 (650) K/hPa; (n - 1) rises 1.5 %
    # from 650 to 450 nm. K is quoted to 4 digits: 1e-4 relative.
    assert _core.air_dispersion_scale(450.0) == pytest.approx(7.978 / 7.901, rel=1e-4)
    # K quoted to 4 digits (comment above).
    assert _core.air_dispersion_scale(650.0) == pytest.approx(7.858 / 7.901, rel=1e-4)
    # 1.015 to 4 digits: 1e-3 is two units of its last digit.
    assert _core.air_dispersion_scale(450.0, 650.0) == pytest.approx(1.015, abs=1e-3)
    assert _core.air_dispersion_scale(550.0) == 1.0
    with pytest.raises(ValueError, match="wavelength"):
        _core.air_dispersion_scale(100.0)


def test_dispersed_field_is_the_field_at_that_wavelength():
    # For dry air Edlen's wavelength term multiplies the whole of n - 1: the wrapper at 450 nm equals
    # PhysicalAtmosphere(wavelength=450) to rounding, index and gradient, curved Earth included.
    field = hot_road()
    points = np.array([[0.0, h, 0.0] for h in (0.0, 0.05, 0.3, 1.4, 100.0, 5000.0)])
    for wavelength in (380.0, 450.0, 650.0, 780.0):
        wrapped = _core.dispersed_field(field, wavelength)
        direct = field.with_params(wavelength=wavelength)
        # n itself is rounded to 2.2e-16 (one ulp of 1): 1.3e-12 of the 1.7e-4 left at 5 km.
        np.testing.assert_allclose(wrapped.ior(points) - 1.0, direct.ior(points) - 1.0, rtol=1e-12, atol=2.3e-16)
        # As n above: 1e-12 relative; 1e-20 where a gradient component is 0.
        np.testing.assert_allclose(wrapped.grad_ior(points), direct.grad_ior(points), rtol=1e-12, atol=1e-20)
        assert wrapped.height_only
        earth = _core.dispersed_field(refracta.CurvedEarth(field), wavelength)
        assert earth.type_name == "CurvedEarth"
        # The same field wrapped twice: double rounding.
        np.testing.assert_allclose(earth.ior(points), refracta.CurvedEarth(direct).ior(points), rtol=1e-15)
    assert _core.field_reference_wavelength(field.with_params(wavelength=600.0)) == 600.0
    assert _core.field_reference_wavelength(refracta.LogisticProfile()) == 550.0
    assert _core.dispersed_field(field, 550.0) is field
    with pytest.raises(ValueError, match="scale"):
        _core.DispersedField(field, 0.0)


def test_a_dispersed_field_knows_its_wavelength():
    # A trial: dispersed to 450 nm, the field said 550 (its base's parameter), so dispersing it again
    # scaled from 550 and astronomical_refraction(wavelength=650) came out 0.35' high.
    import pickle

    field = hot_road()
    blue = _core.dispersed_field(field, 450.0)
    assert _core.field_reference_wavelength(blue) == 450.0 and blue.params["wavelength"] == 450.0
    assert "wavelength=450" in repr(blue)
    points = np.array([[0.0, h, 0.0] for h in (0.0, 0.3, 100.0)])
    for wavelength in (550.0, 650.0):
        again = _core.dispersed_field(blue, wavelength)
        direct = field.with_params(wavelength=wavelength)
        # Two scales' product against one: a few roundings of n - 1 (~1e-4), well inside 1e-12.
        np.testing.assert_allclose(again.ior(points) - 1.0, direct.ior(points) - 1.0, rtol=1e-12, atol=2.3e-16)
    # Its wavelength parameter is its own: set it, and the scale over the base follows.
    green = blue.with_params(wavelength=500.0)
    expected = field.with_params(wavelength=500.0).ior(points) - 1.0
    # As above: one scale against the air formula at 500 nm, rounding of n - 1 (~1e-4) far inside 1e-12.
    np.testing.assert_allclose(green.ior(points) - 1.0, expected, rtol=1e-12, atol=2.3e-16)
    assert _core.field_reference_wavelength(_core.dispersed_field(refracta.CurvedEarth(field), 450.0)) == 450.0
    copy = pickle.loads(pickle.dumps(blue))
    assert _core.field_reference_wavelength(copy) == 450.0 and np.array_equal(copy.ior(points), blue.ior(points))
    # The earlier pickle state (base, scale) still reads: the wavelength then unknown (the base's).
    base, scale, _ = blue.__getstate__()
    older = _core.DispersedField.__new__(_core.DispersedField)
    older.__setstate__((base, scale))
    assert np.array_equal(older.ior(points), blue.ior(points)) and older.params["wavelength"] == 550.0
    # A reference of the caller's (not the field's own 550): the scale is K(450) / K(600), so the
    # wavelength 450 would misstate it; the parameters stay the base's, and an edit keeps the scale.
    odd = _core.dispersed_field(field, 450.0, reference=600.0)
    assert odd.params["wavelength"] == 550.0 and odd.with_params(t_ground=288.15).scale == odd.scale
    # The height-only part (of air with hot spots) keeps it: a spectral render's index floors use it.
    spot = refracta.HotSpot(300.0, 0.0, 50.0, 5.0, footprint="compact")
    with_spot = _core.dispersed_field(refracta.PhysicalAtmosphere(**field.params, hot_spots=[spot]), 450.0)
    assert _core.field_reference_wavelength(with_spot.height_only_part) == 450.0


def test_mirage_boundary_moves_with_wavelength_as_the_k_ratio_predicts():
    field = hot_road()
    traced = {lam: critical_depression_traced(_core.dispersed_field(field, lam)) for lam in (450.0, 650.0)}
    for lam, theta in traced.items():
        # trace_ray through the wrapper follows Bouguer's invariant of the field at that wavelength.
        assert theta == pytest.approx(critical_depression_bouguer(field.with_params(wavelength=lam)), abs=ANGLE_TOL)
    # theta_c ~ sqrt(2 dn): the ratio is sqrt(K(450)/K(650)) to the small-angle approximation
    # (theta_c^2 / 12 relative, 2e-6 here).
    ratio = np.sqrt(_core.air_dispersion_scale(450.0, 650.0))
    # 5x the small-angle error theta_c^2 / 12 = 2e-6 (comment above).
    assert traced[450.0] / traced[650.0] == pytest.approx(ratio, rel=1e-5)
    assert traced[450.0] - traced[650.0] > 3e-5  # blue reaches 0.19 arcmin lower (measured 3.26e-5 rad)


def edge_integrals(rows, depression_edges):
    """Integral over the window of each channel's value [rad]: rows (H, 3) by pixel rows."""
    return (rows * np.diff(depression_edges)[:, None]).sum(axis=0)


def channel_weights(lam):
    """Each sRGB channel's share of D65 white per 1 nm at lam: sum over lam is 1 for each."""
    xyz = spectrum.cie_xyz(lam) * spectrum.d65(lam, normalised=True)[:, None] / spectrum.cie_y_integral()
    return np.array([spectrum.xyz_to_linear_srgb(v) for v in xyz])  # (M, 3)


def test_spectral_render_shows_the_mirage_colour_fringe():
    # A white sky over a black road seen through the hot layer: at depression d the sky is seen at
    # the wavelengths whose critical depression exceeds d, so the boundary is a spectrum -- red
    # first, a blue rim lowest. The integral of each channel over the rows is the window's top
    # plus the channel-weighted mean boundary: predicted from Bouguer's invariant with Edlen's index
    # at each wavelength (PhysicalAtmosphere(wavelength=...), not the wrapper), measured in the render.
    field = hot_road()
    lam = np.arange(360.0, 831.0, 1.0)
    theta_c = np.array([critical_depression_bouguer(field.with_params(wavelength=wl)) for wl in lam])
    weights = channel_weights(lam)
    height, width, pixel = 48, 8, 2.5e-6  # rows, columns, pixel angle [rad]
    centre = 0.5 * (theta_c[lam == 450.0][0] + theta_c[lam == 650.0][0])
    camera = refracta.Camera(
        (0.0, EYE, 0.0),
        (1000.0 * np.cos(centre), EYE - 1000.0 * np.sin(centre), 0.0),
        (0.0, 1.0, 0.0),
        np.degrees(height * pixel),
        width,
        height,
    )
    edges = np.array([-np.arcsin(camera.ray(width / 2, v)[1][1]) for v in range(height + 1)])
    assert edges[0] < theta_c.min() and edges[-1] > theta_c.max()  # the whole fringe is in view
    scene = refracta.Scene()
    scene.add_ground(0.0, 40000.0, material=shading.Diffuse((0.0, 0.0, 0.0)))
    scene.set_environment((1.0, 1.0, 1.0))
    # Tight paths: a 1e-5 m sagitta moves a grazing ray's boundary by ~2e-7 rad (dn/dh at the road
    # 9e-5 /m over sin theta_c), well under the fringe's 8e-5 rad.
    options = dict(tol=1e-7, sagitta=1e-5, max_length=1000.0, progress=False)
    image = refracta.render(scene, camera, field, spp=64, spectral=True, seed=5, **options)
    rows = image.mean(axis=1)
    measured = edges[0] + edge_integrals(rows, edges)
    predicted = edges[0] + (weights * (np.clip(theta_c, edges[0], edges[-1]) - edges[0])[:, None]).sum(axis=0)
    error = np.sqrt((std_error(np.transpose(image, (1, 0, 2))) ** 2 * np.diff(edges)[:, None] ** 2).sum(axis=0))
    assert np.all(np.abs(measured - predicted) <= SIGMAS * error + 1e-6), (measured, predicted, error)
    # Blue's boundary lies lower than red's by about theta_c(450) - theta_c(650).
    assert predicted[2] - predicted[0] > 2e-5
    # The predicted gap (about theta_c(450) - theta_c(650)) exceeds 2e-5 rad.
    assert measured[2] - measured[0] > 2e-5, measured
    # The rim: between red's and blue's critical depressions the pixels are blue, not red.
    rim = (edges[:-1] > theta_c[lam == 650.0][0]) & (edges[1:] < theta_c[lam == 450.0][0])
    assert rim.sum() >= 6
    # Pure blue minus red on the rim is ~1; 0.5 tells blue from a grey edge.
    assert rows[rim, 2].mean() - rows[rim, 0].mean() > 0.5, rows[rim]
    # RGB rendering does not disperse: the three channels share one boundary (theta_c at 550 nm).
    rgb = refracta.render(scene, camera, field, spp=4, **options).mean(axis=1)
    rgb_edges = edges[0] + edge_integrals(rgb, edges)
    # One boundary for all channels: the same rays, so equal up to float sums (< 1e-7 rad).
    assert np.ptp(rgb_edges) < 1e-7
    assert rgb_edges[0] == pytest.approx(critical_depression_bouguer(field), abs=pixel)


# ---------------------------------------------------------------- dispersion of glass

BK7 = (1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653)  # SHADING.md 7
PRISM_APEX = np.radians(60.0)
# The first-order spread dD/dn dn against the exact trace: second-order terms in the 2 deg spread
# and the render's noise; 10 %.
PRISM_FIRST_ORDER = 0.1


def sellmeier(lam_nm):
    um2 = (np.asarray(lam_nm, dtype=float) / 1000.0) ** 2
    b, c = BK7[:3], BK7[3:]
    return np.sqrt(1.0 + sum(bi * um2 / (um2 - ci) for bi, ci in zip(b, c)))


def refract(d, normal, eta):
    """Snell's law in vector form: d (..., 3) unit, normal toward the incident side, eta = n_i/n_t.
    Returns the refracted direction and the unpolarised Fresnel transmittance (Hecht 4.42-4.43)."""
    cos_i = -(d * normal).sum(axis=-1)
    sin2_t = eta**2 * (1.0 - cos_i**2)
    assert np.all(sin2_t < 1.0), "no total internal reflection on the test's paths"
    cos_t = np.sqrt(1.0 - sin2_t)
    t = eta[..., None] * d + (eta * cos_i - cos_t)[..., None] * normal
    rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    return t, 1.0 - 0.5 * (rs**2 + rp**2)


def prism_mesh(half_length=3.0):
    """A 60 deg BK7 prism, apex up at (0, 0.5), base 1 m below it, extruded along z: outward faces."""
    half_base = np.tan(0.5 * PRISM_APEX)
    corners = np.array([[0.0, 0.5], [-half_base, -0.5], [half_base, -0.5]])
    vertices = np.array([[x, y, z] for z in (-half_length, half_length) for x, y in corners])
    quads = [(0, 1, 4, 3), (1, 2, 5, 4), (2, 0, 3, 5)]
    triangles = [(0, 2, 1), (3, 4, 5)] + [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    centre = vertices.mean(axis=0)
    oriented = []
    for t in triangles:  # counter-clockwise seen from outside
        p = vertices[list(t)]
        normal = np.cross(p[1] - p[0], p[2] - p[0])
        oriented.append(t if normal @ (p.mean(axis=0) - centre) > 0 else (t[0], t[2], t[1]))
    return vertices, np.array(oriented)


def test_bk7_prism_spreads_a_white_edge_into_its_spectrum():
    # A white emitter's upper edge seen through a 60 deg BK7 prism near minimum deviation: each
    # wavelength deviates by its own Sellmeier n (blue most), so the edge becomes a spectrum. The
    # prediction traces every pixel's ray through the two faces by Snell's law with n(lambda) and
    # Fresnel transmission (paths of two refractions: max_depth 2), weighs wavelengths by each
    # channel's share of D65, and is compared with the spectral render row by row as integrals.
    normal_left = np.array([-np.cos(0.5 * PRISM_APEX), np.sin(0.5 * PRISM_APEX), 0.0])
    normal_right = np.array([np.cos(0.5 * PRISM_APEX), np.sin(0.5 * PRISM_APEX), 0.0])
    apex = np.array([0.0, 0.5, 0.0])
    incidence = np.arcsin(sellmeier(550.0) * np.sin(0.5 * PRISM_APEX))  # minimum deviation at 550 nm
    elevation = incidence - 0.5 * PRISM_APEX
    forward = np.array([np.cos(elevation), np.sin(elevation), 0.0])
    eye = np.array([-0.5 * np.tan(0.5 * PRISM_APEX), 0.0, 0.0]) - 3.0 * forward  # aimed at the left face's middle
    wall_x, wall_height, wall_half_width = 1000.0, 150.0, 50.0  # far: the edge's parallax is 1 %

    def trace(origins, dirs, lam):
        """(..., 3) rays and (L,) wavelengths -> height on the wall (..., L) and transmittance."""
        n = sellmeier(lam)
        shape = dirs.shape[:-1] + (lam.size,)
        d = np.broadcast_to(dirs[..., None, :], shape + (3,))
        t = ((apex - origins) @ normal_left) / (dirs @ normal_left)
        p = np.broadcast_to((origins + t[..., None] * dirs)[..., None, :], shape + (3,))
        assert np.all(np.abs(p[..., 1]) < 0.45) and np.all(np.abs(p[..., 2]) < 2.5)  # on the face
        d, t1 = refract(d, normal_left, np.broadcast_to(1.0 / n, shape))
        t = ((apex - p) @ normal_right) / (d @ normal_right)
        p = p + t[..., None] * d
        assert np.all(np.abs(p[..., 1]) < 0.45) and np.all(np.abs(p[..., 2]) < 2.5)
        d, t2 = refract(d, -normal_right, np.broadcast_to(n, shape))
        p = p + ((wall_x - p[..., 0]) / d[..., 0])[..., None] * d
        return p[..., 1], p[..., 2], t1 * t2

    # The wall's edge where the 550 nm ray through the face middles lands: it sits mid-image.
    edge_y = float(trace(eye, forward, np.array([550.0]))[0][0])
    height, width = 64, 8
    camera = refracta.Camera(tuple(eye), tuple(eye + forward), (0.0, 1.0, 0.0), 4.0, width, height)
    scene = refracta.Scene()
    vertices, triangles = prism_mesh()
    scene.add_mesh(vertices, triangles, material=shading.Dielectric(sellmeier=BK7))
    low, w = edge_y - wall_height, wall_half_width
    wall = np.array([[wall_x, low, w], [wall_x, edge_y, w], [wall_x, edge_y, -w], [wall_x, low, -w]])
    scene.add_mesh(wall, np.array([[0, 1, 2], [0, 2, 3]]), emission=(1.0, 1.0, 1.0))
    image = refracta.render(scene, camera, None, spp=64, max_depth=2, spectral=True, seed=11, progress=False)

    # The prediction over each pixel: 16 sub-rows x 2 sub-columns, 2 nm steps.
    lam = np.arange(360.0, 831.0, 2.0)
    weights = channel_weights(lam) * 2.0
    sub = 16
    vs = (np.arange(height * sub) + 0.5) / sub
    us = np.array([(x + f) for x in range(width) for f in (0.25, 0.75)])
    dirs = np.array([[camera.ray(u, v)[1] for u in us] for v in vs])
    y, z, transmittance = trace(eye, dirs, lam)
    lit = (
        (y < edge_y) & (y > edge_y - wall_height) & (np.abs(z) < wall_half_width)
    ) * transmittance  # (rows, columns, L)
    predicted_rows = (lit @ weights).mean(axis=1).reshape(height, sub, 3).mean(axis=1)
    edges = np.array([np.arcsin(camera.ray(width / 2, v)[1][1]) for v in range(height + 1)])
    step = np.abs(np.diff(edges))[:, None]
    rows = image.mean(axis=1)
    measured, predicted = (rows * step).sum(axis=0), (predicted_rows * step).sum(axis=0)
    error = np.sqrt((std_error(np.transpose(image, (1, 0, 2))) ** 2 * step**2).sum(axis=0))
    quadrature = step.max() / sub / 2  # midpoint rule of each wavelength's step across a pixel
    assert np.all(np.abs(measured - predicted) <= SIGMAS * error + quadrature), (measured, predicted, error)
    # The spectrum is spread: blue deviates most, so its lit region reaches higher in the image.
    # To first order the edges differ by dD/dn (n_B - n_R), dD/dn = 2 sin(A/2) / cos(i) at minimum
    # deviation, n_B and n_R the channels' D65-weighted mean indices (0.0126 rad for this sRGB B
    # and R; 0.0166 rad between 450 and 650 nm).
    n_mean = (weights * sellmeier(lam)[:, None]).sum(axis=0) / weights.sum(axis=0)
    spread = 2.0 * np.sin(0.5 * PRISM_APEX) / np.cos(incidence) * (n_mean[2] - n_mean[0])
    lit_full = predicted_rows[-1]  # the bottom row sees the wall at every wavelength
    bottom = image[-4:].reshape(-1, 3)
    assert np.all(np.abs(bottom.mean(axis=0) - lit_full) <= SIGMAS * std_error(bottom)), (bottom.mean(axis=0), lit_full)
    centroid = measured / lit_full  # edge integrals as angles below the top of the image
    assert centroid[2] - centroid[0] == pytest.approx(spread, rel=PRISM_FIRST_ORDER), (centroid, spread)


def box_over_the_hot_road():
    """A box 80 m down a green field under a white sky, seen at eye height through 1.5 deg (24 x 12
    pixels): the horizon's mirage and the box's edges, where a dispersive ray's end is most sensitive."""
    scene = refracta.Scene()
    scene.add_ground(0.0, 4000.0, material=shading.Diffuse((0.3, 0.5, 0.2)))
    scene.add_box((80.0, 1.0, 0.0), (4.0, 2.0, 4.0), kd=(0.8, 0.2, 0.1))
    scene.set_environment((1.0, 1.0, 1.0))
    camera = refracta.Camera((0.0, EYE, 0.0), (100.0, EYE - 0.3, 0.0), vfov=1.5, width=24, height=12)
    return scene, camera


def test_dispersive_render_does_not_depend_on_threads_tiles_or_bounds():
    # A pool of casters and integrators, each retuned to the hero wavelength of the sample that holds
    # it (render/hero_casters.h): which caster or thread serves a sample must change nothing.
    scene, camera = box_over_the_hot_road()
    options = dict(spectral=True, spp=4, max_length=1000.0, progress=False)
    whole = refracta.render(scene, camera, hot_road(), **options)
    threads = refracta.get_threads()
    try:
        refracta.set_threads(1)
        single = refracta.render(scene, camera, hot_road(), **options)
    finally:
        refracta.set_threads(threads)
    tiled = refracta.render(scene, camera, hot_road(), tile=5, **options)
    part = refracta.render(scene, camera, hot_road(), pixel_bounds=(6, 2, 20, 10), **options)
    np.testing.assert_array_equal(whole, single)
    np.testing.assert_array_equal(whole, tiled)
    np.testing.assert_array_equal(whole[2:10, 6:20], part)


def test_spectral_eye_tables_serve_camera_rays_as_tracing_does():
    # 24 x 12 pixels at 64 spp: enough camera rays for the eye's tables at 16 dispersion scales
    # (render/hero_casters.h SpectralEyeTables), each sample's ray interpolated between the two
    # scales either side of its hero's where their ends agree to a quarter pixel, else traced.
    scene, camera = box_over_the_hot_road()
    options = dict(spectral=True, spp=64, max_length=1000.0, progress=False)
    tables = refracta.render(scene, camera, hot_road(), **options)
    traced = refracta.render(scene, camera, hot_road(), table=False, **options)
    # Paths within a quarter pixel of the traced ones move a sample across an edge (the horizon's
    # mirage, the image's sides) only where the edge passes within a quarter pixel of it; a spectral
    # sample's colour swings several times its pixel's mean, so one such sample of 64 moves its
    # pixel by ~0.1-0.3. Measured: 1.7 % of the pixels off by more than 1e-3 of the maximum, the
    # mean difference 0.6 % of the mean (the green flash at 64 x 64, 48 spp: 3e-5).
    difference = np.abs(np.asarray(tables) - np.asarray(traced))
    assert np.mean(difference.max(axis=2) > 1e-3 * np.max(traced)) <= 0.03  # edge pixels: 1.7 % measured
    assert np.mean(difference) <= 0.01 * np.mean(traced)  # 0.6 % measured, from those edge samples
    threads = refracta.get_threads()
    try:
        refracta.set_threads(1)
        single = refracta.render(scene, camera, hot_road(), tile=5, **options)
    finally:
        refracta.set_threads(threads)
    np.testing.assert_array_equal(tables, single)


def jackknife_colour(pixels):
    """Colour per unit luminance of the pixels (N, 3) together -- their summed rgb over their summed
    Y -- and its jackknife standard error (leaving out one pixel at a time: independent samples)."""
    total = pixels.sum(axis=0)
    leave_out = (total - pixels) / (total @ LUMINANCE - pixels @ LUMINANCE)[:, None]
    n = len(pixels)
    return total / (total @ LUMINANCE), np.sqrt((n - 1) / n * ((leave_out - leave_out.mean(axis=0)) ** 2).sum(axis=0))


def test_hero_wavelengths_leave_a_dispersion_free_disc_grey_at_its_edges():
    # Issue 19 section 5, the green flash's rim: is a sample's hero wavelength independent of where
    # it falls in its pixel (render/film.h: the correlated multi-jittered position, then the
    # wavelength, from one generator)? If it were not, the samples of an edge pixel that land on a
    # disc would carry a biased mix of wavelengths and every edge would be coloured, left and right
    # too. An equal-energy sun through uniform air (LinearSquaredProfile with alpha = 0: the
    # dispersive path, one hero per sample, but no ray bends at any wavelength): its edge pixels --
    # chosen by the disc's geometry, not by their brightness, which would select on the sampled
    # wavelengths -- must have the colour of the equal-energy spectrum, as its inside does. A hero
    # drawn from the upper half of the range wherever a sample lies right of its pixel's centre
    # would give the left edge R / Y ~ 5.3 instead of 1.2.
    size, radius = 48, 0.265  # [px], the disc's angular radius [deg]
    elevation = np.radians(5.0)
    sun = np.array([np.cos(elevation), np.sin(elevation), 0.0])
    scene = refracta.Scene()
    scene.set_sun(sun, np.ones(2), angular_diameter=2 * radius, wavelengths=np.array([360.0, 830.0]))
    eye = np.array([0.0, 2.0, 0.0])
    camera = refracta.Camera(eye, eye + sun, vfov=0.7, width=size, height=size)
    uniform_air = refracta.LinearSquaredProfile(alpha=0.0)
    image = refracta.render(scene, camera, uniform_air, spectral=True, spp=256, max_length=1e4, progress=False)
    # A pixel is inside when its four corners are (the disc is convex), on the edge when some are.
    corners = np.array([[camera.ray(u, v)[1] for u in range(size + 1)] for v in range(size + 1)])
    inside = np.degrees(np.arccos(np.clip(corners @ sun, -1.0, 1.0))) < radius
    count = inside[:-1, :-1].astype(int) + inside[1:, :-1] + inside[:-1, 1:] + inside[1:, 1:]
    edge = (count > 0) & (count < 4)
    lam = np.arange(360.0, 831.0, 1.0)
    white = np.array([spectrum.xyz_to_linear_srgb(v) for v in spectrum.cie_xyz(lam)]).sum(axis=0)
    white /= white @ LUMINANCE  # the equal-energy spectrum's linear sRGB per unit Y: (1.205, 0.948, 0.909)
    y, x = np.mgrid[0:size, 0:size] + 0.5 - size / 2
    parts = {"inside": count == 4, "left": edge & (x < -np.abs(y)), "right": edge & (x > np.abs(y))}
    parts.update({"top": edge & (y < -np.abs(x)), "bottom": edge & (y > np.abs(x))})
    for name, part in parts.items():
        assert part.sum() >= 30, name  # 36 edge pixels a side, 968 inside
        colour, error = jackknife_colour(image[part])
        # One standard error is 0.6 % of R / Y inside, 4-6 % on an edge's 36 pixels; measured within 1.2.
        assert np.all(np.abs(colour - white) <= SIGMAS * error), (name, colour, white, error)


# The green flash's squeezed sun (python -m refracta demo, frame 2: examples.green_flash with the sun's
# centre 0.74 deg below the true horizon, 0.7 deg over 512 px): the eye 4 m over a sea 3 K warmer
# than the air, a spherical Earth, paths of up to 1500 km.
FLASH_EYE = 4.0  # [m]
FLASH_SIZE, FLASH_VFOV, FLASH_LOOK = 512, 0.7, -0.05  # [px], [deg], [deg]
FLASH_SUN, SUN_RADIUS = -0.74, 0.265  # [deg]
FLASH_FOLD_ROWS = range(237, 241)  # the rows around the mirage's fold in the centre column
# The renderer's camera rays may stray sagitta_pixels (0.25) of a pixel from the exact path.
FLASH_EDGE_TOL = 0.25  # [px]


@pytest.mark.slow
def test_the_sun_cut_by_the_mirage_is_wider_in_blue_as_the_fold_predicts():
    # The coloured rim at the LEFT and RIGHT ends of the green flash's squeezed sun is physics, not
    # horizontal dispersion (a height-only air bends every ray in its vertical plane): the warm
    # sea's mirage shows only the sun above the true elevation t_min(lam) that the fold of its
    # mapping reaches -- the sun's cap above that chord, upright, and below it inverted -- and
    # blue, refracted more, reaches lower into the disc, where its chord is wider. Predicted from
    # trace_ray's t_min at each wavelength (Edlen's index, PhysicalAtmosphere(wavelength=...), not
    # the renderer's dispersion wrapper) and the chord of the disc there; measured where the
    # rendered disc's right edge lies in the fold's rows (its coverage summed along each row, a
    # sun without limb darkening over a black sky).
    eye = np.array([0.0, FLASH_EYE, 0.0])
    look = np.radians(FLASH_LOOK)
    camera = refracta.Camera(
        eye, eye + [np.cos(look), np.sin(look), 0.0], vfov=FLASH_VFOV, width=FLASH_SIZE, height=FLASH_SIZE
    )
    pixel = np.radians(FLASH_VFOV) / FLASH_SIZE  # [rad] at the image's centre
    sun = np.radians(FLASH_SUN)
    scene = refracta.Scene()
    scene.set_sun((np.cos(sun), np.sin(sun), 0.0), (1.0, 1.0, 1.0), angular_diameter=2 * SUN_RADIUS)
    scene.add_ground(0.0, 2.0e5)
    warm_sea = refracta.PhysicalAtmosphere(surface_dt=3.0, surface_depth=2.0)
    earth = refracta.CurvedEarth(warm_sea)
    x0, x1 = 336, 372  # the disc's right end (predicted at 351.4 px at 650 nm, 361.4 px at 450 nm)
    half_widths = {}
    for lam in (450.0, 650.0):
        air = refracta.CurvedEarth(warm_sea.with_params(wavelength=lam))
        elevations = []  # true elevation [rad] seen along the centre column, where the path leaves the air
        for v in FLASH_FOLD_ROWS:
            origin, direction = camera.ray(FLASH_SIZE / 2, v + 0.5)
            path = refracta.trace_ray(air, origin, direction, max_length=1.2e6, trace="stratified", tol=1e-4)
            end, d = path.points[-1], path.directions[-1]
            elevations.append(np.arctan2(d[1], d[0]) - end[0] / earth.radius)  # the flat frame's tilt
        t_min = min(elevations)
        # The azimuth where the sun's rim crosses the chord at t_min (spherical law of cosines).
        cos_azimuth = (np.cos(np.radians(SUN_RADIUS)) - np.sin(t_min) * np.sin(sun)) / (np.cos(t_min) * np.cos(sun))
        predicted = np.arccos(cos_azimuth) / pixel
        image = refracta.render(
            scene,
            camera,
            _core.dispersed_field(earth, lam),
            max_length=1.5e6,
            spp=64,
            table=False,
            pixel_bounds=(x0, FLASH_FOLD_ROWS[0], x1, FLASH_FOLD_ROWS[-1] + 1),
            progress=False,
        )
        luminance = image @ LUMINANCE
        edges = x0 + (luminance / luminance[:, :1]).sum(axis=1)  # [px] the first column is inside
        measured = max(
            np.arctan2(abs(d[2]), d[0]) / pixel
            for d in (camera.ray(x, v + 0.5)[1] for x, v in zip(edges, FLASH_FOLD_ROWS))
        )
        # Measured 105.360 against 105.358 px (450 nm), 95.345 against 95.351 px (650 nm).
        assert measured == pytest.approx(predicted, abs=FLASH_EDGE_TOL), lam
        half_widths[lam] = measured
    # Blue's chord 10 px wider at each end -- the side rim: its t_min 0.0083 deg (6 px) lower (1.7 %
    # of the fold's 0.49 deg of refraction) times the rim's slope there, (t_min - sun) / half-width,
    # 1.5 (450 nm) to 1.8 (650 nm).
    assert half_widths[450.0] - half_widths[650.0] > 9.0
