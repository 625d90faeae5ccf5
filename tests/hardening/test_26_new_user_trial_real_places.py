"""Defects an eighth new-user trial found following the README's real-place and editing workflows
as a photographer would: each is now computed right or refused by name."""

import numpy as np
import pytest

import refracta
from refracta.edit import PointPair, solve

EYE = (0.0, 1.5, 0.0)
AIR = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)


def test_a_source_behind_the_eye_is_missed_by_its_distance():
    # The miss was the offset's part across the path at the closest approach; at the path's start
    # the offset runs along the path, so a source 40 km behind the eye cost 6e-24 m^2 and its
    # stage said "1 of 1 pairs met" while the pair table said 40 km, not met.
    camera = refracta.Camera(EYE, (100.0, 1.5, 0.0), vfov=5.0, width=32, height=16)
    result = solve(AIR, camera, [PointPair((16.0, 8.0), (-1000.0, 1.5, 0.0))], free=["camera_yaw", "camera_pitch"])
    assert not result.success
    assert result.cost == pytest.approx(0.5 * 1000.0**2, rel=1e-6)  # 1/2 |eye - source|^2: nothing turns it
    assert not any("1 of 1 pairs met" in stage for stage in result.stages), result.stages


def test_objects_beyond_the_rays_reach_are_named_though_a_sea_surrounds_the_camera():
    # The sea around the camera made the scene's box reach it: no warning, and a coast 20 km away
    # rendered as sky with the default max_length (5 km). The objects' box leaves flat surfaces out.
    scene = refracta.Scene()
    scene.add_ground(0.0, 100000.0)
    scene.add_box((20000.0, 50.0, 0.0), (100.0, 100.0, 100.0))
    scene.set_sky((1, 1, 1))
    camera = refracta.Camera((0, 10, 0), (20000, 50, 0), vfov=1.0, width=8, height=4)
    lower, _ = scene.object_bounds
    assert lower[0] == pytest.approx(19950.0)  # the box's near face: the ground left out
    with pytest.warns(
        refracta.SceneWarning,
        match=r"nearest of the scene.s objects \(a ground or sea plane aside\) is 19950 m from the camera, "
        r"beyond the rays. reach max_length = 5000 m",
    ):
        refracta.render(scene, camera, AIR, progress=False)


def test_the_command_line_sets_how_far_rays_reach():
    from refracta import cli

    assert cli._metres("120000") == 120000.0
    for text in ("-5", "0", "inf", "far"):
        with pytest.raises(Exception, match=r"must be"):
            cli._metres(text)


def write_tiff(path, data, scale=(0.001, 0.001), tiepoint=(0, 0, 0, 7.0, 46.0, 0), keys=None, nodata=None):
    """A WGS84 GeoTIFF with its tags as given (malformed ones included)."""
    import tifffile

    keys = [1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 1, 2048, 0, 1, 4326] if keys is None else keys
    tags = [
        (33550, "d", len(scale), scale, False),
        (33922, "d", len(tiepoint), tiepoint, False),
        (34735, "H", len(keys), keys, False),
    ]
    if nodata is not None:
        tags.append((42113, "s", 0, nodata, False))
    tifffile.imwrite(path, data, extratags=tags)
    return path


@pytest.mark.parametrize(
    ("tags", "message"),
    [
        (dict(keys=[1, 1, 0, 5, 1024, 0, 1, 2]), r"its GeoKeyDirectory tag is malformed"),
        (dict(scale=(0.001,)), r"its ModelPixelScale tag must hold 2 numbers"),
        (dict(tiepoint=(0.0, 0.0, 0.0)), r"its ModelTiepoint tag must hold 6 numbers"),
        (dict(tiepoint=(0, 0, 0, 400.0, 46.0, 0)), r"its west edge, longitude 400.0005 deg, is outside \[-360, 360\]"),
    ],
)
def test_malformed_geotiff_tags_name_the_file_and_the_tag(tmp_path, tags, message):
    path = write_tiff(tmp_path / "bad.tif", np.zeros((4, 4), np.float32), **tags)
    with pytest.raises(ValueError, match=r"'[^']*bad.tif': " + message):
        refracta.terrain.read_elevation(path)


def test_nodata_is_compared_in_the_band_s_type(tmp_path):
    # float32's lowest value, written as numpy prints it (-3.4028235e+38): the double that text
    # reads as is not the band's float32.
    data = np.full((3, 3), 120.0, np.float32)
    data[1, 1] = np.finfo(np.float32).min
    grid = refracta.terrain.read_elevation(write_tiff(tmp_path / "dem.tif", data, nodata="-3.4028235e+38"))
    assert np.isnan(grid.heights[1, 1]) and np.count_nonzero(np.isnan(grid.heights)) == 1


def test_a_sensor_size_needs_a_focal_length():
    frame = refracta.geo.LocalFrame(46.0, 7.0)
    with pytest.raises(ValueError, match=r"sensor_mm goes with focal_length_mm"):
        frame.camera(10.0, 90.0, 0.0, vfov=2.0, sensor_mm=(36.0, 24.0))


def test_a_converged_solve_is_not_said_to_be_stopped_by_a_limit():
    # The quick start's own cap (quick_iterations) was reported as the solve's "iteration limit".
    truth = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    pairs = []
    for elevation, distance in ((-0.22, 400.0), (-0.12, 600.0)):  # rays turning above the road
        e = np.radians(elevation)
        path = refracta.trace_ray(truth, EYE, [np.cos(e), np.sin(e), 0.0], max_length=distance, stop_height=0.0)
        pairs.append(PointPair((np.cos(e), EYE[1] + np.sin(e), 0.0), tuple(path.points[-1])))
    result = solve(
        truth.with_params(surface_dt=6.0), EYE, pairs, free=["surface_dt"], stop_height=0.0, quick_iterations=1
    )
    assert result.success and result.iterations > 1  # more than the quick stage's one iteration
    assert result.stopped_by == "", (result.stopped_by, result.stages)


def test_pixels_outside_the_camera_s_image_are_refused():
    # Destinations from a photograph twice the camera's size were taken, and the solve fitted a
    # field of view half the true one, silently.
    camera = refracta.Camera(EYE, (100.0, 1.5, 0.0), vfov=5.0, width=32, height=16)
    with pytest.raises(ValueError, match=r"pairs\[0\]: pixel \(64.0, 8.0\) lies outside the camera's 32 x 16 image"):
        solve(AIR, camera, [PointPair((64.0, 8.0), (100.0, 1.5, 0.0))], free=["camera_yaw"])


def test_a_frame_without_the_geographic_readout_is_refused():
    scene = refracta.Scene()
    scene.add_ground()
    scene.set_sky((1, 1, 1))
    camera = refracta.Camera(EYE, (100.0, 0.0, 0.0), vfov=5.0, width=4, height=2)
    with pytest.raises(ValueError, match=r"frame= maps the 'geographic' readout"):
        refracta.render(scene, camera, None, frame=42, progress=False)


@pytest.mark.parametrize(
    ("heights", "message"),
    [([], r"heights is empty"), (["hill.tif", 3], r"heights\[1\] must be an elevation file's path")],
)
def test_terrain_lists_name_what_is_wrong(heights, message):
    with pytest.raises(ValueError, match=message):
        refracta.Scene().add_terrain(heights, frame=refracta.geo.LocalFrame(46.0, 7.0))


@pytest.mark.parametrize("vfov", ["0.0", "200.0", "nan"])
def test_a_scene_file_s_camera_error_names_the_key_s_line(tmp_path, vfov):
    path = tmp_path / "cam.toml"
    path.write_text(f"# a scene\n\n[camera]\nposition = [0, 1, 0]\nlook_at = [10, 1, 0]\nvfov = {vfov}\n")
    with pytest.raises(ValueError, match=r"cam.toml:6: \[camera\] vfov: Camera: vfov must be in \(0, 180\)"):
        refracta.load_scene(path)


def test_the_distance_readout_over_a_curved_earth_is_the_true_length():
    # Straight rays in true space (without_refraction of a CurvedEarth): the readout must equal the
    # true chord from the eye to the hit. The mean of the ends' scales missed the path's sag in the
    # flat frame: L^3 / 12 R^2 too long, 0.15 m at 42 km (a trial).
    radius = 6371e3
    field = refracta.without_refraction(refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius=radius))
    scene = refracta.Scene()
    scene.add_box((42000.0, 150.0, 0.0), (200.0, 300.0, 2000.0))
    scene.set_sky((1, 1, 1))
    camera = refracta.Camera((0.0, 100.0, 0.0), (42000.0, 150.0, 0.0), vfov=0.5, width=8, height=8)
    _, aovs = refracta.render(scene, camera, field, max_length=60000.0, aovs=["distance", "position"], progress=False)
    hit = np.isfinite(aovs["distance"])
    assert hit.sum() >= 24  # the box fills the lower half of the view or more

    def true_point(p):  # the conformal map: x' = R phi, y' = R ln(r / R) (media/curved_earth.h)
        rho, r = np.hypot(p[..., 0], p[..., 2]), radius * np.exp(p[..., 1] / radius)
        phi = rho / radius
        scale = np.where(rho > 0, r * np.sin(phi) / np.maximum(rho, 1e-300), 1.0)
        return np.stack([p[..., 0] * scale, r * np.cos(phi) - radius, p[..., 2] * scale], axis=-1)

    eye = true_point(np.array(camera.position, float))
    chord = np.linalg.norm(true_point(aovs["position"][hit].astype(np.float64)) - eye, axis=1)
    # 0.01 m: the float32 hit positions and readouts (4 mm at 42 km); 1.9 mm measured, 0.15 m before.
    np.testing.assert_allclose(aovs["distance"][hit], chord, atol=0.01)


def test_overlay_names_a_readout_it_does_not_know():
    image = np.zeros((4, 6, 3), np.float32)
    with pytest.raises(ValueError, match=r"overlay: unknown readouts \['foo'\] in aovs"):
        refracta.photo.overlay(image, image, aovs={"foo": np.zeros((4, 6))})
