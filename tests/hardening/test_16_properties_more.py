"""Property-based tests over the surfaces test_12/test_13 do not reach: lights and their sampling,
the physical sky, materials with textures, a scene changed while it renders, the editor's model and
the CLI given special files. Every call returns finite results or raises one of refracta's named
errors; and each suite asserts that a share of its examples really ran (not all rejected), so it
cannot pass vacuously."""

import os
import subprocess
import sys
import threading

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import refracta
from refracta import lights, shading
from tests.hardening.properties import FAST, NAMED_ERRORS, calls, edge, finite, ordinary, ordinary_vec3, vec3

# Below this share of examples that ran to a result (not a named error), the strategies are
# exploring nothing but rejections: the properties would hold vacuously.
MIN_ACCEPTED = 0.2
# Each sky builds its radiance table (~0.3 s): fewer examples than FAST's 50.
SKY = settings(FAST, max_examples=12)


def mostly(valid, other):
    """`valid` four times in five, else `other` (the edges): most examples reach the code."""
    return st.integers(0, 4).flatmap(lambda k: other if k == 0 else valid)


unit = (
    st.tuples(*[st.floats(-1, 1)] * 3)
    .filter(lambda v: np.linalg.norm(v) > 1e-3)
    .map(lambda v: tuple(np.asarray(v) / np.linalg.norm(v)))
)
unit_interval = st.floats(0.0, 1.0, exclude_max=True)
# Mostly valid arguments, the edges one time in five: with `anything` everywhere most lights were
# refused, and whether MIN_ACCEPTED of them ran depended on the derandomized seed (the test's
# source text: reformatting it once left 1 of 50 running).
radiance = mostly(st.one_of(st.floats(0.0, 1e4), st.tuples(*[st.floats(0.0, 1e4)] * 3)), edge)
direction = mostly(ordinary_vec3.filter(lambda v: np.linalg.norm(v) > 1e-3), vec3)


def check_light_sampling(light, points, normals, u) -> bool:
    sample = calls(light.sample_li, points, normals, u)
    if sample is None:
        return False
    wi, L, pdf, distance = sample
    assert finite(wi) and finite(L) and np.all(L >= 0) and finite(pdf) and np.all(pdf >= 0)
    reached = pdf > 0
    assert np.allclose(np.linalg.norm(wi[reached], axis=1), 1.0, atol=1e-9)  # unit vectors in double: rounding
    assert np.all(distance[reached] > 0)
    return True


light_kinds = st.sampled_from(["point", "spot", "sun"])


@st.composite
def any_light(draw):
    kind = draw(light_kinds)
    position = draw(st.tuples(ordinary, ordinary, ordinary))
    if kind == "point":
        return calls(lights.PointLight, position, draw(radiance))
    if kind == "spot":
        return calls(
            lights.SpotLight, position, draw(direction), draw(mostly(st.floats(1.0, 179.0), edge)), draw(radiance)
        )
    return calls(lights.SunLight, draw(direction), draw(radiance), draw(mostly(st.floats(0.01, 10.0), edge)))


def test_lights_sample_unit_directions_and_finite_radiance_or_raise():
    outcomes = []

    @FAST
    @given(
        any_light(),
        st.lists(st.tuples(ordinary, ordinary, ordinary), min_size=1, max_size=3),
        st.lists(st.tuples(unit_interval, unit_interval), min_size=1, max_size=3),
    )
    def prop(light, points, u):
        if light is None:
            outcomes.append(False)
            return
        n = min(len(points), len(u))
        outcomes.append(check_light_sampling(light, np.array(points[:n]), None, np.array(u[:n])))

    prop()
    assert sum(outcomes) >= MIN_ACCEPTED * len(outcomes), f"{sum(outcomes)} of {len(outcomes)} ran"


def test_the_physical_sky_is_finite_for_any_sun_or_raises():
    outcomes = []

    @SKY
    @given(
        mostly(st.tuples(st.floats(-1, 1), st.floats(0.05, 1), st.floats(-1, 1)), vec3),
        mostly(st.floats(0.0, 10.0), edge),
        mostly(st.floats(0.0, 600.0), edge),
        st.lists(st.tuples(unit_interval, unit_interval), min_size=1, max_size=4),
        st.one_of(st.floats(360.0, 830.0), edge),
    )
    def prop(sun, aerosol, ozone, u, wavelength):
        scene = refracta.Scene()
        if calls(scene.set_physical_sky, sun, aerosol=aerosol, ozone_du=ozone) is None and not scene.lights:
            outcomes.append(False)
            return
        sky = next(light for light in scene.lights if hasattr(light, "optical_depth"))
        depth = calls(sky.optical_depth, wavelength)
        if depth is not None:
            assert finite(depth) and depth >= 0
        dirs, pdf, rgb = sky.sample_li(np.array(u))
        assert finite(dirs) and finite(pdf) and np.all(pdf >= 0) and finite(rgb) and np.all(rgb >= 0)
        sampled = pdf > 0
        assert np.allclose(np.linalg.norm(dirs[sampled], axis=1), 1.0, atol=1e-9)  # unit vectors in double: rounding
        outcomes.append(True)

    prop()
    assert sum(outcomes) >= MIN_ACCEPTED * len(outcomes), f"{sum(outcomes)} of {len(outcomes)} ran"


def test_textured_materials_shade_finite_or_raise(tmp_path_factory):
    texture = tmp_path_factory.mktemp("tex") / "albedo.png"
    refracta.io.write_image(str(texture), np.random.default_rng(1).random((8, 8, 3)).astype(np.float32))
    outcomes = []

    @FAST
    @given(
        st.sampled_from(["Diffuse", "BlinnPhong", "Principled"]),
        mostly(st.floats(0.0, 1.0), edge),
        # Mostly the real texture: the bad paths raise, and at least MIN_ACCEPTED of the examples
        # must reach f (with half the paths bad that held only by luck: 9 of 50 ran once).
        st.sampled_from([str(texture)] * 6 + [str(texture) + ".missing", ""]),
        mostly(unit, vec3),
        mostly(unit, vec3),
    )
    def prop(name, value, path, wo, wi):
        material = calls(getattr(shading, name), value, texture=path)
        if material is None:
            outcomes.append(False)
            return
        value_f = calls(material.f, wo, wi)
        if value_f is not None:
            assert finite(value_f) and np.all(np.asarray(value_f) >= 0)
        outcomes.append(value_f is not None)

    prop()
    assert sum(outcomes) >= MIN_ACCEPTED * len(outcomes), f"{sum(outcomes)} of {len(outcomes)} ran"


def test_changes_during_a_render_raise_and_never_corrupt_the_scene():
    # One render of a small scene on a worker thread; the property's changes race it. Each change
    # either lands (the render had finished) or raises RuntimeError naming the running render.
    scene = refracta.Scene()
    scene.add_ground(0.0, 200.0)
    scene.set_sky((0.5, 0.6, 0.9))
    camera = refracta.Camera((0, 1.5, 0), (50, 1.0, 0), width=32, height=16)
    outcomes = []

    @FAST
    @given(st.lists(st.sampled_from(["light", "sphere", "sky", "sun", "material"]), min_size=1, max_size=4))
    def prop(changes):
        errors = []
        worker = threading.Thread(
            target=lambda: refracta.render(
                scene, camera, refracta.PhysicalAtmosphere(), transport="path", spp=2, progress=False
            )
        )
        worker.start()
        for change in changes:
            try:
                if change == "light":
                    scene.add_point_light((5, 2, 0), (1, 1, 1))
                elif change == "sphere":
                    scene.add_sphere((30, 1, 0), 0.5)
                elif change == "sky":
                    scene.set_sky((0.4, 0.5, 0.8))
                elif change == "sun":
                    scene.set_sun((1, 1, 0), (10.0, 10.0, 10.0))
                else:
                    scene.add_box((20, 0.5, 2), (1, 1, 1), material=shading.Diffuse(0.5))
            except RuntimeError as error:
                assert "being rendered" in str(error)
                errors.append(error)
        worker.join()
        image = refracta.render(scene, camera, refracta.PhysicalAtmosphere(), progress=False)
        assert finite(image)
        outcomes.append(True)

    prop()
    assert outcomes


def test_the_editor_model_takes_any_click_or_says_why():
    from refracta.widgets.model import EditorModel

    road = refracta.examples.hot_road(32, 12)
    model = EditorModel(road.scene, road.camera, road.field, free=["surface_dt"], autorender=False)
    outcomes = []

    @FAST
    @given(
        st.lists(
            st.tuples(st.one_of(st.floats(-50, 80), edge), st.one_of(st.floats(-50, 60), edge)), min_size=1, max_size=4
        )
    )
    def prop(clicks):
        for u, v in clicks:
            try:
                model.click(u, v)
                outcomes.append(True)
            except NAMED_ERRORS:
                outcomes.append(False)
            assert isinstance(model.message, str)
        assert all(finite(np.asarray(p.destination, dtype=float)) for p in model.pairs)

    prop()
    assert sum(outcomes) >= MIN_ACCEPTED * len(outcomes), f"{sum(outcomes)} of {len(outcomes)} ran"


def test_the_cli_refuses_special_files_quickly(tmp_path):
    # A FIFO as the pairs file hung `refracta edit --pairs` for 20 s (it waited for a writer).
    fifo = tmp_path / "pairs.json"
    os.mkfifo(fifo)
    scene = tmp_path / "scene.toml"
    scene.write_text('[camera]\nposition = [0, 1.5, 0]\nlook_at = [100, 1.5, 0]\n[atmosphere]\nmodel = "physical"\n')
    for args in (["edit", str(scene), "--pairs", str(fifo)], ["render", str(fifo)], ["edit", "/dev/zero"]):
        # A hang is what this guards against; 60 s is far above the ~1 s start-up of the CLI.
        child = subprocess.run(
            [sys.executable, "-m", "refracta", *args],
            capture_output=True,
            text=True,
            timeout=60,
            stdin=subprocess.DEVNULL,
        )
        assert child.returncode != 0, args
        assert "Traceback" not in child.stderr, child.stderr[-1500:]
