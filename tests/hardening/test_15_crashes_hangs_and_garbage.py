"""Reproducers of crashes, hangs and silent NaNs a new user's day and ~4 000 generated inputs found.

Each case that once killed or hung the process runs in a child process (a crash there fails one
test, not the whole session) under HANG_GUARD; the assertion is on what the call now does: a clear
exception naming the problem, or the right result."""

import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

import refracta
from refracta import shading

# Bound of a child that used to hang for minutes; the calls below now take well under a second
# (0.1-2 s measured), so only a hang or a crash reaches it, however busy the machine.
HANG_GUARD = 120.0  # [s]


def run_child(code: str) -> str:
    """Runs `code` in a fresh interpreter and returns its stdout; fails on a crash or a hang."""
    child = subprocess.run(
        [sys.executable, "-W", "ignore", "-c", textwrap.dedent(code)],
        capture_output=True,
        text=True,
        timeout=HANG_GUARD,
    )
    assert child.returncode == 0, f"exit {child.returncode}: {child.stderr[-2000:]}"
    return child.stdout


def test_a_textured_wall_seen_low_through_a_logistic_profile_renders(tmp_path):
    # Segfaulted in ElevationTable::LazyPath::node <- Caster::meets_plane <- Caster::footprint: a
    # neighbour ray launched exactly at an entry of an exactly traced interval of the eye's table
    # read a stencil that such intervals do not have.
    texture = tmp_path / "albedo.png"
    out = run_child(f"""
        import numpy as np, refracta
        refracta.io.write_image({str(texture)!r}, np.random.default_rng(0).random((16, 16, 3)).astype(np.float32))
        scene = refracta.Scene()
        scene.add_ground(0, 1000)
        v = np.array([[30, 0, -10], [30, 0, 10], [30, 10, 10], [30, 10, -10]], float)
        uv = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
        scene.add_mesh(v, np.array([[0, 1, 2], [0, 2, 3]]), uvs=uv, texture={str(texture)!r})
        scene.set_sun((-1, 1, 0.3), (3.0, 3.0, 3.0))
        camera = refracta.Camera((0, 0.3, 0), (10, 0.3, 0), vfov=20, width=8, height=4)
        table = refracta.render(scene, camera, refracta.LogisticProfile(), max_length=500, progress=False)
        traced = refracta.render(scene, camera, refracta.LogisticProfile(), max_length=500, table=False,
                                 progress=False)
        print(table.mean(), traced.mean(), np.isfinite(table).all())
    """)
    table_mean, traced_mean, finite = out.split()
    assert finite == "True"
    assert float(table_mean) > 0.0
    # The table interpolates paths to a quarter pixel: texture lookups shift by that much.
    QUARTER_PIXEL_SHIFT = 0.05
    assert float(table_mean) == pytest.approx(float(traced_mean), rel=QUARTER_PIXEL_SHIFT)


def test_changing_a_scene_while_it_renders_raises_instead_of_corrupting_it():
    # Adding lights while another thread path-traced the scene aborted in Embree; set_physical_sky
    # during a render segfaulted. A render holds the scene; changes raise until it returns.
    road = refracta.examples.hot_road(64, 24)
    started, errors = threading.Event(), []

    def progress(done, total):
        if started.is_set():
            return
        started.set()
        for change in (
            lambda: road.scene.add_point_light((5, 2, 0), (10, 10, 10)),
            lambda: road.scene.set_physical_sky((-0.3, 0.25, 0.2)),
            lambda: road.scene.add_sphere((20, 1, 0), 1.0),
        ):
            try:
                change()
            except RuntimeError as error:
                errors.append(str(error))

    image = refracta.render(road.scene, road.camera, road.field, transport="path", spp=2, progress=progress)
    assert started.is_set() and np.isfinite(image).all()
    assert len(errors) == 3 and all("the scene is being rendered" in e for e in errors), errors
    road.scene.add_point_light((5, 2, 0), (10, 10, 10))  # after the render: allowed again


@pytest.mark.parametrize("radius", [1e30, 1e39])
def test_a_sphere_beyond_embrees_float_range_is_refused(radius):
    # Rendered for 120 s (the ior floors sampled over +-1e30 m of height).
    with pytest.raises(ValueError, match="reaches beyond 1e7 m"):
        refracta.Scene().add_sphere((0, 0, 0), radius)


def test_a_sagitta_below_embrees_precision_is_refused():
    # sagitta=1e-300 cut every path into ~1e150 chords (90 s for 16 x 8 pixels).
    road = refracta.examples.hot_road(16, 8)
    with pytest.raises(ValueError, match="sagitta must be >= 1e-06 m"):
        refracta.render(road.scene, road.camera, road.field, sagitta=1e-300, progress=False)


@pytest.mark.slow
def test_an_eye_table_for_rays_climbing_100_km_is_built_in_whole_panels():
    # A camera looking up through PhysicalAtmosphere with max_length 100 km: 60 s for 16 x 8 pixels.
    # Rays whose invariant is below every n they can meet never turn, so the stratified tracer
    # no longer scans their heights metre by metre (70 000 nodes a path, 4 GB of stencils).
    field = refracta.PhysicalAtmosphere()
    table = refracta.ElevationTable(field, 1.5, 30, 60, tol=1e-3, max_length=100e3)
    # Against a direct rk45 trace at an elevation between the table's entries.
    e = np.radians(44.123)
    ends, _, _ = table.ends(np.array([44.123]), np.array([0.0]))
    exact = refracta.trace_ray(field, [0, 1.5, 0], [np.cos(e), np.sin(e), 0], trace="rk45", tol=1e-6, max_length=100e3)
    # The table's tolerance (1e-3 m) plus its per-metre angular part (none here) and rk45's 1e-6 m.
    TABLE_TOLERANCE = 1e-3 + 1e-6  # [m]
    assert np.abs(ends[0] - exact.points[-1]).max() <= TABLE_TOLERANCE


def test_rk45_shrinks_a_trial_step_that_reaches_below_the_modelled_range():
    # trace_ray over a CurvedEarth with stop_height=0 raised "height -1081.6 m is below the
    # modelled range": the first trial step (24 km long) put its stages there. A ducted ray at
    # -0.03 deg stays above the surface; rk45 and the exact stratified integral must agree.
    field = refracta.CurvedEarth(
        refracta.PhysicalAtmosphere(t_ground=276.15, inversion_dt=10, inversion_base=8, inversion_thickness=6)
    )
    e = np.radians(-0.03)
    paths = {
        m: refracta.trace_ray(field, [0, 4, 0], [np.cos(e), np.sin(e), 0], max_length=24000, stop_height=0.0, trace=m)
        for m in ("rk45", "stratified")
    }
    assert {p.stop for p in paths.values()} == {"max_length"}
    # Both trace to their default tolerance of 1e-6 m over the path.
    BOTH_TOLERANCES = 2e-6  # [m]
    assert np.abs(paths["rk45"].points[-1] - paths["stratified"].points[-1]).max() <= BOTH_TOLERANCES
    # The same ray told about a ground it does reach stops there.
    steep = np.radians(-0.3)
    path = refracta.trace_ray(
        field, [0, 4, 0], [np.cos(steep), np.sin(steep), 0], max_length=24000, stop_height=0.0, trace="rk45"
    )
    assert path.stop == "stop_height" and path.points[-1][1] == pytest.approx(0.0, abs=1e-9)


def test_projecting_the_camera_position_and_rays_far_outside_the_image_raise_or_stay_unit():
    camera = refracta.Camera((0, 1, 0), (10, 1, 0), width=8, height=4)
    with pytest.raises(ValueError, match="camera's own position"):
        camera.project((0, 1, 0))
    with pytest.raises(ValueError, match="too far outside"):
        camera.ray(1e308, 2)
    _, direction = camera.ray(1e200, 2)  # overflowed to NaN before
    assert np.linalg.norm(direction) == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("wavelength", [0.0, float("nan"), -550.0, 1e9])
def test_interior_ior_refuses_wavelengths_outside_the_rendered_range(wavelength):
    with pytest.raises(ValueError, match="wavelength must be in"):
        shading.Dielectric(1.5).interior_ior(wavelength)


def test_material_sample_refuses_nan_random_numbers():
    with pytest.raises(ValueError, match="u must be in"):
        shading.Dielectric(1.5).sample([0, 0, 1], [np.nan, 0.5, 0.5])


@pytest.mark.parametrize("wavelength", [float("nan"), 0.0, 2000.0])
def test_sky_optical_depths_refuse_wavelengths_outside_their_tables(wavelength):
    scene = refracta.Scene()
    scene.set_physical_sky((0, 1, 0))
    sky = next(light for light in scene.lights if hasattr(light, "optical_depth"))
    for name in ("optical_depth", "rayleigh_optical_depth"):
        with pytest.raises(ValueError, match="wavelength must be in"):
            getattr(sky, name)(wavelength)


@pytest.mark.parametrize(
    "points", [np.array([[0, 1 + 1j, 0]]), np.array([["0", "1", "0"]]), np.array([[0, None, 0]], dtype=object)]
)
def test_index_fields_refuse_non_real_points(points):
    with pytest.raises(ValueError, match="must hold real numbers"):
        refracta.PhysicalAtmosphere().ior(points)


def test_turbulence_statistics_refuse_nan_and_negative_arguments():
    from refracta import turbulence as tb

    with pytest.raises(ValueError, match="cn2 must be"):
        tb.tilt_variance(float("nan"), 100.0, inner_scale=0.005)
    with pytest.raises(ValueError, match="path_length must be"):
        tb.tilt_variance(1e-8, -1.0, inner_scale=0.005)
    air = refracta.Turbulence(cells=16, spacing=0.1)
    for tolerance in (-0.1, float("nan")):
        with pytest.raises(ValueError, match="tolerance must be > 0"):
            air.separations_within(tolerance)


def test_the_reference_without_refraction_keeps_the_curved_earth():
    # render(scene, camera, None) of a CurvedEarth scene showed a flat Earth: what the bulge hides
    # appeared in the "without the atmosphere" image. The reference is the same Earth, uniform air.
    assert refracta.without_refraction(None) is None
    assert refracta.without_refraction(refracta.PhysicalAtmosphere()) is None
    ship = refracta.examples.cold_sea(48, 16)
    reference = refracta.without_refraction(ship.field)
    assert isinstance(reference, refracta.CurvedEarth) and reference.radius == ship.field.radius
    # A level ray over the sphere of radius R in uniform air rises above the surface by d^2 / (2R)
    # in the flattened frame (to first order in d/R), and the straight render's flat ground would
    # have it at the eye height.
    eye, d = 5.0, 20e3
    path = refracta.trace_ray(reference, [0, eye, 0], [1, 0, 0], max_length=d, trace="stratified", tol=1e-6)
    # Second-order terms of the flattening: (d/R)^2 relative, 1e-5 of d^2/2R here.
    FLATTENING_ORDER = 1e-4
    assert path.points[-1][1] - eye == pytest.approx(d * d / (2 * reference.radius), rel=FLATTENING_ORDER)
    with pytest.raises(ValueError, match="must be an IndexField"):
        refracta.without_refraction("air")
