"""Two new-user trials (real places; a photographer's realism features): each test failed before its fix.

(Aiming a camera at a latitude and longitude: tests/geo/test_geographic_camera.py; a frame of another
Earth than the field's: tests/render/test_readouts.py; either longitude convention in a scene file:
tests/render/test_scene_file_geographic.py; an overlay's fractional object ids: tests/photo.)
"""

import io

import numpy as np
import pytest
import scipy.optimize

import refracta
from refracta import geo, photo, terrain
from refracta._progress import ProgressBar


def _truncated(tmp_path, suffix):
    image = np.random.default_rng(3).random((48, 64, 3)).astype(np.float32)
    whole = tmp_path / f"whole{suffix}"
    refracta.io.write_image(whole, image)
    data = whole.read_bytes()
    cut = tmp_path / f"cut{suffix}"
    cut.write_bytes(data[: len(data) // 2])
    return cut


@pytest.mark.parametrize("suffix", [".jpg", ".tif", ".png", ".exr"])
def test_a_truncated_image_is_refused_not_filled_with_grey(tmp_path, suffix):
    # A half-written JPEG or TIFF read "successfully", its lower rows grey or black, the damage
    # only in OpenImageIO's error message; a photograph so read went into an overlay or a fit.
    with pytest.raises(refracta.IoError, match="cannot read"):
        photo.load(_truncated(tmp_path, suffix))


@pytest.mark.parametrize("suffix", [".jpg", ".tif", ".png", ".exr"])
def test_a_truncated_image_is_refused_without_a_word_on_stderr(tmp_path, suffix, capfd):
    # libpng printed "libpng error: IDAT: Read error: hit end of file" to the terminal beside the
    # IoError (its own reader's default, which OpenImageIO does not quiet): a truncated PNG is now
    # refused from its chunks before libpng reads it, naming the chunk it ends in.
    cut = _truncated(tmp_path, suffix)
    capfd.readouterr()
    with pytest.raises(refracta.IoError, match="cannot read") as raised:
        refracta.io.read_image(cut)
    assert capfd.readouterr().err == ""
    if suffix == ".png":
        assert "ends inside its IDAT chunk" in str(raised.value)


def test_a_jpeg_libjpeg_only_warns_about_still_loads(tmp_path):
    # OIIO reports libjpeg's warnings as errors too; a JPEG with two stray bytes before a marker
    # ("Corrupt JPEG data: 2 extraneous bytes", which every viewer shows) is a photograph.
    from PIL import Image

    pixels = (np.random.default_rng(0).random((32, 48, 3)) * 255).astype(np.uint8)
    whole = tmp_path / "whole.jpg"
    Image.fromarray(pixels).save(whole, "JPEG")
    data = whole.read_bytes()
    marker = data.index(b"\xff\xdb")
    stray = tmp_path / "stray.jpg"
    stray.write_bytes(data[:marker] + b"\x00\x00" + data[marker:])
    np.testing.assert_array_equal(photo.load(stray).image, photo.load(whole).image)


def test_a_photographs_camera_is_refused_beyond_the_pixels_a_camera_holds():
    image = np.full((8, 12, 3), 0.5, dtype=np.float32)
    picture = photo.Photo(image=image, linear=False, exif=photo.Exif(focal_length_35mm=50.0), path=None)
    with pytest.raises(ValueError, match=r"width must be a whole number of pixels in \[1, 16777216\]"):
        picture.camera((0, 20, 0), (0, 20, -1), width=2**31)
    assert picture.camera((0, 20, 0), (0, 20, -1), width=24).height == 16


def test_a_scene_point_beyond_the_reach_in_height_is_refused():
    with pytest.raises(ValueError, match="a scene height of 3.23e\\+07 m, beyond the scene's reach"):
        geo.LocalFrame(50.0, 1.0).to_scene(50.1, 1.0, 1e9)


def test_geodesy_names_none_and_shapes_that_do_not_broadcast():
    with pytest.raises(ValueError, match=r"lat1 must be a number or an array of numbers \(got None\)"):
        geo.inverse(None, 1.0, 50.0, 1.0)
    with pytest.raises(ValueError, match=r"do not broadcast together: lat1 \(2,\), lon1 \(3,\)"):
        geo.inverse([50.0, 51.0], [1.0, 2.0, 3.0], 50.0, 1.0)


def test_elevation_file_errors_name_the_call_and_keep_tifffile_quiet(tmp_path, capsys):
    bad = tmp_path / "bad.tif"
    bad.write_bytes(b"II*\x00" + b"\xff" * 40)  # a TIFF header pointing nowhere
    with pytest.raises(ValueError, match="^read_elevation: .*not a readable TIFF file: damaged or truncated"):
        terrain.read_elevation(bad)
    with pytest.raises(refracta.IoError, match="^read_elevation: no such elevation file"):
        terrain.read_elevation(tmp_path / "N46E007.hgt")
    with pytest.raises(ValueError, match="^add_terrain: .*not a readable TIFF file"):
        refracta.Scene().add_terrain(bad, frame=geo.LocalFrame(46.0, 7.0))
    assert "invalid offset" not in capsys.readouterr().err  # tifffile's own log line
    grid = np.zeros((3, 3))
    with pytest.raises(refracta.IoError, match="^add_terrain: no such orthophoto"):
        refracta.Scene().add_terrain(grid, origin=(0, 0), spacing=(1, 1), orthophoto=tmp_path / "photo.tif")


def test_a_progress_bar_of_a_few_items_shows_no_rate_of_millions():
    stream = io.StringIO()
    bar = ProgressBar("eye table", stream=stream)
    bar(0, 10)
    bar(10, 10)
    text = stream.getvalue()
    assert "10/10" in text and "it/s" not in text  # was "7577944.20it/s" for items ended in microseconds


def test_fog_the_multiple_scattering_table_does_not_resolve_is_warned_of():
    # A trial's horizon against visibility (sun 30 deg up): 0.0085 at 0.5 km, 0.0105 at 0.55, 0.0047
    # at 0.65, 0.0053 at 1 km -- below 0.8 km the table's steps do not resolve the fog.
    with pytest.warns(UserWarning, match="visibility 0.5 km is fog the sky's multiple-scattering table does not"):
        refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0), visibility=0.5)
    with pytest.warns(UserWarning, match="Scene.set_physical_sky: visibility 0.3 km is fog"):
        refracta.Scene().set_physical_sky((0.0, 1.0, 0.0), visibility=0.3)
    # The same fog given by its aerosol (the review: only visibility= was warned of).
    aerosol = refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0), visibility=1.0).aerosol * 2.0
    with pytest.warns(UserWarning, match=r"visibility 0.50\d* km is fog"):
        refracta.spectrum.PhysicalSky((0.0, 1.0, 0.0), aerosol=aerosol)


def test_numpy_times_are_refused_not_read_as_counts_of_their_unit():
    # animate read timedelta64[ms] (0, 1000) as 0 and 1000 s, datetime64 as seconds since 1970.
    field = refracta.PhysicalAtmosphere()
    camera = refracta.Camera((0.0, 1.5, 0.0), (100.0, 1.0, 0.0), (0, 1, 0), 10.0, 8, 4)
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    noise = dict(rms=1e-5, correlation_pixels=2)
    for times in (np.array([0, 1000], dtype="timedelta64[ms]"), np.array(["2026-06-21T19:50"], dtype="datetime64[s]")):
        with pytest.raises(ValueError, match="animate: times must be numbers.*give seconds"):
            refracta.animate(scene, camera, field, times, noise=noise, progress=False)


def test_a_spectrum_wholly_outside_the_rendered_wavelengths_is_refused():
    # A sun given at 900-1200 nm rendered black, spectral and RGB alike, without a word.
    scene = refracta.Scene()
    with pytest.raises(ValueError, match="wavelengths 900-1200 nm lie outside the rendered 360-830 nm"):
        scene.set_sun((0.0, 1.0, 0.0), np.full(4, 1e3), wavelengths=[900.0, 1000.0, 1100.0, 1200.0])
    scene.set_sun((0.0, 1.0, 0.0), np.full(4, 1e3), wavelengths=[700.0, 800.0, 900.0, 1000.0])  # its red part shows


def test_an_empty_sweep_is_refused_as_the_empty_grid_is():
    # sweep(f, {}) raised, but an axis without values or an empty list of points returned [].
    for grid, message in (({"sun_elevation": []}, r"grid\['sun_elevation'\] has no values"), ([], "empty list")):
        with pytest.raises(ValueError, match=message):
            refracta.sweep(lambda **point: 0, grid, progress=False)


def test_readouts_of_another_size_than_the_image_are_refused_and_none_has_no_unit():
    # The figure hovered pixel (2, 2)'s values over pixel (20, 20) of a 32 x 32 image.
    from refracta import plot
    from refracta._readout_text import readout_text

    with pytest.raises(ValueError, match=r"readouts_figure: aovs\['distance'\] is \(3, 3\), the image \(32, 32\)"):
        plot.readouts_figure(np.ones((32, 32, 3)), {"distance": np.zeros((3, 3))})
    text = readout_text({"true_elevation": np.full((2, 2), np.nan), "distance": np.ones((2, 2))}, 0.5, 0.5)
    assert "true_elevation: none\n" in text + "\n" and "distance: 1.00 m" in text  # was "none deg"


def test_angles_given_as_strings_or_beyond_the_zenith_are_refused():
    from refracta import plot

    air = refracta.PhysicalAtmosphere()
    with pytest.raises(ValueError, match="apparent elevation must be numbers"):
        refracta.astronomical_refraction(air, "0")  # was 33.01'
    with pytest.raises(ValueError, match="ray_fan: elevations must be numbers"):
        plot.ray_fan(air, 1.5, elevations="0.1", max_length=100.0)
    with pytest.raises(ValueError, match=r"ray_fan: elevations must be .* in \[-90, 90\] deg"):
        plot.ray_fan(air, 1.5, elevations=[100.0], max_length=100.0)


def test_a_curved_earths_ray_fan_shows_the_airs_own_profiles():
    # Its index panel showed the flat frame's n e^(y / R), rising with height (277.8 -> 290.9 at
    # 100 m: air growing denser upward), and its temperature panel was missing.
    import matplotlib

    matplotlib.use("Agg")
    from refracta import plot

    air = refracta.PhysicalAtmosphere()
    figure = plot.ray_fan(refracta.CurvedEarth(air, 6371e3), 2.0, elevations=[-0.1, 0.1], max_length=20000.0)
    titles = [axes.get_title() for axes in figure.axes]
    assert "temperature" in titles
    index = figure.axes[titles.index("index")].lines[0]
    n, y = np.asarray(index.get_xdata()), np.asarray(index.get_ydata())
    assert np.all(np.diff(n) < 0) and np.all(np.diff(y) > 0)  # the standard atmosphere thins upward
    lowest = air.ior(np.array([0.0, y[0], 0.0]))  # a few metres from the ground
    assert n[0] == pytest.approx((float(lowest) - 1.0) * 1e6, rel=1e-9)  # flat and true heights differ by y^2/2R


def test_a_level_ray_from_a_hot_road_the_air_lifts_leaves_it_in_the_stratified_trace_too():
    # A trial (the ray tracer against exact solutions): 'stratified' ended a level ray launched on
    # the road at once, where rk45 and rk4 follow it up (4.168 m after 1 km over the 10 K road).
    road = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    ends = {}
    for trace in ("stratified", "rk45"):
        path = refracta.trace_ray(road, [0, 0, 0], [1, 0, 0], trace=trace, max_length=1000.0, stop_height=0.0)
        assert path.stop == "max_length"
        ends[trace] = path.points[-1]
    np.testing.assert_allclose(ends["stratified"], ends["rk45"], atol=1e-6)  # rk45's default tol, 1e-7 m, with margin
    # Level where the air does not lift it (n falling with height): it ends there, as before.
    still = refracta.trace_ray(refracta.PhysicalAtmosphere(), [0, 0, 0], [1, 0, 0], trace="stratified", stop_height=0.0)
    assert still.stop == "stop_height"


def test_an_rk4_step_too_long_for_the_air_is_refused_not_followed_to_garbage():
    # A 0.3 mm-wide hot layer (LogisticProfile a_hot 1e-3) that reflects the ray: rk4's fixed steps
    # jumped it (the path ended at y = 31.2 m, |v| / n at 1.27) where rk45 and 'stratified' agree
    # on the reflection, y = 2.003 m.
    air = refracta.LogisticProfile(a_hot=1e-3, n_hot=3.0)
    start, direction = [0.0, 1.0, 0.0], [1.0, -0.05, 0.0]
    with pytest.raises(refracta.NumericalError, match=r"rk4: its fixed step of .* m is too long for this air"):
        refracta.trace_ray(air, start, direction, trace="rk4", max_length=60.0)
    reference = refracta.trace_ray(air, start, direction, trace="rk45", max_length=60.0, tol=1e-9)
    assert reference.points[-1][1] == pytest.approx(2.0035, abs=1e-3)  # the trial's 2.00349, to its digits


def test_a_batch_names_the_ray_a_field_failed_on():
    # A CustomField's NaN inside trace_rays named a point but not the ray (other batch errors do).
    def index(points):
        return np.where(points[:, 0] > 50.0, np.nan, 1.0003)

    field = refracta.CustomField(index, lambda points: np.zeros_like(points))
    origins, directions = np.tile([0.0, 1.0, 0.0], (3, 1)), np.tile([1.0, 0.0, 0.0], (3, 1))
    with pytest.raises(refracta.NumericalError, match=r"^ray \d: CustomField: ior returned n = nan"):
        refracta.trace_rays(field, origins, directions, max_length=100.0)
    with pytest.raises(ValueError, match=r"distance must be in \[1, 1\.1\d+e\+06\] m"):  # the rule, for NaN too
        refracta.refraction_coefficient(refracta.PhysicalAtmosphere(), 2.0, float("nan"))


@pytest.mark.parametrize("offset", [0.0, 1e-9, 1e-6, -1e-6, 1e-5])
@pytest.mark.parametrize("elevation", [0.0, 3e-8, 1e-7])
def test_a_ray_in_a_duct_within_round_off_of_its_maximum(offset, elevation):
    # A level ray 1 um above the hot road's maximum of n (0.8196 m) turns about it within n's
    # round-off: 'stratified' refused it ("cannot resolve a duct"), and one 3e-8 rad above level
    # from the maximum came back 5e109 m away. It now follows the harmonic oscillation dn/dh gives
    # (rays/stratified.h harmonic_duct), against rk45 at a thousandth of its tolerance.
    road = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    start = [0.0, 0.819575485306 + offset, 0.0]
    direction = [np.cos(elevation), np.sin(elevation), 0.0]
    path = refracta.trace_ray(road, start, direction, trace="stratified", max_length=2e4, tol=1e-6)
    reference = refracta.trace_ray(road, start, direction, trace="rk45", max_length=2e4, tol=1e-9)
    assert path.length == pytest.approx(2e4, rel=1e-12)  # it runs its whole length
    # Measured: <= 1.7e-7 m; the tolerance is tol, as for every trace (rk45's own error ~1e-9 m).
    assert np.linalg.norm(path.points[-1] - reference.points[-1]) < 1e-6


@pytest.mark.parametrize("offset", [0.0, 1e-8, -1e-6, 1e-5])
@pytest.mark.parametrize("elevation", [0.0, 1e-9, 3e-8, 1e-6])
def test_a_shallow_duct_at_a_tight_tolerance(offset, elevation):
    # A sounding cooling 1 K/m to 5 m, then warming: n peaks at 4.9148 m (k = -n'' ~ 4e-7 1/m^2,
    # oscillations ~10 km long). Rays launched by the peak oscillate micrometres about it;
    # 'stratified' at tol 1e-9 m follows them (harmonically where n - beta is ~1e-15) as rk45 does.
    sounding = refracta.TemperatureProfile(heights=[0, 5, 10, 20], temperatures=[290, 285, 290, 291])
    peak = scipy.optimize.brentq(lambda h: sounding.grad_ior(np.array([[0.0, h, 0.0]]))[0][1], 4.0, 5.0, xtol=1e-15)
    start = [0.0, peak + offset, 0.0]
    direction = [np.cos(elevation), np.sin(elevation), 0.0]
    path = refracta.trace_ray(sounding, start, direction, trace="stratified", max_length=3000.0, tol=1e-9)
    reference = refracta.trace_ray(sounding, start, direction, trace="rk45", max_length=3000.0, tol=1e-11)
    # Measured: <= 6.6e-10 m (1e-6 rad: Bouguer's quadrature; the rest harmonic, <= 2e-11); tol 1e-9 m.
    assert np.linalg.norm(path.points[-1] - reference.points[-1]) < 1e-9
