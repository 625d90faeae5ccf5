"""Defects found by trials of 7 December (the last notes' leftovers, a photographer's trial of the
real-places workflow, an edge-case trial of the renderers): compare.format_table raised KeyError on
rows it was not made for; scene.terrain_height (the flat frame's y) was offered as a geographic
camera's ground; a 1 nm surface layer sent rays below the ground; a star reflected back at a low
top of the air was taken as leaving level, and top=0 as no top; a misspelt keyword of animate was
blamed on a missing one; a camera at the end of scene coordinates was asked for max_length <= 0;
an editing trial's bounds where the model is undefined, max_iterations silently ignored by nlopt,
the command line's size of a pixel_bounds render, ray_fan's eye_height as a string."""

import warnings

import numpy as np
import pytest

import refracta
from refracta import compare, examples, geo


def test_format_table_names_what_a_foreign_row_lacks():
    # A row of the user's own (or one of transparency()'s among shadows()'s) raised KeyError: 'p99_error'.
    with pytest.raises(ValueError, match=r"rows\[0\] lacks 'p99_error', 'nan_count', 'bytes_per_pixel', 'seconds'"):
        compare.format_table([{"method": "mine", "mean_error": 0.1}])
    shadow = {
        "method": "pcf",
        "kernel": 3,
        "reference": "ray",
        "mean_error": 0.1,
        "p99_error": 0.2,
        "light_leak": 0.0,
        "over_shadow": 0.0,
        "nan_count": 0,
        "bits_per_texel": 32,
        "seconds": 0.1,
    }
    transparency = {
        "method": "mboit",
        "mean_error": 0.1,
        "p99_error": 0.2,
        "nan_count": 0,
        "bytes_per_pixel": 16.0,
        "seconds": 0.1,
    }
    with pytest.raises(ValueError, match=r"rows\[1\] lacks 'kernel', 'reference'"):
        compare.format_table([shadow, transparency])
    with pytest.raises(ValueError, match=r"rows\[0\] lacks 'method'"):
        compare.format_table(["pcf"])
    assert compare.format_table([shadow]).splitlines()[1].startswith("pcf")
    assert compare.format_table([]).count("\n") == 0  # the header alone


# --- A photographer's trial of the real-places workflow --------------------------------------------


def plateau(tmp_path, height):
    """A flat 5 000 m plateau 0.2 deg across around (46.0, 7.0): a WGS84 GeoTIFF."""
    import tifffile

    keys = [1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326]
    tags = [
        (33550, "d", 3, (0.01, 0.01, 0.0), False),
        (33922, "d", 6, (0, 0, 0, 6.9, 46.1, 0), False),
        (34735, "H", len(keys), keys, False),
    ]
    path = tmp_path / "plateau.tif"
    tifffile.imwrite(path, np.full((21, 21), height, np.float32), extratags=tags)
    return path


def test_the_ground_under_a_geographic_camera_is_its_true_height(tmp_path):
    # scene.terrain_height is the flat frame's y, 3.9 m short of 5 000 m above the ellipsoid (h^2 / R):
    # the warning told users to add an eye's 1.7 m to it for frame.camera, which put the eye 0.26 m
    # under the plateau. frame.ground_height gives the height frame.camera takes.
    frame = geo.LocalFrame(46.0, 7.0)
    scene = refracta.Scene()
    scene.add_terrain(plateau(tmp_path, 5000.0), frame=frame)
    ground = frame.ground_height(scene)
    # A flat grid: its own height, to the terrain's float32 positions (a unit of 4.9e-4 m at 4 998 m).
    assert ground == pytest.approx(5000.0, abs=1e-3)
    assert frame.ground_height(scene, (46.05, 7.05)) == pytest.approx(5000.0, abs=1e-3)  # as above
    assert frame.ground_height(scene, (47.0, 7.0)) is None  # no terrain 100 km north
    camera = frame.camera(ground + 1.7, 90.0, 0.0, vfov=10.0)
    y = scene.terrain_height(0.0, 0.0)
    # 1.7 m above the ground in the flat frame too (dy/dh = R / (R + h): 1.7 m less 1.3 mm).
    assert camera.position[1] - y == pytest.approx(1.7, abs=2e-3)
    with pytest.raises(ValueError, match=r"position\[0\] \(lat\) must be"):
        frame.camera(10.0, 0.0, 0.0, vfov=10.0, position=(95.0, 7.0))
    with pytest.raises(ValueError, match=r"position\[1\] \(lon\) must be"):
        frame.ground_height(scene, (46.0, 700.0))
    with pytest.raises(ValueError, match=r"ground_height: scene must be a refracta.Scene \(got str\)"):
        frame.ground_height("plateau.tif")


# --- An edge-case trial of the renderers -----------------------------------------------------------


def test_a_surface_layer_thinner_than_a_tenth_of_a_millimetre_is_refused():
    # A 1 nm layer sent the eye table's rays 1.7 km below the ground ("add a ground": it had one).
    for depth in (1e-9, 0.0, 1e5):
        with pytest.raises(ValueError, match=r"surface_depth must be in \[0.0001, 10000\] m"):
            refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=depth)
    assert refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=1e-4).params["surface_depth"] == 1e-4


def test_a_star_reflected_back_at_a_low_top_of_the_air_is_an_error():
    # Where n drops from n_top to 1 at the top, a ray flatter than the critical angle there cannot
    # leave; it was taken as leaving level (60' at 1 deg and 31' at 2 deg, through a 1 m atmosphere).
    air = refracta.PhysicalAtmosphere()
    with pytest.raises(refracta.NumericalError, match=r"too flat to leave it.*n cos e = 1.0001"):
        refracta.astronomical_refraction(air, 1.0, top=1.0)
    with pytest.raises(refracta.NumericalError, match=r"reflected back"):
        refracta.astronomical_refraction(air, 0.0, top=1000.0)
    # Steeper than the critical angle (acos(1 / n_top) = 1.35 deg at 1 m) it leaves, bent at the top.
    assert 0.0 < refracta.astronomical_refraction(air, 2.0, top=1.0) < 60.0 * 2.0
    # top=0 is a top at the ground, not "the field's own top" (which is top=None).
    with pytest.raises(ValueError, match=r"the top of the air \(0 m\) must lie above the eye \(5 m\)"):
        refracta.astronomical_refraction(air, 0.0, eye_height=5.0, top=0.0)
    assert refracta.astronomical_refraction(air, 0.0, top=None) == pytest.approx(33.0, abs=0.05)  # 33.0' (README)


def test_a_misspelt_keyword_of_animate_is_named():
    road = examples.hot_road(8, 4)
    turbulence = refracta.Turbulence(1e-10, cells=16)
    with pytest.raises(ValueError, match=r"animate: unknown option 'turbulance'"):
        refracta.animate(road.scene, road.camera, road.field, [0.0], turbulance=turbulence)


def test_a_camera_at_the_end_of_scene_coordinates_is_told_so():
    # "give max_length at most 0 m" asked for what no render takes.
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    camera = refracta.Camera((0.0, 1e7, 0.0), (300.0, 1e7, 0.0), (0, 1, 0), 20.0, 8, 4)
    with pytest.raises(ValueError, match=r"the camera is 10000000 m from the origin, at the end of scene coordinates"):
        refracta.render(scene, camera, None, progress=False)


def test_turbulence_cells_too_fine_to_trace_are_named():
    # Cells of 1 um: each ray failed on "TraceOptions: rk45 with step 4e-06 m needs more than ...".
    road = examples.hot_road(8, 4)
    air = refracta.PhysicalAtmosphere(
        **road.field.params, turbulence=refracta.Turbulence(1e-10, cells=16, spacing=1e-6)
    )
    with pytest.raises(ValueError, match=r"through the turbulence .*Turbulence\(spacing=\.\.\.\)"):
        refracta.render(road.scene, road.camera, air, max_length=road.max_length, progress=False)


def test_a_spectral_render_is_denoised_once_its_negative_colours_are_clipped():
    # Out-of-gamut spectral colours are negative: "image must lie in [0, 3.4e+38]" did not say why.
    image = np.ones((8, 8, 3), np.float32)
    image[2, 3, 0] = -3.0
    with pytest.raises(ValueError, match=r"outside sRGB's gamut come out negative; denoise np.maximum\(image, 0\)"):
        refracta.denoise(image)
    assert refracta.denoise(np.maximum(image, 0.0)).shape == (8, 8, 3)


def test_unknown_keywords_of_the_geographic_cameras_are_named():
    # width= raised Python's own TypeError naming the internal geographic_camera().
    with pytest.raises(refracta.ArgumentError, match=r"Camera.geographic: unknown keyword 'width' .*image_width="):
        refracta.Camera.geographic(46.0, 7.0, 100.0, 0.0, 0.0, vfov=10.0, width=8)
    with pytest.raises(refracta.ArgumentError, match=r"LocalFrame.camera: unknown keyword 'widht' \(it takes height,"):
        geo.LocalFrame(46.0, 7.0).camera(10.0, 0.0, 0.0, vfov=10.0, widht=8)
    assert refracta.Camera.geographic(46.0, 7.0, 100.0, 0.0, 0.0, vfov=10.0, image_width=8).width == 8


def test_a_ray_batch_is_indexed_as_the_tuple_it_unpacks_as():
    batch = refracta.trace_rays(refracta.PhysicalAtmosphere(), [[0.0, 1.0, 0.0]] * 4, [1.0, 0.0, 0.0], max_length=10.0)
    points, directions, lengths = batch
    assert batch[0] is points and batch[2] is lengths and len(batch) == 3
    assert batch == batch and batch != refracta.trace_rays(refracta.PhysicalAtmosphere(), points, directions)


def test_tolerances_below_round_off_and_tops_beyond_reach_are_named():
    road = examples.hot_road(8, 4)
    # "ElevationTable: stratified: tol must be at least ..." named a table the user never made.
    with pytest.raises(ValueError, match=r"RenderOptions: tol must be at least 1e-15 x max_length = 1.2e-11 m"):
        refracta.render(road.scene, road.camera, road.field, max_length=road.max_length, tol=1e-12, progress=False)
    # "TraceOptions: stratified with step 100 m needs more than ..." did not name top.
    with pytest.raises(ValueError, match=r"astronomical_refraction: top must be at most 10000000 m"):
        refracta.astronomical_refraction(refracta.PhysicalAtmosphere(), 0.0, top=1e9)


def test_animate_says_when_turbulence_replaces_the_fields_own():
    road = examples.hot_road(8, 4)
    turbulence = refracta.Turbulence(1e-10, cells=16, wind=(1.0, 0.0))
    air = refracta.PhysicalAtmosphere(**road.field.params, turbulence=turbulence)
    with pytest.warns(refracta.SceneWarning, match=r"the field has turbulence of its own, and turbulence= replaces"):
        refracta.animate(road.scene, road.camera, air, [0.0], turbulence=turbulence, progress=False)


# --- A technical artist's trial of editing, scene files and the command line -------------------------


def traced_pairs():
    """Three pairs traced through a known surface layer (12 K over 0.15 m) from an eye 1.5 m up."""
    from refracta.edit import PointPair

    truth = refracta.PhysicalAtmosphere(surface_dt=12.0, surface_depth=0.15)
    eye = np.array([0.0, 1.5, 0.0])
    pairs = []
    for elevation, length in [(-0.003, 400.0), (-0.0025, 700.0), (-0.002, 900.0)]:
        d = np.array([1.0, elevation, 0.0]) / np.hypot(1.0, elevation)
        end = refracta.trace_ray(truth, eye, d, max_length=length, stop_height=0.0).points[-1]
        pairs.append(PointPair(tuple(eye + 100.0 * d), tuple(end)))
    return eye, pairs


def test_bounds_beyond_where_the_model_is_defined_are_refused_up_front():
    # humidity in [-1, 3] was taken: the solve spent all 200 iterations on air it could not trace.
    from refracta import edit

    eye, pairs = traced_pairs()
    start = refracta.PhysicalAtmosphere(surface_dt=5.0, surface_depth=0.3)
    with pytest.raises(ValueError, match=r"bounds of 'humidity' must lie where PhysicalAtmosphere is defined: at -1, "):
        edit.solve(start, eye, pairs, free=["humidity"], bounds={"humidity": (-1.0, 3.0)}, stop_height=0.0)
    # The editor checks them when it is made, not in the background solve.
    from refracta.widgets import EditorModel

    road = examples.hot_road(48, 16)
    for bounds, message in (({"surface_dt": (5.0, 1.0)}, "lower < upper"), ({"humidity": (0.0, 3.0)}, "at 3, ")):
        with pytest.raises(ValueError, match=message):
            EditorModel(
                road.scene,
                road.camera,
                road.field,
                free=list(bounds),
                solve_options={"bounds": bounds},
                autorender=False,
            )


def test_max_iterations_given_to_an_nlopt_backend_is_said_to_have_no_effect():
    from refracta import edit

    eye, pairs = traced_pairs()
    start = refracta.PhysicalAtmosphere(surface_dt=5.0, surface_depth=0.3)
    with pytest.warns(RuntimeWarning, match=r"max_iterations counts Ceres' iterations; nlopt:LN_BOBYQA has none"):
        result = edit.solve(
            start,
            eye,
            pairs,
            free=["surface_dt"],
            backend="nlopt:LN_BOBYQA",
            max_iterations=1,
            max_evaluations=20,
            strategy="local",
            stop_height=0.0,
        )
    assert result.evaluations <= 20 + 2  # max_evaluations holds (and the measures of the best point after)


def test_the_command_line_says_the_size_it_wrote(tmp_path, capsys):
    from refracta import cli

    scene = tmp_path / "s.toml"
    scene.write_text(
        "[camera]\nposition = [0, 1.5, 0]\nlook_at = [100, 1.5, 0]\nvfov = 20\nsize = [48, 16]\n"
        "[sky]\nzenith = [1, 1, 1]\nhorizon = [1, 1, 1]\n"
    )
    assert cli.main(["render", str(scene), "-o", str(tmp_path / "p.exr"), "--set", "pixel_bounds=[4,2,20,10]"]) == 0
    assert "(16x8," in capsys.readouterr().out  # the part written, not the camera's 48 x 16
    assert refracta.io.read_image(tmp_path / "p.exr").shape[:2] == (8, 16)


def test_ray_fan_names_an_eye_height_that_is_no_number():
    with pytest.raises(ValueError, match=r"ray_fan: eye_height must be a finite number above the ground \(got '1.5'\)"):
        refracta.plot.ray_fan(refracta.PhysicalAtmosphere(), "1.5", [0.1], 500.0)


def test_a_stage_stopped_by_its_own_cap_says_so():
    # "local from the start: 15 iterations ... stopped by the iteration limit" read as the solve's
    # max_iterations (200), which was not reached.
    from refracta import edit

    eye, pairs = traced_pairs()
    start = refracta.PhysicalAtmosphere(surface_dt=5.0, surface_depth=0.3)
    result = edit.solve(start, eye, pairs, free=["surface_dt", "surface_depth"], quick_iterations=1, stop_height=0.0)
    assert result.stages[0].endswith("stopped at the stage's own cap of iterations (quick_iterations)")
    assert result.stopped_by == ""


def test_a_sky_environment_file_that_cannot_be_read_is_located(tmp_path):
    from refracta import scene_file

    (tmp_path / "text.exr").write_text("hello")
    scene = tmp_path / "s.toml"
    scene.write_text('[camera]\nposition = [0, 1.5, 0]\nlook_at = [100, 1.5, 0]\n[sky]\nenvironment = "text.exr"\n')
    with pytest.raises(refracta.IoError, match=r"s.toml:5: \[sky\] environment: cannot read '.*text.exr'"):
        scene_file.load_scene(scene)


def test_a_white_balance_without_positive_cone_responses_is_a_display_setting_error():
    # (1, -0.1, 0.36) has X, Y, Z > 0 but a negative cone response: the adaptation's own message came,
    # without "display settings: white_balance", in normalised XYZ.
    with pytest.raises(ValueError, match=r"display settings: white_balance as an RGB white .*cone responses > 0"):
        refracta.io.to_display(np.ones((4, 4, 3), np.float32), white_balance=(1.0, -0.1, 0.36))


def test_a_camera_shut_in_an_object_that_no_light_reaches_is_told_so():
    # An eye 1 mm up, inside the hot road's 2 mm road slab, rendered a black image without a word.
    road = examples.hot_road(16, 8)
    inside = refracta.Camera((10.0, 0.001, 0.0), (300.0, 0.001, 0.0), (0, 1, 0), road.camera.vfov, 16, 8)
    shut_in = r"the camera at \(10, 0.001, 0\) m is inside object 1: rays in 256 directions"
    with pytest.warns(refracta.SceneWarning, match=shut_in):
        image = refracta.render(road.scene, inside, road.field, max_length=road.max_length, progress=False)
    seen = refracta.render(road.scene, road.camera, road.field, max_length=road.max_length, progress=False)
    # What the warning says: dark. Only the aerial perspective's in-scatter along the camera rays'
    # metres inside the slab (~1e-5 /m of sunlight, unshadowed) is left: measured 1e-4 of the road's mean.
    assert image.max() < 1e-2 * seen.mean()
    assert road.scene._dark_enclosure(road.camera.position) is None  # the eye above the road
    # Glass around the eye is seen through; a closed room with a light inside it is lit.
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    glass = scene.add_box((0.0, 0.0, 0.0), (4.0, 4.0, 4.0), material=refracta.shading.Dielectric(1.33))
    assert scene._dark_enclosure((0.0, 0.5, 0.0)) is None
    scene.remove(glass)
    scene.add_box((0.0, 0.0, 0.0), (4.0, 4.0, 4.0), kd=0.5)
    assert scene._dark_enclosure((0.0, 0.5, 0.0)) is not None
    scene.add_point_light((0.0, 1.0, 0.0), 10.0)
    assert scene._dark_enclosure((0.0, 0.5, 0.0)) is None


def _room(window: bool):
    """A 4 m room of one opaque mesh around (0, 2, 0), with or without a 1 m window in its +x wall
    off every axis through the room's middle."""

    def quad(a, b, c, d):
        i = len(vertices)
        vertices.extend([a, b, c, d])
        triangles.extend([(i, i + 1, i + 2), (i, i + 2, i + 3)])

    vertices, triangles = [], []
    quad((-2, 0, -2), (2, 0, -2), (2, 0, 2), (-2, 0, 2))
    quad((-2, 4, -2), (-2, 4, 2), (2, 4, 2), (2, 4, -2))
    quad((-2, 0, -2), (-2, 0, 2), (-2, 4, 2), (-2, 4, -2))
    quad((-2, 0, -2), (-2, 4, -2), (2, 4, -2), (2, 0, -2))
    quad((-2, 0, 2), (2, 0, 2), (2, 4, 2), (-2, 4, 2))
    if window:  # the +x wall around a window at y in [2.5, 3.5], z in [0.5, 1.5]
        quad((2, 0, -2), (2, 0, 2), (2, 2.5, 2), (2, 2.5, -2))
        quad((2, 3.5, -2), (2, 3.5, 2), (2, 4, 2), (2, 4, -2))
        quad((2, 2.5, -2), (2, 2.5, 0.5), (2, 3.5, 0.5), (2, 3.5, -2))
        quad((2, 2.5, 1.5), (2, 2.5, 2), (2, 3.5, 2), (2, 3.5, 1.5))
    else:
        quad((2, 0, -2), (2, 0, 2), (2, 4, 2), (2, 4, -2))
    scene = refracta.Scene()
    scene.set_sky((0.5, 0.6, 0.9))
    scene.set_sun((1.0, 0.3, 0.0), 2e4)
    scene.add_mesh(np.array(vertices, float), np.array(triangles), kd=0.6)
    return scene


def test_a_room_with_a_window_is_lit_and_no_camera_in_it_is_warned():
    # A review: the six axes' rays from the eye all met the walls, so a sunlit room with a window off
    # those axes was called dark (its image: a sunlit patch, max 0.26). Rays in 256 directions find it.
    eye = (0.0, 2.0, 0.0)
    assert _room(window=True)._dark_enclosure(eye) is None
    assert _room(window=False)._dark_enclosure(eye) == 0
    camera = refracta.Camera(eye, (-3.0, 1.0, 0.0), (0, 1, 0), 100.0, 24, 16)
    with warnings.catch_warnings():
        warnings.simplefilter("error", refracta.SceneWarning)
        lit = refracta.render(_room(window=True), camera, None, spp=4, progress=False)
        assert lit.max() > 0.1  # the sun through the window on the wall behind the eye's view
        # The rasterizer's alpha and shadows='none' let light through walls: no such hint there.
        refracta.render_raster(_room(window=False), camera, shadows="none")
