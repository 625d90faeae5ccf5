"""Two trials: a technical artist importing assets (OBJ/MTL, textures, models in UTM coordinates)
and a numerical analyst auditing the integrators. What they found."""

import warnings

import numpy as np
import pytest

import refracta
from refracta import compare


def _plate_over_ground(x0, height):
    scene = refracta.Scene()
    ground = np.array([[x0 - 1, 0, -1], [x0 - 1, 0, 1], [x0 + 1, 0, 1], [x0 + 1, 0, -1]], float)
    plate = np.array(
        [[x0 - 0.5, height, -0.5], [x0 - 0.5, height, 0.5], [x0 + 0.5, height, 0.5], [x0 + 0.5, height, -0.5]]
    )
    scene.add_mesh(ground, np.array([[0, 1, 2], [0, 2, 3]]))
    scene.add_mesh(plate, np.array([[0, 1, 2], [0, 2, 3]]))
    scene.set_sun((0.0, 1.0, 0.0), 1e4)
    return scene


@pytest.mark.parametrize("x0", [0.0, 3e5, 1e6])
def test_a_plate_a_metre_up_shadows_the_ground_far_from_the_origin(x0):
    # Shadow rays started 2e-6 of the largest coordinate off the surface: 2 m at 1000 km (UTM), and
    # a plate 1 m up cast nothing. Now |n| . the float error per axis (pbrt-v4): a level ground is
    # exact in float across it, and its offset is 1e-5 m wherever it lies.
    scene = _plate_over_ground(x0, 1.0)
    camera = refracta.Camera((x0 - 4.0, 0.5, 0.0), (x0, 0.0, 0.0), vfov=40, width=32, height=32)
    image, aovs = refracta.render(scene, camera, None, progress=False, aovs=["object_id", "position"])
    p = aovs["position"]
    ground = aovs["object_id"] == 0
    under = ground & (np.abs(p[..., 0] - x0) < 0.4) & (np.abs(p[..., 2]) < 0.4)
    lit = ground & (np.abs(p[..., 0] - x0) > 0.6)
    assert under.any() and lit.any()
    # The sun overhead, the plate over those points: no direct light at all (the sky is black).
    assert image[under].max() == 0.0 and image[lit].min() > 0.0


@pytest.mark.parametrize("half, slope", [(3e4, 0.3), (1e5, 0.05)])
def test_a_large_tilted_triangle_does_not_shadow_itself(half, slope):
    # A review: offset by 5e-7 of the point's own coordinates (1000 m here), a quad 60 km wide met
    # its own shadow rays (182 and 10 black pixels of 2304): Embree rounds its vertices, 3e4 m out,
    # to float. The offset now follows the primitive's coordinates across it (Hit::extent).
    scene = refracta.Scene()
    corners = [[-half, -slope * half, -half], [half, slope * half, -half], [half, slope * half, half]]
    scene.add_mesh(np.array(corners + [[-half, -slope * half, half]], float), np.array([[0, 2, 1], [0, 3, 2]]))
    elevation = np.radians(73.0)
    scene.set_sun((np.cos(elevation), np.sin(elevation), 0.0), 1e4)
    target = np.array([1000.0, slope * 1000.0, 0.0])
    camera = refracta.Camera(tuple(target + [-30.0, 40.0, 30.0]), tuple(target), (0, 1, 0), 30, 48, 48)
    image, aovs = refracta.render(scene, camera, None, progress=False, aovs=["object_id"])
    on_quad = aovs["object_id"] == 0
    assert on_quad.all()  # the sun lights the whole quad's front: no pixel may be black
    assert np.count_nonzero(image.max(axis=2)[on_quad] == 0.0) == 0


def _write(path, text):
    path.write_text(text, encoding="utf-8", newline="")
    return str(path)


def test_obj_coordinates_keep_double_precision_for_the_offset(tmp_path):
    # Read as floats, 500000.30 became 500000.3125 before offset= could bring it near the origin.
    obj = _write(
        tmp_path / "utm.obj", "v 500000.30 0 5000000.30\nv 500010.30 0 5000000.30\nv 500010.30 0 4999990.30\nf 1 2 3\n"
    )
    scene = refracta.Scene()
    scene.add_obj(obj, offset=(-5e5, 0.0, -5e6))
    lower, upper = scene.bounds
    # Double parsing and a subtraction: round-off of 5e6 (1e-9 m), far below float's 0.5 m steps.
    np.testing.assert_allclose(lower, [0.3, 0.0, -9.7], atol=1e-8)
    np.testing.assert_allclose(upper, [10.3, 0.0, 0.3], atol=1e-8)  # as above


def test_a_byte_order_mark_does_not_drop_the_first_vertex(tmp_path):
    obj = _write(tmp_path / "bom.obj", "\ufeffv 0 0 0\nv 1 0 0\nv 1 1 0\nv 5 5 5\nf 1 2 3\n")
    scene = refracta.Scene()
    scene.add_obj(obj)
    lower, upper = scene.bounds
    assert list(lower) == [0.0, 0.0, 0.0] and list(upper) == [1.0, 1.0, 0.0]


def test_one_mtllib_line_may_name_several_libraries(tmp_path):
    _write(tmp_path / "a1.mtl", "\ufeffnewmtl m1\nKd 1 0 0\n")
    _write(tmp_path / "a2.mtl", "newmtl m2\nKd 0 1 0\n")
    obj = _write(
        tmp_path / "two.obj",
        "mtllib a1.mtl a2.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl m1\nf 1 2 3\nusemtl m2\nf 1 3 4\n",
    )
    scene = refracta.Scene()
    materials = [repr(scene.material(geometry)) for geometry in scene.add_obj(obj)]
    assert len(materials) == 2 and materials[0] != materials[1], materials


def test_mtl_maps_refracta_does_not_render_are_named_not_dropped(tmp_path):
    refracta.io.write_image(str(tmp_path / "mask.png"), np.ones((4, 4, 3), np.float32))
    _write(tmp_path / "leaf.mtl", "newmtl leaf\nKd 0.5 0.5 0.5\nmap_Kd mask.png\nmap_d mask.png\nmap_Bump mask.png\n")
    obj = _write(tmp_path / "leaf.obj", "mtllib leaf.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl leaf\nf 1 2 3\n")
    with pytest.warns(UserWarning) as caught:
        refracta.Scene().add_obj(obj)
    message = " ".join(str(w.message) for w in caught)
    for named in ("map_Kd on faces without texture coordinates", "map_d", "bump, normal or displacement maps"):
        assert named in message


def test_rk4_ends_exactly_at_max_length_within_max_steps():
    # Summed 0.1 m steps fell short of 100 m by round-off (99.9999999999986), and the sliver step
    # that followed overran a max_steps of exactly max_length / step.
    road = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
    for step, length in [(0.1, 100.0), (0.3, 2000.0)]:
        steps = int(round(length / step))
        path = refracta.trace_ray(
            road, [0, 1.5, 0], [1, -0.001, 0], trace="rk4", step=step, max_length=length, max_steps=steps
        )
        assert path.stop == "max_length" and path.length == length and len(path.points) == steps + 1


def test_set_sky_given_a_file_says_where_a_map_goes():
    with pytest.raises(ValueError, match="give an environment map file as environment="):
        refracta.Scene().set_sky("/tmp/nowhere/env.exr")


def test_the_last_classes_without_a_repr_have_one():
    turbulence = refracta.Turbulence(cn2=1e-10, cells=16, seed=1)
    sky = refracta.spectrum.PhysicalSky(sun_direction=(0.0, 0.6, 0.8))
    shown = [
        repr(refracta.shading.Beckmann(0.25)),
        repr(turbulence.grid),
        repr(turbulence.layer),
        repr(refracta.spectrum.AerialPerspective(sky)),
    ]
    assert shown[0] == "Beckmann(alpha=0.25)"
    assert all(" object at 0x" not in text for text in shown), shown


def test_option_fields_state_their_defaults_in_help():
    assert refracta.RenderOptions.spp.__doc__.endswith("(default: 1)")
    assert refracta.TraceOptions.tol.__doc__.endswith("(default: 1e-06)")
    assert refracta.RenderOptions().spp == 1  # the field itself unchanged


def test_a_transparency_comparison_with_nothing_transparent_says_nan_for_every_row():
    scene = refracta.Scene()
    scene.add_ground(0.0, 20.0)
    scene.add_box((0.0, 0.0, -3.0), (1.0, 1.0, 1.0))
    scene.set_sun((0.3, 0.8, 0.2), 1.0)
    camera = refracta.Camera((0, 2, 4), (0, 0, -3), (0, 1, 0), 50, 32, 24)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # whatever the comparison notes about an opaque scene
        rows, _ = compare.transparency(scene, camera, figure=False)
    assert all(row["pixels"] == 0 and np.isnan(row["mean_error"]) for row in rows)
    assert "pixels" in compare.format_table(rows).splitlines()[0]


def test_the_other_missing_files_are_file_not_found_errors_too(tmp_path):
    from refracta import edit, terrain

    obj = _write(tmp_path / "m.obj", "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n")
    with pytest.raises(refracta.MissingFileError, match="gone.mtl"):
        refracta.Scene().add_obj(obj)
    with pytest.raises(refracta.MissingFileError, match="no such file"):
        edit.load_pairs(tmp_path / "pairs.json")
    assert issubclass(terrain.ElevationFileNotFoundError, refracta.MissingFileError)
