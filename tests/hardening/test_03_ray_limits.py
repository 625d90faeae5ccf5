"""Ray traces always end (issue 13): a path that would need more than max_steps = 1e7 steps is
refused before any work, with a ValueError naming the method, step and max_length; before, a
stratified trace with max_length 1e12 or 1e30 (or step 1e-9) grew by ~40 MB/s and ignored Ctrl-C.
rk45 with a requested small step is no longer called "singular"."""

import numpy as np
import pytest

import refracta

ROAD = dict(surface_dt=10.0, surface_depth=0.1)


@pytest.mark.parametrize("options", [dict(max_length=1e12), dict(max_length=1e30), dict(step=1e-9)])
def test_stratified_paths_beyond_the_step_limit_are_refused_up_front(options):
    field = refracta.PhysicalAtmosphere(**ROAD)
    with pytest.raises(ValueError, match=r"stratified with step .* needs more than 10000000 steps"):
        refracta.trace_ray(field, [0, 1.5, 0], [1, 0, 0], trace="stratified", **options)
    with pytest.raises(ValueError, match="needs more than 10000000 steps"):
        refracta.trace_rays(field, [0, 1.5, 0], [[1, 0, 0]], trace="stratified", **options)


def test_rk45_with_a_tiny_largest_step_names_the_step_not_a_singular_field():
    field = refracta.PhysicalAtmosphere(**ROAD)
    with pytest.raises(ValueError, match=r"rk45 with step 1e-09 m needs more than 10000000 steps") as error:
        refracta.trace_ray(field, [0, 1.5, 0], [1, 0, 0], step=1e-9)
    assert "singular" not in str(error.value)


def test_a_small_requested_step_within_the_limit_traces_the_same_path():
    # 1e6 steps of 1 mm: accepted (no "singular" after 1000 tiny steps), and the same end as the
    # adaptive trace within both tolerances (1e-6 m each over 1 km).
    field = refracta.PhysicalAtmosphere(**ROAD)
    small = refracta.trace_ray(field, [0, 1.5, 0], [1, -0.002, 0], step=1e-3, max_length=1000.0)
    free = refracta.trace_ray(field, [0, 1.5, 0], [1, -0.002, 0], max_length=1000.0)
    np.testing.assert_allclose(small.points[-1], free.points[-1], atol=2e-6)


def test_height_only_renders_with_an_impossible_max_length_are_refused_not_hung():
    from refracta import examples

    road = examples.hot_road(16, 8)
    with pytest.raises(ValueError, match="max_length 1e\\+30 m with chord 1000 m needs more than 10000000 steps"):
        refracta.render(road.scene, road.camera, road.field, max_length=1e30, progress=False)
