"""Per-pixel readouts of render(aovs=[...]) (issue 20 section 3; cpp/refracta/render/readouts.h):
distance, position, object id, apparent and true elevation, hidden heights and mirage
multiplicity, checked against closed forms and against rays traced here, not against the
readouts themselves."""

import math
from pathlib import Path

import numpy as np
import pytest

import refracta
from refracta import cli, examples

R = 6371e3  # [m] the sphere of the curved-Earth scenes
READOUTS = ["distance", "position", "object_id", "apparent_elevation", "apparent_azimuth", "true_elevation"]


def _flat_scene():
    """A ground plane, a box 50 m east of the eye (its west face at x = 49 m) and a sphere beside it."""
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    ground = scene.add_ground(0.0, 1000.0)
    box = scene.add_box((50.0, 2.0, 0.0), (2.0, 4.0, 4.0))
    ball = scene.add_sphere((40.0, 1.0, -6.0), 1.0)
    return scene, ground, box, ball


def _elevations(camera, column):
    """Elevations [deg] of the column's pixel-centre rays (Camera.ray, an independent path)."""
    rays = [camera.ray(column + 0.5, row + 0.5)[1] for row in range(camera.height)]
    return np.degrees(np.arcsin([d[1] for d in rays]))


def test_straight_readouts_are_the_euclidean_geometry():
    scene, ground, box, ball = _flat_scene()
    eye = np.array([0.0, 1.5, 0.0])
    camera = refracta.Camera(eye, (50.0, 1.5, -3.0), (0, 1, 0), 16.0, 40, 24)
    _, out = refracta.render(scene, camera, None, method="straight", aovs=READOUTS, progress=False)
    ids, distance, position = out["object_id"], out["distance"], out["position"].astype(np.float64)
    assert {ground, box, ball, -1} <= set(np.unique(ids))  # each object told apart, and the sky
    for row in range(camera.height):
        for column in range(camera.width):
            _, d = camera.ray(column + 0.5, row + 0.5)
            if ids[row, column] == box and abs(d[2] / d[0] * 49.0) < 1.9:  # the west face x = 49 (not its edge)
                expected = 49.0 / d[0]  # the face plane
            elif ids[row, column] == ground:
                expected = -1.5 / d[1]  # the plane y = 0
            else:
                continue
            assert distance[row, column] == pytest.approx(expected, rel=2e-6)  # float32: 6e-8 relative, and Embree's t
            assert position[row, column] == pytest.approx(eye + expected * d, abs=1e-4)  # float32 of ~60 m: 4e-6 m
    sky = ids == -1
    assert np.all(np.isinf(distance[sky])) and np.all(np.isnan(position[sky]))
    # Straight rays over a flat Earth: the true elevation is the apparent one, and both are the
    # camera's ray elevation; the azimuth is clockwise from north = -z (east, +x, is 90 deg).
    for column in (0, 17, 39):
        expected = _elevations(camera, column)
        np.testing.assert_allclose(out["apparent_elevation"][:, column], expected, atol=1e-5)  # float32 degrees
        met = ids[:, column] >= 0
        np.testing.assert_allclose(out["true_elevation"][met, column], expected[met], atol=1e-4)  # float32 positions
    _, d = camera.ray(0.5, 12.5)
    azimuth = np.degrees(np.arctan2(d[0], -d[2])) % 360.0
    assert out["apparent_azimuth"][12, 0] == pytest.approx(azimuth, abs=1e-4)  # float32 of ~90 deg: 8e-6 deg


def test_true_elevation_of_a_known_point_over_the_sphere():
    """A sphere's top seen across 8 km over a CurvedEarth: the readout maps the flat-frame hit back
    to the true geometry; the closed form here puts eye and point on the sphere by hand."""
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    scene.add_ground(0.0, 20000.0)
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), R)
    centre = R * np.log1p(60.0 / R)  # the flat height of a true 60 m (geo conventions: y' = R ln(1 + h/R))
    scene.add_sphere((8000.0, centre, 0.0), 2.0)
    eye = 12.0
    # Aimed along the sphere's true elevation (the flat frame is conformal: angles at the eye are
    # true), ~0.3 deg; the air lifts it by k d / (2R) ~ 0.006 deg, within the 0.05 deg view.
    aim = np.arctan2((R + 60.0) * np.cos(8000.0 / R) - (R + eye), (R + 60.0) * np.sin(8000.0 / R))
    camera = refracta.Camera((0.0, eye, 0.0), (8000.0, eye + 8000.0 * np.tan(aim), 0.0), (0, 1, 0), 0.05, 1, 41)
    _, out = refracta.render(scene, camera, field, aovs=READOUTS, progress=False, max_length=10000.0)
    met = np.flatnonzero(out["object_id"][:, 0] >= 0)
    assert met.size > 3
    for row in met:
        x, y, z = out["position"][row, 0].astype(np.float64)
        theta, h = np.hypot(x, z) / R, R * np.expm1(y / R)  # central angle, true height
        h_eye = R * np.expm1(eye / R)
        dx, dy = (R + h) * np.sin(theta), (R + h) * np.cos(theta) - (R + h_eye)
        expected = np.degrees(np.arctan2(dy, dx))
        assert out["true_elevation"][row, 0] == pytest.approx(expected, abs=2e-6)  # float32 of ~0.3 deg
    # The standard atmosphere lifts the image: apparent - true = k d / (2R) with k ~ 0.13-0.2.
    lift = np.radians(out["apparent_elevation"][met, 0] - out["true_elevation"][met, 0]) * 2 * R / 8000.0
    assert np.all((lift > 0.1) & (lift < 0.25))


def _hidden_scene(distance):
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    scene.add_ground(0.0, 3 * distance)
    scene.add_box((distance + 1.0, 50.0, 0.0), (2.0, 100.0, 200.0))  # its face at x = distance
    return scene


def _face_rows(out):
    return np.flatnonzero(out["object_id"][:, 0] == 1)


def test_hidden_height_without_air_is_the_sphere_closed_form():
    """Uniform air over a sphere bends nothing: the eye's tangent to the sphere hides, at central
    angle theta = d / R beyond the horizon's theta0 = acos(R / (R + h_eye)),
    h_hidden = R (sec(theta - theta0) - 1) ~ (d - sqrt(2 R h_eye))^2 / (2R): both readouts."""
    d, eye = 20000.0, 10.0
    field = refracta.CurvedEarth(refracta.LinearSquaredProfile(n0=1.0003, alpha=0.0), R)
    camera = refracta.Camera((0.0, eye, 0.0), (d, eye, 0.0), (0, 1, 0), 0.5, 1, 30)
    _, out = refracta.render(
        _hidden_scene(d), camera, field, aovs=["hidden_height", "object_id"], progress=False, max_length=1.5 * d
    )
    rows = _face_rows(out)
    assert rows.size > 10
    h_eye = R * np.expm1(eye / R)
    exact = R * (1.0 / np.cos(d / R - np.arccos(R / (R + h_eye))) - 1.0)
    approximate = (d - np.sqrt(2 * R * h_eye)) ** 2 / (2 * R)
    assert exact == pytest.approx(approximate, abs=1e-4)  # the small-angle form holds to 0.1 mm here
    hidden = out["hidden_height"][rows, 0]
    np.testing.assert_allclose(hidden[:, 0], exact, rtol=2e-6)  # float32 (and the face at x = d in float32)
    # The refracted one traces the grazing ray (bisection on its elevation) through the uniform
    # air: the same tangent, to the tracer's tolerance.
    np.testing.assert_allclose(hidden[:, 1], exact, atol=1e-4)


def test_hidden_height_in_a_standard_atmosphere_against_a_traced_grazing_ray():
    """With air the grazing ray is the one whose invariant n' cos e' (flat frame) equals n'(0):
    traced here from the eye, its true height at the target's distance is the hidden height."""
    d, eye = 20000.0, 10.0
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), R)
    camera = refracta.Camera((0.0, eye, 0.0), (d, eye, 0.0), (0, 1, 0), 0.5, 1, 30)
    _, out = refracta.render(
        _hidden_scene(d), camera, field, aovs=["hidden_height", "object_id"], progress=False, max_length=1.5 * d
    )
    n0, n_eye = field.ior(np.array([[0.0, 0.0, 0.0], [0.0, eye, 0.0]]))
    e = -np.arccos(n0 / n_eye)
    path = refracta.trace_ray(
        field, (0.0, eye, 0.0), (np.cos(e), np.sin(e), 0.0), trace="stratified", max_length=d + 100
    )
    points = path.points
    y = np.interp(d, points[:, 0], points[:, 1])
    traced = R * np.expm1(y / R)
    geometric = (d - np.sqrt(2 * R * eye)) ** 2 / (2 * R)
    assert 0.5 * geometric < traced < 0.8 * geometric  # refraction hides less (k ~ 0.13-0.2)
    rows = _face_rows(out)
    assert rows.size > 10
    # float32 (4 m to 1e-6 m) and linear interpolation of the traced path between its nodes (the
    # ray's height is curved by d^2/(2 R'): over 100 m node spacing, under 0.2 mm)
    np.testing.assert_allclose(out["hidden_height"][rows, 0, 1], traced, atol=5e-4)


def test_hidden_height_over_a_hot_surface_layer_against_a_bisected_grazing_ray():
    """Over a hot road the grazing ray turns within millimetres of the ground, where each exact
    trace is slow (a readout of any image took half a minute when the search went to 1e-14 rad at
    1e-7 m). Found here by our own bisection to 1e-11 rad on traces ten times finer than the
    render's, its true height at the target is the hidden height."""
    d, eye = 3000.0, 1.4
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1), R)
    camera = refracta.Camera((0.0, eye, 0.0), (d, eye, 0.0), (0, 1, 0), 0.5, 1, 30)
    max_length = 1.5 * d
    _, out = refracta.render(
        _hidden_scene(d), camera, field, aovs=["hidden_height", "object_id"], progress=False, max_length=max_length
    )

    def path(e):
        direction = (np.cos(e), np.sin(e), 0.0)
        return refracta.trace_ray(
            field, (0.0, eye, 0.0), direction, trace="stratified", tol=1e-5, max_length=max_length, stop_height=0.0
        )

    lo, hi = -0.01, 0.0  # meets the ground / passes over it
    assert path(lo).stop == "stop_height" and path(hi).stop != "stop_height"
    while hi - lo > 1e-11:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if path(mid).stop == "stop_height" else (lo, mid)
    points = path(hi).points
    traced = R * np.expm1(np.interp(d, points[:, 0], points[:, 1]) / R)
    # It comes down at |e| to turn on the road ~eye/|e| out and leaves it at about the same angle.
    mirrored = abs(hi) * d - 2 * eye
    assert abs(traced - mirrored) < 0.2 * mirrored
    rows = _face_rows(out)
    assert rows.size > 5
    # The render traces to 1e-4 m, this to 1e-5 m; float32 (1e-7 m here); the path's nodes
    # interpolated linearly (the grazing ray's curvature over a node spacing: well under 1e-4 m).
    np.testing.assert_allclose(out["hidden_height"][rows, 0, 1], traced, atol=3e-4)


def _traced_images(field, eye, elevations, face_x, heights, max_length):
    """How many rays of a fine fan (these elevations [deg], in the x-y plane) cross the plane
    x = face_x at each height: the number of images of that point, counted by tracing alone."""
    ys = []
    for e in np.radians(elevations):
        path = refracta.trace_ray(
            field,
            (0.0, eye, 0.0),
            (np.cos(e), np.sin(e), 0.0),
            trace="stratified",
            max_length=max_length,
            stop_height=0.0,
        )
        p = path.points
        ys.append(np.interp(face_x, p[:, 0], p[:, 1]) if p[-1, 0] >= face_x else np.nan)
    ys = np.array(ys)
    counts = []
    for h in heights:
        s = np.sign(ys - h)
        both = np.isfinite(ys[1:]) & np.isfinite(ys[:-1])
        counts.append(int(np.sum(both & (s[1:] != s[:-1]))))
    return np.array(counts)


def _check_images(field, camera, face_x, max_length, expected_most):
    _, out = refracta.render(
        _wall_scene(face_x),
        camera,
        field,
        aovs=["images", "position", "object_id"],
        progress=False,
        max_length=max_length,
    )
    rows = np.flatnonzero(out["object_id"][:, 0] == 1)
    heights = out["position"][rows, 0, 1].astype(np.float64)
    centres = _elevations(camera, 0)
    fan = np.linspace(centres[0], centres[-1], 8 * camera.height)  # 8 rays a pixel over the pixel centres
    eye = camera.position[1]
    # A pixel stands for a band of heights: compare where the count is the same across the band
    # (half a row's height step either side), away from the folds where two images merge.
    gaps = np.abs(np.diff(heights))
    step = np.maximum(np.r_[gaps[0], gaps], np.r_[gaps, gaps[-1]])  # to the farther neighbour
    low, mid, high = (_traced_images(field, eye, fan, face_x, heights + k * step, max_length) for k in (-0.5, 0, 0.5))
    stable = (low == mid) & (mid == high)
    assert np.sum(stable & (mid == expected_most)) >= 3  # the test sees the multiple images it is about
    np.testing.assert_array_equal(out["images"][rows, 0][stable], mid[stable])


def _wall_scene(face_x):
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    scene.add_ground(0.0, 3 * face_x)
    scene.add_box((face_x + 1.0, 20.0, 0.0), (2.0, 40.0, 400.0))
    return scene


def test_images_two_over_a_hot_road_as_the_traced_fan_shows(hot_road):
    eye, tilt = 1.5, np.radians(-0.05)
    camera = refracta.Camera((0.0, eye, 0.0), (300.0, eye + 300.0 * np.tan(tilt), 0.0), (0, 1, 0), 0.3, 1, 60)
    _check_images(hot_road, camera, 1000.0, 2000.0, 2)


@pytest.mark.slow
def test_images_three_over_a_cold_sea_as_the_traced_fan_shows():
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(**examples.COLD_SEA_INVERSION), R)
    eye, d = examples.COLD_SEA_EYE, 13000.0
    camera = refracta.Camera((0.0, eye, 0.0), (d, eye + d * np.tan(np.radians(0.12)), 0.0), (0, 1, 0), 0.25, 1, 50)
    _check_images(field, camera, d, 20000.0, 3)


def test_readouts_are_bit_identical_across_threads_and_tiles(hot_road):
    scene, *_ = _flat_scene()
    camera = refracta.Camera((0.0, 1.5, 0.0), (50.0, 1.0, -3.0), (0, 1, 0), 16.0, 24, 16)
    names = [*READOUTS, "hidden_height", "images"]

    def run(**extra):
        return refracta.render(scene, camera, hot_road, spp=4, aovs=names, progress=False, max_length=300.0, **extra)

    results = []
    try:
        for n in (1, 2):
            refracta.set_threads(n)
            results.append(run())
    finally:
        refracta.set_threads(None)
    results.append(run(tiles=(2, 3)))
    (image, out), *others = results
    for other_image, other in others:
        assert np.array_equal(image, other_image)
        for name in names:
            assert np.array_equal(out[name], other[name], equal_nan=True), name
    # Several samples: the nearest hit, never a blend -- every position lies on a surface.
    met = out["object_id"] >= 0
    ground = out["object_id"] == 0
    assert np.all(np.abs(out["position"][ground][:, 1]) < 1e-5)  # float32 zero of the plane y = 0
    assert np.all(np.isfinite(out["position"][met]))


def test_readouts_of_a_part_of_the_image_are_the_whole_images(hot_road):
    # pixel_bounds promises every pixel as in the whole image: the mirage multiplicity ('images')
    # counts branches down the whole column, and a trial found 81 of 1000 pixels off (2 against 1)
    # when it saw only the bounds' rows.
    example = refracta.examples.hot_road(96, 48)
    names = [*READOUTS, "hidden_height", "images", "samples"]

    def run(**extra):
        return refracta.render(
            example.scene,
            example.camera,
            example.field,
            aovs=names,
            progress=False,
            max_length=example.max_length,
            **extra,
        )

    image, whole = run()
    assert np.any(whole["images"] >= 2)  # the road's mirage: a case that can fail
    part_image, part = run(pixel_bounds=(10, 20, 60, 40))
    assert part_image.shape == (20, 50, 3) and part["images"].shape == (20, 50)
    assert np.array_equal(part_image, image[20:40, 10:60])
    for name in names:
        assert np.array_equal(part[name], whole[name][20:40, 10:60], equal_nan=True), name


def test_bad_aov_names_and_geographic_without_a_frame_are_refused():
    scene, *_ = _flat_scene()
    camera = refracta.Camera((0.0, 1.5, 0.0), (50.0, 1.5, 0.0), (0, 1, 0), 16.0, 8, 6)
    with pytest.raises(ValueError, match="unknown aovs.*'depth'.*valid names: albedo, normal, distance"):
        refracta.render(scene, camera, None, aovs=["depth"], progress=False)
    with pytest.raises(ValueError, match="'geographic' needs frame="):
        refracta.render(scene, camera, None, aovs=["geographic"], progress=False)
    with pytest.raises(ValueError, match="readouts need method 'straight' or 'curved'"):
        refracta.render(scene, camera, None, method="raster_march", aovs=["distance"], progress=False)


def test_geographic_goes_through_the_frame():
    """The frame's to_geographic gets the hit points (a stand-in frame here: refracta.geo's
    LocalFrame is tested with its own module); no hit stays NaN."""

    class Frame:
        def to_geographic(self, points):
            points = np.asarray(points)
            return points[..., 0] * 2.0, points[..., 2] * 3.0, points[..., 1] + 100.0

    scene, *_ = _flat_scene()
    camera = refracta.Camera((0.0, 1.5, 0.0), (50.0, 1.5, 0.0), (0, 1, 0), 40.0, 8, 6)
    _, out = refracta.render(scene, camera, None, aovs=["geographic", "position"], frame=Frame(), progress=False)
    p = out["position"].astype(np.float64)
    met = np.isfinite(p[..., 0])
    assert met.any() and (~met).any()
    np.testing.assert_array_equal(out["geographic"][met], np.stack([p[met, 0] * 2, p[met, 2] * 3, p[met, 1] + 100], -1))
    assert np.all(np.isnan(out["geographic"][~met]))


def test_cli_writes_readouts_as_exr_layers(tmp_path):
    scene_file = Path(__file__).resolve().parents[1] / "data" / "hot_road.toml"
    output = tmp_path / "readouts.exr"
    argv = ["render", str(scene_file), "-o", str(output), "--size", "24x8", "--aovs", "distance,position,hidden_height"]
    assert cli.main(argv) == 0
    names = refracta.io.channel_names(output)  # OpenEXR keeps channels sorted by name: compare as sets
    assert sorted(names) == sorted(
        [
            "R",
            "G",
            "B",
            "distance.Y",
            "position.X",
            "position.Y",
            "position.Z",
            "hidden_height.geometric",
            "hidden_height.refracted",
        ]
    )
    pixels = refracta.io.read_image(output)
    scene, camera, field = refracta.load_scene(scene_file)
    _, out = refracta.render(scene, camera.resized(24, 8), field, aovs=["distance"], progress=False)
    assert np.array_equal(pixels[..., names.index("distance.Y")], out["distance"])  # the layer is the readout, inf kept
    assert cli.main(["render", str(scene_file), "-o", str(tmp_path / "x.png"), "--aovs", "distance"]) == 1
    # --key shapes only displayed images: said for the layered EXR as write_image says it (it was ignored).
    argv = ["render", str(scene_file), "-o", str(output), "--size", "24x8", "--aovs", "distance", "--key", "0.3"]
    with pytest.warns(UserWarning, match="written linear: --key shape only displayed images"):
        assert cli.main(argv) == 0


def test_geographic_of_a_target_placed_by_latitude_and_longitude():
    """A 1 m ball placed 5 km east by geo.forward and LocalFrame.to_scene: the geographic readout of
    every pixel on it lies within the ball's radius of its centre (geodesic distance, height)."""
    from refracta import geo

    frame = geo.LocalFrame(60.0, 10.0, earth_radius=np.inf)  # a flat-Earth scene: y is the height
    lat, lon, _ = geo.forward(60.0, 10.0, 90.0, 5000.0)
    centre = frame.to_scene(lat, lon, 20.0)
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    scene.add_sphere(centre, 1.0)
    camera = refracta.Camera((0.0, 5.0, 0.0), centre, (0, 1, 0), 0.04, 9, 9)
    _, out = refracta.render(scene, camera, None, method="straight", aovs=["geographic"], frame=frame, progress=False)
    met = np.isfinite(out["geographic"][..., 0])
    assert met.sum() > 20
    for hit_lat, hit_lon, height in out["geographic"][met]:
        distance, _, _ = geo.inverse(hit_lat, hit_lon, lat, lon)
        assert np.hypot(distance, height - 20.0) < 1.0 + 1e-3  # on the ball (float32 positions: 4e-4 m at 5 km)


def test_a_ridge_from_elevation_data_against_refraction_coefficient():
    """Issue 20's check: a synthetic ridge (a Gaussian, 200 m high, 30 km away, as elevation data)
    seen from 10 m over a curved Earth in a standard atmosphere. Its crest's apparent elevation is
    where refracta.refraction_coefficient's exact trace puts a 200 m target at 30 km; each hit's
    true elevation and hidden heights (without and with the air) are what it computes for that hit
    (its own tracing, independent of the renderer's); apparent - true is k d / (2R)."""
    d, peak, eye = 30000.0, 200.0, 10.0
    field = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), R)
    x, z = np.arange(d - 1000.0, d + 1001.0, 20.0), np.arange(-500.0, 501.0, 20.0)
    heights = np.repeat(peak * np.exp(-0.5 * ((x - d) / 300.0) ** 2)[None, :], z.size, axis=0)
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    scene.add_ground(0.0, 3 * d)
    scene.add_terrain(heights, origin=(x[0], z[0]), spacing=(20.0, 20.0), earth_radius=R)
    crest = refracta.refraction_coefficient(field, eye, d, target_height=peak)
    aim = np.radians(crest.apparent_elevation)
    camera = refracta.Camera((0.0, eye, 0.0), (d, eye + d * np.tan(aim), 0.0), (0, 1, 0), 0.05, 1, 50)
    names = ["object_id", "apparent_elevation", "true_elevation", "hidden_height", "position"]
    _, out = refracta.render(scene, camera, field, aovs=names, progress=False, max_length=1.5 * d)
    rows = np.flatnonzero(out["object_id"][:, 0] >= 1)  # the terrain (the sea is id 0)
    top = rows[0]
    # The crest's silhouette lies in the top terrain row: within a pixel (0.001 deg) of the trace.
    assert abs(out["apparent_elevation"][top, 0] - crest.apparent_elevation) < camera.vfov / camera.height
    for row in rows[:: max(1, rows.size // 4)]:
        px, py, pz = out["position"][row, 0].astype(np.float64)
        ground, height = np.hypot(px, pz), R * np.expm1(py / R)  # along the surface; true height
        expected = refracta.refraction_coefficient(field, eye, ground, target_height=height)
        assert out["true_elevation"][row, 0] == pytest.approx(expected.true_elevation, abs=1e-6)  # float32 degrees
        hidden = out["hidden_height"][row, 0]
        assert hidden[0] == pytest.approx(expected.hidden_height_straight, abs=1e-3)  # float32 positions (mm)
        assert hidden[1] == pytest.approx(expected.hidden_height_refracted, abs=1e-3)  # and both traces' tolerances
        # apparent - true = k d / (2R), the surveyors' small-angle form
        lift = np.radians(out["apparent_elevation"][row, 0] - out["true_elevation"][row, 0])
        kd = expected.k * ground / (2 * R)
        assert lift == pytest.approx(kd, rel=0.02)  # k is the level ray's; this line climbs 0.23 deg: other air


def test_a_frame_of_another_earth_than_the_fields_is_warned_of():
    """frame= flattening another Earth than the rays' field: the 'geographic' readout would map
    points the render did not see (a new user's trial: accepted silently)."""
    from refracta import geo

    scene, *_ = _flat_scene()
    camera = refracta.Camera((0.0, 1.5, 0.0), (50.0, 1.5, 0.0), (0, 1, 0), 40.0, 8, 6)
    curved = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), 6.0e6)
    for frame, field in (
        (geo.LocalFrame(50.0, 1.0, earth_radius=6.381e6), curved),  # two radii
        (geo.LocalFrame(50.0, 1.0), refracta.PhysicalAtmosphere()),  # a curved frame, flat air
        (geo.LocalFrame(50.0, 1.0, earth_radius=math.inf), curved),  # a flat frame, curved air
    ):
        with pytest.warns(refracta.SceneWarning, match="frame= flattens an Earth"):
            refracta.render(scene, camera, field, aovs=["geographic"], frame=frame, progress=False)
    refracta.render(scene, camera, curved, aovs=["geographic"], frame=geo.LocalFrame(50.0, 1.0, earth_radius=curved))
