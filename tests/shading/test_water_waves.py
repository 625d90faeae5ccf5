"""Waves larger than a pixel (issue 19 section 2): refracta.OceanWaves, a Tessendorf 2001 height
field synthesised by FFT from the Phillips spectrum scaled to Pierson & Moskowitz's significant
wave height, and Scene.add_sea, which tiles it near the camera, fades it into a flat sea, and
hands the slopes it does not resolve to Water's microfacets (resolved + unresolved = Cox & Munk).

The spectrum's oracle is written here from the formulas (numpy), not read from the library."""

import pickle

import numpy as np
import pytest

import refracta
from refracta import shading

G = 9.80665  # [m/s^2]
PHILLIPS_A = 2.0 * (0.21 / 4.0) ** 2 / np.pi  # Pierson-Moskowitz H_s = 0.21 U^2 / g = 4 sigma_h
# Closed forms evaluated in double precision by both sides.
FORMULA_TOLERANCE = 1e-12
# A realisation's variance is a sum of independent exponential mode powers (|h~(k)|^2, one per pair
# {k, -k}): its relative standard deviation is sqrt(2 sum p^2) / sum p (p = Phi dk^2 per mode),
# computed from the spectrum below; a test over n seeds allows 4 of those divided by sqrt(n).
SIGMAS = 4.0
SEEDS = range(6)
# The finite difference across a node pair against the mean of the spectral slopes: the same
# stationary statistic at the patch's wrap as inside when the field is periodic (a seam would be a
# jump of the height's scale, ~0.13 m / 0.39 m = 0.35 against 0.022); over one column of 256
# correlated nodes its rms scatters by ~10 % (measured 0.96-1.09 over 4 seeds).
SEAM_RATIO_TOLERANCE = 0.3
# The vertex-averaged slope variance of the mesh's inner disc (r < 35 m, 35 % of the 100 m patch's
# area at the default layout; the coarse level's ring 50-140 m) against the whole patch's: a sample
# of the same stationary field; measured within 3 %.
DISC_SAMPLE_TOLERANCE = 0.1


def phillips(kx, kz, wind_speed, wind=(1.0, 0.0)):
    """The Phillips spectrum as Tessendorf 2001 writes it, with A from Pierson-Moskowitz."""
    lw = wind_speed**2 / G
    k2 = kx**2 + kz**2
    w = np.asarray(wind, float) / np.hypot(*wind)
    with np.errstate(divide="ignore", invalid="ignore"):
        value = PHILLIPS_A * np.exp(-1.0 / (k2 * lw**2)) / k2**2 * (kx * w[0] + kz * w[1]) ** 2 / k2
    return np.where(k2 > 0, value, 0.0)


def mode_powers(waves):
    """Phi dk^2 on the synthesised modes: -N/2 < m, n < N/2, k != 0; and k^2 of each."""
    n, dk = waves.resolution, 2 * np.pi / waves.patch_size
    m = np.arange(-n // 2 + 1, n // 2)
    kx, kz = np.meshgrid(m * dk, m * dk)
    return phillips(kx, kz, waves.wind_speed, waves.wind_direction) * dk**2, kx**2 + kz**2


def test_01_spectrum_is_phillips_scaled_by_pierson_moskowitz():
    waves = refracta.OceanWaves(wind_speed=7.0, wind_direction=(1.0, 2.0))
    assert refracta.OceanWaves.phillips_a == pytest.approx(PHILLIPS_A, rel=FORMULA_TOLERANCE)
    assert waves.significant_wave_height == pytest.approx(0.21 * 49.0 / G, rel=FORMULA_TOLERANCE)
    assert waves.spectrum_height_variance == pytest.approx(
        (waves.significant_wave_height / 4) ** 2, rel=FORMULA_TOLERANCE
    )
    k = np.random.default_rng(0).uniform(-3.0, 3.0, (2, 200))
    np.testing.assert_allclose(
        waves.spectrum(k[0], k[1]), phillips(k[0], k[1], 7.0, (1.0, 2.0)), rtol=FORMULA_TOLERANCE
    )
    p, k2 = mode_powers(waves)
    assert waves.expected_height_variance == pytest.approx(p.sum(), rel=1e-10)  # summation order
    assert waves.expected_slope_variance == pytest.approx((k2 * p).sum(), rel=1e-10)


def test_02_the_patch_holds_the_spectrum_between_its_cutoffs():
    """The whole spectrum integrates to (H_s / 4)^2; between wavenumbers k0 and k1 (a ring) to
    (H_s / 4)^2 (exp(-1/(k1 L_w)^2) - exp(-1/(k0 L_w)^2)) (substitute s = 1/k^2). A large, fine
    patch's modes fill the square |kx|, |kz| < pi N / L: between the rings inscribed and
    circumscribed, the long-wave cutoff 2 pi / L negligible (e^-1e4)."""
    waves = refracta.OceanWaves(wind_speed=5.0, patch_size=2000.0, resolution=1024)
    lw, kn = waves.wind_length, np.pi * 1024 / 2000.0
    total = waves.spectrum_height_variance
    inscribed, circumscribed = total * np.exp(-1 / (kn * lw) ** 2), total * np.exp(-1 / (np.sqrt(2) * kn * lw) ** 2)
    assert inscribed < waves.expected_height_variance < circumscribed  # measured 0.942 < 0.952 < 0.971 of the total


@pytest.mark.parametrize("quantity", ["height", "slope"])
def test_03_field_variance_matches_the_spectrum(quantity):
    ratios = []
    for seed in SEEDS:
        waves = refracta.OceanWaves(seed=seed)
        if quantity == "height":
            ratios.append(waves.height_variance / waves.expected_height_variance)
            assert abs(waves.heights().mean()) < 1e-12  # k = 0 is empty
        else:
            ratios.append(waves.slope_variance / waves.expected_slope_variance)
            s = waves.slopes()
            # The same mean of squares computed in C++ and numpy: rounding.
            assert np.mean(s[..., 0] ** 2 + s[..., 1] ** 2) == pytest.approx(waves.slope_variance, rel=1e-12)
    p, k2 = mode_powers(waves)
    if quantity == "slope":
        p = k2 * p
    relative_sigma = np.sqrt(2 * (p**2).sum()) / p.sum()  # 3.5 % for heights, 0.8 % for slopes
    assert np.mean(ratios) == pytest.approx(1.0, abs=SIGMAS * relative_sigma / np.sqrt(len(SEEDS)))
    # The same variance computed in C++ and numpy: rounding.
    assert np.var(waves.heights()) == pytest.approx(waves.height_variance, rel=1e-12)


def test_04_slopes_are_the_heights_derivatives_and_the_patch_tiles_without_a_seam():
    for seed in range(3):
        waves = refracta.OceanWaves(seed=seed, wind_direction=(1.0, 1.0))
        h, s, d = waves.heights(), waves.slopes(), waves.spacing
        for axis, component in ((1, 0), (0, 1)):  # [j, i]: x along axis 1
            difference = (np.roll(h, -1, axis) - h) / d - 0.5 * (
                s[..., component] + np.roll(s[..., component], -1, axis)
            )
            inside = np.sqrt(np.mean(np.take(difference, range(h.shape[axis] - 1), axis) ** 2))
            wrap = np.sqrt(np.mean(np.take(difference, [-1], axis) ** 2))
            assert wrap / inside == pytest.approx(1.0, abs=SEAM_RATIO_TOLERANCE)
            # The trapezoid rule agrees with the FFT's slopes but for the modes near Nyquist, where it
            # errs by ~(k spacing)^2 / 12: measured 14 % of the slopes' rms.
            assert inside < 0.25 * np.sqrt(waves.slope_variance)
    # The sea's mesh repeats the patch: the water under (x, z) and (x + L, z + L) is at one height.
    scene = refracta.Scene()
    waves = refracta.OceanWaves(patch_size=20.0, resolution=64)
    scene.add_sea(waves, detail_radius=60.0)
    for x, z in np.random.default_rng(1).uniform(-15.0, 0.0, (20, 2)):
        a = scene.intersect((x, 5.0, z), (0, -1, 0))[0][1]
        b = scene.intersect((x + 20.0, 5.0, z + 20.0), (0, -1, 0))[0][1]
        assert a == pytest.approx(b, abs=1e-5)  # Embree's float vertices at 20 m: ~1e-6 m


def test_04b_the_levels_meet_without_a_crack():
    """Grazing rays from a 2 m eye across the fine grid's border (50 m), the coarse grid's (200 m)
    and the flat rings all meet the sea: the levels share their border vertices' heights and the
    flat plane is cut in rings (one 100 km sliver ring lost 13 % of such rays to float precision)."""
    scene = refracta.Scene()
    scene.add_sea()
    rng = np.random.default_rng(2)
    distance = np.concatenate(
        [rng.uniform(40.0, 60.0, 2000), rng.uniform(150.0, 260.0, 2000), rng.uniform(260.0, 5000.0, 1000)]
    )
    azimuth = rng.uniform(-np.pi, np.pi, distance.size)
    misses = sum(
        scene.intersect((0.0, 2.0, 0.0), (d * np.cos(a), -2.0, d * np.sin(a))) is None
        for d, a in zip(distance, azimuth)
    )
    assert misses == 0


def test_05_seeded_deterministic_and_finer_grids_keep_the_long_waves():
    a, b = refracta.OceanWaves(seed=3), refracta.OceanWaves(seed=3)
    assert np.array_equal(a.heights(), b.heights()) and np.array_equal(a.slopes(), b.slopes())
    # Another seed's heights differ everywhere far beyond numpy's default 1e-5/1e-8.
    assert not np.allclose(a.heights(), refracta.OceanWaves(seed=4).heights())
    fine = refracta.OceanWaves(seed=3, resolution=512)
    # numpy's forward FFT / N^2 recovers h~(k) (the field is the unscaled inverse transform).
    coarse_modes, fine_modes = np.fft.fft2(a.heights()) / 256**2, np.fft.fft2(fine.heights()) / 512**2
    kept = np.r_[0:128, -127:0]
    # The coarse grid holds exactly the fine grid's longer modes: FFT rounding.
    np.testing.assert_allclose(fine_modes[np.ix_(kept, kept)], coarse_modes[np.ix_(kept, kept)], atol=1e-15)
    moved = refracta.OceanWaves(seed=3, time=2.0)
    assert moved.height_variance == pytest.approx(a.height_variance, rel=0.3)  # the same sea, dispersed
    assert not np.allclose(moved.heights(), a.heights())
    copy = pickle.loads(pickle.dumps(a))
    assert np.array_equal(copy.heights(), a.heights()) and repr(copy) == repr(a)


def test_05b_the_sea_runs_downwind():
    # Each mode is one wave travelling along +k where k points downwind (its h~ turns by
    # exp(-i w dt)) and along -k where k points upwind (exp(+i w dt)), w = sqrt(g k): none runs
    # against the wind (a trial found 52 % of the energy running upwind, a partly standing sea).
    wind = np.array([1.0, 0.5])
    now = refracta.OceanWaves(seed=3, resolution=64, wind_direction=tuple(wind))
    later = refracta.OceanWaves(seed=3, resolution=64, wind_direction=tuple(wind), time=0.7)
    n, size = now.resolution, now.patch_size
    modes_now, modes_later = np.fft.fft2(now.heights()) / n**2, np.fft.fft2(later.heights()) / n**2
    wavenumbers = np.fft.fftfreq(n, d=1.0 / n) * 2.0 * np.pi / size
    kz, kx = np.meshgrid(wavenumbers, wavenumbers, indexing="ij")  # heights are [j (z), i (x)]
    downwind = np.sign(kx * wind[0] + kz * wind[1])
    omega = np.sqrt(9.80665 * np.hypot(kx, kz))  # deep water, standard gravity
    held = np.abs(modes_now) > 1e-6 * np.abs(modes_now).max()
    assert held.sum() > 1000  # most of the 64^2 modes carry a wave
    turned = modes_now * np.exp(-1j * downwind * omega * 0.7)
    error = np.abs(modes_later - turned)[held] / np.abs(modes_now)[held]
    assert error.max() < 1e-8  # FFT rounding relative to modes >= 1e-6 of the largest (1e-10 expected)


def test_05c_a_patch_too_small_for_the_wind_warns():
    # The default 100 m patch holds a 10 m/s sea (its synthesised variance over the spectrum's: 1.06)
    # but 26 % of a 20 m/s sea's (H_s 4.4 m against Pierson-Moskowitz's 8.6): that warns.
    with pytest.warns(UserWarning, match=r"100 m patch holds 26 % .*H_s 4.4 m, not 8.6"):
        refracta.OceanWaves(wind_speed=20.0)
    held = refracta.OceanWaves(wind_speed=20.0, patch_size=410.0, resolution=1024)  # 10 L_w: quiet
    assert held.expected_height_variance / held.spectrum_height_variance > 0.8  # the warning's threshold
    refracta.OceanWaves(wind_speed=10.0)  # warnings are errors here
    refracta.OceanWaves(wind_speed=5.0, resolution=16)  # short waves cut by the grid, not the patch: quiet


def test_06_resolved_and_microfacet_slopes_add_up_to_cox_munk():
    scene = refracta.Scene()
    waves = refracta.OceanWaves(wind_speed=8.0)
    ids = scene.add_sea(waves, material=shading.Water(wind_speed=8.0))
    total = 0.003 + 5.12e-3 * 8.0
    materials = [scene.material(i) for i in ids]
    assert len(ids) == 9  # per level (fine, coarse) the full waves and 3 fade rings, then the flat sea
    for water in materials:
        assert water.mean_square_slope == pytest.approx(total, rel=FORMULA_TOLERANCE)
        assert water.roughness**2 + water.resolved_slope_variance == pytest.approx(total, rel=FORMULA_TOLERANCE)
    resolved = [w.resolved_slope_variance for w in materials]
    assert resolved[0] == pytest.approx(waves.slope_variance, rel=DISC_SAMPLE_TOLERANCE)
    # The coarse level is the same sea at a quarter of the resolution: its longer modes exactly.
    coarse = refracta.OceanWaves(wind_speed=8.0, resolution=64)
    assert resolved[4] == pytest.approx(coarse.slope_variance, rel=DISC_SAMPLE_TOLERANCE)
    # Fewer slopes resolved with distance, more left to the microfacets; the flat sea has Cox-Munk's all.
    assert resolved[0] > resolved[4] > resolved[5] > resolved[6] > resolved[7] > resolved[8] == 0.0
    # The default material is the waves' Water; the default waves the material's wind.
    defaults = refracta.Scene()
    ids = defaults.add_sea(material=shading.Water(wind_speed=3.0))
    assert defaults.material(ids[-1]).wind_speed == 3.0 and defaults.material(ids[0]).resolved_slope_variance > 0.0
    # A material without microfacet statistics is used as given.
    other = refracta.Scene()
    ids = other.add_sea(material=shading.Diffuse((0.1, 0.2, 0.3)))
    assert all("Diffuse" in repr(other.material(i)) for i in ids)
    # Scenes with a sea pickle (the Water's resolved_slope_variance is a parameter).
    copy = pickle.loads(pickle.dumps(scene))
    assert [copy.material(i).resolved_slope_variance for i in range(9)] == resolved


def close_sea(waves: bool):
    """A 2 m eye over a 5 m/s sea, looking 1 degree down, the sun to the side; fine waves out to 10 m,
    coarse ones to 40 m."""
    scene = refracta.Scene()
    e, a = np.radians(30.0), np.radians(70.0)
    scene.set_physical_sky(np.array([np.cos(e) * np.cos(a), np.sin(e), np.cos(e) * np.sin(a)]))
    if waves:
        scene.add_sea(detail_radius=10.0)
    else:
        scene.add_ground(0.0, 2e5, material=shading.Water())
    look = np.radians(-1.0)
    camera = refracta.Camera.photographic(
        (0, 2, 0), (100 * np.cos(look), 2 + 100 * np.sin(look), 0), 28.0, width=192, height=128
    )
    return refracta.render(scene, camera, None, spp=4, progress=False)


def block_means(image, rows):
    """8 x 8 pixel block means of the luminance over `rows`: structure larger than ~8 pixels, the
    4-spp noise averaged down 64 times."""
    y = image[rows] @ np.array([0.2126, 0.7152, 0.0722])
    h, w = y.shape[0] // 8 * 8, y.shape[1] // 8 * 8
    return y[:h, :w].reshape(h // 8, 8, w // 8, 8).mean(axis=(1, 3))


# The wave structure: the variance of the block means of the sea with waves over those of the flat
# sea (same sky, material and sample seeds, so the flat sea's gradients and most of the noise
# divide out; raw block statistics at 4 spp are dominated by noise). Measured 0.10 near (32 % rms),
# 5.7e-5 far.
NEAR_STRUCTURE = 0.01  # at least 10 % rms: waves one sees
FAR_FACTOR = 100.0  # the near water's structure over the far water's


@pytest.mark.slow
def test_07_a_close_sea_shows_its_waves_near_the_camera():
    # 128 rows over 46.4 deg (2.76 rows per degree): the horizon at row 61; near: rows 104-128, 4.5-7.2 m
    # away (the full fine waves reach 7 m); far: rows 62-70, 35-320 m away (the end of the coarse waves'
    # fade, 28-40 m, then the flat sea).
    with_waves, flat = close_sea(True), close_sea(False)
    assert np.isfinite(with_waves).all() and with_waves.min() >= 0.0
    near, far = slice(104, 128), slice(62, 70)
    near_structure = np.var(block_means(with_waves, near) / block_means(flat, near))
    far_structure = np.var(block_means(with_waves, far) / block_means(flat, far))
    assert near_structure > NEAR_STRUCTURE
    assert near_structure > FAR_FACTOR * far_structure


def test_08_bad_inputs_name_the_argument():
    cases = [
        (dict(resolution=100), "resolution"),
        (dict(resolution=2048), "resolution"),
        (dict(resolution=4), "resolution"),
        (dict(patch_size=0.0), "patch_size"),
        (dict(patch_size=float("nan")), "patch_size"),
        (dict(wind_speed=0.0), "wind_speed"),
        (dict(wind_speed=31.0), "wind_speed"),
        (dict(wind_speed=float("inf")), "wind_speed"),
        (dict(wind_direction=(0.0, 0.0)), "wind_direction"),
        (dict(wind_direction=(1.0, 2.0, 3.0)), "wind_direction"),
        (dict(seed=-1), "seed"),
        (dict(time=float("inf")), "time"),
    ]
    for kwargs, name in cases:
        with pytest.raises(ValueError, match=name):
            refracta.OceanWaves(**kwargs)
    with pytest.raises(ValueError, match="patch_size.*resolution|resolution.*patch_size"):  # every problem reported
        refracta.OceanWaves(patch_size=-1.0, resolution=3)
    scene = refracta.Scene()
    for kwargs, name in [
        (dict(detail_radius=1e4), "detail_radius"),
        (dict(detail_radius=0.0), "detail_radius"),
        (dict(detail_radius=1e-9), "detail_radius must be at least the waves' spacing"),  # segfaulted (a trial)
        (dict(size=80.0), "size"),
        (dict(centre=(float("nan"), 0.0)), "centre"),
        (dict(height=float("inf")), "height"),
        (dict(centre=(1.0, 2.0, 3.0)), "centre"),
        (dict(material=shading.Water(wind_speed=8.0)), "wind_speed"),
        (dict(material=shading.Water(resolved_slope_variance=0.01)), "resolved_slope_variance"),
        (dict(material="water"), "material"),
    ]:
        with pytest.raises(ValueError, match=name):
            scene.add_sea(refracta.OceanWaves(), **kwargs) if "wind_speed" in name else scene.add_sea(**kwargs)
    for bad in (-1e-3, 0.0287, float("nan")):
        with pytest.raises(ValueError, match="resolved_slope_variance"):
            shading.Water(wind_speed=5.0, resolved_slope_variance=bad)
    with pytest.warns(UserWarning, match="2 m patch holds 3 %"):  # 2 m of a 5 m/s sea: a small patch
        tiny = refracta.OceanWaves(patch_size=2.0, resolution=1024, wind_speed=5.0)
    with pytest.raises(ValueError, match="resolution"):  # a grid resolving more than Cox-Munk's total slope
        scene.add_sea(tiny, detail_radius=0.5)
