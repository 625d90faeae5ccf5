"""Rays leaving PhysicalAtmosphere's modelled heights ([-1000, 86000] m) (issue 13): one such ray
failed the whole render with "height -nan m is outside the modelled range". Above the column the
air is uniform at its top state, so a climbing ray leaves straight along its direction there (and
sees the sky); below it there is ground, and the error says so and what to do."""

import numpy as np
import pytest

import refracta
from refracta import examples

TOP = 86000.0  # [m] PhysicalAtmosphere's modelled top (U.S. Standard Atmosphere 1976)
ROAD = dict(surface_dt=10.0, surface_depth=0.1)


def test_above_the_top_the_air_is_uniform_at_its_top_state():
    field = refracta.PhysicalAtmosphere(**ROAD)
    top = field.ior([0.0, TOP, 0.0])
    for h in (TOP + 1e-3, 1e5, 1e7):
        assert field.ior([0.0, h, 0.0]) == top
        np.testing.assert_array_equal(field.grad_ior([0.0, h, 0.0]), [0.0, 0.0, 0.0])


def test_a_climbing_ray_leaves_straight_with_bouguers_invariant():
    field = refracta.PhysicalAtmosphere(**ROAD)
    eye, t0 = np.array([0.0, 1.5, 0.0]), np.array([1.0, 0.3, 0.0]) / np.hypot(1.0, 0.3)
    stratified = refracta.trace_ray(field, eye, t0, trace="stratified", max_length=1e6)
    rk45 = refracta.trace_ray(field, eye, t0, trace="rk45", max_length=1e6)
    # Two independent integrators of the same ray agree (both to tol 1e-6 m; 1e-5 m allowed).
    np.testing.assert_allclose(stratified.points[-1], rk45.points[-1], atol=1e-5)
    # n(h) cos e = n(eye) cos e0 (Bouguer) holds at the end, where n is the top's.
    n0, n_top = field.ior(eye), field.ior([0.0, TOP, 0.0])
    end = stratified.directions[-1]
    assert n_top * np.hypot(end[0], end[2]) == pytest.approx(n0 * np.hypot(t0[0], t0[2]), rel=1e-12)
    # Above the top the path is a straight line: one stratified node from 86 km to the end.
    above = stratified.points[:, 1] > TOP + 1e-6
    assert above.sum() == 1 and stratified.points[-2, 1] == pytest.approx(TOP, abs=1e-6)


def test_a_ray_below_the_bottom_names_the_range_and_the_remedy():
    field = refracta.PhysicalAtmosphere(**ROAD)
    with pytest.raises(refracta.NumericalError, match=r"below the modelled range \[-1000, 86000\] m .*add a ground"):
        refracta.trace_ray(field, [0, 1.5, 0], [1, -0.5, 0], max_length=5000.0)


@pytest.mark.slow  # the eye's table traces ~150 rays through 86 km of air
def test_a_render_of_the_sky_past_the_top_is_finite_and_independent_of_max_length():
    # The hot road's air, looked at 15-25 degrees up: every camera ray (the eye's ElevationTable)
    # and every ray toward the sky from the road crosses 86 km within 340 km. Past the top each
    # goes straight, so a longer path sees the same sky along the same direction.
    road = examples.hot_road(16, 8)
    eye = np.asarray(road.camera.position)
    up = np.radians(20.0)
    camera = refracta.Camera(eye, eye + [np.cos(up), np.sin(up), 0.0], vfov=10, width=16, height=8)
    images = [
        refracta.render(road.scene, camera, road.field, max_length=length, progress=False) for length in (4e5, 1e6)
    ]
    assert np.isfinite(images[0]).all() and images[0].min() > 0.0
    np.testing.assert_allclose(images[0], images[1], rtol=1e-6)


def test_a_billboard_without_ground_renders_alike_by_both_methods(tmp_path):
    # Rays aimed below the horizon used to descend out of the modelled air (raster_march: the
    # march had no lower end). Both methods see the same sky and billboard through the same air.
    texture = tmp_path / "photo.png"
    refracta.io.write_image(texture, np.full((8, 8, 3), 0.5, np.float32))
    scene = refracta.Scene()
    scene.set_sky([0.8, 0.8, 0.8], [0.3, 0.4, 0.9])
    scene.add_billboard([50, 1, 0], 4, 2, str(texture))
    camera = refracta.Camera([0, 1.5, 0], [50, 1, 0], vfov=40, width=32, height=16)
    images = [
        refracta.render(
            scene, camera, refracta.PhysicalAtmosphere(**ROAD), method=method, max_length=1e5, progress=False
        )
        for method in ("raster_march", "curved")
    ]
    for image in images:
        assert np.isfinite(image).all() and image.min() > 0.0
    # 0.01: the two methods' sky directions differ by the march's step and the table's tolerance.
    np.testing.assert_allclose(images[0], images[1], atol=0.01)
