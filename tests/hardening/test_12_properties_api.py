"""Property-based tests over the public API (issue 13): every call returns finite results or
raises one of refracta's named errors -- never NaN, a crash or another exception. Random fields
(parameters inside, outside and at the edges of their bounds, NaN), rays, cameras, scenes,
materials, point pairs and moment inputs. The `fuzz` marker runs the larger budget."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import refracta
from refracta import moments, oit, shading
from refracta.edit import PointPair
from tests.hardening.properties import (
    FAST,
    FUZZ,
    anything,
    calls,
    edge,
    finite,
    ordinary,
    ordinary_vec3,
    render_checking_scene_warnings,
    vec3,
)

MODELS = [refracta.PhysicalAtmosphere, refracta.LogisticProfile, refracta.LinearSquaredProfile]


@st.composite
def fields(draw):
    model = draw(st.sampled_from(MODELS))
    defaults = dict(model().params)
    bounds = dict(model().bounds)
    chosen = draw(st.lists(st.sampled_from(sorted(defaults)), max_size=3, unique=True))
    params = {}
    for name in chosen:
        lo, hi = bounds[name]
        params[name] = draw(st.one_of(st.floats(lo, hi), st.floats(2 * lo - hi, 2 * hi - lo), edge))
    return model, params


def check_field(model, params, points):
    field = calls(model, **params)
    if field is None:
        return
    n = calls(field.ior, points)
    if n is not None:
        assert finite(n) and np.all(np.asarray(n) > 0)
    grad = calls(field.grad_ior, points)
    if grad is not None:
        assert finite(grad)


points = st.lists(st.tuples(ordinary, st.one_of(ordinary, edge), ordinary), min_size=1, max_size=4)


@FAST
@given(fields(), points)
def test_fields_return_positive_finite_n_or_raise(field, p):
    check_field(*field, np.array(p))


@pytest.mark.fuzz
@FUZZ
@given(fields(), points)
def test_fields_fuzz(field, p):
    check_field(*field, np.array(p))


def check_trace(model, params, origin, direction, method, tol, step, max_length, stop_height):
    field = calls(model, **params)
    if field is None:
        return
    path = calls(
        refracta.trace_ray,
        field,
        origin,
        direction,
        trace=method,
        tol=tol,
        step=step,
        max_length=max_length,
        stop_height=stop_height,
    )
    if path is None:
        return
    assert finite(path.points) and finite(path.directions) and finite(path.arc_length)
    assert path.length <= max_length * (1 + 1e-9)
    assert path.stop in ("max_length", "stop_height")


traces = dict(
    field=fields(),
    origin=st.tuples(ordinary, st.one_of(st.floats(-50, 3000), edge), ordinary),
    direction=vec3,
    method=st.sampled_from(["rk45", "rk4", "stratified"]),
    tol=st.one_of(st.floats(1e-6, 1.0), edge),
    step=st.one_of(st.none(), st.floats(0.5, 100.0), edge),
    max_length=st.one_of(st.floats(1.0, 2000.0), edge),
    stop_height=st.one_of(st.none(), st.floats(-10, 10)),
)


@FAST
@given(**traces)
def test_rays_are_finite_or_raise(field, origin, direction, method, tol, step, max_length, stop_height):
    check_trace(*field, origin, direction, method, tol, step, max_length, stop_height)


@pytest.mark.fuzz
@FUZZ
@given(**traces)
def test_rays_fuzz(field, origin, direction, method, tol, step, max_length, stop_height):
    check_trace(*field, origin, direction, method, tol, step, max_length, stop_height)


@FAST
@given(
    vec3,
    vec3,
    vec3,
    st.one_of(st.floats(0.01, 179.0), edge),
    st.integers(-2, 64),
    st.integers(-2, 64),
    st.tuples(st.floats(-1e6, 1e6), st.floats(-1e6, 1e6)),
    ordinary_vec3,
)
def test_cameras_give_unit_rays_or_raise(position, look_at, up, vfov, width, height, uv, point):
    camera = calls(refracta.Camera, position, look_at, up, vfov, width, height)
    if camera is None:
        return
    result = calls(camera.ray, *uv)
    if result is not None:
        origin, direction = result
        assert finite(origin) and finite(direction)
        assert np.linalg.norm(direction) == pytest.approx(1.0, abs=1e-12)
    projected = calls(camera.project, point)
    if projected is not None:
        assert not np.any(np.isnan(projected))


@st.composite
def scenes(draw):
    scene = refracta.Scene()
    for _ in range(draw(st.integers(0, 3))):
        kind = draw(st.sampled_from(["box", "sphere", "ground", "mesh"]))
        if kind == "box":
            calls(scene.add_box, draw(vec3), draw(vec3), kd=draw(st.one_of(st.floats(0, 1), edge)))
        elif kind == "sphere":
            calls(scene.add_sphere, draw(vec3), draw(anything))
        elif kind == "ground":
            calls(scene.add_ground, draw(anything), draw(st.one_of(st.floats(1, 1e5), edge)))
        else:
            vertices = draw(st.lists(vec3, min_size=3, max_size=5))
            triangles = draw(st.lists(st.tuples(*[st.integers(-1, 6)] * 3), min_size=1, max_size=3))
            calls(scene.add_mesh, vertices, triangles)
    if draw(st.booleans()):
        calls(scene.set_sun, draw(vec3), draw(vec3))
    if draw(st.booleans()):
        calls(scene.set_sky, draw(vec3), draw(vec3))
    return scene


@FAST
@given(
    scenes(),
    st.sampled_from(["straight", "curved", "raster_march"]),
    st.integers(1, 4),
    st.sampled_from(["direct", "path"]),
)
def test_tiny_renders_are_finite_or_raise(scene, method, spp, transport):
    camera = refracta.Camera((0.0, 1.5, 0.0), (10.0, 1.0, 0.0), vfov=30.0, width=6, height=4)
    field = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    image = render_checking_scene_warnings(
        scene, camera, field, method=method, spp=spp, transport=transport, max_length=200.0, progress=False
    )
    if image is not None:
        assert image.shape == (4, 6, 3) and finite(image) and image.min() >= 0.0


MATERIALS = {
    "Diffuse": lambda d: shading.Diffuse(d(anything)),
    "BlinnPhong": lambda d: shading.BlinnPhong(d(anything), d(anything), d(anything)),
    "Conductor": lambda d: shading.Conductor(d(anything), d(anything)),
    "RoughConductor": lambda d: shading.RoughConductor(d(anything), eta=d(anything), k=d(anything)),
    "Dielectric": lambda d: shading.Dielectric(d(anything)),
    "RoughDielectric": lambda d: shading.RoughDielectric(d(anything), d(anything)),
    "Plastic": lambda d: shading.Plastic(d(anything), d(anything), d(anything)),
    "Principled": lambda d: shading.Principled(d(anything), d(anything), d(anything), d(anything)),
    "ThinFilm": lambda d: shading.ThinFilm(d(anything), d(anything), d(anything)),
    "Water": lambda d: shading.Water(d(anything), d(anything), d(anything)),
}


@FAST
@given(st.data(), st.sampled_from(sorted(MATERIALS)), vec3, vec3, st.tuples(*[st.floats(0, 1, exclude_max=True)] * 3))
def test_materials_evaluate_finite_or_raise(data, name, wo, wi, u):
    material = calls(MATERIALS[name], data.draw)
    if material is None:
        return
    for value in (calls(material.f, wo, wi), calls(material.pdf, wo, wi)):
        if value is not None:
            assert finite(value) and np.all(np.asarray(value) >= 0)
    sample = calls(material.sample, wo, u)
    if sample is not None:
        for key in ("wi", "weight", "f", "pdf"):
            assert finite(sample[key]), key


@FAST
@given(st.one_of(st.tuples(anything, anything), vec3), vec3, anything)
def test_point_pairs_are_valid_or_raise(destination, source, weight):
    pair = calls(PointPair, destination, source, weight)
    if pair is not None:
        assert finite(pair.source) and finite(pair.weight) and pair.weight >= 0


@FAST
@given(
    st.lists(st.one_of(st.floats(-2, 2), edge), min_size=4, max_size=4),
    st.one_of(st.floats(-1, 1), edge),
    st.sampled_from(["msm_hamburger", "msm_hausdorff", "vsm"]),
    st.sampled_from(["unit", "signed"]),
    st.sampled_from(["fp64", "fp32", "unorm16"]),
)
def test_moment_shadows_are_in_the_unit_interval_or_raise(b, z, method, depth_range, storage):
    s = calls(moments.shadow_intensity, np.array(b), z, method=method, depth_range=depth_range, storage=storage)
    if s is not None:
        assert finite(s) and np.all((0.0 <= s) & (s <= 1.0))
    m = calls(moments.power_moments, np.array(b))
    if m is not None:
        assert finite(m)


@FAST
@given(
    st.lists(
        st.tuples(
            st.one_of(st.floats(0.01, 100), edge),
            st.one_of(st.floats(0, 1), edge),
            st.tuples(*[st.one_of(st.floats(0, 1), edge)] * 3),
        ),
        min_size=0,
        max_size=6,
    ),
    st.sampled_from(["exact", "peel", "wboit", "mboit"]),
    st.sampled_from([4, 6, 8]),
)
def test_transparency_composites_are_finite_or_raise(fragments, method, count):
    depths = np.array([f[0] for f in fragments], dtype=float)
    alphas = np.array([f[1] for f in fragments], dtype=float)
    colors = np.array([f[2] for f in fragments], dtype=float).reshape(-1, 3)
    out = calls(oit.composite, depths, alphas, colors, method=method, moments=count)
    if out is not None:
        assert finite(out)
