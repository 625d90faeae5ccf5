"""A Python library developer's audit of the public API: what it found. Objects that took an
assignment and kept their old behaviour, deprecation warnings a script never saw, and missing files
that `except FileNotFoundError` did not catch."""

import pickle
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest

import refracta
from refracta import geo


def test_a_turbulence_refuses_assignments_it_would_not_follow():
    # t.cn2 = 4e-10 changed the repr and the closed-form statistics (4x), the pattern stayed 1e-10.
    turbulence = refracta.Turbulence(cn2=1e-10, cells=16, seed=1)
    before = turbulence.evaluate([[0.1, 0.05, 0.2]])
    for name, value in [("cn2", 4e-10), ("seed", 99), ("wind", (5.0, 0.0)), ("layer", None), ("time", 1.0)]:
        with pytest.raises(AttributeError, match=f"Turbulence.{name} cannot be set"):
            setattr(turbulence, name, value)
    settings = turbulence.settings  # a copy: changing it changes nothing here
    settings.cn2 = 5e-10
    assert turbulence.cn2 == 1e-10 and turbulence.settings.cn2 == 1e-10
    np.testing.assert_array_equal(turbulence.evaluate([[0.1, 0.05, 0.2]])[0], before[0])
    # Still pickled, copied and moved as before.
    copied = pickle.loads(pickle.dumps(turbulence.at_time(0.5)))
    assert copied.time == 0.5 and copied.cn2 == 1e-10 and copied.generation_seconds == 0.0


def test_a_local_frame_refuses_a_new_origin():
    # f.lat = 45 changed the repr; to_scene kept projecting about 28 deg.
    frame = geo.LocalFrame(28.0, -15.0)
    for name in ("lat", "lon", "height", "earth_radius"):
        with pytest.raises(AttributeError, match=f"LocalFrame.{name} cannot be set"):
            setattr(frame, name, 1.0)
    assert frame.lat == 28.0 and pickle.loads(pickle.dumps(frame)).lon == -15.0


_OLD_SPELLINGS = """
import numpy as np, refracta
from refracta import edit
refracta.set_threads(1)
air = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.2)
refracta.trace_ray(air, (0, 1.5, 0), (1, -0.002, 0), method="rk45", max_length=50.0)
refracta.trace_rays(air, (0, 1.5, 0), [(1, -0.002, 0)], method="rk45", max_length=50.0)
pair = edit.PointPair((1.0, 1.498, 0.0), (50.0, 1.4, 0.0))
edit.distances(air, (0, 1.5, 0), [pair], ground=0.0)
edit.solve(air, (0, 1.5, 0), [pair], free=["surface_dt"], integrator="rk45", max_iterations=1)
"""


def test_deprecated_spellings_warn_at_the_user_s_line_so_a_script_shows_them():
    # Python's default filters show a DeprecationWarning only when it is attributed to __main__; three
    # were attributed to refracta's own wrappers, and a script printed nothing.
    done = subprocess.run([sys.executable, "-c", _OLD_SPELLINGS], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    warned = [line for line in done.stderr.splitlines() if "DeprecationWarning" in line]
    assert len(warned) == 4, done.stderr
    assert all(line.startswith("<string>:") for line in warned), done.stderr


def test_a_deprecation_from_inside_refracta_is_attributed_to_the_caller():
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        refracta.trace_ray(refracta.PhysicalAtmosphere(), (0, 1.5, 0), (1, 0, 0), method="rk45", max_length=10.0)
    assert [w.filename for w in caught if w.category is DeprecationWarning] == [__file__]


@pytest.mark.parametrize(
    "read",
    [
        lambda missing: refracta.Scene().add_obj(str(missing / "city.obj")),
        lambda missing: refracta.io.read_image(str(missing / "photo.png")),
        lambda missing: refracta.load_scene(str(missing / "scene.toml")),
        lambda missing: refracta.photo.load(str(missing / "coast.jpg")),
        lambda missing: refracta.Scene().set_environment(str(missing / "sky.exr")),
    ],
)
def test_a_missing_file_is_a_file_not_found_error(tmp_path, read):
    # Each was a refracta.IoError only (an OSError), which `except FileNotFoundError` missed.
    with pytest.raises(FileNotFoundError) as raised:
        read(tmp_path / "nowhere")
    assert isinstance(raised.value, refracta.IoError) and isinstance(raised.value, refracta.MissingFileError)
    assert "nowhere" in str(raised.value)


def test_an_unreadable_existing_file_stays_an_io_error_only(tmp_path):
    folder = tmp_path / "a_folder.png"
    folder.mkdir()
    with pytest.raises(refracta.IoError) as raised:
        refracta.io.read_image(str(folder))
    assert not isinstance(raised.value, FileNotFoundError)


def test_a_texture_not_found_is_still_each_of_its_kinds():
    assert issubclass(refracta.TextureNotFoundError, refracta.MissingFileError)
    assert issubclass(refracta.TextureNotFoundError, FileNotFoundError)
    assert issubclass(refracta.TextureNotFoundError, refracta.IoError)


def test_the_warning_helper_imports_alone():
    # The C++ side imports refracta._warn by name: it must work on its own.
    code = textwrap.dedent("""
        import refracta._warn as w
        import warnings
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            w.deprecated("x")
        print(caught[0].filename)
    """)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and done.stdout.strip() == "<string>", done.stderr
