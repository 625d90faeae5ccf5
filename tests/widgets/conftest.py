"""Shared fixtures of the editor tests: the hot road at 320 x 120 and editors on it that stop their
background threads afterwards."""

import numpy as np
import pytest

import refracta
from refracta import examples

WIDTH, HEIGHT = 320, 120
CAR = (189.1, 59.8)  # a pixel on the blue car, 258 m away (notebook 02's bottom source)
SKY = (160.0, 5.0)  # a pixel showing only sky: no scene point


@pytest.fixture(scope="session")
def road():
    """The hot-road example (its sky table is built once per session: ~2 s)."""
    return examples.hot_road(WIDTH, HEIGHT)


@pytest.fixture
def make_model(road):
    """make_model(**kwargs) -> an EditorModel on the road (no render unless autorender=True); closed
    after the test."""
    from refracta.widgets import EditorModel

    made = []

    def make(**kwargs):
        kwargs.setdefault("free", ["surface_dt"])
        kwargs.setdefault("stop_height", 0.0)
        kwargs.setdefault("max_length", road.max_length)
        kwargs.setdefault("autorender", False)
        model = EditorModel(road.scene, road.camera, road.field, **kwargs)
        made.append(model)
        return model

    yield make
    for model in made:
        model.close()


def truth_source(field, camera, u, v, distance=350.0):
    """The point `distance` [m] along the light path `field` sends through pixel (u, v): a source
    that `field` meets exactly at destination (u, v)."""
    origin, direction = camera.ray(u, v)
    path = refracta.trace_ray(field, origin, direction, tol=1e-10, max_length=distance + 50.0, stop_height=0.0)
    return np.asarray(path.point_at(distance)[0])
