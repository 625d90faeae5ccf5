"""New-user trials of 6 December: a physicist's rays in odd atmospheres (the stratified tracer's
near-level launches and shallow ducts are in tests/rays/test_closed_forms.py and test_33, the
curved Earth's height in tests/media/test_curved_earth.py, astronomical refraction above a
sounding in tests/rays/test_astronomical_refraction.py), a technical artist's bad inputs, and a
photographer's real places: what silently gave a wrong picture, a wrong number or the wrong error."""

import math

import numpy as np
import pytest

import refracta
from refracta import edit, examples, geo, terrain
from refracta import scene_file as sf


def test_the_rasterizer_sees_geometry_2_cm_from_the_lens():
    # A lens 2 cm above the ground: render_raster clipped everything nearer than 5 cm and showed
    # sky in the bottom row, where the ray tracer sees the ground. The clipping distance is 0.1 mm.
    scene = refracta.Scene()
    scene.add_ground()
    scene.set_sky((0.5, 0.6, 0.9))
    camera = refracta.Camera((0, 0.02, 0), (1, 0.02, 0), vfov=60, width=8, height=6)
    traced = refracta.render(scene, camera, None, progress=False)
    rasterized = refracta.render_raster(scene, camera)
    # Same surfaces, same unlit colour: the rows agree exactly in which pixels see ground.
    np.testing.assert_array_equal(traced[:, 0, 0] < 0.4, rasterized[:, 0, 0] < 0.4)
    assert rasterized[-1, 0, 0] < 0.4  # the bottom row sees the ground (0.15), not the sky (0.5)


def test_the_original_editors_march_says_it_stops_short_of_the_scene():
    # march='rk4' walks step x max_steps = 300 m (the original editor's settings) whatever
    # max_length is: a box 500 m away was silently sky. Now a SceneWarning says so and how to reach it.
    scene = refracta.Scene()
    scene.add_ground()
    scene.set_sky((0.5, 0.6, 0.9))
    scene.add_box((500, 3, 0), (10, 6, 10), kd=(0.9, 0.1, 0.1))
    camera = refracta.Camera((0, 1.5, 0), (500, 3, 0), vfov=2, width=16, height=8)
    air = refracta.PhysicalAtmosphere(surface_dt=5)
    with pytest.warns(refracta.SceneWarning, match=r"step x max_steps = 300 m.*max_steps= \(or march='rk45'\)"):
        refracta.render(scene, camera, air, method="raster_march", march="rk4", progress=False)
    image = refracta.render(scene, camera, air, method="raster_march", march="rk4", max_steps=2000, progress=False)
    assert image[4, 8, 0] > 2 * image[4, 8, 2]  # the red box, reached in 600 m of steps


def test_the_green_flash_example_shows_the_last_gleam_by_default():
    # Its default sun elevation, -0.8 deg, lay below the mirage's cut: an empty sky (brightest
    # pixel 36 at 40 x 40). Now -0.776, the demo's last gleam: measured 3227 there, the sun's disc.
    example = examples.green_flash(40, 40)
    image = refracta.render(
        example.scene,
        example.camera,
        example.field,
        max_length=example.max_length,
        spectral=True,
        spp=2,
        progress=False,
    )
    assert image.max() > 300.0  # ten times the empty frame's brightest sky: some of the sun is in view


def test_scene_file_writers_name_what_they_were_given():
    camera = "[camera]\nposition = [0.0, 1.5, 0.0]\nlook_at = [100.0, 1.5, 0.0]\n"
    text = camera + '\n[atmosphere]\nmodel = "PhysicalAtmosphere"\n'
    with pytest.raises(ValueError, match=r"atmosphere_table: field must be a refracta field.*\(got str\)"):
        sf.atmosphere_table("PhysicalAtmosphere")
    with pytest.raises(ValueError, match=r"camera_table: camera must be a refracta.Camera \(got NoneType\)"):
        sf.with_camera(text, None)
    # None: a scene without air (load_scene's field of a file with no [atmosphere]): the table goes.
    without = sf.with_atmosphere(text, None)
    assert "[atmosphere]" not in without and "[camera]" in without
    assert sf.with_atmosphere(without, None) == without
    jittered = refracta.Camera((0, 1, 0), (10, 1, 0), vfov=5, width=8, height=4).jittered(np.full((4, 8, 2), 1e-4))
    with pytest.raises(ValueError, match="keeps no jitter map"):
        sf.with_camera(text, jittered)


def test_render_raster_progress_never_passes_its_total():
    # Its rasterizing and shadow-map loops added to one count: (1038, 16) for a 16 x 8 image.
    scene = refracta.Scene()
    scene.add_ground()
    scene.add_box((5, 0.5, 0), (1, 1, 1))
    scene.set_sun((0.3, 1.0, 0.2), 3.0)
    calls = []
    camera = refracta.Camera((0, 1, 0), (5, 0.5, 0), width=16, height=8)
    refracta.render_raster(scene, camera, progress=lambda done, total: calls.append((done, total)))
    assert calls and all(0 <= done <= total for done, total in calls)
    assert calls[-1][0] == calls[-1][1]  # it ends at its total


def test_an_image_size_beyond_a_cpp_int_is_named():
    with pytest.raises(
        refracta.ArgumentError, match=r"Camera: width must be a whole number of magnitude below 2\*\*31"
    ):
        refracta.Camera((0, 1, 0), (1, 1, 0), width=10**12, height=10)


def test_set_threads_refuses_more_than_onetbb_keeps():
    before = refracta.get_threads()
    with pytest.raises(ValueError, match=r"set_threads: n must be in \[0, 256\]"):
        refracta.set_threads(10**6)
    assert refracta.get_threads() == before


@pytest.mark.parametrize(
    "text, message",
    [
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967299\n", "indices must be non-zero whole numbers below 2\\*\\*31"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n", "below 2\\*\\*31"),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n", "non-zero"),
        ("v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "'v' has 2 coordinates; it needs x y z"),
    ],
)
def test_malformed_obj_indices_and_vertices_are_refused(tmp_path, text, message):
    # tinyobjloader read index 4294967299 as vertex 3 and 'v 0 0' as (0, 0, 0), silently.
    path = tmp_path / "bad.obj"
    path.write_text(text)
    with pytest.raises(refracta.IoError, match=message):
        refracta.Scene().add_obj(str(path))


# From a third trial, real places and photographs.


def test_a_sea_level_target_within_the_horizon_has_an_apparent_elevation():
    # From 100 m the horizon lies 35.7 km out, so a waterline 20 km away is in view; the hidden
    # height's bisection stopped nanometres up and the target at 0 m counted as hidden (None).
    air = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), 6371000.0)
    sea = refracta.refraction_coefficient(air, 100.0, 20000.0, target_height=0.0)
    one_metre = refracta.refraction_coefficient(air, 100.0, 20000.0, target_height=1.0)
    assert sea.hidden_height_refracted == 0.0
    # 1 m lower at 20 km is 1 / 20000 rad = 0.0029 deg lower, less the air's lift (k ~ 0.17: ~1 %).
    assert sea.apparent_elevation == pytest.approx(one_metre.apparent_elevation - np.degrees(1 / 20000), abs=1e-4)


@pytest.mark.parametrize(
    "lat, when, declination",
    [
        (90.0, "2024-06-21T12:00:00Z", 23.437),
        (-90.0, "2024-12-21T12:00:00Z", 23.439),
        (90.0, "2024-03-20T12:00:00Z", 0.147),
    ],
)
def test_the_sun_at_a_pole_stands_at_its_declination(lat, when, declination):
    # astral computes at most 89.8 deg from the equator: at a pole the sun stood 0.2 deg off
    # (23.637 at midsummer). The declinations are the trial's own (Meeus); the NOAA series they
    # and astral use agree to ~0.001 deg.
    assert geo.sun_position(lat, 0.0, when)[1] == pytest.approx(declination, abs=2e-3)
    # Just inside the clamp the place is astral's own (the same series, turned the same way).
    inside = geo.sun_position(89.79, 20.0, when)
    assert geo._polar_sun_position(89.79, 20.0, geo._utc(when)) == pytest.approx(inside, abs=1e-9)  # round-off


def test_geotiff_heights_in_feet_are_read_in_metres(tmp_path):
    # VerticalUnitsGeoKey (4099) was ignored: a US tile in feet stood 3.28 times too tall.
    import tifffile

    def write(name, unit):
        keys = [1, 1, 0, 4, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326, 4099, 0, 1, unit]
        tags = [
            (33550, "d", 3, (0.01, 0.01, 0.0), False),
            (33922, "d", 6, (0.0, 0.0, 0.0, 8.0, 47.0, 0.0), False),
            (34735, "H", len(keys), keys, False),
        ]
        tifffile.imwrite(tmp_path / name, np.full((3, 3), 1000.0, np.float32), extratags=tags)
        return tmp_path / name

    assert terrain.read_elevation(write("feet.tif", 9002)).heights[0, 0] == pytest.approx(304.8, rel=1e-7)  # float32
    assert terrain.read_elevation(write("metres.tif", 9001)).heights[0, 0] == 1000.0
    with pytest.raises(ValueError, match=r"heights in EPSG unit 9999 \(VerticalUnitsGeoKey\)"):
        terrain.read_elevation(write("other.tif", 9999))


# From a fourth trial, editing.


def test_a_parameter_idle_at_the_start_is_still_solved_for():
    # From the default air (surface_dt 0) surface_depth changes nothing, and was held fixed as
    # "no pair depends on it"; the solve then said no atmosphere puts the images where asked, though
    # (12 K, 0.3 m) lies in the bounds. A parameter is now idle only if also idle at the bounds' centre.
    eye = np.array([0, 1.5, 0])
    truth = refracta.PhysicalAtmosphere(surface_dt=12, surface_depth=0.3)
    pairs = []
    for elevation in (-0.1, -0.15, -0.2):
        d = np.array([np.cos(np.radians(elevation)), np.sin(np.radians(elevation)), 0])
        path = refracta.trace_ray(truth, eye, d, max_length=600, stop_height=0.0, tol=1e-10)
        pairs.append(edit.PointPair(tuple(eye + 100 * d), tuple(path.crossings([1, 0, 0], 400.0)[0][0])))
    result = edit.solve(
        refracta.PhysicalAtmosphere(), eye, pairs, free=["surface_dt", "surface_depth"], stop_height=0.0
    )
    assert result.success and list(result.insensitive) == []
    # Three pairs fix both parameters; the misses are round-off (measured 2e-13 m).
    assert result.field.params["surface_dt"] == pytest.approx(12.0, rel=1e-6)
    assert result.field.params["surface_depth"] == pytest.approx(0.3, rel=1e-6)  # as surface_dt: round-off


def test_a_hot_spot_in_the_air_names_itself_as_what_is_not_height_only():
    spot = refracta.PhysicalAtmosphere(hot_spots=[refracta.HotSpot(0, 0, 10, 5)])
    with pytest.raises(ValueError, match=r"height only \(this PhysicalAtmosphere carries hot_spots\)"):
        refracta.refraction_coefficient(spot, 2.0, 100.0)


def test_a_void_the_nodata_text_misses_is_named_with_its_file(tmp_path):
    # GDAL_NODATA '-3.40282e+38' is not float32's lowest (-3.4028235e+38): the void stayed a height,
    # and CurvedEarth refused "-3.402823466e+38 m" without naming the file or the sample.
    import tifffile

    keys = [1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326]
    tags = [
        (33550, "d", 3, (0.01, 0.01, 0.0), False),
        (33922, "d", 6, (0.0, 0.0, 0.0, 8.0, 47.0, 0.0), False),
        (34735, "H", len(keys), keys, False),
        (42113, "s", 0, "-3.40282e+38", False),
    ]
    path = tmp_path / "void.tif"
    tifffile.imwrite(path, np.array([[1.0, np.finfo(np.float32).min], [3.0, 4.0]], np.float32), extratags=tags)
    with pytest.raises(ValueError, match=r"void.tif'?: sample \(row 0, column 1\) is -3.40282e\+38 m.*a void value"):
        refracta.Scene().add_terrain(str(path), frame=geo.LocalFrame(47.0, 8.0))


def test_a_flat_tile_beside_the_camera_is_not_the_ground_under_it():
    # A constant 300 m tile 20 km off warned "the camera is at y = 20 m, at or below the scene's
    # ground": a scene whose geometry is all at one height counted as ground wherever it lay.
    scene = refracta.Scene()
    scene.add_terrain(np.full((4, 4), 300.0), origin=(20000.0, 0.0), spacing=(100.0, 100.0))
    scene.set_sky((0.5, 0.6, 0.9))
    camera = refracta.Camera((0, 20, 150), (20150, 300, 150), width=16, height=8)
    refracta.render(scene, camera, None, progress=False)  # pytest's filter turns a SceneWarning into an error
    ground = refracta.Scene()
    ground.add_ground()
    ground.set_sky((0.5, 0.6, 0.9))
    with pytest.warns(refracta.SceneWarning, match="at or below the scene's ground"):
        refracta.render(ground, refracta.Camera((0, -1, 0), (10, -1, 0), width=16, height=8), None, progress=False)


def test_a_luminous_efficacy_without_a_photographic_exposure_is_refused():
    # K turns EV100 into an exposure; under automatic exposure it was accepted and ignored.
    image = np.ones((4, 4, 3), np.float32)
    with pytest.raises(ValueError, match="luminous_efficacy .* applies to a photographic exposure"):
        refracta.io.to_display(image, luminous_efficacy=100.0)
    refracta.io.to_display(image, ev100=0.0, luminous_efficacy=100.0)
    # Refused where used, not where built: a preset may carry K for the EV100 each call gives.
    preset = refracta.DisplaySettings(luminous_efficacy=100.0)
    refracta.io.to_display(image, display=preset, ev100=0.0)


def test_refraction_coefficient_refuses_a_sight_line_above_the_air():
    # 9 900 km (below the old bound, a quarter of the circumference) scanned 10^7 nodes per ray and
    # failed after 18 s; 3 000 km ran 70 s. The bound: the straight horizontal line 100 km over the
    # surface, R acos(R / (R + 100 km)) = 1 121 km over the Earth (geometry, independent of the air).
    air = refracta.PhysicalAtmosphere()
    radius = refracta.CurvedEarth(air).radius
    longest = radius * math.acos(radius / (radius + 100e3))
    assert 1.12e6 < longest < 1.14e6  # [m] the Earth's figure, to its first three digits
    for distance in (1.01 * longest, 9.9e6):
        with pytest.raises(ValueError, match=r"100 km up, above the air"):
            refracta.refraction_coefficient(air, 10.0, distance)
    small = refracta.CurvedEarth(air, 1.0e6)  # a small planet: the bound follows its radius
    with pytest.raises(ValueError, match=r"distance must be in \[1, 429700\] m"):
        refracta.refraction_coefficient(small, 10.0, 5.0e5)


def test_aim_takes_heights_above_the_earths_centre_and_targets_within_reach():
    # aim gave an elevation of -90.13 for a target 1e7 m below the ellipsoid, an eye below the
    # Earth's centre aimed without a word, and the antipode made a camera looking straight down.
    frame = geo.LocalFrame(46.0, 7.5, earth_radius=6371e3)
    with pytest.raises(ValueError, match=r"target's height must be finite in \[-6\.371e\+06"):
        frame.aim((46.0, 8.0, -1e7), 10.0)
    with pytest.raises(ValueError, match=r"^height must be finite in \[-6\.371e\+06"):
        frame.aim((46.0, 8.0, 100.0), -1e7)
    with pytest.raises(ValueError, match="target's height"):  # not the elevation it was turned into
        refracta.Camera.geographic(46.0, 7.5, 10.0, target=(46.0, 8.0, -1e7), vfov=5.0)
    with pytest.raises(ValueError, match=r"2e\+07 m from the eye, beyond the scene's reach"):
        frame.aim((-46.0, -172.5), 10.0)
    # A real aim: 38.6 km east at 46 N, 100 m above a 10 m eye, the Earth's drop d^2/2R = 117 m.
    azimuth, elevation = frame.aim((46.0, 8.0, 100.0), 10.0)
    assert azimuth == pytest.approx(89.82, abs=0.01)  # the geodesic's bearing (meridian convergence)
    assert elevation == pytest.approx(-0.0410, abs=1e-4)  # atan((90 - 117) / 38.6 km), to 1e-4 deg


def test_terrain_arrays_are_checked_as_files_are():
    scene = refracta.Scene()
    grid = dict(origin=(0.0, 0.0), spacing=(1.0, 1.0))
    with pytest.raises(ValueError, match=r"heights\[0, 0\] is 2e\+07 m, beyond 100000 m of any terrain"):
        scene.add_terrain(np.full((3, 3), 2e7), earth_radius=6371e3, **grid)
    with pytest.raises(ValueError, match="array of real numbers"):  # numpy dropped the imaginary part
        scene.add_terrain(np.full((3, 3), 1 + 5j), **grid)
    with pytest.raises(ValueError, match=r"spacing \(1e-30, 1e-30\) m is below 0\.0001 m: samples would coincide"):
        scene.add_terrain(np.zeros((3, 3)), origin=(0.0, 0.0), spacing=(1e-30, 1e-30))
    with pytest.raises(ValueError, match="water_level must be finite, within 100000 m"):
        scene.add_terrain(np.zeros((3, 3)), water_level=1e7, **grid)


def test_sun_position_names_what_is_wrong_with_a_time():
    for when, message in (
        ("2024-02-30T12:00:00Z", "day is out of range for month"),
        ("2016-12-31T23:59:60Z", r"second must be in 0\.\.59"),  # a leap second: datetime has none
        ("0001-01-01T00:00:00+05:00", "outside the years 1-9999 in UTC"),  # OverflowError before
    ):
        with pytest.raises(ValueError, match=message):
            geo.sun_position(45.0, 7.0, when)
    with pytest.warns(RuntimeWarning, match="0500 is outside 1800-2100|500 is outside 1800-2100"):
        geo.sun_position(45.0, 7.0, "0500-06-21T12:00:00Z")


def test_astronomical_refraction_and_refraction_coefficient_name_their_numbers():
    air = refracta.PhysicalAtmosphere()
    with pytest.raises(ValueError, match=r"eye_height must be a number \(got '5'\)"):  # float() read it
        refracta.astronomical_refraction(air, 5.0, "5")
    with pytest.raises(ValueError, match="earth_radius must be finite and > 0 m"):  # "> 0 (got inf)" before
        refracta.astronomical_refraction(air, 5.0, earth_radius=math.inf)
    with pytest.raises(ValueError, match="at least 100000 m"):  # said ">= 0" for -1, then refused 0
        refracta.refraction_coefficient(air, 2.0, 1000.0, earth_radius=-1.0)


@pytest.mark.parametrize("tol", [1e-6, 1e-8])
@pytest.mark.parametrize("elevation", [-0.2, -0.3])
def test_stratified_paths_hold_tol_between_their_nodes(tol, elevation):
    # A ray dipping into the hot road's layer: the panels' quadrature alone left nodes 75 m apart
    # across it, and crossings() between them (the quintic through the nodes) missed the path by
    # 1.4e-4 m at tol 1e-6 (a physicist's trial: 3e-5..9e-5 m at tol 1e-10). Against rk45 at 1e-12.
    road = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    e = math.radians(elevation)
    start, direction = (0.0, 1.2, 0.0), (math.cos(e), math.sin(e), 0.0)
    path = refracta.trace_ray(road, start, direction, trace="stratified", tol=tol, max_length=1000.0)
    reference = refracta.trace_ray(road, start, direction, trace="rk45", tol=1e-12, max_length=1000.0)
    worst = 0.0
    for x in np.linspace(5.0, 995.0, 199):
        (ours, *_), (theirs, *_) = path.crossings((1.0, 0.0, 0.0), x)[0], reference.crossings((1.0, 0.0, 0.0), x)[0]
        worst = max(worst, abs(ours[1] - theirs[1]))
    assert worst <= tol  # the path's own tolerance, now between nodes too


def test_an_8_bit_environment_map_is_decoded_from_srgb_as_a_texture_is(tmp_path):
    # A PNG's 128 was radiance 0.502 as a sky and 0.216 as a texture; a uint8 array's was 128.
    from PIL import Image

    path = tmp_path / "g128.png"
    Image.fromarray(np.full((8, 16, 3), 128, np.uint8)).save(path)
    decoded = ((128 / 255 + 0.055) / 1.055) ** 2.4  # IEC 61966-2-1: 0.2158605
    looking = refracta.Camera((0.0, 0.0, 0.0), (0.0, 0.0, -1.0), width=4, height=4)
    scene = refracta.Scene()
    scene.set_environment(path)
    sky = refracta.render(scene, looking, None, progress=False)[2, 2]
    np.testing.assert_allclose(sky, decoded, rtol=1e-6)  # float32 radiance
    ground = refracta.Scene()
    ground.add_ground(material=refracta.shading.Diffuse(1.0, texture=str(path)))
    ground.set_environment((1.0, 1.0, 1.0))
    down = refracta.Camera((0.0, 5.0, 0.0), (0.0, 0.0, 0.0), up=(0.0, 0.0, -1.0), vfov=20.0, width=4, height=4)
    texel = refracta.render(ground, down, None, progress=False)[2, 2]
    np.testing.assert_allclose(texel, sky, rtol=1e-3)  # the texture's half-float MIP copy
    with pytest.raises(ValueError, match="set_environment: an image array holds linear radiance as floats"):
        scene.set_environment(np.full((8, 16, 3), 128, np.uint8))
    with pytest.raises(ValueError, match=r"EnvironmentLight: image holds linear radiance as floats \(got dtype bool"):
        refracta.lights.EnvironmentLight(np.ones((8, 16, 3), bool))


def test_environment_textures_and_denoise_name_what_is_wrong(tmp_path):
    scene = refracta.Scene()
    with pytest.raises(ValueError, match=r"set_environment: scale must be finite and >= 0 \(got -1\)"):
        scene.set_environment((1.0, 1.0, 1.0), scale=-1.0)  # "emission must be ..." before
    with pytest.raises(ValueError, match=r"set_environment: radiance must be finite and >= 0 per channel"):
        scene.set_environment((-1.0, 1.0, 1.0))
    folder = tmp_path / "adir.png"
    folder.mkdir()
    with pytest.raises(refracta.IoError, match="not a regular file"):  # "no such texture file" before
        refracta.shading.Diffuse(0.5, texture=str(folder))
    with pytest.raises(ValueError, match=r"H and W >= 1 \(got \(0, 0, 3\)\)"):
        refracta.denoise(np.zeros((0, 0, 3), np.float32))


def test_the_albedo_readout_is_the_materials_directional_albedo():
    # Under a unit uniform sky a surface's radiance is its directional albedo. The readout sampled a
    # 4 x 4 grid whose row also chose the lobe: a rough gold 15 % high, a red plastic's green 28 % low.
    shading = refracta.shading
    gold = shading.RoughConductor(alpha=0.3, eta=(0.2, 0.92, 1.1), k=(3.9, 2.45, 2.14))
    for material in (gold, shading.Plastic((0.7, 0.1, 0.1), alpha=0.2)):
        scene = refracta.Scene()
        scene.add_ground(0.0, 1000.0, material=material)
        scene.set_environment((1.0, 1.0, 1.0))
        camera = refracta.Camera((0.0, 2.0, 0.0), (0.0, 0.0, -10.0), vfov=60.0, width=4, height=12)
        image, readouts = refracta.render(scene, camera, None, spp=1024, aovs=["albedo"], progress=False)
        # 10 %: 64 fixed quasi-random samples of a glossy lobe (measured 0.3 % for the gold, 9 % for
        # the plastic's faint green), against 15 % and 28 % before.
        np.testing.assert_allclose(readouts["albedo"][8, 2], image[8, 2], rtol=0.10)
