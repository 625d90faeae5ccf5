"""Bad constructor and call input raises ValueError naming the parameter."""

import numpy as np
import pytest

from refracta.lights import (
    AreaLight,
    ConstantEnvironment,
    EnvironmentLight,
    LightSampler,
    PointLight,
    SphereLight,
    SpotLight,
    SunLight,
)

NAN = float("nan")
TRI_V, TRI_T = [[0, 1, 0], [1, 1, 0], [0, 1, 1]], [[0, 1, 2]]


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda: PointLight([0, NAN, 0], 1.0), "position"),
        (lambda: PointLight([0, 0, 0], -1.0), "intensity"),
        (lambda: PointLight([0, 0, 0], [1.0, NAN, 1.0]), "intensity"),
        (lambda: PointLight([0, 0, 0], [1.0, 2.0]), "intensity"),
        (lambda: SpotLight([0, 0, 0], [0, 0, 0], 60.0, 1.0), "direction"),
        (lambda: SpotLight([0, 0, 0], [0, -1, 0], 0.0, 1.0), "angle"),
        (lambda: SpotLight([0, 0, 0], [0, -1, 0], 400.0, 1.0), "angle"),
        (lambda: SpotLight([0, 0, 0], [0, -1, 0], 60.0, 1.0, inner_angle=70.0), "inner_angle"),
        (lambda: SpotLight([0, 0, 0], [0, -1, 0], 60.0, -2.0), "intensity"),
        (lambda: SunLight([0, 0, 0], 1.0), "direction"),
        (lambda: SunLight([0, 1, 0], -1.0), "radiance"),
        (lambda: SunLight([0, 1, 0], 1.0, angular_diameter=0.0), "angular_diameter"),
        (lambda: SunLight([0, 1, 0], 1.0, angular_diameter=NAN), "angular_diameter"),
        # A disc whose solid angle underflows (its sampling density would be inf).
        (lambda: SunLight([0, 1, 0], 1.0, angular_diameter=1e-300), "angular_diameter"),
        (lambda: SunLight([0, 1, 0], 1.0, limb_darkening=1.5), "limb_darkening"),
        (lambda: AreaLight([[0, 0, 0], [1, 0, 0], [2, 0, 0]], TRI_T, 1.0), "area"),
        (lambda: AreaLight(TRI_V, [[0, 1, 5]], 1.0), "triangles"),
        (lambda: AreaLight([[0, 1, 0], [1, NAN, 0], [0, 1, 1]], TRI_T, 1.0), "vertices"),
        (lambda: AreaLight(TRI_V, np.zeros((0, 3), int), 1.0), "triangles"),
        (lambda: AreaLight(TRI_V, TRI_T, -3.0), "emission"),
        (lambda: SphereLight([0, 0, 0], 0.0, 1.0), "radius"),
        (lambda: SphereLight([0, 0, 0], -1.0, 1.0), "radius"),
        (lambda: SphereLight([NAN, 0, 0], 1.0, 1.0), "centre"),
        (lambda: SphereLight([0, 0, 0], 1.0, NAN), "emission"),
        (lambda: EnvironmentLight(np.zeros((0, 4, 3))), "image"),
        (lambda: EnvironmentLight(np.zeros((1, 4, 3))), "image"),
        (lambda: EnvironmentLight(np.full((4, 8, 3), -1.0)), "texel"),
        (lambda: EnvironmentLight(np.full((4, 8, 3), np.inf)), "pixel"),
        (lambda: EnvironmentLight(np.ones((4, 8, 2))), "channels"),
        (lambda: EnvironmentLight(np.ones((4, 8, 3)), scale=-1.0), "scale"),
        (lambda: EnvironmentLight(np.ones((4, 8, 3)), rotation=np.diag([1.0, 1.0, -1.0])), "rotation"),
        (lambda: EnvironmentLight(np.ones((4, 8, 3)), rotation=2 * np.eye(3)), "rotation"),
        (lambda: EnvironmentLight(np.ones((4, 8, 3)), rotation=NAN), "rotation"),
        (lambda: ConstantEnvironment(-0.1), "radiance"),
        (lambda: ConstantEnvironment(1.0, sampling="bsdf"), "sampling"),
        (lambda: LightSampler([PointLight([0, 0, 0], 1.0)], strategy="random"), "strategy"),
    ],
)
def test_bad_constructor_input_raises_value_error(make, match):
    with pytest.raises(ValueError, match=match):
        make()


def test_bad_call_input_raises_value_error():
    light = PointLight([0, 1, 0], 1.0)
    with pytest.raises(ValueError, match="u"):
        light.sample_li(np.zeros((2, 3)), None, np.zeros((3, 2)))
    with pytest.raises(ValueError, match="u"):
        light.sample_li(np.zeros((1, 3)), None, np.ones((1, 2)))
    with pytest.raises(ValueError, match="normals"):
        light.sample_li(np.zeros((1, 3)), np.array([[0.0, 2.0, 0.0]]), np.zeros((1, 2)))
    with pytest.raises(ValueError, match="points"):
        light.sample_li(np.array([[NAN, 0, 0]]), None, np.zeros((1, 2)))
    with pytest.raises(ValueError, match="wi"):
        light.pdf_li(np.zeros((1, 3)), None, np.array([[0.0, 0.5, 0.0]]))
    with pytest.raises(ValueError, match="dirs"):
        SunLight([0, 1, 0], 1.0).Le(np.array([[0.0, 0.0, 0.0]]))
    with pytest.raises(ValueError, match="radius"):
        SunLight([0, 1, 0], 1.0).preprocess([0, 0, 0], 0.0)
    with pytest.raises(ValueError, match="u"):
        LightSampler([light]).sample(np.array([1.5]))
