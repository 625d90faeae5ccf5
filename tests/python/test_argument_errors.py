"""A refused argument of a bound function is named (refracta/_arguments.py): pybind11's generic
"incompatible function arguments" TypeError becomes an ArgumentError (a TypeError and a
ValueError) saying which argument and what it must be."""

import inspect
import pickle
import re

import numpy as np
import pytest

import refracta
from refracta import _arguments, _core

EYE, AHEAD = (0.0, 1.5, 0.0), (0.0, 1.5, 10.0)


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda: refracta.Camera(EYE, AHEAD, vfov="wide"), "Camera: vfov must be a number (got 'wide')"),
        (lambda: refracta.Camera(EYE, AHEAD, width=64.0), "Camera: width must be a whole number or None (got 64.0)"),
        (lambda: refracta.Camera(EYE), "Camera: missing argument 'look_at'"),
        (
            lambda: refracta.Camera(EYE, AHEAD, fov=30.0),
            "Camera: unknown argument 'fov' (arguments: position, look_at, up, vfov, width, height)",
        ),
        (
            lambda: refracta.Camera(EYE, AHEAD, (0, 1, 0), 30.0, 64, 32, 7),
            "Camera takes at most 6 arguments by position (got 7)",
        ),
        (lambda: refracta.HotSpot(0.0, 300.0, "big", 8.0), "HotSpot: radius must be a number (got 'big')"),
        (lambda: refracta.HotSpot(0.0, 300.0, 40.0, 8.0, footprint=2), "HotSpot: footprint must be a string (got 2)"),
        (lambda: refracta.HotSpot(0.0, 300.0, 40.0, 8.0, depth="deep"), "HotSpot: depth must be a number or None"),
        (
            lambda: refracta.Camera.photographic(EYE, AHEAD, 50.0, sensor_mm=36),
            "Camera.photographic: sensor_mm must be a pair of numbers (got 36)",
        ),
        (  # pybind11's tuple caster fails inside with "len() of unsized object"
            lambda: refracta.Camera.photographic_vfov(50.0, sensor_mm=np.array(36)),
            "Camera.photographic_vfov: sensor_mm must be a pair of numbers (got array(36))",
        ),
        (lambda: refracta.Scene().add_obj(3), "Scene.add_obj: path must be a path (str or os.PathLike) (got 3)"),
        (lambda: refracta.set_threads("two"), "set_threads: n must be a whole number or None (got 'two')"),
    ],
)
def test_a_refused_argument_is_named(call, message):
    with pytest.raises(refracta.ArgumentError, match=re.escape(message)) as caught:
        call()
    assert isinstance(caught.value, TypeError) and isinstance(caught.value, ValueError)
    assert "incompatible" not in str(caught.value)


def test_a_refracta_class_argument_names_the_class():
    scene = refracta.Scene()
    message = "Scene.add_light: light must be a refracta.Light (got 'sun')"
    with pytest.raises(refracta.ArgumentError, match=re.escape(message)):
        scene.add_light("sun")


def test_a_failed_constructor_leaves_no_unconstructed_self_in_the_traceback():
    # A traceback that shows its frames' locals (pytest's long tracebacks, IPython's verbose mode)
    # would take repr() of the `self` whose __init__ failed; pybind11 crashes on such an instance.
    import traceback

    for make in (lambda: refracta.PhysicalAtmosphere(t_ground="x"), lambda: refracta.HotSpot(1.0, 2.0, "r", 3.0)):
        with pytest.raises(ValueError) as caught:
            make()
        shown = "".join(traceback.TracebackException.from_exception(caught.value, capture_locals=True).format())
        assert "    args = " not in shown and "Unconstructed" not in shown  # the wrapper's frame: no arguments
        assert "refracta/_arguments.py" in shown  # (through the wrapper)


def test_good_calls_are_unchanged():
    camera = refracta.Camera(EYE, AHEAD, vfov=np.float32(30.0), width=np.int64(32), height=16)
    assert (camera.vfov, camera.width, camera.height) == (30.0, 32, 16)
    assert pickle.loads(pickle.dumps(camera)).vfov == 30.0  # pickling keeps pybind11's own methods
    spot = refracta.HotSpot(0.0, 300.0, 40.0, 8.0)
    assert spot == refracta.HotSpot(0.0, 300.0, 40.0, 8.0)


def test_an_error_raised_inside_a_call_is_not_rewritten():
    # A TypeError from the function's own work (here a CustomField's Python callback) is the
    # caller's to see as it is, not a diagnosis of the call's arguments.
    def index(points):
        raise TypeError("the callback's own error")

    field = refracta.CustomField(index, lambda points: np.zeros_like(points))
    with pytest.raises(TypeError, match="the callback's own error"):
        field.ior(np.array([[0.0, 1.0, 0.0]]))


def test_every_public_function_and_method_of_core_is_wrapped():
    # A stated property of install(): nothing public of the compiled module answers with pybind11's
    # bare message (dunders other than __init__ keep pybind11's own: pickling, operators).
    unwrapped = []
    for name, value in vars(_core).items():
        if name.startswith("__"):
            continue
        if isinstance(value, type):
            for member_name, member in vars(value).items():
                if member_name.startswith("_") and member_name != "__init__":
                    continue
                target = member.__func__ if isinstance(member, staticmethod) else member
                if type(target).__name__ in ("instancemethod", "builtin_function_or_method"):
                    unwrapped.append(f"{name}.{member_name}")
        elif type(value).__name__ == "builtin_function_or_method":
            unwrapped.append(name)
    assert unwrapped == []
    assert inspect.isfunction(refracta.trace_ray) and refracta.trace_ray.__qualname__ == "trace_ray"


@pytest.mark.parametrize(
    ("params", "args", "kwargs", "expected"),
    [
        ("self: X, a: typing.SupportsFloat | typing.SupportsIndex, b: str = 'x'", (1.0,), {"b": 2}, "b must be a str"),
        ("a: typing.SupportsInt | typing.SupportsIndex, *, b: bool = False", (), {"a": 1.5}, "a must be a whole"),
        ("a: typing.SupportsInt | typing.SupportsIndex, *, b: bool = False", (1, True), {}, "at most 1 arguments"),
        ("a: tuple[float, float] = (0.0, 1.0), b: bool = False", (), {"b": "no"}, "f: b must be True or False"),
        ("a: object, b: collections.abc.Sequence[float]", ("x", "y"), {}, None),  # the C++ names those
        ("*args, **kwargs", (1,), {}, None),
    ],
)
def test_the_diagnosis_reads_the_signature_pybind11_prints(params, args, kwargs, expected):
    header = "f(): incompatible function arguments. The following argument types are supported:"
    message = f"{header}\n    1. ({params}) -> None\n"
    found = _arguments.diagnose("f", message, args, kwargs)
    assert found == expected if expected is None else expected in found


def test_only_a_sure_refusal_is_blamed():
    # pybind11 takes __float__ objects for a float and any sequence for a tuple: the wrapper must not
    # blame those, but the argument it surely refuses (a review: Decimal(50) was named, not width='x').
    from decimal import Decimal

    with pytest.raises(refracta.ArgumentError, match="photographic_vfov: width must be a whole number"):
        refracta.Camera.photographic_vfov(Decimal(50), width="x")
    assert refracta.Camera.photographic_vfov(Decimal(50), sensor_mm=range(24, 48, 12)) > 0  # (24, 36)
    with pytest.raises(refracta.ArgumentError, match=r"takes at most 4 arguments by position \(got 5\)$"):
        refracta.Camera.photographic_vfov(50, 1, 2, 3, 4)  # no keyword-only marker: no "pass the rest by name"


def test_module_functions_keep_their_names_for_pickling():
    import pickle

    assert pickle.loads(pickle.dumps(_core._build_options)) is _core._build_options
    assert pickle.loads(pickle.dumps(refracta.trace_ray)) is refracta.trace_ray
