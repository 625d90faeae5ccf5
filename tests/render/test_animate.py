"""Shimmer (issue 10): refracta.geometric_noise (a non-physical angle map: its rms, correlation,
seeding and motion), rebuilding a field around advected turbulence, and refracta.animate (frames
that change, GIF / MP4 / frame files, executors, bad input)."""

import concurrent.futures
import gc
import math
import subprocess
import warnings

import numpy as np
import pytest

import refracta
from refracta import _animate

PIL_Image = pytest.importorskip("PIL.Image")

# A 256 x 256 map holds ~(256 / (2.5 l))^2 ~ 420 independent patches at l = 5 pixels: the sample
# rms of each component is within ~2 / sqrt(2 * 420) ~ 7 % (2 sigma) of the asked one.
RMS_TOLERANCE = 0.1
# The correlation at a lag of l, measured over the same map: exp(-1/2) = 0.607 within 0.08.
CORRELATION_TOLERANCE = 0.08


# -- 1. geometric noise (not physical) -----------------------------------------------------------


def test_noise_map_has_the_asked_rms_and_correlation():
    rms, ell = 2e-3, 5.0
    angles = _animate.geometric_noise_map(256, 256, rms, ell, seed=4)
    assert angles.shape == (256, 256, 2)
    for c in range(2):
        a = angles[:, :, c]
        assert a.std() == pytest.approx(rms, rel=RMS_TOLERANCE)
        lag = int(ell)
        across = np.mean(a[:, lag:] * a[:, :-lag]) / a.var()
        down = np.mean(a[lag:, :] * a[:-lag, :]) / a.var()
        for value in (across, down):
            assert value == pytest.approx(math.exp(-0.5), abs=CORRELATION_TOLERANCE)
        assert abs(np.mean(a[:, 4 * lag :] * a[:, : -4 * lag]) / a.var()) < 0.1  # exp(-8): uncorrelated
    assert abs(np.corrcoef(angles[:, :, 0].ravel(), angles[:, :, 1].ravel())[0, 1]) < 0.1


def test_noise_map_is_seeded_and_moves_with_its_speed():
    a = _animate.geometric_noise_map(40, 60, 1e-3, 3.0, seed=1)
    np.testing.assert_array_equal(a, _animate.geometric_noise_map(40, 60, 1e-3, 3.0, seed=1))
    # The map's scale is 1e-3: another seed's differs by several times it somewhere.
    assert np.abs(a - _animate.geometric_noise_map(40, 60, 1e-3, 3.0, seed=2)).max() > 1e-3
    # After 0.5 s at (4, 6) pixels/s the pattern sits 2 pixels right and 3 down (exact: a phase shift).
    b = _animate.geometric_noise_map(40, 60, 1e-3, 3.0, seed=1, time=0.5, speed=(4.0, 6.0))
    # An exact phase shift of values ~1e-3: rounding only.
    np.testing.assert_allclose(b[3:, 2:], a[:-3, :-2], rtol=0, atol=1e-15)


def test_noise_camera_turns_each_ray_by_its_angles():
    camera = refracta.Camera((0, 1, 0), (10, 1, 0), vfov=10, width=8, height=6)
    noisy = refracta.geometric_noise(camera, 1e-3, 2.0, seed=3)
    angles = _animate.geometric_noise_map(6, 8, 1e-3, 2.0, seed=3)
    for x, y in [(0, 0), (3, 2), (7, 5)]:
        _, d0 = camera.ray(x + 0.5, y + 0.5)
        _, d1 = noisy.ray(x + 0.5, y + 0.5)
        # The turn's size (its direction depends on the camera's frame); the corners' rays, 5 deg
        # off the axis, are turned in the image plane: within cos^2(5 deg) ~ 1 %.
        assert np.arccos(np.clip(d0 @ d1, -1, 1)) == pytest.approx(np.hypot(*angles[y, x]), rel=1e-2)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(rms=-1.0), "rms must be"),
        (dict(correlation_pixels=0.0), "correlation_pixels must be"),
        (dict(seed=-1), "seed must be"),
        (dict(speed=(1.0,)), "speed must be"),
        (dict(time=float("nan")), "time must be"),
    ],
)
def test_noise_bad_input(kwargs, message):
    arguments = dict(rms=1e-3, correlation_pixels=2.0) | kwargs
    with pytest.raises(ValueError, match=message):
        _animate.geometric_noise_map(4, 4, **arguments)


# -- 2. the air at time t ------------------------------------------------------------------------------


def test_field_rebuilt_around_moved_turbulence_keeps_its_air():
    air = refracta.Turbulence(1e-10, cells=16, spacing=0.05, depth=0.1, wind=(1.0, 2.0))
    spots = [refracta.HotSpot(30.0, 1.0, 4.0, 6.0, depth=0.2)]
    for field in (
        refracta.PhysicalAtmosphere(surface_dt=9.0, surface_depth=0.12, hot_spots=spots),
        refracta.LogisticProfile(n_hot=0.2, hot_spots=[refracta.HotSpot(3.0, 0.0, 2.0, 1.0)], turbulence=air),
    ):
        later = _animate.field_at_time(field, air, 0.5)
        assert later.params == field.params and later.hot_spots == field.hot_spots
        p = np.array([[30.0, 0.05, 1.0], [3.0, 0.3, 0.2], [100.0, 2.0, 0.0]])
        moved = air.at_time(0.5).evaluate(p)[0]
        calm = (
            refracta.PhysicalAtmosphere if isinstance(field, refracta.PhysicalAtmosphere) else refracta.LogisticProfile
        )
        without = _animate.with_turbulence(field, None)
        assert without.turbulence is None
        # The same sum n + dn in double: ulps of n ~ 1.
        np.testing.assert_allclose(later.ior(p), without.ior(p) + moved, rtol=0, atol=1e-15)
        assert isinstance(without, calm)


def test_fields_that_cannot_carry_turbulence_are_refused():
    air = refracta.Turbulence(cells=16)
    with pytest.raises(ValueError, match="PhysicalAtmosphere or LogisticProfile"):
        _animate.with_turbulence(refracta.LinearSquaredProfile(), air)
    with pytest.raises(ValueError, match="PhysicalAtmosphere or LogisticProfile"):
        _animate.with_turbulence(refracta.CurvedEarth(refracta.PhysicalAtmosphere()), air)


def test_a_height_only_part_keeps_its_fixed_data_under_turbulence():
    # A LogisticProfile's height_only_part has its hot layer switched off: not a constructor's
    # field. The rebuild from params by reflection refused it ("cannot be rebuilt"); the model's
    # own with_turbulence keeps its fixed data, so its air less the turbulence is the part's.
    air = refracta.Turbulence(1e-10, cells=16, spacing=0.05, depth=0.1)
    part = refracta.LogisticProfile(hot_spots=[refracta.HotSpot(3.0, 0.0, 2.0, 1.0)]).height_only_part
    stirred = _animate.with_turbulence(part, air)
    p = np.array([[3.0, 0.02, 0.0], [3.0, 0.3, 0.2], [100.0, 2.0, 0.0]])
    assert stirred.params == part.params and not stirred.height_only
    # The same sum n + dn in double: ulps of n ~ 1.
    np.testing.assert_allclose(stirred.ior(p), part.ior(p) + air.evaluate(p)[0], rtol=0, atol=1e-15)
    # Not the constructor's field: that one has the hot layer (4.5e-4 in n at 2 cm, measured).
    rebuilt = refracta.LogisticProfile(**part.params, turbulence=air)
    assert np.max(np.abs(stirred.ior(p) - rebuilt.ior(p))) > 1e-4  # far above the 1e-15 round-off


# -- 3. animate ---------------------------------------------------------------------------------------


def checker_wall():
    """A wall of 10 cm black and white squares 10 m ahead, filling a 4 deg view (a square spans
    ~1.1 pixels of 8.7 mrad), lit by a sun behind the camera."""
    scene = refracta.Scene()
    black, white = refracta.shading.Diffuse((0.03, 0.03, 0.03)), refracta.shading.Diffuse((0.8, 0.8, 0.8))
    for i in range(24):
        for j in range(12):
            scene.add_box(
                (10.0, 0.3 + 0.1 * (j - 5.5), 0.1 * (i - 11.5)),
                (0.05, 0.1, 0.1),
                material=white if (i + j) % 2 else black,
            )
    scene.add_light(refracta.lights.SunLight((-0.8, 0.5, 0.3), 2e4))  # ~1.3 W/m^2 from a 0.53 deg disc
    camera = refracta.Camera((0.0, 0.3, 0.0), (10.0, 0.3, 0.0), vfov=4, width=16, height=8)
    return scene, camera


def strong_turbulence():
    # cn2 1e-7 over 10 m of 5 cm cells turns rays by ~3 mrad rms, a third of a pixel here.
    return refracta.Turbulence(1e-7, cells=16, spacing=0.05, depth=None, wind=(0.0, 2.0), seed=1)


def test_animate_writes_a_gif_whose_frames_shimmer(tmp_path):
    scene, camera = checker_wall()
    field = refracta.PhysicalAtmosphere(surface_dt=0.0)
    times = [0.0, 0.05, 0.1]
    frames = refracta.animate(
        scene,
        camera,
        field,
        times,
        path=tmp_path / "shimmer.gif",
        turbulence=strong_turbulence(),
        progress=False,
        max_length=12.0,
    )
    assert frames.shape == (3, 8, 16, 3) and frames.dtype == np.float32
    with PIL_Image.open(tmp_path / "shimmer.gif") as gif:
        assert gif.n_frames == 3 and gif.size == (16, 8)
        assert gif.info["duration"] == 50  # fps = 1 / 0.05 s
    # The wind moves the pattern: a real share of the pixels change by a tenth of the wall's
    # contrast between frames; and the calm air renders another picture.
    contrast = frames[0].max() - frames[0].min()
    changed = np.abs(frames[1] - frames[0]).max(axis=2) > 0.1 * contrast
    # Shares argued in the comment above (strong turbulence, 3 frames 50 ms apart).
    assert contrast > 0.2 and changed.mean() > 0.1, (contrast, changed.mean())
    still = refracta.render(scene, camera, field, progress=False, max_length=12.0)
    # The calm render differs by a quarter of the wall's contrast (> 0.2) somewhere.
    assert np.abs(frames[0] - still).max() > 0.05


def test_a_gifs_frames_share_one_palette_so_still_regions_stay_still(tmp_path):
    # A sky gradient (above row 80) with a patch moving below it, changing colour: each frame quantised alone
    # changed 37-50 % of the still sky's pixels from frame to frame by a level or two. With one
    # palette the rows above the first changed pixel are identical (Floyd-Steinberg's error only
    # runs forward), and the colours stay within the dither's few levels of the frames'.
    rows, columns = 120, 320
    y = np.linspace(0.0, 1.0, rows)[:, None]
    x = np.linspace(0.0, 1.0, columns)[None, :]
    sky = np.stack([0.2 + 0.5 * y + 0 * x, 0.3 + 0.4 * y + 0.1 * x, 0.6 + 0.3 * y + 0 * x], axis=-1)
    frames = np.repeat(sky[None], 4, axis=0)
    colours = np.random.default_rng(1).random((4, 3)) * 2.0
    for t in range(4):
        frames[t, 80:100, 40 * t : 40 * t + 60] = colours[t]
    refracta.io.write_animation(tmp_path / "sky.gif", frames, fps=10)
    with PIL_Image.open(tmp_path / "sky.gif") as gif:
        assert gif.n_frames == 4
        shown = []
        for k in range(4):
            gif.seek(k)
            shown.append(np.asarray(gif.convert("RGB"), dtype=int))
    for a, b in zip(shown, shown[1:]):
        assert np.array_equal(a[:80], b[:80])
    expected = _animate._display_bytes(frames, None, None).astype(int)
    error = np.stack(shown) - expected
    # Dithering with 256 colours: each pixel within a few levels (measured 0.8 on average on such a sky)
    assert np.abs(error[:, :80]).mean() < 3.0
    # ... and the 8 x 8 means within 1.5 levels (measured 0.3): no banding
    assert np.abs(error[:, :80].reshape(4, 10, 8, 40, 8, 3).mean(axis=(2, 4))).max() < 1.5


# The turbulent field's n differs between y = 0 and the wall's foot, which render's ground check (a
# SceneWarning) reads as a misplaced ground; animate checks the calm field, once.
@pytest.mark.filterwarnings("ignore::refracta.SceneWarning")
def test_animate_denoises_each_frame_as_render_does():
    # One implementation: a denoised frame is render(denoise=True) of the field at that time (Open
    # Image Denoise is deterministic on the same input), and denoise=False keeps the plain render.
    scene, camera = checker_wall()
    field, air = refracta.PhysicalAtmosphere(surface_dt=0.0), strong_turbulence()
    times = [0.0, 0.05]
    frames = refracta.animate(
        scene, camera, field, times, turbulence=air, progress=False, max_length=12.0, denoise=True
    )
    plain = refracta.animate(scene, camera, field, times, turbulence=air, progress=False, max_length=12.0)
    for k, t in enumerate(times):
        at_t = _animate.field_at_time(field, air, t)
        expected = refracta.render(scene, camera, at_t, progress=False, max_length=12.0, denoise=True)
        np.testing.assert_array_equal(frames[k], expected)
        np.testing.assert_array_equal(plain[k], refracta.render(scene, camera, at_t, progress=False, max_length=12.0))
    assert not np.array_equal(frames, plain)  # the denoiser did something
    with pytest.raises(ValueError, match="denoise must be True or False"):
        refracta.animate(scene, camera, field, times, turbulence=air, progress=False, denoise="yes")


def test_animate_on_an_executor_matches_in_process(tmp_path):
    scene, camera = checker_wall()
    field = refracta.PhysicalAtmosphere(surface_dt=0.0)
    noise = dict(rms=3e-3, correlation_pixels=2.0, seed=5)
    here = refracta.animate(scene, camera, field, [0.0, 0.2], noise=noise, progress=False, max_length=12.0)
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        there = refracta.animate(
            scene, camera, field, [0.0, 0.2], noise=noise, executor=pool, progress=False, max_length=12.0
        )
    np.testing.assert_array_equal(here, there)
    assert np.abs(here[1] - here[0]).max() > 0.05  # the noise moved (10 pixels/s by default)


def test_animate_writes_mp4_and_frame_files(tmp_path):
    ffmpeg = pytest.importorskip("imageio_ffmpeg")
    scene, camera = checker_wall()
    camera = camera.resized(15, 7)  # odd sizes: padded for H.264
    field = refracta.PhysicalAtmosphere(surface_dt=0.0)
    noise = dict(rms=3e-3, correlation_pixels=2.0)
    refracta.animate(
        scene,
        camera,
        field,
        [0.0, 0.1, 0.2, 0.3],
        path=tmp_path / "shimmer.mp4",
        noise=noise,
        progress=False,
        max_length=12.0,
    )
    # Default rel 1e-6: 4 frames at 10 fps is 0.4 s as the container stores it.
    assert ffmpeg.count_frames_and_secs(str(tmp_path / "shimmer.mp4")) == (4, pytest.approx(0.4))
    with warnings.catch_warnings():  # imageio-ffmpeg's reader leaves its pipe to the collector
        warnings.simplefilter("ignore", ResourceWarning)
        reader = ffmpeg.read_frames(str(tmp_path / "shimmer.mp4"))
        meta = next(reader)
        reader.close()
        del reader
        gc.collect()
    # Default rel 1e-6: the container's frame rate, 10 exactly up to its rational.
    assert meta["size"] == (16, 8) and meta["fps"] == pytest.approx(10.0)
    refracta.animate(
        scene,
        camera,
        field,
        [0.0, 0.1],
        path=str(tmp_path / "frames" / "f{:02d}.png"),
        noise=noise,
        progress=False,
        max_length=12.0,
    )
    assert sorted(p.name for p in (tmp_path / "frames").iterdir()) == ["f00.png", "f01.png"]


def test_an_mp4_is_converted_and_tagged_as_bt709(tmp_path):
    # Flat patches of saturated and grey colours, decoded by BT.709's matrix as players do for tagged
    # (and HD) video: within 2 levels (H.264 at crf 10 and 4:2:0 chroma on 32-pixel patches: 0-2
    # measured). Encoded by ffmpeg's default BT.601 matrix and untagged, the green was 26 levels off.
    ffmpeg = pytest.importorskip("imageio_ffmpeg")
    linear = np.array([(0.6, 0.02, 0.02), (0.02, 0.6, 0.02), (0.02, 0.02, 0.6), (0.2, 0.2, 0.2), (0.8, 0.6, 0.05)])
    frames = np.zeros((2, 32, 32 * len(linear), 3), dtype=np.float32)
    for i, colour in enumerate(linear):
        frames[:, :, 32 * i : 32 * (i + 1)] = colour
    refracta.io.write_animation(tmp_path / "patches.mp4", frames, fps=10, exposure=1.0, tonemap="linear")
    expected = _animate._display_bytes(frames, 1.0, "linear")[0]
    exe = ffmpeg.get_ffmpeg_exe()
    probe = subprocess.run([exe, "-i", str(tmp_path / "patches.mp4")], capture_output=True, text=True).stderr
    stream = [line for line in probe.splitlines() if "Video:" in line]
    assert len(stream) == 1 and "bt709/bt709/iec61966-2-1" in stream[0], stream
    decode = [exe, "-i", str(tmp_path / "patches.mp4"), "-vf", "scale=in_color_matrix=bt709:in_range=tv"]
    raw = subprocess.run([*decode, "-f", "rawvideo", "-pix_fmt", "rgb24", "-v", "error", "-"], capture_output=True)
    decoded = np.frombuffer(raw.stdout, dtype=np.uint8).reshape(2, 32, -1, 3)[0].astype(int)
    centres = [(16, 32 * i + 16) for i in range(len(linear))]
    errors = [np.abs(decoded[c] - expected[c].astype(int)).max() for c in centres]
    assert max(errors) <= 2, errors


def test_animate_bad_input(tmp_path):
    scene, camera = checker_wall()
    field = refracta.PhysicalAtmosphere(surface_dt=0.0)
    air = refracta.Turbulence(cells=16)
    with pytest.raises(ValueError, match="every frame is the same"):
        refracta.animate(scene, camera, field, [0.0, 1.0], progress=False)
    with pytest.raises(ValueError, match=r"must end in \.gif or \.mp4"):
        refracta.animate(scene, camera, field, [0.0, 1.0], path=tmp_path / "x.avi", turbulence=air, progress=False)
    with pytest.raises(ValueError, match="times must be"):
        refracta.animate(scene, camera, field, [[0.0]], turbulence=air, progress=False)
    with pytest.raises(ValueError, match="times do not increase"):  # a file's frame rate (frames in an array need none)
        refracta.animate(scene, camera, field, [1.0, 0.0], path=tmp_path / "x.gif", turbulence=air, progress=False)
    with pytest.raises(ValueError, match="PhysicalAtmosphere or LogisticProfile"):
        refracta.animate(scene, camera, refracta.LinearSquaredProfile(), [0.0], turbulence=air, progress=False)
    with pytest.raises(ValueError, match="unknown option"):
        refracta.animate(scene, camera, field, [0.0], turbulence=air, progress=False, no_such_option=1)
    with pytest.raises(ValueError, match="noise takes rms, .* not 'foo'"):
        refracta.animate(scene, camera, field, [0.0], noise=dict(rms=1e-4, correlation_pixels=3, foo=1), progress=False)
    # A trial's: noise that does not move (its frames identical, like windless turbulence's), and
    # a camera or scene that is none (AttributeErrors on their attributes).
    for still in (dict(rms=0.0, correlation_pixels=3), dict(rms=1e-4, correlation_pixels=3, speed=(0, 0))):
        with pytest.raises(ValueError, match="the noise does not move"):
            refracta.animate(scene, camera, field, [0.0, 1.0], noise=still, progress=False)
    with pytest.raises(ValueError, match="animate: camera must be a refracta.Camera"):
        refracta.animate(scene, None, field, [0.0], turbulence=air, progress=False)
    with pytest.raises(ValueError, match="animate: scene must be a refracta.Scene"):
        refracta.animate(None, camera, field, [0.0], turbulence=air, progress=False)
    with pytest.raises(ValueError, match="geometric_noise: camera must be a refracta.Camera"):
        refracta.geometric_noise(None, 1e-4, 3)
    jittered = refracta.geometric_noise(camera, 1e-4, 3)
    with pytest.warns(refracta.SceneWarning, match="noise= replaces its jitter"):
        refracta.animate(scene, jittered, field, [0.0], noise=dict(rms=1e-4, correlation_pixels=3), progress=False)


def test_identical_frames_longer_than_a_gif_frame_holds_are_refused(tmp_path):
    # Pillow writes identical frames as one; at 0.01 fps eight of them overflowed its 16-bit delay
    # (a bare OverflowError after every frame had rendered).
    frames = np.ones((8, 4, 4, 3), np.float32)
    with pytest.raises(ValueError, match="GIF: frames 0 to 7 are identical .* 800 s"):
        refracta.io.write_animation(tmp_path / "still.gif", frames, fps=0.01)
    refracta.io.write_animation(tmp_path / "ok.gif", frames, fps=1.0)  # 8 s in one frame: allowed
    with PIL_Image.open(tmp_path / "ok.gif") as gif:
        assert gif.info["duration"] == 8000


def test_a_missing_folder_is_refused_before_any_frame_is_rendered(tmp_path, monkeypatch):
    scene, camera = checker_wall()
    rendered = []
    monkeypatch.setattr(_animate, "_render_frame", lambda *args: rendered.append(args))
    with pytest.raises(FileNotFoundError, match="does not exist"):
        refracta.animate(
            scene,
            camera,
            refracta.PhysicalAtmosphere(surface_dt=0.0),
            [0.0, 0.1],
            path=tmp_path / "nowhere" / "x.gif",
            noise=dict(rms=1e-4, correlation_pixels=2.0),
            progress=False,
        )
    assert rendered == []
