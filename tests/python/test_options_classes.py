"""Every bound options class behaves alike (issue 22, item 1): built from keywords (validated, an
unknown name refused by name), compared by value, pickled through its fields; and a Camera, which
does not change once made, compares and hashes by what it renders."""

import pickle

import numpy as np
import pytest

from refracta import _core, _options, examples

# Every options and settings class the package binds, with one non-default field value each.
OPTIONS = {
    "RenderOptions": ("spp", 16),
    "TraceOptions": ("tol", 1e-5),
    "ElevationTableOptions": ("initial_rays", 33),
    "SolveSettings": ("max_iterations", 40),
    "PairOptions": ("reach", 2.0),
    "TurbulenceSettings": ("cells", 32),
    "ObjOptions": ("scale", 2.0),
    "DisplaySettings": ("key", 0.25),
    "MomentShadowSettings": ("bias", 1e-4),
    "ShadowMapOptions": ("resolution", 512),
    "MboitSettings": ("moments", 6),
    "OitSettings": ("layers", 8),
    "RasterRenderOptions": ("tile", 32),
}


def test_the_list_holds_every_bound_options_class():
    classes = [name for name in dir(_core) if isinstance(getattr(_core, name), type)]
    assert {name for name in classes if name.endswith(("Options", "Settings"))} == set(OPTIONS)


@pytest.mark.parametrize("name", sorted(OPTIONS))
def test_keywords_build_the_same_object_as_setting_the_field(name):
    cls = getattr(_core, name)
    field, value = OPTIONS[name]
    by_keyword = cls(**{field: value})
    by_setting = cls()
    setattr(by_setting, field, value)
    assert getattr(by_keyword, field) == value
    assert by_keyword == by_setting and by_keyword != cls()
    assert by_keyword == _options.build(cls, **{field: value})
    assert pickle.loads(pickle.dumps(by_keyword)) == by_keyword
    assert (by_keyword == object()) is False  # another type: not equal, no error
    with pytest.raises(ValueError, match=rf"unknown option '{field}x'"):
        cls(**{field + "x": value})


def test_nested_options_compare_by_their_fields():
    table = _core.ElevationTableOptions(trace=_core.TraceOptions(tol=1e-5))
    assert table != _core.ElevationTableOptions()
    assert table == _core.ElevationTableOptions(trace=_core.TraceOptions(tol=1e-5))


def test_keywords_are_validated():
    with pytest.raises(ValueError, match="spp must be >= 1"):
        _core.RenderOptions(spp=0)


def test_cameras_compare_and_hash_by_what_they_render():
    camera = examples.hot_road(32, 16).camera
    copy = pickle.loads(pickle.dumps(camera))
    assert copy == camera and hash(copy) == hash(camera) and {camera: 1}[copy] == 1
    assert camera.resized(33, 16) != camera
    assert camera.with_lens(0.01, 100.0) != camera
    jitter = camera.jittered(np.full((16, 32, 2), 1e-4))
    assert jitter != camera and pickle.loads(pickle.dumps(jitter)) == jitter


def test_a_chord_too_short_for_the_traces_names_chord():
    # chord is also the curved traces' largest node spacing: 1e-9 m was refused as "stratified with
    # step 1e-09 m ... (raise step or lower max_length)", naming an option the user never set.
    with pytest.raises(ValueError, match=r"chord 1e-09 m needs more than 10000000 .*raise chord to at least 0.0005"):
        _core.RenderOptions(chord=1e-9)


@pytest.mark.parametrize("field, value", [("spp", True), ("tol", False), ("seed", True)])
def test_a_boolean_is_not_a_number_of_an_options_field(field, value):
    # True was taken as 1 sample (new-user trial), as pybind11 converts it; models and scene files refuse it.
    with pytest.raises(ValueError, match=rf"RenderOptions: {field} must be a number \(got {value}\)"):
        _core.RenderOptions(**{field: value})
    assert _core.RenderOptions(adaptive=True, spp=8).adaptive is True  # a bool field takes it
