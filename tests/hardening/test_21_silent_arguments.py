"""Arguments that were accepted and then ignored (a new-user trial): each is now either used or
refused by name, and the defaults they stood beside are unchanged."""

import json

import numpy as np
import pytest

import refracta
from refracta import edit, io, shading

BK7 = (1.03961212, 0.231792344, 1.01046945, 0.00600069867, 0.0200179144, 103.560653)  # Schott N-BK7


@pytest.mark.parametrize(
    "add",
    [
        lambda s: s.add_box((0, 0, 0), (1, 1, 1), material=shading.Diffuse(0.5), kd=(1, 0, 0)),
        lambda s: s.add_box((0, 0, 0), (1, 1, 1), material=shading.Diffuse(0.5), alpha=0.5),
        lambda s: s.add_sphere((0, 0, 0), 1.0, material=shading.Diffuse(0.5), ns=20.0),
        lambda s: s.add_ground(material=shading.Diffuse(0.5), kd=0.2),
        lambda s: s.add_mesh([[0, 0, 0], [1, 0, 0], [0, 0, 1]], [[0, 1, 2]], material=shading.Diffuse(0.5), ks=0.1),
    ],
)
def test_a_material_and_the_shorthand_together_are_refused(add):
    with pytest.raises(ValueError, match="give `material` or the kd/ks/ns/alpha/texture shorthand, not both"):
        add(refracta.Scene())


def test_the_shorthand_keeps_its_defaults_and_its_values():
    scene = refracta.Scene()
    box = scene.add_box((0, 0, 0), (1, 1, 1))
    ground = scene.add_ground()
    sphere = scene.add_sphere((0, 3, 0), 1.0, kd=0.2, ks=0.1, ns=30.0)
    assert str(scene.material(box)) == "BlinnPhong(kd=(0.5, 0.5, 0.5), ks=(0, 0, 0), ns=1)"
    assert str(scene.material(ground)) == "BlinnPhong(kd=(0.3, 0.3, 0.3), ks=(0, 0, 0), ns=1)"
    assert str(scene.material(sphere)) == "BlinnPhong(kd=(0.2, 0.2, 0.2), ks=(0.1, 0.1, 0.1), ns=30)"
    with pytest.raises(ValueError, match="alpha must be a number"):
        scene.add_box((0, 0, 0), (1, 1, 1), alpha="half")


def test_a_dielectric_takes_ior_or_sellmeier_not_both():
    with pytest.raises(ValueError, match="give ior or sellmeier, not both"):
        shading.Dielectric(ior=1.5, sellmeier=BK7)
    with pytest.raises(ValueError, match="sellmeier must be six numbers .* ior='bk7'"):
        shading.RoughDielectric(0.1, sellmeier="BK7")
    with pytest.raises(ValueError, match="ior must be a number"):
        shading.ThinDielectric(ior=True)
    assert str(shading.Dielectric()) == "Dielectric(ior=1.5)"  # the default, written once in C++
    assert str(shading.Dielectric(sellmeier=BK7)) == str(shading.Dielectric(ior="bk7"))


def test_reinhards_white_is_refused_with_another_tone_curve():
    image = np.full((2, 2, 3), 0.5, np.float32)
    with pytest.raises(ValueError, match="white .* applies to tonemap='reinhard' only"):
        io.to_display(image, white=2.0)  # the default curve is ACES
    shown = dict(tonemap="reinhard", exposure=1.0, gamma="linear")
    # Reinhard's eq. 4, L (1 + L / W^2) / (1 + L), at L = 0.5, W = 1: 0.5; eq. 3 (no white): 1/3.
    np.testing.assert_allclose(io.to_display(image, white=1.0, **shown), 0.5, rtol=1e-6)  # float32 output
    np.testing.assert_allclose(io.to_display(image, **shown), 1.0 / 3.0, rtol=1e-6)  # float32 output


def _glass_scene():
    scene = refracta.Scene()
    scene.add_ground()
    scene.add_box((0, 1, 0), (1, 1, 1), alpha=0.5)
    scene.add_box((0, 1, 3), (2, 2, 1), kd=(0.9, 0.1, 0.1), alpha=0.5)  # a second layer: weights matter
    scene.set_sun((0.3, 1.0, -0.2), 2e4)  # lit brightly enough that the layers' colours show
    scene.set_sky((0.5, 0.6, 0.8), (0.2, 0.3, 0.7))
    return scene


@pytest.mark.parametrize(
    "keywords, named",
    [
        (dict(transparency="mboit", weight="eq9"), "weight applies to transparency='wboit', not with .*'mboit'"),
        (dict(transparency="wboit", moments=6), "moments applies to transparency='mboit'"),
        (dict(transparency="exact", layers=2), "layers applies to transparency='peel', not with transparency='exact'"),
        (dict(layers=2), r"layers= sets transparency.layers, but transparency is None"),
    ],
)
def test_render_raster_refuses_a_transparency_setting_its_method_does_not_use(keywords, named):
    camera = refracta.Camera((0, 1, -5), (0, 1, 0), width=16, height=8)
    with pytest.raises(ValueError, match=named):
        refracta.render_raster(_glass_scene(), camera, shadows="embree", **keywords)


def test_render_raster_uses_the_settings_of_its_method():
    camera = refracta.Camera((0, 1, -5), (0, 1, 0), width=16, height=8)
    eq7 = refracta.render_raster(_glass_scene(), camera, shadows="embree", transparency="wboit", weight="eq7")
    eq9 = refracta.render_raster(_glass_scene(), camera, shadows="embree", transparency="wboit", weight="eq9")
    assert eq7.shape == eq9.shape == (8, 16, 3) and np.all(np.isfinite(eq9))
    assert not np.array_equal(eq7, eq9)  # McGuire & Bavoil's two depth weights composite the glass apart


def test_a_pairs_file_with_an_unknown_key_is_refused_naming_it(tmp_path):
    path = tmp_path / "pairs.json"
    pair = {"destination": [0.0, 1.0, 100.0], "source": [0.0, 0.5, 100.0]}
    path.write_text(json.dumps({"pairs": [pair], "free": ["surface_dt"], "max_iteratoins": 5}))
    with pytest.raises(ValueError, match=r"pairs.json: unknown key 'max_iteratoins' \(besides 'pairs'.*max_iterations"):
        edit.load_pairs(path)
    path.write_text(json.dumps({"pairs": [pair], "free": ["surface_dt"], "max_iterations": 5, "tol": 1e-6}))
    pairs, options = edit.load_pairs(path)
    assert len(pairs) == 1 and options == {"free": ["surface_dt"], "max_iterations": 5, "tol": 1e-6}


def test_framing_shows_the_objects_on_a_wide_ground():
    scene = refracta.Scene()
    scene.add_ground(size=20000.0)
    scene.add_box((10, 1, 20), (2, 2, 2))
    camera = refracta.Camera.framing(scene, width=64, height=48)
    assert str(camera) == str(refracta.Camera.framing(((9, 0, 19), (11, 2, 21)), width=64, height=48))
    # The box's centre is the image's (framing aims there); its nearest corner is a few metres off.
    assert np.linalg.norm(camera.position - np.array([10.0, 1.0, 20.0])) < 10.0
    ground_only = refracta.Scene()
    ground_only.add_ground(size=100.0)  # nothing else: the ground is what there is to frame
    assert np.linalg.norm(refracta.Camera.framing(ground_only).position) > 50.0


def _spot_scene(angle):
    scene = refracta.Scene()
    scene.add_ground()
    scene.add_spot_light((0, 3, 0), (0, -1, 0), angle=angle, intensity=50.0)
    return scene


def test_a_spot_light_wider_than_a_shadow_map_is_refused_only_by_shadow_maps():
    with pytest.raises(ValueError, match="spot light 0 is 200 deg wide: a shadow map covers at most 170 deg"):
        refracta.render_raster(_spot_scene(200.0), refracta.Camera((0, 2, -6), (0, 0, 0), width=16, height=8))
    # Ground 30 m from the foot of a light 3 m up is 84 deg off its axis: inside a 200-deg cone (100
    # deg each side), outside a 160-deg one.
    far = refracta.Camera((30, 2, -4), (30, 0, 0), width=16, height=8)
    for renderer in (lambda s: refracta.render_raster(s, far, shadows="embree"), lambda s: refracta.render(s, far)):
        assert renderer(_spot_scene(200.0)).mean() > 0.0 and renderer(_spot_scene(160.0)).mean() == 0.0
