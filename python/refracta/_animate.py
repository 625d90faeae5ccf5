"""refracta.animate and refracta.geometric_noise: shimmering mirages over time (issue 10).

animate renders one frame per time through the same air with its turbulence carried by the wind
(refracta.Turbulence.at_time) -- the physical shimmer -- and/or through a camera whose rays are
turned by a seeded random angle map (geometric_noise: the follow-up editor's cheap shimmer, not
physical), and writes a GIF (Pillow), an MP4 (imageio-ffmpeg, ``pip install refracta[animation]``)
or a numbered frame sequence (refracta.io: EXR linear, PNG tone mapped). Frames are tasks of the
executor path shared with refracta.render and refracta.sweep (refracta._sweep.map_ordered).
"""

from __future__ import annotations

import contextlib
import math
import os
import subprocess
import tempfile
import warnings
from collections.abc import Sequence
from fractions import Fraction
from typing import Callable

import numpy as np

from refracta import _core, _options
from refracta._checks import finite_pair, is_number, is_seed, real_array
from refracta._render import (
    SceneWarning,
    _check_scene,
    _denoised,
    _surface_outputs,
    render_options,
    warn_if_perturbed_refused,
)
from refracta._sweep import map_ordered

__all__ = ["animate", "field_at_time", "geometric_noise", "geometric_noise_map"]

# -- the physical shimmer: the air at time t ----------------------------------------------------


def with_turbulence(field, turbulence):
    """The same air as `field` (a PhysicalAtmosphere or LogisticProfile: its parameters, hot spots
    and fixed data) with `turbulence` (a refracta.Turbulence, a TurbulenceLayer or None: calm) in
    place of its own: ``field.with_turbulence(turbulence)``. Raises ValueError for other fields."""
    if not isinstance(field, _core.IndexField):
        raise ValueError(
            f"animate: the field must be a PhysicalAtmosphere or LogisticProfile to carry turbulence "
            f"(got {type(field).__name__})"
        )
    try:
        return field.with_turbulence(turbulence)
    except ValueError as error:
        raise ValueError(f"animate: {error}") from None


def field_at_time(field, turbulence, t: float):
    """`field` with `turbulence` carried by its wind to time t [s] (turbulence.at_time(t))."""
    return with_turbulence(field, turbulence.at_time(t))


# -- the cheap shimmer: a random angle map (not physical) ----------------------------------------

# The pattern's default drift [pixels/s] (geometric_noise_map, geometric_noise, animate's noise=).
_NOISE_SPEED = (10.0, 0.0)


def geometric_noise_map(
    height: int,
    width: int,
    rms: float,
    correlation_pixels: float,
    seed: int = 0,
    time: float = 0.0,
    speed: Sequence[float] = _NOISE_SPEED,
) -> np.ndarray:
    """A seeded random map of small angles [rad], float64 (height, width, 2) (toward the image's
    right and up), for Camera.jittered: NOT PHYSICAL -- the follow-up editor's "geometric noise to
    rays", a stand-in for turbulence when tracing it costs too much.

    Each component is a stationary Gaussian random field with standard deviation `rms` [rad] and
    correlation exp(-d^2 / (2 l^2)) at a distance of d pixels, l = correlation_pixels > 0 (spectrum
    exp(-k^2 l^2 / 2)), synthesised by FFT on a periodic grid 4 l larger than the image on each
    side (so that opposite edges are uncorrelated). time [s] and speed (right, down) [pixels/s]:
    the pattern translated by speed * time (exact, sub-pixel: a phase shift of its spectrum).
    """
    problems = []
    if not (is_seed(height) and is_seed(width) and height >= 1 and width >= 1):
        problems.append(f"height and width must be whole numbers >= 1 (got {height!r}, {width!r})")
    if not (is_number(rms) and 0.0 <= rms < 0.1):
        problems.append(f"rms must be in [0, 0.1) rad (got {rms!r})")
    if not (is_number(correlation_pixels) and 0.0 < correlation_pixels < 1e4):
        problems.append(f"correlation_pixels must be in (0, 1e4) (got {correlation_pixels!r})")
    if not is_seed(seed):
        problems.append(f"seed must be a whole number >= 0 (got {seed!r})")
    if not (is_number(time) and math.isfinite(time)):
        problems.append(f"time must be a finite number of seconds (got {time!r})")
    velocity = finite_pair(speed)
    if velocity is None:
        problems.append(f"speed must be (right, down) [pixels/s], finite (got {speed!r})")
    if problems or velocity is None:  # velocity None is one of the problems
        raise ValueError("geometric_noise: " + "; ".join(problems))
    vx, vy = velocity
    height, width = int(height), int(width)  # numpy integers have no bit_length (_fft_size)
    pad = int(math.ceil(4.0 * correlation_pixels))
    ny, nx = _fft_size(height + pad), _fft_size(width + pad)
    if ny * nx > _MAX_NOISE_CELLS:  # a 9999-pixel correlation asked for ~40000^2 cells: the OS killed it
        raise ValueError(
            f"geometric_noise: correlation_pixels={correlation_pixels!r} on a {height}x{width} image needs a "
            f"{ny}x{nx} FFT grid (the image plus 4 correlation lengths), more than {_MAX_NOISE_CELLS} cells "
            f"({_MAX_NOISE_CELLS * 16 >> 20} MB a complex array); a correlation much longer than the image "
            f"only tilts it as a whole: use one of at most a few times the image size"
        )
    rng = np.random.default_rng(seed)
    ky = 2.0 * math.pi * np.fft.fftfreq(ny)[:, None]
    kx = 2.0 * math.pi * np.fft.rfftfreq(nx)[None, :]
    # Unit-variance white noise filtered by sqrt(N P_k), sum_k P_k = 1 over the full spectrum.
    power = np.exp(-0.5 * (kx * kx + ky * ky) * correlation_pixels**2)
    full = (
        np.exp(-0.5 * (2.0 * math.pi * np.fft.fftfreq(nx)) ** 2 * correlation_pixels**2).sum()
        * np.exp(-0.5 * (2.0 * math.pi * np.fft.fftfreq(ny)) ** 2 * correlation_pixels**2).sum()
    )
    shift_x, shift_y = vx * time, vy * time
    if not (math.isfinite(shift_x) and math.isfinite(shift_y)):
        raise ValueError(f"geometric_noise: speed x time must be a finite shift in pixels (got {speed!r} x {time!r})")
    # The pattern repeats with the grid: its shift modulo the grid is the same pattern, and stays
    # exact however long the animation runs (time=1e308 gave NaN angles, reported by Camera.jittered).
    shift_x, shift_y = math.fmod(shift_x, nx), math.fmod(shift_y, ny)
    gain = np.sqrt(nx * ny * power / full) * np.exp(-1j * (kx * shift_x + ky * shift_y))
    out = np.empty((height, width, 2))
    for c in range(2):
        noise = rng.standard_normal((ny, nx))
        out[:, :, c] = np.fft.irfft2(np.fft.rfft2(noise) * gain, s=(ny, nx))[:height, :width] * rms
    out[:, :, 1] *= -1.0  # rows grow downward; the camera's second angle is toward the image's up
    return out


def geometric_noise(
    camera: _core.Camera,
    rms: float,
    correlation_pixels: float,
    seed: int = 0,
    time: float = 0.0,
    speed: Sequence[float] = _NOISE_SPEED,
) -> _core.Camera:
    """`camera` with every ray turned by geometric_noise_map(camera.height, camera.width, rms,
    correlation_pixels, seed, time, speed) -- NOT PHYSICAL: a seeded per-pixel angular jitter [rad]
    with a Gaussian spectrum (the follow-up editor's cheap shimmer; refracta.Turbulence is the
    physical one). Camera.project ignores the jitter."""
    if not isinstance(camera, _core.Camera):
        raise ValueError(f"geometric_noise: camera must be a refracta.Camera (got {type(camera).__name__})")
    return camera.jittered(geometric_noise_map(camera.height, camera.width, rms, correlation_pixels, seed, time, speed))


# The largest FFT grid geometric_noise_map synthesises on: 4096^2 cells, 256 MB per complex array.
_MAX_NOISE_CELLS = 1 << 24


def _fft_size(n: int) -> int:
    """The smallest 2^a 3^b 5^c >= n (a fast FFT length)."""
    best = 1 << max(0, (n - 1).bit_length())
    f5 = 1
    while f5 < best:
        f35 = f5
        while f35 < best:
            size = f35
            while size < n:
                size *= 2
            best = min(best, size)
            f35 *= 3
        f5 *= 5
    return best


# -- animation ----------------------------------------------------------------------------------


def animate(
    scene: _core.Scene,
    camera: _core.Camera,
    field,
    times,
    path: None | str | os.PathLike = None,
    fps: float | None = None,
    turbulence=None,
    noise: dict | None = None,
    executor=None,
    progress: bool | Callable[[int, int], None] = True,
    exposure: float | None = None,
    tonemap: str | None = None,
    denoise: bool = False,
    **options,
) -> np.ndarray:
    """Render a shimmering mirage: one frame per time in `times` [s]; returns linear radiance,
    float32 (T, H, W, 3), and writes it to `path` if given.

    turbulence: a refracta.Turbulence; frame t renders `field` (a PhysicalAtmosphere or
    LogisticProfile: its parameters and hot spots, its own turbulence replaced) with
    turbulence.at_time(t), the pattern carried by its wind (physical). noise: keywords of
    refracta.geometric_noise (rms [rad], correlation_pixels, seed, speed [pixels/s]): frame t's
    camera is ``geometric_noise(camera, time=t, **noise)`` -- NOT PHYSICAL, a cheap stand-in. Give
    either or both (ValueError if neither: every frame would be the same).

    path: '.gif' (Pillow; loops), '.mp4' (H.264 through imageio-ffmpeg, frames padded to even
    sizes), or a pattern with a '{}' field for the frame number ('frames/f{:03d}.exr': one file
    per frame through refracta.io.write_image: EXR linear, PNG tone mapped). GIF and MP4 frames are
    tone mapped like refracta.io.to_display(frame, exposure, tonemap) with one exposure for every
    frame (no flicker): `exposure`, or by default the automatic exposure of all the frames
    together (refracta.io.exposure_of; tonemap None: io's default curve). Frame files get
    write_image's defaults (PNG: each frame exposed automatically; EXR linear) unless `exposure`
    is given. fps: frames per second of the file (default: 1 / the median step of
    `times`). executor: None renders the frames one after another here (each on every core); a
    concurrent.futures.Executor or a dask.distributed Client renders one frame per task (scene,
    camera, field and turbulence sent to each dask worker once). progress: a bar of frames on
    stderr (True), a callable progress(done, total), or False. denoise: each frame denoised as
    render(denoise=True) does it (Open Image Denoise with the frame's own albedo and normal), so
    that only the shimmer moves, not the sampling noise. Further keywords: render's (method, spp,
    max_length, turbulence_trace, ...: see refracta.render).
    """
    # render's keywords first: a misspelt one (turbulance=) was blamed on a missing turbulence=.
    _options.build(_core.RenderOptions, where="animate", **options)
    # Named before anything reads them (camera=None was an AttributeError on its width).
    if not isinstance(scene, _core.Scene):
        raise ValueError(f"animate: scene must be a refracta.Scene (got {type(scene).__name__})")
    if not isinstance(camera, _core.Camera):
        raise ValueError(f"animate: camera must be a refracta.Camera (got {type(camera).__name__})")
    times = real_array(times, "animate: times")  # not True/False, nor a string
    if times.ndim != 1 or times.size < 1:
        raise ValueError(f"animate: times must be a non-empty 1-D array of finite seconds (got shape {times.shape})")
    if not np.all(np.isfinite(times)):
        bad = int(np.flatnonzero(~np.isfinite(times))[0])
        raise ValueError(f"animate: times must be finite seconds (got times[{bad}] = {times[bad]})")
    if turbulence is None and noise is None:
        raise ValueError(
            "animate: give turbulence= (a refracta.Turbulence carried by its wind) or noise= "
            "(geometric_noise keywords): without either every frame is the same"
        )
    if turbulence is not None and not hasattr(turbulence, "at_time"):
        raise ValueError(f"animate: turbulence must be a refracta.Turbulence (got {type(turbulence).__name__})")
    if turbulence is not None and noise is None and len(np.unique(times)) > 1:
        # Frozen turbulence moves with its wind only (Taylor's hypothesis): without wind, or without
        # strength, every frame was the same (a trial: 45 s a frame for identical frames).
        still = "has no wind (wind=(0, 0))" if not any(turbulence.wind) else None
        still = still or ("has no strength (cn2=0)" if not turbulence.cn2 > 0.0 else None)
        if still:
            raise ValueError(
                f"animate: the turbulence {still}, so every frame is the same: give it a wind and a cn2 > 0, "
                "or noise= (geometric_noise keywords)"
            )
    if noise is not None:
        if not isinstance(noise, dict) or "time" in noise:
            raise ValueError(f"animate: noise must be a dict of geometric_noise keywords, without time (got {noise!r})")
        unknown = sorted(set(noise) - {"rms", "correlation_pixels", "seed", "speed"})
        if unknown:
            raise ValueError(
                f"animate: noise takes rms, correlation_pixels, seed and speed (geometric_noise's "
                f"keywords), not {', '.join(map(repr, unknown))}"
            )
        missing = sorted({"rms", "correlation_pixels"} - set(noise))
        if missing:
            needs = " and ".join(missing)
            raise ValueError(f"animate: noise needs {needs} (geometric_noise's keywords; got {noise!r})")
        geometric_noise_map(1, 1, **noise)  # checks the values before any work
        moving = noise["rms"] > 0.0 and any(noise.get("speed", _NOISE_SPEED))
        if not moving and (turbulence is None or not any(turbulence.wind)) and len(np.unique(times)) > 1:
            raise ValueError(
                "animate: the noise does not move (rms 0 or speed (0, 0)), so every frame is the same: "
                "give it an rms > 0 and a speed, or turbulence= with a wind"
            )
        if camera.jitter is not None:
            warnings.warn(
                "animate: the camera is jittered, and noise= replaces its jitter in every frame "
                "(give camera.without_jitter() to say so)",
                SceneWarning,
                stacklevel=2,
            )
    if turbulence is not None:
        with_turbulence(field, turbulence)  # checks the field before any work
        if getattr(field, "turbulence", None) is not None:
            warnings.warn(
                "animate: the field has turbulence of its own, and turbulence= replaces it in every frame "
                "(give field.with_turbulence(None) to say so)",
                SceneWarning,
                stacklevel=2,
            )
    given_fps = fps
    unused = [name for name, value in (("fps", fps), ("exposure", exposure), ("tonemap", tonemap)) if value is not None]
    if path is None and unused:
        raise ValueError(
            f"animate: {', '.join(unused)} shape{'s' if len(unused) == 1 else ''} the file written to `path`, "
            "and no path is given (the returned frames are linear radiance: refracta.io.to_display shows them)"
        )
    if path is not None:
        path = os.fsdecode(os.fspath(path))  # a bytes path too
        rate = None if "{" in path else _frame_rate(times, fps)
        fps = _checked_file(path, rate, given_fps, exposure, tonemap, times.size)
    _check_frames_fit(times.size, camera, path, exposure)
    if not isinstance(denoise, (bool, np.bool_)):
        raise ValueError(f"animate: denoise must be True or False (got {denoise!r})")
    if denoise:
        options["surface_aovs"] = True  # the denoiser's guides
    settings = render_options(**options)
    _check_scene(scene, camera, field, settings.method)  # render's SceneWarnings, once for all frames
    first = field_at_time(field, turbulence, float(times[0])) if turbulence is not None and times.size else field
    warn_if_perturbed_refused(first, settings, camera, "animate")
    outcomes = map_ordered(
        _render_frame,
        [(float(t),) for t in times],
        executor,
        progress,
        "rendering frames",
        shared=(scene, camera, field, settings, turbulence, noise, bool(denoise)),
    )
    x0, y0, x1, y1 = settings.bounds_in(camera.width, camera.height)  # pixel_bounds: frames of the window
    frames = np.empty((times.size, y1 - y0, x1 - x0, 3), dtype=np.float32)
    for i, (ok, value) in enumerate(outcomes):
        if not ok:
            raise value[0]
        frames[i] = value
    if path is not None:
        _writer_for(path)(path, frames, fps, exposure, tonemap)
    return frames


def _checked_file(
    path: str, fps: float | None, given_fps, exposure, tonemap, count: int, where: str = "animate"
) -> float | None:
    """The frame rate to write `path` at (None for frame files), after the checks made before any
    work: a GIF's or an MP4's rate within what its file holds, fps only for a GIF or an MP4, a
    known format and its package, the exposure and tone map, a pattern naming each of the `count`
    frames apart, the folder there and the file writable."""
    _writer_for(path, where)  # an unknown format or a missing package fails before rendering
    if "{" not in path:
        if fps is None:
            raise ValueError(f"{where}: give fps (frames per second) for {path!r}")
        _check_frame_rate(path, fps, "" if given_fps is not None else ", from the times", where)
    elif given_fps is not None:
        raise ValueError(f"{where}: fps is a GIF's or an MP4's; frame files ({path!r}) have no rate")
    _check_output_settings(path, exposure, tonemap, count, where)
    folder = os.path.dirname(os.path.abspath(path))
    if "{" not in path and not os.path.isdir(folder):  # ... and so does a folder that is not there
        # (frame files make theirs)
        raise FileNotFoundError(f"{where}: the folder of {path!r} does not exist ({folder})")
    if "{" not in path:  # ... or a file that cannot be written there (tried: /proc takes none)
        _check_writable(path)
    return None if "{" in path else fps


def write_animation(path, frames, fps: float | None = None, exposure: float | None = None, tonemap: str | None = None):
    """Write frames of linear radiance, float (T, H, W, 3), as animate writes its own: '.gif'
    (Pillow; loops), '.mp4' (H.264 through imageio-ffmpeg) at `fps` frames per second (needed for
    them), or a pattern with a '{}' field for the frame number (one file per frame through
    refracta.io.write_image). GIF and MP4 frames share one exposure (`exposure`, or the automatic
    exposure of all the frames together; tonemap None: io's default curve), so nothing flickers.
    A GIF holds a run of identical consecutive frames as one frame of their delays together
    (Pillow's writing: the timing is kept, the frame count not).
    For frames made otherwise than by animate: a sweep's (refracta.sweep), a turntable's.

    Raises:
        ValueError: frames not (T, H, W, 3) finite numbers with T >= 1, fps missing or out of
            range for the format (a GIF: 1/655.35 to 50 fps; an MP4: 1/655.35 fps to 1e4), an
            unknown format, a pattern that names two frames alike, identical GIF frames lasting
            more than 655.35 s together.
        ImportError: Pillow or imageio-ffmpeg missing for a GIF or an MP4.
        FileNotFoundError, OSError: the folder missing, the file not writable.
        refracta.IoError: ffmpeg failed to write the MP4 (its message given).
    """
    try:
        frames = np.asarray(frames, dtype=np.float32)
    except (TypeError, ValueError):
        raise ValueError(f"write_animation: frames must be an array of numbers (got {type(frames).__name__})") from None
    if frames.ndim != 4 or frames.shape[0] < 1 or frames.shape[3] != 3 or 0 in frames.shape:
        raise ValueError(f"write_animation: frames must be (T, H, W, 3) with T >= 1 (got shape {frames.shape})")
    if not np.all(np.isfinite(frames)):
        raise ValueError("write_animation: frames hold NaN or inf")
    path = os.fsdecode(os.fspath(path))
    if "{" not in path and fps is not None:
        fps = _frame_rate(np.zeros(0), fps, "write_animation")  # its range checked
    fps = _checked_file(path, fps, fps, exposure, tonemap, frames.shape[0], "write_animation")
    _writer_for(path)(path, frames, fps, exposure, tonemap)


def _render_frame(scene, camera, field, settings, turbulence, noise, denoise, t):
    """One frame on a worker: the image at time t (linear float32 (H, W, 3)), denoised if asked."""
    air = field_at_time(field, turbulence, t) if turbulence is not None else field
    view = geometric_noise(camera, time=t, **noise) if noise is not None else camera
    image, _ = _core._render(scene, view, air, settings, None)
    colour = np.ascontiguousarray(image[..., :3])
    if not denoise:
        return colour
    return _denoised(colour, _surface_outputs(image), settings)


def _check_frames_fit(count: int, camera, path: str | None, exposure) -> None:
    """ValueError before any work when the returned frames (float32 RGB) would take more than half
    this machine's memory (the rest: each frame's render buffers). A GIF or MP4 needs about twice
    that again while it is written: the frames stacked for their joint exposure (unless `exposure`
    is given), and their 8-bit display copies."""
    needed = 12.0 * count * camera.width * camera.height
    if path is not None and "{" not in path:
        needed *= 1.25 if exposure is not None else 2.25
    memory = _core.physical_memory_bytes()
    if memory > 0 and needed > memory / 2:
        raise ValueError(
            f"animate: {count} times of {camera.width} x {camera.height} frames need {needed / 1e9:.1f} GB "
            f"for the frames and the file, more than half this machine's {memory / 1e9:.1f} GB: render fewer "
            "times per call (or a smaller camera)"
        )


def _check_frame_rate(path: str, fps: float, source: str, where: str) -> None:
    """ValueError unless a GIF's or an MP4's file holds frames at `fps` (`source`: where fps came from)."""
    if path.lower().endswith(".gif") and fps > _GIF_FASTEST:
        raise ValueError(
            f"{where}: a GIF's frame delays are whole hundredths of a second, at least 2 (browsers slow "
            f"shorter ones to 0.1 s): at most {_GIF_FASTEST:g} fps (got {fps:g}{source}); give fps= or "
            "write an MP4"
        )
    if fps < _SLOWEST and path.lower().endswith(".gif"):
        raise ValueError(
            f"{where}: a GIF's frame delays are 16-bit hundredths of a second, at most 655.35 s: at least "
            f"{_SLOWEST:.6g} fps (got {fps:g}{source}); give fps= (a time-lapse plays faster than it was shot)"
        )
    if fps < _SLOWEST:
        raise ValueError(
            f"{where}: an MP4 shows a frame at most 655.35 s (ffmpeg's muxer fails on longer ones): at least "
            f"{_SLOWEST:.6g} fps (got {fps:g}{source}); give fps= (a time-lapse plays faster than it was shot)"
        )


def _check_output_settings(path: str, exposure, tonemap, count: int, where: str = "animate") -> None:
    """The file's display settings and frame pattern checked before any frame is rendered: the
    pattern names each of the `count` frames apart (ValueError naming two it names alike)."""
    from refracta import io

    io.settings(None, exposure=exposure, tonemap=tonemap)  # ValueError naming the setting
    if "{" in path:
        try:
            distinct = path.format(0) != path.format(1)
            problem = "" if distinct else ": it names every frame alike"
        except (KeyError, IndexError, ValueError, TypeError, AttributeError) as error:
            problem = f": {error!r}"
        if problem:
            raise ValueError(
                f"{where}: path's pattern must have one '{{}}' field for the frame number, as "
                f"'frames/f{{:03d}}.png' (got {path!r}{problem})"
            )
        _check_frame_names(path, count, where)
        _core._check_image_format(path.format(0))  # a format OpenImageIO writes: IoError naming the file


def _check_frame_names(path: str, count: int, where: str) -> None:
    """ValueError naming the first two of frames 0..count-1 that `path`'s pattern names alike (one
    file written over the other: '{:.0e}' names 10 and 11 both '1e+01'), as the same file
    ('d{}/../f.png' names every frame 'f.png'), or a frame it cannot name."""
    first_of: dict[str, int] = {}
    for i in range(count):
        try:
            name = path.format(i)
        except (KeyError, IndexError, ValueError, TypeError, AttributeError, OverflowError) as error:
            raise ValueError(f"{where}: path's pattern {path!r} cannot name frame {i}: {error}") from None
        file = os.path.normcase(os.path.abspath(name))
        if file in first_of:
            raise ValueError(
                f"{where}: path's pattern {path!r} names frames {first_of[file]} and {i} alike ({name!r}): "
                f"one would overwrite the other; give a field that writes every frame number of 0..{count - 1} "
                f"apart, as '{{:03d}}'"
            )
        first_of[file] = i
    # Their folders, made when written, must not be blocked by a file of that name (a trial: every
    # frame rendered, then a bare FileExistsError).
    for folder in sorted({os.path.dirname(file) for file in first_of}):
        ancestor = folder
        while ancestor and not os.path.exists(ancestor) and os.path.dirname(ancestor) != ancestor:
            ancestor = os.path.dirname(ancestor)
        if ancestor and os.path.exists(ancestor) and not os.path.isdir(ancestor):
            raise NotADirectoryError(
                f"{where}: path's pattern {path!r} writes frames into {folder!r}, but {ancestor!r} is a file"
            )


# A GIF's frame delay is a whole number of hundredths of a second; browsers play 0 or 1 as 10.
_GIF_FASTEST = 50.0
# The longest frame a GIF or an MP4 holds [s]: a GIF's delay is 16-bit hundredths of a second
# (655.35 s); ffmpeg's MP4 muxer fails on frames near 2^16 s and longer ("Not yet implemented" at
# 1/65535 fps from 30 frames on, at 1e-5 fps always; below 1e-6 fps the rational rate _write_mp4
# passes rounds to 0) and wrote 20000 frames of 655.35 s: the GIF's bound serves both.
_SLOWEST = 1.0 / 655.35


def _check_writable(path: str) -> None:
    """Opens `path` for appending (creating it, then removing what it created): OSError naming it now,
    not after every frame has rendered."""
    existed = os.path.exists(path)
    try:
        with open(path, "ab"):
            pass
    except OSError as error:
        raise OSError(f"animate: cannot write {path!r}: {error.strerror}") from None
    if not existed:
        os.remove(path)


def _frame_rate(times: np.ndarray, fps: float | None, where: str = "animate") -> float:
    if fps is not None:
        if not (is_number(fps) and 0.0 < fps < 1e4):
            raise ValueError(f"{where}: fps must be in (0, 1e4) (got {fps!r})")
        return float(fps)
    steps = np.diff(times)
    if steps.size == 0:
        return 1.0
    step = float(np.median(steps))
    if not step > 0.0:
        raise ValueError("animate: times do not increase; give fps")
    return 1.0 / step


def _writer_for(path: str, where: str = "animate"):
    """The writer of `path`'s format (raising ValueError for an unknown one, ImportError naming the
    package for a missing one)."""
    if "{" in path:
        return _write_sequence
    _core._check_writable(path)  # a FIFO would block the write once every frame is rendered
    extension = os.path.splitext(path)[1].lower()
    if extension == ".gif":
        try:
            import PIL.Image  # noqa: F401
        except ImportError:
            raise ImportError(f"{where}: writing a GIF needs Pillow (pip install pillow)") from None
        return _write_gif
    if extension == ".mp4":
        try:
            import imageio_ffmpeg  # noqa: F401
        except ImportError:
            raise ImportError(
                f"{where}: writing an MP4 needs imageio-ffmpeg (pip install 'refracta[animation]')"
            ) from None
        return _write_mp4
    raise ValueError(f"{where}: path must end in .gif or .mp4, or hold a '{{}}' field for frame files (got {path!r})")


def _display_bytes(frames, exposure, tonemap) -> np.ndarray:
    """uint8 (T, H, W, 3) display frames (refracta.io.to_display), one exposure for all."""
    from refracta.io import exposure_of, to_display

    if exposure is None:  # the frames' joint log-average, stacked as one tall image
        with warnings.catch_warnings():  # black frames stay black at any exposure
            warnings.filterwarnings("ignore", "exposure_of: the image has no light", RuntimeWarning)
            exposure = exposure_of(np.concatenate(list(frames), axis=0))
    return np.stack([np.round(to_display(f, exposure, tonemap) * 255.0).astype(np.uint8) for f in frames])


# The longest delay a GIF frame holds [ms]: a 16-bit count of hundredths of a second.
_GIF_LONGEST_DELAY = 655_350


def _write_gif(path, frames, fps, exposure, tonemap):
    """Pillow writes a run of identical frames as one frame holding their delays together (the
    animation's timing is kept, its frame count not), which a GIF keeps only up to 655.35 s: a
    longer run is refused by name (it was a bare OverflowError after every frame had rendered)."""
    images = _gif_frames(_display_bytes(frames, exposure, tonemap))
    delays = _gif_delays(len(images), fps)
    start, held = 0, delays[0]
    for i in range(1, len(images) + 1):
        if i < len(images) and images[i].tobytes() == images[i - 1].tobytes():
            held += delays[i]
            continue
        if held > _GIF_LONGEST_DELAY:
            raise ValueError(
                f"GIF: frames {start} to {i - 1} are identical and would be one GIF frame of {held / 1000:g} s, "
                f"longer than the {_GIF_LONGEST_DELAY / 1000:g} s a GIF frame holds: write an MP4 or frame files, "
                "or raise fps"
            )
        if i < len(images):
            start, held = i, delays[i]
    images[0].save(path, save_all=True, append_images=images[1:], duration=delays, loop=0, optimize=False)


# Pixels (of every frame together) the GIF's shared palette is chosen from: median cut on ~1 MB.
_GIF_PALETTE_SAMPLE = 300_000


def _gif_frames(data: np.ndarray) -> list:
    """uint8 (T, H, W, 3) display frames as palette images that share one 256-colour palette (median
    cut over pixels of all frames), Floyd-Steinberg dithered. Each frame quantised alone (Pillow's
    default) chose its own palette: a still sky changed by a level or two in 37-50 % of its pixels
    from frame to frame, flickering; with one palette a still region above the first changed pixel
    is identical, and the dither's spread below it changes 1-4 % (tests/render/test_animate.py)."""
    import PIL.Image

    stride = max(1, int(np.ceil(np.sqrt(data[..., 0].size / _GIF_PALETTE_SAMPLE))))
    sample = data[:, ::stride, ::stride]
    mosaic = np.ascontiguousarray(sample.reshape(-1, sample.shape[2], 3))  # the frames stacked as one tall image
    palette = PIL.Image.fromarray(mosaic).quantize(colors=256, method=PIL.Image.Quantize.MEDIANCUT)
    dither = PIL.Image.Dither.FLOYDSTEINBERG
    return [PIL.Image.fromarray(frame).quantize(palette=palette, dither=dither) for frame in data]


def _gif_delays(count: int, fps: float) -> list[int]:
    """Each frame's delay [ms]: a GIF keeps whole hundredths of a second, so each frame ends at its
    time rounded to one (24 fps: 40, 40, 50, 40, 40, 50 ... ms), and the animation runs at `fps` on
    average instead of at the nearest whole delay's rate (25 fps); at least 20 ms each (animate
    checked fps <= _GIF_FASTEST)."""
    ends = [round((i + 1) * 100.0 / fps) for i in range(count)]
    return [10 * max(2, end - start) for start, end in zip([0] + ends[:-1], ends)]


# The MP4's colours: converted to Y'CbCr by BT.709's matrix in video range and tagged so (with sRGB's
# transfer curve, which to_display applied, and BT.709's primaries, sRGB's). Untagged, ffmpeg's
# default conversion was BT.601's, which players read as BT.709 for HD video (browsers): saturated
# colours were off by up to 26 of 255 levels (tests/render/test_animate.py).
_MP4_COLOUR_TAGS = "colorprim=bt709:transfer=iec61966-2-1:colormatrix=bt709"


def _write_mp4(path, frames, fps, exposure, tonemap):
    """H.264 in yuv420p through the ffmpeg imageio-ffmpeg ships, run here with the command its
    write_frames(quality=8) builds for libx264 (crf 10) -- write_frames reads neither ffmpeg's exit
    status nor its messages: a rate ffmpeg refused wrote no file, or a 261-byte unreadable one, and
    returned normally. IoError naming the file and ffmpeg's message when ffmpeg fails (the file it
    began removed)."""
    import imageio_ffmpeg

    data = _display_bytes(frames, exposure, tonemap)
    # H.264 in yuv420p needs even sizes: repeat the last row / column.
    data = np.pad(data, ((0, 0), (0, data.shape[1] % 2), (0, data.shape[2] % 2), (0, 0)), mode="edge")
    command = [
        imageio_ffmpeg.get_ffmpeg_exe(),
        *("-y", "-f", "rawvideo", "-vcodec", "rawvideo", "-s", f"{data.shape[2]}x{data.shape[1]}"),
        *("-pix_fmt", "rgb24", "-r", str(Fraction(fps).limit_denominator()), "-i", "-", "-an"),
        *("-vf", "scale=out_color_matrix=bt709:out_range=tv", "-vcodec", "libx264", "-pix_fmt", "yuv420p"),
        *("-x264-params", _MP4_COLOUR_TAGS, "-crf", "10", "-v", "error", path),
    ]
    with tempfile.TemporaryFile() as log:  # a file, not a pipe: ffmpeg never waits for a reader
        existed = os.path.exists(path)  # a failure removes only a file of its own making
        ffmpeg = subprocess.Popen(command, stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=log)
        pipe = ffmpeg.stdin
        assert pipe is not None  # stdin=PIPE
        try:
            try:
                for frame in data:
                    pipe.write(np.ascontiguousarray(frame).tobytes())
            except BrokenPipeError:  # ffmpeg stopped reading: its status and log say why
                pass
            with contextlib.suppress(BrokenPipeError):  # (closed all the same)
                pipe.close()
            status = ffmpeg.wait()
        except BaseException:  # Ctrl-C: no ffmpeg left behind
            ffmpeg.kill()
            ffmpeg.wait()
            raise
        log.seek(0)
        message = log.read().decode(errors="replace").strip()
    if status != 0:
        if os.path.isfile(path) and not existed:
            os.remove(path)  # what ffmpeg began is no movie
        said = " | ".join(message.splitlines()[-4:]) or "no message"
        raise _core.IoError(f"cannot write the MP4 {path!r}: ffmpeg (H.264) stopped with status {status}: {said}")


def _write_sequence(path, frames, fps, exposure, tonemap):
    from refracta import io

    for i, frame in enumerate(frames):
        target = path.format(i)
        folder = os.path.dirname(target)
        if folder:
            os.makedirs(folder, exist_ok=True)
        io.write_image(target, frame, exposure=exposure, tonemap=tonemap)
