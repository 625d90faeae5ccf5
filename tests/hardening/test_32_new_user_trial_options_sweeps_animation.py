"""Fifth new-user trial (options, sweeps, animation, the editor): each test failed before its fix."""

import gc
import math
import pickle
import sys

import numpy as np
import pytest

import refracta
from refracta import examples
from refracta._render import render_options


def test_none_leaves_an_on_off_field_at_its_default():
    # pybind11 took None as False: render(differentials=None) turned ray differentials off.
    built = render_options(differentials=None, table=None, texture_filter=None)
    assert (built.differentials, built.table, built.texture_filter) == (True, True, True)
    assert refracta.RasterRenderOptions(use_sun=None).use_sun


@pytest.mark.parametrize("kwargs", [dict(spectral=2.5), dict(adaptive=math.nan), dict(table=0.5), dict(table=1)])
def test_an_on_off_field_takes_true_or_false_only(kwargs):
    (name,) = kwargs
    with pytest.raises(ValueError, match=f"{name} must be True or False"):
        refracta.RenderOptions(**kwargs)


def test_render_refuses_return_stats_and_tiles_that_are_not_theirs():
    road = examples.hot_road(16, 6)
    with pytest.raises(ValueError, match="return_stats must be True or False"):
        refracta.render(road.scene, road.camera, None, return_stats="no", progress=False)  # "no" is truthy
    with pytest.raises(ValueError, match=r"tiles must be a tile size or \(nx, ny\)"):
        refracta.render(road.scene, road.camera, None, tiles=(True, 1), progress=False)


def test_a_nested_options_problem_is_one_problem():
    # A bad resolution also blamed the valid kernel (kernel <= resolution).
    options = refracta.RasterRenderOptions()
    options.shadow_map.resolution = -1
    with pytest.raises(ValueError) as error:
        options.validate()
    # Named as the nested field it is (it read "resolution must be ...").
    assert "shadow_map.resolution must be in [2, 8192]" in str(error.value) and "kernel" not in str(error.value)


@pytest.mark.parametrize("cls", [refracta.RasterRenderOptions, refracta.TurbulenceSettings, refracta.RenderOptions])
def test_an_options_repr_evaluates_back_to_an_equal_object(cls):
    # Infinite defaults (shadow_distance, outer_scale) printed as a bare inf: NameError.
    names = {name: getattr(refracta, name) for name in dir(refracta) if name[:1].isupper()}
    assert eval(repr(cls()), names) == cls()


def test_render_stats_compare_by_value():
    road = examples.hot_road(16, 6)
    _, stats = refracta.render(road.scene, road.camera, road.field, return_stats=True, progress=False)
    assert pickle.loads(pickle.dumps(stats)) == stats
    assert stats != refracta.RenderStats()


def _noise():
    return dict(rms=2e-4, correlation_pixels=3.0)


def test_a_gif_with_delays_beyond_its_16_bits_is_refused_before_rendering(tmp_path):
    # A time-lapse a frame every 20 min rendered every frame, then Pillow's OverflowError.
    road = examples.hot_road(16, 6)
    with pytest.raises(ValueError, match="at most 655.35 s"):
        refracta.animate(road.scene, road.camera, road.field, np.arange(3) * 1200.0, tmp_path / "t.gif", noise=_noise())
    with pytest.raises(ValueError, match="at most 655.35 s"):
        refracta.animate(road.scene, road.camera, road.field, [0.0, 1.0], tmp_path / "t.gif", fps=1e-3, noise=_noise())


def test_animate_takes_a_bytes_path_and_checks_it_can_write_first(tmp_path):
    road = examples.hot_road(16, 6)
    times = [0.0, 0.1]
    refracta.animate(road.scene, road.camera, road.field, times, bytes(tmp_path / "b.gif"), noise=_noise())
    assert (tmp_path / "b.gif").stat().st_size > 0
    with pytest.raises(OSError, match="cannot write"):  # /proc takes no new file: found after rendering
        refracta.animate(road.scene, road.camera, road.field, times, "/proc/x.gif", noise=_noise())


def test_sweep_refuses_an_empty_grid_and_an_unordered_axis():
    with pytest.raises(ValueError, match="grid names no parameter"):
        refracta.sweep(lambda: 0, {})  # ran f() once
    with pytest.raises(ValueError, match="must be ordered values"):
        refracta.sweep(lambda x: x, {"x": {1, 2}})


def test_the_editor_refuses_bad_options_when_made():
    from refracta.widgets.model import EditorModel

    road = examples.hot_road(32, 12)
    for kwargs, match in (
        (dict(render_options={"sppp": 2}), "unknown option 'sppp'"),
        (dict(render_options={"spp": 0}), "spp must be >= 1"),
        (dict(max_length=-5.0), "max_length must be > 0"),
        (dict(solve_options={"bogus": 1}), "unknown option 'bogus'"),
    ):
        with pytest.raises(ValueError, match=match):  # they failed only later, in the background
            EditorModel(road.scene, road.camera, road.field, **kwargs)
    EditorModel(road.scene, road.camera, road.field, render_options={"spp": 2, "denoise": False}).close()


def test_an_editor_whose_constructor_failed_collects_quietly():
    pytest.importorskip("ipywidgets")
    from refracta.widgets import MirageEditor

    road = examples.hot_road(32, 12)
    unraisable = []
    hook, sys.unraisablehook = sys.unraisablehook, unraisable.append
    try:
        with pytest.raises(ValueError, match="scene must be a refracta.Scene"):
            MirageEditor(None, road.camera, road.field)
        gc.collect()
    finally:
        sys.unraisablehook = hook
    assert not unraisable  # it printed AttributeError: 'MirageEditor' object has no attribute 'model'
