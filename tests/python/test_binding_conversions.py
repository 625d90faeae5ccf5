"""One rule per kind of input across the bindings (bindings/convert.h): a colour is a number or three
in every function that takes one, a unit vector has one tolerance, sample numbers lie in [0, 1)."""

import pickle

import numpy as np
import pytest

import refracta
from refracta import lights, shading

# Unit vectors are accepted within 1e-6 of length 1 (convert.h kUnitTolerance): 5e-7 off passes,
# 2e-6 off fails, in lights and materials alike.
INSIDE_TOLERANCE, OUTSIDE_TOLERANCE = 5e-7, 2e-6


def test_a_colour_is_a_number_or_three_in_scene_lights_as_in_lights():
    scene = refracta.Scene()
    index = scene.add_point_light([0.0, 2.0, 0.0], 100.0)
    direct = lights.PointLight([0.0, 2.0, 0.0], 100.0)
    points, u = np.zeros((1, 3)), np.full((1, 2), 0.5)
    for a, b in zip(scene.lights[index].sample_li(points, None, u), direct.sample_li(points, None, u)):
        np.testing.assert_array_equal(a, b)
    assert repr(scene.lights[index]) == repr(lights.PointLight([0.0, 2.0, 0.0], (100.0, 100.0, 100.0)))


def test_a_grey_kd_is_the_grey_triple_as_in_shading():
    scene = refracta.Scene()
    grey = scene.material(scene.add_box([0, 0, 0], [1, 1, 1], kd=0.5))
    triple = scene.material(scene.add_box([2, 0, 0], [1, 1, 1], kd=(0.5, 0.5, 0.5)))
    assert grey.parameters == triple.parameters
    assert grey.parameters["kd"] == (0.5, 0.5, 0.5)
    wo, wi = [0.0, 0.0, 1.0], [0.0, 0.6, 0.8]
    np.testing.assert_array_equal(grey.f(wo, wi), shading.BlinnPhong(0.5).f(wo, wi))


@pytest.mark.parametrize(
    "make",
    [
        lambda s: s.add_point_light([0, 1, 0], [1.0, 2.0]),
        lambda s: s.add_box([0, 0, 0], [1, 1, 1], kd=[0.1, 0.2, 0.3, 0.4]),
        lambda s: s.add_sphere([0, 0, 0], 1.0, emission=-1.0),
    ],
)
def test_bad_colours_raise_value_errors_naming_the_argument(make):
    with pytest.raises(ValueError, match="intensity|kd|emission"):
        make(refracta.Scene())


def test_one_unit_vector_tolerance_for_lights_and_materials():
    inside = np.array([[0.0, 0.0, 1.0 + INSIDE_TOLERANCE]])
    outside = np.array([[0.0, 0.0, 1.0 + OUTSIDE_TOLERANCE]])
    sun = lights.SunLight([0, 0, 1], 1.0)
    material = shading.Diffuse(0.5)
    sun.Le(inside)
    material.f(inside, inside)
    with pytest.raises(ValueError, match="dirs"):
        sun.Le(outside)
    with pytest.raises(ValueError, match="wo"):
        material.f(outside, inside)


def test_sample_numbers_lie_in_zero_one_for_every_sampler():
    below_one = np.nextafter(1.0, 0.0)
    shading.Dielectric(1.5).sample([0.0, 0.0, 1.0], [below_one, 0.5, 0.5])
    lights.PointLight([0, 1, 0], 1.0).sample_li(np.zeros((1, 3)), None, np.array([[below_one, 0.5]]))
    with pytest.raises(ValueError, match=r"u must be in \[0, 1\)"):
        shading.Dielectric(1.5).sample([0.0, 0.0, 1.0], [1.0, 0.5, 0.5])
    with pytest.raises(ValueError, match=r"u must be in \[0, 1\)"):
        lights.PointLight([0, 1, 0], 1.0).sample_li(np.zeros((1, 3)), None, np.array([[1.0, 0.5]]))
    with pytest.raises(ValueError, match=r"u must be in \[0, 1\)"):
        lights.LightSampler([lights.PointLight([0, 1, 0], 1.0)]).sample(np.array([1.0]))
    with pytest.raises(ValueError, match=r"u must be in \[0, 1\)"):
        shading.TrowbridgeReitz(0.3, 0.3).sample_wm([0.0, 0.0, 1.0], np.array([[1.0, 0.5]]))


def test_bsdf_sample_is_a_read_only_class_and_the_dict_access_is_deprecated():
    s = shading.Diffuse(0.5).sample(np.tile([0.0, 0.6, 0.8], (3, 1)), np.full((3, 3), 0.25))
    assert type(s).__name__ == "BsdfSample"
    assert s.fields == ("wi", "weight", "f", "pdf", "flags", "is_delta", "eta", "valid", "terminated")
    assert s.wi.shape == (3, 3) and s.weight.shape == (3, 3) and s.pdf.shape == (3,) and s.valid.all()
    with pytest.raises(AttributeError):
        s.pdf = np.zeros(3)
    with pytest.warns(DeprecationWarning, match=r"BsdfSample\['pdf'\] is deprecated"):
        pdf = s["pdf"]
    np.testing.assert_array_equal(pdf, s.pdf)
    with pytest.warns(DeprecationWarning, match="iteration"):
        assert list(s) == list(s.fields)
    with pytest.raises(KeyError):
        s["nothing"]
    copy = pickle.loads(pickle.dumps(s))
    for key in s.fields:
        np.testing.assert_array_equal(getattr(copy, key), getattr(s, key))


def test_more_than_six_arguments_are_keyword_only():
    scene = refracta.Scene()
    with pytest.raises(TypeError):
        scene.add_mesh(np.eye(3), [[0, 1, 2]], None, None, False, None, None)  # uvs by position
    with pytest.raises(TypeError):
        shading.Principled(0.5, 0.0, 0.5, 0.0, 0.5, 0.0, 0.0)  # sheen by position
    scene.add_mesh(np.eye(3), [[0, 1, 2]], uvs=np.zeros((3, 2)), kd=0.25, alpha=0.5)
    assert shading.Principled(0.5, sheen=0.3).parameters["sheen"] == 0.3
