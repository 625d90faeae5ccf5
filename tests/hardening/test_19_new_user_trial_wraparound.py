"""Bad input a second new-user trial (4 December) found accepted silently (integer wraparound, float
indices truncated, a curved Earth flattened twice) or refused with a misleading message: each now
raises ValueError naming the argument and its value."""

import numpy as np
import pytest

import refracta
from refracta import examples, shading


def tiny_camera():
    return refracta.Camera((0, 1, 0), (1, 1, 0), width=4, height=4)


def render_tiny(**options):
    return refracta.render(sky_scene(), tiny_camera(), None, **{"progress": False, **options})


def short_path():
    return refracta.trace_ray(refracta.PhysicalAtmosphere(), (0.0, 1.5, 0.0), (1.0, 0.0, 0.0), max_length=100.0)


def sky_scene():
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    return scene


@pytest.mark.parametrize(
    "make, message",
    [
        # 2**32 + 16 cells wrapped to a 16^3 grid in the int the grid is indexed by.
        (
            lambda: refracta.Turbulence(1e-10, cells=2**32 + 16, spacing=0.1),
            r"cells must be a whole number in \[8, 65536\] \(got 4294967312\)",
        ),
        (
            lambda: refracta.Turbulence(1e-10, size=1e9, spacing=0.1),
            r"size / spacing must be at most 65536 cells \(got size=1000000000, spacing=0.1\)",
        ),
        # The byte count printed through an int64_t wrapped negative (a 1e9 x 1e9 camera, before
        # cameras stopped at 2**24 pixels a side); printed whole, as doubles.
        (
            lambda: refracta.render(
                sky_scene(), refracta.Camera((0, 1, 0), (1, 1, 0), width=10**7, height=10**7), None
            ),
            r"needs at least 2400000000000000 bytes \(2400000 GB\)",
        ),
        # Float indices were truncated: 1.7 made vertex 1.
        (
            lambda: refracta.Scene().add_mesh(np.eye(3), np.array([[0.0, 1.7, 2.0]])),
            r"triangles must hold whole vertex indices \(got 1.7\)",
        ),
        (lambda: examples.sun_direction(float("nan"), 0.0), r"elevation must be in \[-90, 90\] deg \(got nan\)"),
        (lambda: examples.sun_direction(100.0, 0.0), r"elevation must be in \[-90, 90\] deg \(got 100"),
        (lambda: examples.sun_direction(10.0, float("inf")), r"azimuth must be finite \(got inf\)"),
        # The Earth's curvature applied twice.
        (
            lambda: refracta.CurvedEarth(refracta.CurvedEarth(refracta.PhysicalAtmosphere())),
            r"CurvedEarth: the base field is already over a curved Earth",
        ),
        # The refusal named an OceanWaves the caller never made.
        (
            lambda: refracta.Scene().add_sea(material=shading.Water(wind_speed=0.0)),
            r"add_sea: the Water material's wind_speed is 0 m/s: calm water has no waves",
        ),
        # A thin lens cannot focus nearer than its focal length.
        (
            lambda: refracta.Camera.photographic((0, 1, 0), (1, 1, 0), 50.0, f_number=2.0, focus_distance=0.02),
            r"focus_distance must exceed the focal length \(0.05 m\) \(got 0.02\)",
        ),
        # RenderOptions.march is parsed as a trace method; its error said 'trace'.
        (lambda: setattr(refracta.RenderOptions(), "march", "foo"), r"^march must be"),
        # Whole numbers an integer field cannot hold: pybind11's TypeError named neither field nor value.
        (lambda: render_tiny(spp=2**31), r"render: spp=2147483648 is out of the range of RenderOptions.spp"),
        (lambda: render_tiny(seed=-1), r"render: seed=-1 is out of the range of RenderOptions.seed"),
        (lambda: render_tiny(seed=2**70), r"seed=1180591620717411303424 is out of the range"),
        (lambda: render_tiny(spp=2.5), r"render: spp must be a whole number \(got 2.5\)"),
        # A string reached C++ and failed there as "'str' object is not callable".
        (lambda: render_tiny(progress="x"), r"progress must be True, False or a callable"),
        # A misspelt keyword was refused in trace_ray's name with trace_ray's option list.
        (
            lambda: refracta.refraction_coefficient(refracta.PhysicalAtmosphere(), 2.0, 1000.0, target_hieght=3),
            r"refraction_coefficient: unknown option 'target_hieght' \(its keywords: target_height",
        ),
        # Radiances past float32's range filled every pixel with inf.
        (
            lambda: refracta.Scene().set_sky((1.0, 1.0, 1.0), scale=1e300),
            r"set_sky: the sky's radiance times scale must be at most 1e\+30",
        ),
        (lambda: refracta.Scene().set_sun((0, 1, 0), (3e38,) * 3), r"radiance must be at most 1e\+30 per channel"),
        (
            lambda: refracta.Scene().add_sphere((0, 0, 0), 1.0, emission=(3e38,) * 3),
            r"emission must be at most 1e\+30 per channel",
        ),
        # py::vectorize's RuntimeError named no argument.
        (
            lambda: shading.water_ior([400.0, 500.0, 600.0], [10.0, 20.0]),
            r"must broadcast together as numpy arrays do \(got wavelength_nm \(3,\), temperature_c \(2,\)",
        ),
        (lambda: short_path().at_height(float("nan")), r"at_height: y must be a finite height \[m\] \(got nan\)"),
        # 2**31 - 1 points asked the allocator for 51 GB.
        (lambda: short_path().sample(2**31 - 1), r"sample: count=2147483647 points need .* GB .*, more than half"),
        (
            lambda: refracta.animate(
                sky_scene(), tiny_camera(), refracta.PhysicalAtmosphere(), [0.0, float("nan")], noise=dict(rms=1e-3)
            ),
            r"animate: times must be finite seconds \(got times\[1\] = nan\)",
        ),
    ],
)
def test_refused_with_a_message_naming_the_argument(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_whole_float_indices_still_make_a_mesh():
    # np.array([[0.0, 1.0, 2.0]]) is a triangle: only fractional indices are refused.
    scene = refracta.Scene()
    assert scene.add_mesh(np.eye(3), np.array([[0.0, 1.0, 2.0]])) == 0
    assert scene.add_mesh(np.eye(3), [[0, 1, 2]]) == 1
    assert scene.geometry_count == 2


def test_a_folder_is_not_a_scene_file(tmp_path):
    # It was "no such scene file", of a folder that is there.
    with pytest.raises(refracta.IoError, match=r"cannot read scene file '.*': not a regular file"):
        refracta.load_scene(tmp_path)


def test_a_binary_file_is_not_a_scene_file(tmp_path):
    # Bytes that are not UTF-8 raised a raw UnicodeDecodeError.
    path = tmp_path / "scene.toml"
    path.write_bytes(b"\xff\xfe\x00 not text")
    with pytest.raises(ValueError, match=r"scene.toml: not a TOML scene file \(not UTF-8 text"):
        refracta.load_scene(path)


def test_reprs_say_what_the_objects_hold():
    # Two cameras looking different ways printed alike; the options classes and Scene printed
    # '<... object at 0x...>'.
    east, north = refracta.Camera((0, 1, 0), (1, 1, 0)), refracta.Camera((0, 1, 0), (0, 1, 1))
    assert repr(east) != repr(north) and "look_at=(1, 1, 0)" in repr(east) and "up=(0, 1, 0)" in repr(east)
    assert repr(refracta.RenderOptions()).startswith("RenderOptions(adaptive=False, chord=1000.0,")
    assert "backend='ceres'" in repr(refracta._core.SolveSettings())
    assert "distance='continuous'" in repr(refracta._core.PairOptions())
    scene = sky_scene()
    scene.add_ground(0.0, 10.0)
    assert repr(scene) == "Scene(geometry_count=1, lights=1, aerial_perspective=False)"
