"""An adversarial trial's findings whose fix lies in the Python layer: animations written at rates
their files cannot hold (no file, or an unreadable MP4, and a normal return), frame patterns that
wrote two frames to one file, a tilt variance of NaN or inf for scales it took, the command line's
--set table=True, empty --aovs names and an empty -o, wavelength samples of a string, a background
colour called a point, and spectra whose overflow came back as NaN. Each failed before its fix."""

import math
import os
from pathlib import Path

import numpy as np
import pytest

import refracta
from refracta import cli, examples, io, oit, spectrum
from refracta import turbulence as tb

DATA = Path(__file__).resolve().parents[1] / "data"
FRAMES = np.random.default_rng(3).random((2, 8, 16, 3))


def _noise():
    return dict(rms=2e-4, correlation_pixels=3.0)


# -- animations ---------------------------------------------------------------------------------


@pytest.mark.parametrize("fps", [1e-300, 1e-10, 1e-6, 1e-3])
def test_an_mp4_rate_ffmpeg_cannot_write_is_refused_before_writing(tmp_path, fps):
    # 1e-300 and 1e-10 wrote no file, 1e-6 a 261-byte unreadable one; write_animation returned normally.
    pytest.importorskip("imageio_ffmpeg")
    path = tmp_path / "x.mp4"
    with pytest.raises(ValueError, match=r"write_animation: an MP4 shows a frame at most 655.35 s.*at least 0.00152"):
        io.write_animation(path, FRAMES, fps=fps)
    assert not path.exists()
    road = examples.hot_road(16, 6)
    with pytest.raises(ValueError, match=r"animate: an MP4 shows a frame at most 655.35 s"):
        refracta.animate(road.scene, road.camera, road.field, [0.0, 1.0], path, fps=fps, noise=_noise())
    with pytest.raises(ValueError, match=r"from the times"):  # a rate from the times: 1e10 s apart
        refracta.animate(road.scene, road.camera, road.field, [0.0, 1e10], path, noise=_noise())


def test_an_mp4_at_the_slowest_rate_is_a_movie_of_every_frame(tmp_path):
    ffmpeg = pytest.importorskip("imageio_ffmpeg")
    path = tmp_path / "slow.mp4"
    io.write_animation(path, FRAMES, fps=1.0 / 655.35)
    frames, _ = ffmpeg.count_frames_and_secs(str(path))
    assert frames == 2


@pytest.mark.skipif(os.name != "posix", reason="the stand-in ffmpeg is a shell script")
@pytest.mark.parametrize("size", [(8, 16), (256, 256)])  # the frames fit the pipe's buffer, or not
def test_an_mp4_ffmpeg_fails_to_write_raises_io_error_with_its_message(tmp_path, monkeypatch, size):
    # ffmpeg's failures went to stderr only, and write_animation returned as if it had written.
    ffmpeg = pytest.importorskip("imageio_ffmpeg")
    failing = tmp_path / "ffmpeg"
    failing.write_text(
        "#!/bin/sh\nfor last; do :; done\nprintf 'partial' > \"$last\"\n"
        "echo \"[vost#0:0] Unknown encoder 'libx264'\" >&2\nexit 8\n"
    )
    failing.chmod(0o755)
    monkeypatch.setattr(ffmpeg, "get_ffmpeg_exe", lambda: str(failing))
    path = tmp_path / "x.mp4"
    with pytest.raises(refracta.IoError, match=r"x\.mp4.*status 8.*Unknown encoder 'libx264'"):
        io.write_animation(path, np.full((2, *size, 3), 0.5), fps=10.0)
    assert not path.exists()  # what ffmpeg began is removed


def test_a_frame_pattern_that_names_two_frames_alike_is_refused(tmp_path):
    # '{:.0e}' wrote 11 files for 12 frames: 10 and 11 are both '1e+01'.
    frames = np.random.default_rng(4).random((12, 4, 8, 3))
    with pytest.raises(
        ValueError, match=r"write_animation: path's pattern .*pc\{:.0e\}.* names frames 10 and 11 alike"
    ):
        io.write_animation(str(tmp_path / "pc{:.0e}.exr"), frames)
    with pytest.raises(ValueError, match=r"names frames 0 and 1 alike"):  # one file however numbered
        io.write_animation(str(tmp_path / "d{}" / ".." / "f.exr"), frames)
    assert list(tmp_path.iterdir()) == []
    road = examples.hot_road(16, 6)
    with pytest.raises(ValueError, match=r"animate: path's pattern .* names frames 10 and 11 alike"):
        refracta.animate(
            road.scene, road.camera, road.field, np.arange(12) * 0.1, str(tmp_path / "pc{:.0e}.exr"), noise=_noise()
        )
    io.write_animation(str(tmp_path / "f{:.0e}.exr"), frames[:10])  # 0e+00 .. 9e+00: ten names
    assert len(list(tmp_path.iterdir())) == 10


# -- the continuous spectrum's tilt -------------------------------------------------------------

# In units of its smallest scale the quadrature is the same at any scale: the values agree to
# rounding (2e-16 measured); 1e-12 leaves room for the exponentials of other platforms.
SCALE_FREE_TOLERANCE = 1e-12


@pytest.mark.parametrize(
    ("scales", "reference"),
    [
        (dict(inner_scale=1e-100), dict(inner_scale=0.005)),
        (dict(inner_scale=1e300), dict(inner_scale=0.005)),
        (dict(inner_scale=5e-324), dict(inner_scale=0.005)),
        (dict(aperture=1e-300), dict(aperture=0.01)),
        (dict(inner_scale=1e-100, outer_scale=1e-98), dict(inner_scale=0.005, outer_scale=0.5)),
    ],
)
def test_tilt_variance_is_finite_and_scales_as_the_scale_to_the_minus_one_third(scales, reference):
    # NaN for 1e-100 and 1e300 m, and for an aperture of 1e-300 m, with numpy's RuntimeWarning.
    value = tb.tilt_variance(1e-10, 100.0, **scales)
    expected = tb.tilt_variance(1e-10, 100.0, **reference)
    ratio = next(iter(scales.values())) / next(iter(reference.values()))
    assert math.isfinite(value)
    assert value == pytest.approx(expected * ratio ** (-1.0 / 3.0), rel=SCALE_FREE_TOLERANCE)


def test_tilt_variance_refuses_what_would_be_inf_or_nan():
    with pytest.raises(ValueError, match=r"path_length must be > 0 m and at most 1e\+07 m"):
        tb.tilt_variance(1.0, 1e308, 0.005)  # was inf
    with pytest.raises(ValueError, match=r"cn2 must be at most 1 m\^\(-2/3\), as refracta.Turbulence takes it"):
        tb.tilt_variance(1e300, 100.0, 0.005)
    with pytest.raises(ValueError, match="aperture must be at most 1e\\+20 outer scales"):
        tb.tilt_variance(1e-10, 100.0, 0.0, outer_scale=1e-300, aperture=0.01)  # was NaN
    with pytest.raises(ValueError, match="outer_scale must exceed inner_scale, or be inf"):
        tb.tilt_variance(1e-10, 100.0, 0.005, outer_scale=0.001)
    with pytest.raises(ValueError, match=r"plane_wave_tilt_variance: cn2 must be at most 1 .*path_length must be > 0"):
        tb.plane_wave_tilt_variance(1e300, 1e300, 0.1)  # was inf


def test_a_scale_far_beyond_the_others_is_left_out_of_the_tilt():
    # An outer scale 1e30 inner scales out is none; an inner scale 1e-30 of the aperture is none.
    assert tb.tilt_variance(1e-10, 100.0, 0.005, outer_scale=5e27) == tb.tilt_variance(1e-10, 100.0, 0.005)
    assert tb.tilt_variance(1e-10, 100.0, 1e-32, aperture=0.01) == tb.tilt_variance(1e-10, 100.0, aperture=0.01)


# -- the command line ---------------------------------------------------------------------------


@pytest.mark.parametrize(("text", "value"), [("True", True), ("False", False), ("TRUE", True), ("true", True)])
def test_set_takes_python_spellings_of_true_and_false(text, value):
    # 'render: table must be True or False (got 'True')'.
    assert cli._option(f"table={text}") == ("table", value)


def test_set_table_true_and_false_render(tmp_path):
    for text in ("True", "False"):
        out = tmp_path / f"{text}.exr"
        argv = ["render", str(DATA / "hot_road.toml"), "--size", "8x4", "--spp", "1", "-o", str(out)]
        assert cli.main([*argv, "--set", f"table={text}"]) == 0
        assert out.is_file()


@pytest.mark.parametrize("names", [",distance", "distance,", "distance,,position"])
def test_an_empty_readout_name_is_refused(tmp_path, capsys, names):
    # ',distance' rendered as if 'distance' were given.
    with pytest.raises(SystemExit):
        cli.main(["render", str(DATA / "hot_road.toml"), "-o", str(tmp_path / "o.exr"), "--aovs", names])
    assert "has an empty name" in capsys.readouterr().err
    assert not (tmp_path / "o.exr").exists()


@pytest.mark.parametrize("command", ["render", "edit"])
def test_an_empty_output_is_called_empty_not_a_folder(tmp_path, capsys, command):
    # -o '' was "the output . is a folder".
    extra = ["--pairs", str(tmp_path / "pairs.json")] if command == "edit" else []
    with pytest.raises(SystemExit):
        cli.main([command, str(DATA / "hot_road.toml"), *extra, "-o", ""])
    err = capsys.readouterr().err
    assert "argument -o/--output: is empty" in err and "folder" not in err


# -- spectra and compositing ----------------------------------------------------------------------


@pytest.mark.parametrize("u", ["0.5", [0.5 + 1j], True, ["0.5"]])
def test_sample_wavelengths_takes_numbers_only(u):
    # '0.5' was sampled as 0.5; complex input gave numpy's TypeError, naming nothing.
    with pytest.raises(ValueError, match=r"sample_wavelengths: u must be numbers"):
        spectrum.sample_wavelengths(u)


def test_a_composite_background_is_called_a_colour():
    # (1, 0) was "must have shape (3,), one point (x, y, z)".
    depths, alphas, colors = [1.0, 2.0], [0.5, 0.5], [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    for background in ((1.0, 0.0), [[1.0, 0.0, 0.0]], 0.5):
        with pytest.raises(ValueError, match=r"composite: background must be a colour \(r, g, b\), shape \(3,\)"):
            oit.composite(depths, alphas, colors, background=background)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (
            lambda: spectrum.to_linear_srgb(np.ones((1, 4)), np.full((1, 4), 500.0), np.full((1, 4), 1e-320)),
            r"to_linear_srgb: radiance / pdf overflows float64 \(radiance up to 1, pdf down to 9.9\d*e-321",
        ),
        (
            lambda: spectrum.to_linear_srgb(np.full((1, 4), 1e308), np.full((1, 4), 555.0), np.full((1, 4), 1 / 470)),
            r"to_linear_srgb: radiance / pdf overflows float64 \(radiance up to 1e\+308",
        ),
        (
            lambda: spectrum.to_linear_srgb("1", np.full((1, 4), 555.0), np.full((1, 4), 1 / 470)),
            r"to_linear_srgb: radiance must be numbers",
        ),
        (
            lambda: spectrum.rgb_to_spectrum([1e308, 1.0, 1.0], [500.0], kind="unbounded"),
            r"rgb_to_spectrum: rgb up to 1e\+308 overflows float64 in the unbounded spectrum",
        ),
        (
            lambda: spectrum.xyz_to_linear_srgb([1e308] * 3),
            r"xyz_to_linear_srgb: xyz up to 1e\+308 overflows float64",
        ),
    ],
)
def test_spectra_that_overflow_are_named_not_nan(call, message):
    # Each gave NaN or inf.
    with pytest.raises(ValueError, match=message):
        call()


def test_an_mp4_ffmpeg_refuses_before_opening_leaves_a_file_that_was_there(tmp_path, monkeypatch):
    # A review: a failure removed `path` whether or not ffmpeg had made it (a user's earlier movie).
    ffmpeg = pytest.importorskip("imageio_ffmpeg")
    failing = tmp_path / "ffmpeg"
    failing.write_text("#!/bin/sh\necho 'Unrecognized option' >&2\nexit 1\n")
    failing.chmod(0o755)
    monkeypatch.setattr(ffmpeg, "get_ffmpeg_exe", lambda: str(failing))
    path = tmp_path / "x.mp4"
    path.write_bytes(b"an earlier movie")
    with pytest.raises(refracta.IoError, match="Unrecognized option"):
        io.write_animation(path, np.full((2, 8, 8, 3), 0.5), fps=10.0)
    assert path.read_bytes() == b"an earlier movie"
