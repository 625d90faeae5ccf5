"""Aerial perspective (issue 19 section 1): the physical sky's own air dims and lights every
segment the renderers cast. Checked against Koschmieder's law, a brute-force quadrature of the
same in-scatter integral, the sky itself (a segment that leaves the air sees the sky's radiance),
and in renders: a black target fading into the sky with distance, RGB against spectral, a finite
light's shadow ray, pickling, and aerial_perspective=False keeping surfaces unlit by the air."""

import math
import pickle

import numpy as np
import pytest

import refracta
from refracta import shading, spectrum

KOSCHMIEDER = 3.912  # -ln 0.02: extinction x visibility


def sun_at(elevation_deg, azimuth_deg=90.0):
    e, a = math.radians(elevation_deg), math.radians(azimuth_deg)
    return (math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a))


@pytest.fixture(scope="module")
def clear_air():
    return spectrum.AerialPerspective(spectrum.PhysicalSky(sun_at(30.0), below_horizon="horizon"))


@pytest.mark.parametrize("visibility", [2.0, 5.0, 20.0])
@pytest.mark.parametrize("distance", [500.0, 1000.0, 2000.0, 4000.0])
def test_koschmieder_transmittance_at_the_ground(visibility, distance):
    # At 550 nm the total extinction at the ground is 3.912 / V. The horizontal chord at y = 0
    # rises d^2 / 2R over the sky's sphere (1.3 m at 4 km): the Mie density (1.2 km scale height)
    # falls by < 0.11 %, so the optical depth matches to 0.2 %.
    sky = spectrum.PhysicalSky(sun_at(30.0), below_horizon="horizon", visibility=visibility)
    transmittance, _ = spectrum.AerialPerspective(sky).along((0, 0, 0), (distance, 0, 0), 550.0)
    expected = KOSCHMIEDER * distance / (visibility * 1e3)
    # The Mie density's < 0.11 % fall along the chord: 0.2 % (comment above).
    assert -math.log(transmittance) == pytest.approx(expected, rel=2e-3)


@pytest.mark.parametrize("distance", [300.0, 1000.0, 3000.0])
def test_a_black_target_loses_contrast_against_the_horizon_sky_as_koschmieder_says(distance):
    # Near-uniform air (visibility 2 km, the extinction saturating within ~10 km of the ground,
    # where the sky's sphere lifts a horizontal ray by 8 m): the black target's radiance is the
    # in-scatter S(d) = J (1 - e^-sigma d), the horizon sky's is J, so its contrast 1 - S / L_sky is
    # e^-sigma d. The sky's horizon radiance holds light from up to ~20 km away, where the ray has
    # risen 30 m and the sun's transmittance changed: 2 % of J, hence the tolerance.
    sky = spectrum.PhysicalSky(sun_at(30.0), below_horizon="horizon", visibility=2.0)
    air = spectrum.AerialPerspective(sky)
    direction = np.array([1.0, 0.0, 0.0])
    _, inscatter = air.along((0, 0, 0), tuple(distance * direction), 550.0)
    horizon = sky.radiance(direction[None], [550.0], direct=True)[0, 0]
    contrast = 1.0 - inscatter / horizon
    # 2 % of J from the horizon sky's far light (comment above).
    assert contrast == pytest.approx(math.exp(-KOSCHMIEDER * distance / 2000.0), abs=0.02)


@pytest.mark.parametrize(
    "case",
    [
        # (a, b, sun elevation [deg], earth radius): horizontal, slant up a mountain, down to the sea
        # from a cliff, a low sun, and a CurvedEarth's flat frame.
        ((0, 1.5, 0), (28000, 1.5, 0), 30.0, math.inf),
        ((0, 1.5, 0), (6000, 2500, 3000), 30.0, math.inf),
        ((0, 300, 0), (2000, 0, -500), 10.0, math.inf),
        ((0, 5, 0), (28000, 10, 2000), 2.0, math.inf),
        ((0, 5, 0), (28000, 10, 2000), 2.0, 6371e3),
    ],
)
def test_in_scatter_matches_a_brute_force_quadrature(case):
    # The closed-form pieces against 20 000 midpoints with every point's sun column traced; the
    # pieces assume the sunlight (sun transmittance, table-interpolated) constant along each piece
    # of <= 250 m height change and 10 km length: 0.1 % measured, 0.5 % allowed.
    a, b, elevation, radius = case
    air = spectrum.AerialPerspective(spectrum.PhysicalSky(sun_at(elevation, 60.0), below_horizon="horizon"))
    for wavelength in (450.0, 550.0, 650.0):
        _, inscatter = air.along(a, b, wavelength, earth_radius=radius)
        reference = air.inscatter_reference(a, b, wavelength, steps=20000, earth_radius=radius)
        assert inscatter == pytest.approx(reference, rel=5e-3)  # 0.1 % measured, 0.5 % allowed (comment above)


@pytest.mark.parametrize("elevation", [0.0, 2.0, 10.0])
def test_a_segment_that_leaves_the_air_sees_the_sky(clear_air, elevation):
    # In-scatter along 2000 km from the sky's observer (y = 0) in a direction: the sky's own
    # scattering integral (PhysicalSky.radiance direct, multiple scattering included), whose quadrature it shares up to
    # the pieces' discretisation: 0.1 % measured at these elevations, 0.5 % allowed.
    e, a = math.radians(elevation), 1.0
    direction = np.array([math.cos(e) * math.cos(a), math.sin(e), math.cos(e) * math.sin(a)])
    sky = spectrum.PhysicalSky(sun_at(30.0), below_horizon="horizon")
    for wavelength in (450.0, 550.0, 650.0):
        transmittance, inscatter = clear_air.along((0, 0, 0), tuple(2e6 * direction), wavelength)
        assert transmittance < 0.5 or elevation > 0.0  # 2000 km of air below the top: opaque unless the ray climbs
        # The pieces' discretisation: 0.1 % measured, 0.5 % allowed (comment above).
        assert inscatter == pytest.approx(sky.radiance(direction[None], [wavelength], direct=True)[0, 0], rel=5e-3)


@pytest.mark.parametrize("radius", [math.inf, 6371e3])
def test_a_longer_segment_holds_the_shorter(clear_air, radius):
    # Level from 2 m: a straight ray of the flat scene climbs out of the sky's sphere (at ~1000 km
    # it is above the top), a CurvedEarth's stays at 2 m. The air of the shorter segment is part of
    # the longer's: T cannot rise and S cannot fall with length (a trial found T = 0.86 at 1e10 m,
    # where pieces of 40 000 km had skipped the air). Beyond the top nothing changes.
    lengths = [1e3, 1e4, 1e5, 1e6, 3e6, 1e7]
    segments = [clear_air.along((0, 2, 0), (d, 2, 0), 550.0, earth_radius=radius) for d in lengths]
    transmittances, inscatters = np.array(segments).T
    # Up to the pieces' discretisation, which changes with the length (at most 256 pieces): 5e-6
    # of the value measured, 1e-5 allowed.
    assert np.all(np.diff(transmittances) <= 1e-5 * transmittances[1:])
    assert np.all(np.diff(inscatters) >= -1e-5 * inscatters[1:])  # 1e-5: the discretisation, as above
    if radius == math.inf:  # both clipped at the top: the same air, up to the exit points' rounding
        np.testing.assert_allclose(segments[-1], segments[-2], rtol=1e-9)
    with pytest.raises(ValueError, match=r"AerialPerspective.along: b must be finite and within 10000000 m"):
        clear_air.along((0, 2, 0), (1e300, 2, 0), 550.0, earth_radius=radius)


def test_the_sun_reaching_a_point_is_the_sky_model_s():
    # The table against the sky's own sun transmittance at the observer (the sky's altitude, 0 m).
    sky = spectrum.PhysicalSky(sun_at(8.0), below_horizon="horizon")
    air = spectrum.AerialPerspective(sky)
    for wavelength in (400.0, 550.0, 700.0):
        # The table's interpolation against the sky's own column: 0.2 %.
        assert air.sun_transmittance(0.0, 8.0, wavelength) == pytest.approx(
            sky.sun_transmittance([wavelength])[0], rel=2e-3
        )
    assert air.sun_transmittance(0.0, -3.0, 550.0) == 0.0  # below the horizon at the ground
    assert air.sun_transmittance(3000.0, 5.0, 550.0) > air.sun_transmittance(0.0, 5.0, 550.0)


def black_target_scene(distance, aerial=True, visibility=10.0):
    """A black wall `distance` m away across the view's left half, the horizon sky on the right."""
    scene = refracta.Scene()
    scene.set_physical_sky(
        sun_at(30.0, 120.0), below_horizon="horizon", aerial_perspective=aerial, visibility=visibility
    )
    scene.add_box((distance, 0.0, -200.0), (1.0, 200.0, 400.0), material=shading.Diffuse(0.0))
    camera = refracta.Camera((0.0, 1.5, 0.0), (distance, 1.5, 0.0), vfov=0.5, width=16, height=8)
    return scene, camera


def test_a_black_target_fades_into_the_sky_behind_it():
    # Rendered (RGB): the target's pixel is the air's in-scatter along the camera ray (along_rgb of
    # the same chord: 0.5 % for the few-mm differences of where the pixel's ray meets the wall), it
    # rises with distance toward the sky's pixel beside it, and is black without the air.
    fractions = []
    for distance in (1000.0, 4000.0, 16000.0, 60000.0):
        scene, camera = black_target_scene(distance)
        image = refracta.render(scene, camera, progress=False, max_length=1e5)
        target, sky = image[4, 2], image[4, 13]
        origin, direction = camera.ray(2.5, 4.5)  # the pixel's centre; its ray meets the wall's face
        hit = origin + direction * (distance - 0.5 - origin[0]) / direction[0]
        _, expected = scene.aerial_perspective.along_rgb(origin, hit)
        # 0.5 % for the few-mm difference of where the ray meets the wall (docstring above).
        np.testing.assert_allclose(target, expected, rtol=5e-3)
        fractions.append(float(target[1] / sky[1]))
        plain, camera = black_target_scene(distance, aerial=False)
        assert np.all(refracta.render(plain, camera, progress=False, max_length=1e5)[4, 2] == 0.0)
    assert all(b > a for a, b in zip(fractions, fractions[1:])), fractions
    assert fractions[0] < 0.35 and fractions[-1] > 0.95, fractions  # 1 - e^-0.39 ... ~1


def test_spectral_and_rgb_renders_agree():
    # The target's in-scatter rendered spectrally (hero wavelengths, 256 spp: noise ~1 %) against
    # the RGB render (the in-scatter at the sky's 48 nodes projected to RGB): 3 % covers the noise
    # and the RGB projection's gamut clipping.
    scene, camera = black_target_scene(4000.0)
    rgb = refracta.render(scene, camera, progress=False, max_length=1e5)[4, 2]
    spectral = refracta.render(scene, camera, progress=False, max_length=1e5, spectral=True, spp=256)[3:6, 1:4]
    # 256-spp noise ~1 % and the RGB projection's clipping: 3 % (comment above).
    np.testing.assert_allclose(spectral.mean(axis=(0, 1)), rgb, rtol=0.03)


def test_a_finite_light_is_seen_through_the_air_both_ways():
    # A white plate lit by a point light 3 km away, seen from 2 km: with the air its pixel is
    # T_eye T_light x the pixel without, plus the eye's in-scatter (both from along_rgb; 0.5 % for
    # the pixel's few-cm offset from the chord used here).
    def plate(aerial):
        scene = refracta.Scene()
        scene.set_physical_sky(sun_at(-30.0), below_horizon="horizon", aerial_perspective=aerial, visibility=8.0)
        scene.add_box((2000.0, 1.5, 0.0), (0.1, 10.0, 10.0), material=shading.Diffuse(0.8))
        scene.add_point_light((0.0, 1.5, 3000.0), (1e9, 1e9, 1e9))
        camera = refracta.Camera((0.0, 1.5, 0.0), (2000.0, 1.5, 0.0), vfov=0.1, width=4, height=4)
        return scene, refracta.render(scene, camera, progress=False, max_length=1e5)[2, 2]

    scene, with_air = plate(True)
    _, without = plate(False)
    air = scene.aerial_perspective
    t_eye, s_eye = air.along_rgb((0.0, 1.5, 0.0), (1999.95, 1.5, 0.0))
    t_light, _ = air.along_rgb((1999.95, 1.5, 0.0), (0.0, 1.5, 3000.0))
    # 0.5 % for the pixel's few-cm offset from this chord (comment above).
    np.testing.assert_allclose(with_air, t_eye * t_light * without + s_eye, rtol=5e-3)
    assert with_air[1] < 0.5 * without[1]  # 5 km of 8 km-visibility air: e^-2.4 of the light


def test_pickled_scene_keeps_its_air():
    scene, camera = black_target_scene(4000.0)
    copy = pickle.loads(pickle.dumps(scene))
    assert copy.aerial_perspective is not None
    np.testing.assert_array_equal(
        refracta.render(copy, camera, progress=False, max_length=1e5),
        refracta.render(scene, camera, progress=False, max_length=1e5),
    )


def test_replacing_the_sky_ends_the_air():
    scene, _ = black_target_scene(4000.0)
    scene.set_sky((0.5, 0.6, 0.9))
    assert scene.aerial_perspective is None


@pytest.mark.parametrize(
    "visibility, message",
    [
        (0.0, "visibility must be >= 0.001 km"),
        (-3.0, "visibility must be >= 0.001 km"),
        (float("nan"), "visibility must be >= 0.001 km"),
        (float("inf"), "visibility must be >= 0.001 km"),
        (1000.0, "beyond what the air's molecules"),
    ],
)
def test_bad_visibility_is_refused(visibility, message):
    with pytest.raises(ValueError, match=message):
        refracta.Scene().set_physical_sky(sun_at(30.0), visibility=visibility)
    with pytest.raises(ValueError, match=message):
        spectrum.PhysicalSky(sun_at(30.0), visibility=visibility)


def test_aerosol_and_visibility_are_one_or_the_other():
    with pytest.raises(ValueError, match="aerosol or visibility"):
        refracta.Scene().set_physical_sky(sun_at(30.0), aerosol=3.0, visibility=10.0)
    # The clear default aerosol corresponds to ~110 km; 10 km is a hazy day.
    assert spectrum.PhysicalSky(sun_at(30.0), visibility=10.0).aerosol > 10.0


def test_bad_segments_are_refused(clear_air):
    with pytest.raises(ValueError, match="wavelength"):
        clear_air.along((0, 0, 0), (100, 0, 0), 200.0)
    for radius in (0.0, -6.371e6, float("nan")):
        with pytest.raises(ValueError, match="earth_radius"):
            clear_air.along((0, 0, 0), (100, 0, 0), 550.0, earth_radius=radius)
        with pytest.raises(ValueError, match="earth_radius"):
            clear_air.along_rgb((0, 0, 0), (100, 0, 0), earth_radius=radius)
        with pytest.raises(ValueError, match="earth_radius"):
            clear_air.inscatter_reference((0, 0, 0), (100, 0, 0), 550.0, steps=8, earth_radius=radius)
    with pytest.raises(ValueError):
        clear_air.along((0, float("nan"), 0), (100, 0, 0), 550.0)


def test_aerial_perspective_pickles(clear_air):
    copy = pickle.loads(pickle.dumps(clear_air))
    assert copy.along((0, 1.5, 0), (9000, 40, 300), 500.0) == clear_air.along((0, 1.5, 0), (9000, 40, 300), 500.0)


SCENE_FILE = """
[camera]
position = [0, 1.5, 0]
look_at = [100, 1.5, 0]
vfov = 20
size = [16, 8]
[environment]
type = "physical_sky"
sun_direction = [0.3, 0.5, 0.2]
"""


@pytest.mark.parametrize(
    "keys, aerial, error",
    [
        ("visibility = 10.0\naerial_perspective = true\n", True, None),
        ("", True, None),
        ("aerial_perspective = false\n", False, None),
        (
            "visibility = 10.0\naerosol = 3.0\n",
            None,
            r"s.toml:11: \[environment\] aerosol: give aerosol or visibility",
        ),
        ("aerial_perspective = 1\n", None, r"s.toml:10: \[environment\] aerial_perspective: must be true or false$"),
    ],
)
def test_scene_files_set_the_air(tmp_path, keys, aerial, error):
    path = tmp_path / "s.toml"
    path.write_text(SCENE_FILE + keys)
    if error:
        with pytest.raises(ValueError, match=error):
            refracta.load_scene(path)
    else:
        assert (refracta.load_scene(path).scene.aerial_perspective is not None) == aerial


def test_set_aerial_perspective_turns_the_air_off_and_on():
    scene, camera = black_target_scene(4000.0)
    scene.set_aerial_perspective(False)
    assert scene.aerial_perspective is None
    assert np.all(refracta.render(scene, camera, progress=False, max_length=1e5)[3, 2] == 0.0)
    scene.set_aerial_perspective(True)
    assert scene.aerial_perspective is not None
    bare = refracta.Scene()
    bare.set_sky((0.5, 0.6, 0.9))
    with pytest.raises(ValueError, match="physical sky"):
        bare.set_aerial_perspective(True)


@pytest.mark.parametrize(("height", "method"), [(200.0, "straight"), (200.0, "raster_march"), (1850.0, "straight")])
def test_from_a_raised_camera_a_black_target_fades_into_the_sky_seen_from_there(height, method):
    # The sky behind a target is the sky seen from the camera's height, the haze on it the air's
    # at that height (render/raised_sky.h). A trial's 200 m camera in 5 km visibility saw black
    # boxes 5 and 10 km away 20 % brighter than the ground's horizon sky beside them. Koschmieder
    # at the camera's height: sigma(h) = beta_R(550) e^(-h / 8 km) + (3.912 / V - beta_R(550))
    # e^(-h / 1.2 km) (physical_sky.h's densities; no ozone below 10 km), the contrast e^(-sigma d).
    visibility, beta_rayleigh = 5.0, 1.2126e-5
    sigma = beta_rayleigh * math.exp(-height / 8000.0) + (KOSCHMIEDER / (visibility * 1e3) - beta_rayleigh) * math.exp(
        -height / 1200.0
    )
    for distance in (1000.0, 3000.0, 20000.0 if height < 1000.0 else 60000.0):
        scene = refracta.Scene()
        scene.set_physical_sky(sun_at(30.0), below_horizon="horizon", visibility=visibility)
        scene.add_box((distance, height, 0.0), (1.0, 0.02 * distance, 0.02 * distance), material=shading.Diffuse(0.0))
        camera = refracta.Camera((0.0, height, 0.0), (distance, height, 0.0), (0, 1, 0), 3.0, 16, 16)
        image = refracta.render(scene, camera, None, method=method, progress=False, max_length=1e5)
        contrast = 1.0 - image[8, 8, 1] / image[8, 0, 1]
        # The green channel stands for 550 nm (the aerosol's extinction is grey, Rayleigh's 1.5 % of
        # it), and the sky's far light and the chord's rise over the sky's sphere: 0.005.
        assert contrast == pytest.approx(math.exp(-sigma * distance), abs=0.005), (distance, contrast)


def _irradiance_on_a_level_plate(sky):
    """E_sun cos(60 deg) + the integral of the sky's radiance x cos over the upper hemisphere
    (96 x 192 midpoints), for a sun 30 deg up of 0.53 deg."""
    disc = 2.0 * math.pi * (1.0 - math.cos(math.radians(0.265)))
    sun = np.asarray(sky.sun_radiance_rgb()) * disc * math.sin(math.radians(30.0))
    theta = (np.arange(96) + 0.5) / 96 * (math.pi / 2)
    phi = (np.arange(192) + 0.5) / 192 * (2 * math.pi)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    dirs = np.stack([np.sin(t) * np.cos(p), np.cos(t), np.sin(t) * np.sin(p)], axis=-1).reshape(-1, 3)
    radiance = np.asarray(sky.rgb_radiance(dirs)).reshape(96, 192, 3)
    weight = (np.cos(t) * np.sin(t))[..., None] * (math.pi / 2 / 96) * (2 * math.pi / 192)
    return sun + (radiance * weight).sum(axis=(0, 1))


@pytest.mark.parametrize("height", [5.0, 400.0])
def test_a_white_plate_by_a_raised_camera_is_lit_by_the_sun_and_sky_of_its_height(height):
    # A white Lambertian plate 1 m below the camera: its radiance is (E_sun + E_sky) / pi with the
    # sun and sky of its own height -- from 400 m in 5 km visibility 29 % more than the ground's
    # (the sun through 0.26 less Mie depth, straight up). The same air: the ground sky's aerosol
    # (PhysicalSky(visibility=) sets it for visibility at the observer's own height).
    ground = spectrum.PhysicalSky(sun_at(30.0), below_horizon="horizon", visibility=5.0)
    own = spectrum.PhysicalSky(sun_at(30.0), below_horizon="horizon", aerosol=ground.aerosol, altitude=height)
    scene = refracta.Scene()
    scene.set_physical_sky(sun_at(30.0), below_horizon="horizon", visibility=5.0)
    scene.add_box((0.0, height - 1.5, 0.0), (4.0, 1.0, 4.0), material=shading.Diffuse(1.0))
    camera = refracta.Camera((0.0, height, 0.0), (0.0, height - 1.0, 0.0), (1, 0, 0), 20.0, 8, 8)
    image = refracta.render(scene, camera, None, spp=256, progress=False, max_length=1e5)
    expected = _irradiance_on_a_level_plate(own if height >= 10.0 else ground) / math.pi
    # Light sampling's noise over 16 384 samples and the sky table's interpolation: 1 %.
    np.testing.assert_allclose(image.reshape(-1, 3).mean(axis=0), expected, rtol=0.01)
