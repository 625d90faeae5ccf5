"""Every public object pickles: a round trip gives an object that behaves bit for bit as the
original (same n and grad n, same BSDF and light samples, same render), in this process and in
another one (concurrent.futures.ProcessPoolExecutor, spawned: a fresh interpreter)."""

import concurrent.futures
import multiprocessing
import pickle

import cloudpickle
import numpy as np
import pytest

import refracta
from refracta import lights, shading
from refracta.edit import PointPair, solve
from tests.scale import scenes

POINTS = np.array([[0.0, 0.01, 0.0], [3.0, 0.3, -2.0], [50.0, 1.7, 4.0], [-20.0, 40.0, 7.0]])


def round_trip(obj):
    return pickle.loads(pickle.dumps(obj))


@pytest.fixture(scope="module")
def texture(tmp_path_factory):
    return scenes.write_texture(tmp_path_factory.mktemp("scale") / "checker.exr")


@pytest.fixture(scope="module")
def spawned_pool():
    """One worker in a fresh interpreter: nothing is inherited, everything arrives by pickle."""
    with concurrent.futures.ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn")) as pool:
        yield pool


def fields():
    road = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1, humidity=0.4, wavelength=600.0)
    return {
        "logistic": refracta.LogisticProfile(n_inv=0.2, h_ciso=3.0, a_hot=0.7),
        "physical": road,
        "sounding": refracta.TemperatureProfile(
            [0.0, 2.0, 30.0, 300.0], [305.0, 296.0, 292.0, 290.0], pressure=100500.0
        ),
        "linear_squared": refracta.LinearSquaredProfile(alpha=6e-6),
        "curved_earth": refracta.CurvedEarth(road, radius=6.4e6),
        "dispersed": refracta.DispersedField(road, 1.01),
        "dispersed_curved_earth": refracta.dispersed_field(refracta.CurvedEarth(road), 450.0),
        "custom": refracta.CustomField(scenes.custom_ior, scenes.custom_grad, height_only=True),
    }


@pytest.mark.parametrize("name", list(fields()))
def test_fields_round_trip_with_the_same_index_and_gradient(name):
    field = fields()[name]
    copy = round_trip(field)
    assert type(copy) is type(field) and repr(copy) == repr(field)
    assert copy.params == field.params and copy.height_only == field.height_only
    assert np.array_equal(copy.ior(POINTS), field.ior(POINTS))
    assert np.array_equal(copy.grad_ior(POINTS), field.grad_ior(POINTS))
    if isinstance(field, (refracta.CurvedEarth, refracta.DispersedField)):
        assert type(copy.base) is type(field.base) and copy.base.params == field.base.params


def test_custom_field_of_a_lambda_fails_clearly_with_pickle_and_travels_by_cloudpickle():
    field = refracta.CustomField(lambda p: 1.0 + 0.0 * p[:, 1], lambda p: 0.0 * p, height_only=True)
    with pytest.raises((pickle.PicklingError, AttributeError), match="lambda"):  # the pickler names it
        pickle.dumps(field)
    copy = cloudpickle.loads(cloudpickle.dumps(field))  # what dask uses
    assert np.array_equal(copy.ior(POINTS), np.ones(len(POINTS)))


def test_fields_evaluate_identically_in_another_process(spawned_pool):
    for name, field in fields().items():
        n, grad = spawned_pool.submit(scenes.ior_and_gradient, field, POINTS).result()
        assert np.array_equal(n, field.ior(POINTS)), name
        assert np.array_equal(grad, field.grad_ior(POINTS)), name


def test_camera_round_trip_gives_the_same_rays():
    camera = refracta.Camera(
        (1e3, 1.7, -3.0), (1e3 + 250.0, 1.1, 40.0), up=(0.1, 1.0, 0.0), vfov=17.0, width=33, height=21
    )
    copy = round_trip(camera)
    for attribute in ("position", "look_at", "up"):
        assert np.array_equal(getattr(copy, attribute), getattr(camera, attribute))
    assert (copy.vfov, copy.width, copy.height) == (camera.vfov, camera.width, camera.height)
    for u, v in [(0.0, 0.0), (16.5, 10.5), (33.0, 21.0), (3.25, 17.75)]:
        assert np.array_equal(copy.ray(u, v)[1], camera.ray(u, v)[1])


def test_render_options_round_trip_every_field():
    options = refracta.RenderOptions()
    options.method, options.transport, options.spp, options.seed = "straight", "path", 9, 12345678901
    options.trace, options.table, options.pixel_bounds, options.max_length = "rk45", False, (1, 2, 5, 7), 777.0
    copy = round_trip(options)
    names = [n for n in dir(refracta.RenderOptions) if isinstance(getattr(refracta.RenderOptions, n), property)]
    assert len(names) >= 20
    for name in names:
        assert getattr(copy, name) == getattr(options, name), name


MATERIALS = [
    shading.Diffuse((0.7, 0.2, 0.1), texture=2),
    shading.BlinnPhong(0.3, (0.4, 0.4, 0.2), 50.0, texture=0, alpha=0.8),
    shading.Conductor(),
    shading.Conductor((0.2, 0.9, 1.1), (3.9, 2.4, 2.2)),
    shading.RoughConductor(alpha_u=0.1, alpha_v=0.3, eta=1.5, k=4.0),
    shading.Dielectric("bk7", priority=1),
    shading.Dielectric(sellmeier=(1.1, 0.2, 0.9, 0.006, 0.02, 100.0)),
    shading.RoughDielectric(0.2, ior=1.33, priority=3),
    shading.ThinDielectric(1.52),
    shading.Plastic((0.1, 0.3, 0.6), ior=1.45, alpha=0.15, texture=1),
    shading.Plastic(0.5),
    shading.Principled((0.6, 0.1, 0.1), metallic=0.5, roughness=0.3, anisotropic=0.4, clearcoat=1.0, sheen=0.2),
    shading.ThinFilm(420.0, film_ior=1.4, eta=1.2, k=2.0, alpha_u=0.05, alpha_v=0.2),
    shading.Water(7.0, temperature_c=12.0, salinity=30.0),
    shading.Water(3.0, body=False, priority=2),
]


@pytest.mark.parametrize("material", MATERIALS, ids=lambda m: type(m).__name__)
def test_materials_round_trip_with_the_same_bsdf(material, rng):
    copy = round_trip(material)
    assert type(copy) is type(material) and repr(copy) == repr(material)
    assert copy.parameters == material.parameters
    opacity = shading.Material.alpha.fget  # the raster's opacity (Water.alpha: its roughness, deprecated)
    assert (copy.priority, opacity(copy)) == (material.priority, opacity(material))
    wo = rng.normal(size=(64, 3))
    wo[:, 2] = np.abs(wo[:, 2])
    wo /= np.linalg.norm(wo, axis=1, keepdims=True)
    wi = rng.normal(size=(64, 3))
    wi /= np.linalg.norm(wi, axis=1, keepdims=True)
    u = rng.uniform(size=(64, 3))
    lam = np.array([450.0, 520.0, 600.0, 680.0])
    assert np.array_equal(copy.f(wo, wi), material.f(wo, wi))
    assert np.array_equal(copy.f(wo, wi, wavelengths=lam), material.f(wo, wi, wavelengths=lam))
    assert np.array_equal(copy.pdf(wo, wi), material.pdf(wo, wi))
    a, b = copy.sample(wo, u), material.sample(wo, u)
    for key in a.fields:
        assert np.array_equal(getattr(a, key), getattr(b, key)), key


def test_ior_round_trip():
    for ior in (shading.Ior(1.33), shading.Ior("bk7")):
        copy = round_trip(ior)
        assert repr(copy) == repr(ior) and copy.at(486.1) == ior.at(486.1)


def light_list():
    mesh = dict(vertices=[[0, 2, 0], [1, 2, 0], [0, 2, 1]], triangles=[[0, 2, 1]])
    return [
        lights.PointLight((1.0, 2.0, 3.0), (5.0, 4.0, 3.0)),
        lights.SpotLight((0.0, 3.0, 0.0), (0.2, -1.0, 0.1), 40.0, 30.0, inner_angle=25.0),
        lights.SpotLight((0.0, 3.0, 0.0), (0.2, -1.0, 0.1), 40.0, 30.0),
        lights.SunLight((0.3, 0.4, 0.5), (900.0, 800.0, 700.0), angular_diameter=1.5, limb_darkening=0.6),
        lights.AreaLight(emission=(2.0, 3.0, 4.0), two_sided=True, **mesh),
        lights.SphereLight((0.5, 1.5, -0.5), 0.25, 7.0),
        lights.EnvironmentLight(scenes.environment_map(), scale=1.7, rotation=40.0),
        lights.ConstantEnvironment((0.3, 0.4, 0.5), sampling="uniform"),
    ]


@pytest.mark.parametrize("index", range(len(light_list())))
def test_lights_round_trip_with_the_same_samples(index, rng):
    light = light_list()[index]
    copy = round_trip(light)
    assert type(copy) is type(light) and repr(copy) == repr(light)
    points = rng.uniform(-1.0, 1.0, size=(32, 3))
    normals = np.tile([0.0, 1.0, 0.0], (32, 1))
    u = rng.uniform(0.0, 1.0, size=(32, 2))
    for a, b in zip(copy.sample_li(points, normals, u), light.sample_li(points, normals, u)):
        assert np.array_equal(a, b)
    dirs = rng.normal(size=(32, 3))
    dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
    assert np.array_equal(copy.Le(dirs), light.Le(dirs))


@pytest.mark.slow  # two sky tables (~1 s each)
def test_physical_sky_round_trip():
    sun = np.array([0.3, 0.2, 0.9]) / np.linalg.norm([0.3, 0.2, 0.9])
    sky = refracta.spectrum.PhysicalSky(sun, aerosol=2.0, ozone_du=250.0, altitude=100.0)
    copy = round_trip(sky)
    dirs = np.array([[0.0, 1.0, 0.0], [0.6, 0.1, 0.79372539], [0.0, -0.3, 0.95393920]])
    assert repr(copy) == repr(sky)
    assert np.array_equal(copy.rgb_radiance(dirs), sky.rgb_radiance(dirs))


@pytest.mark.slow
@pytest.mark.parametrize("sky", ["environment", "physical", "gradient", "constant"])
def test_scene_round_trip_renders_bit_for_bit(sky, texture):
    scene = scenes.every_kind_scene(texture, sky)
    copy = round_trip(scene)
    assert copy.geometry_count == scene.geometry_count
    assert [repr(light) for light in copy.lights] == [repr(light) for light in scene.lights]
    for g in range(scene.geometry_count):
        assert repr(copy.material(g)) == repr(scene.material(g))
    camera, field = scenes.camera(), scenes.hot_road()
    for transport in ("direct", "path"):
        expected = scenes.render_quietly(scene, camera, field, transport=transport, spp=4)
        assert expected.max() > 0.0
        assert np.array_equal(scenes.render_quietly(copy, camera, field, transport=transport, spp=4), expected)
    spectral = scenes.render_quietly(scene, camera, field, spectral=True, spp=2)
    assert np.array_equal(scenes.render_quietly(copy, camera, field, spectral=True, spp=2), spectral)


def test_a_scene_renders_identically_in_another_process(texture, spawned_pool):
    scene, camera, field = scenes.every_kind_scene(texture, "environment"), scenes.camera(), scenes.hot_road()
    local = scenes.render_quietly(scene, camera, field, transport="path", spp=4)
    remote = spawned_pool.submit(scenes.render_quietly, scene, camera, field, transport="path", spp=4).result()
    assert np.array_equal(remote, local)


def test_a_scene_file_round_trips():
    loaded = refracta.load_scene("tests/data/hot_road.toml")
    copy = round_trip(loaded)
    assert copy._fields == loaded._fields == ("scene", "camera", "field")
    assert copy.turbulence is None and loaded.turbulence is None
    camera = loaded.camera.resized(16, 8)
    assert np.array_equal(
        scenes.render_quietly(copy.scene, camera, copy.field), scenes.render_quietly(loaded.scene, camera, loaded.field)
    )


def test_ray_paths_batches_and_tables_round_trip(hot_road):
    path = refracta.trace_ray(hot_road, [0, 1.5, 0], [1, -0.0035, 0], max_length=800.0, stop_height=0.0)
    copy = round_trip(path)
    assert (copy.stop, copy.evaluations, len(copy)) == (path.stop, path.evaluations, len(path))
    for attribute in ("points", "directions", "ray_vectors", "arc_length", "ior"):
        assert np.array_equal(getattr(copy, attribute), getattr(path, attribute)), attribute
    target = [400.0, 0.3, 0.0]
    assert copy.closest_point(target)[1] == path.closest_point(target)[1]
    assert np.array_equal(copy.point_at(123.4)[0], path.point_at(123.4)[0])

    batch = refracta.trace_rays(hot_road, [0, 1.5, 0], [[1, -0.003, 0], [1, 0.001, 0]], max_length=500.0)
    batch_copy = round_trip(batch)
    for a, b in zip(
        (batch_copy.end_points, batch_copy.lengths, batch_copy.stops), (batch.end_points, batch.lengths, batch.stops)
    ):
        assert np.array_equal(a, b)

    table = refracta.ElevationTable(hot_road, 1.5, -1.0, 0.5, max_length=600.0)
    table_copy = round_trip(table)
    elevations = np.linspace(-1.0, 0.5, 77)
    assert table_copy.size == table.size
    assert np.array_equal(table_copy.ends(elevations, 10.0).end_points, table.ends(elevations, 10.0).end_points)


def test_edit_pairs_and_results_round_trip():
    pair = PointPair(destination=(1.0, 1.5, 0.0), source=(1000.0, 3.0, 0.0), weight=2.0)
    pixel_pair = PointPair((180.4, 64.06), (258.0, 0.5, 3.0))
    assert round_trip(pair) == pair and round_trip(pixel_pair) == pixel_pair
    result = solve(refracta.LinearSquaredProfile(), (0.0, 1.5, 0.0), [pair], free="alpha", tol=1e-11)
    copy = round_trip(result)
    assert copy.field.params == result.field.params and repr(copy) == repr(result)
    assert np.array_equal(copy.distances, result.distances)
    assert np.array_equal(copy.paths()[0].points, result.paths()[0].points)


def test_unpickled_physical_skies_share_the_process_table():
    """A worker unpickles a sweep's scene for every task: the sky's table is built once per process
    (PhysicalSky::shared), the copy reading the very same table (the same build, to the bit)."""
    sun = np.array([0.2, 0.5, -0.3]) / np.linalg.norm([0.2, 0.5, -0.3])
    sky = refracta.spectrum.PhysicalSky(sun, aerosol=1.3)
    copy = round_trip(sky)
    assert copy.build_seconds == sky.build_seconds  # one build, measured once
    other = refracta.spectrum.PhysicalSky(sun, aerosol=1.4)
    dirs = np.array([[0.0, 1.0, 0.0], [0.6, 0.1, 0.79372539]])
    assert not np.array_equal(other.rgb_radiance(dirs), sky.rgb_radiance(dirs))  # other settings, own table


def test_microfacet_distribution_and_light_sampler_round_trip(rng):
    ggx = shading.TrowbridgeReitz(0.05, 0.3)
    copy = round_trip(ggx)
    m = rng.normal(size=(16, 3))
    m[:, 2] = np.abs(m[:, 2])
    m /= np.linalg.norm(m, axis=1, keepdims=True)
    assert (copy.alpha_x, copy.alpha_y) == (0.05, 0.3) and np.array_equal(copy.D(m), ggx.D(m))
    sampler = lights.LightSampler(light_list()[:3], strategy="uniform")
    sampler_copy = round_trip(sampler)
    u = np.linspace(0.0, 0.999, 25)
    for a, b in zip(sampler_copy.sample(u), sampler.sample(u)):
        assert np.array_equal(a, b)
    assert len(sampler_copy) == 3 and sampler_copy.pmf(1) == sampler.pmf(1)


def test_an_environment_map_file_travels_as_its_path(tmp_path):
    path = tmp_path / "sky.exr"
    image = np.repeat(np.repeat(scenes.environment_map(), 8, axis=0), 8, axis=1)  # 64 x 128 texels, 98 KB
    refracta.io.write_image(str(path), image)
    scene = refracta.Scene()
    scene.add_sphere((5.0, 1.0, 0.0), 1.0, material=shading.Conductor())
    scene.set_environment(str(path), rotation=20.0, scale=1.5)
    data = pickle.dumps(scene)
    assert str(path).encode() in data and len(data) < image.nbytes / 10
    camera = scenes.camera()
    assert np.array_equal(
        scenes.render_quietly(pickle.loads(data), camera, None, spp=2),
        scenes.render_quietly(scene, camera, None, spp=2),
    )


def test_an_obj_scene_with_textures_in_a_sibling_folder_round_trips(tmp_path):
    """A downloaded model: OBJ + MTL, the texture in ../textures found by texture_dirs. The pickle
    holds the meshes and the texture's resolved absolute path, so it renders the same from another
    working directory."""
    (tmp_path / "model").mkdir()
    (tmp_path / "textures").mkdir()
    scenes.write_texture(tmp_path / "textures" / "brick.exr")
    (tmp_path / "model" / "wall.mtl").write_text("newmtl brick\nKd 0.9 0.8 0.7\nmap_Kd brick.exr\n")
    (tmp_path / "model" / "wall.obj").write_text(
        "mtllib wall.mtl\nv 8 0 -2\nv 8 0 2\nv 8 3 2\nv 8 3 -2\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "usemtl brick\nf 1/1 3/3 2/2\nf 1/1 4/4 3/3\n"
    )
    scene = refracta.Scene()
    scene.add_obj(str(tmp_path / "model" / "wall.obj"), texture_dirs=[str(tmp_path / "textures")])
    scene.set_environment((0.5, 0.5, 0.5))
    data = pickle.dumps(scene)
    assert str(tmp_path / "textures" / "brick.exr").encode() in data
    camera = scenes.camera()
    image = scenes.render_quietly(scene, camera, None, spp=2)
    assert image.std() > 0.0  # the checker shows
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(tmp_path / "model")
        assert np.array_equal(scenes.render_quietly(pickle.loads(data), camera, None, spp=2), image)


ABSTRACT = {"IndexField", "Material", "Light"}  # bases: their objects are always of a subclass


def test_every_public_class_pickles():
    """A guard for new classes: every concrete class of the compiled module defines its pickling,
    and every class refracta exports pickles or is one of the compiled ones."""
    import inspect

    compiled = {
        name: obj
        for name, obj in vars(refracta._core).items()
        if inspect.isclass(obj) and not name.startswith("_") and not issubclass(obj, BaseException)
    }
    missing = [name for name, obj in compiled.items() if name not in ABSTRACT and "__setstate__" not in vars(obj)]
    assert not missing, f"classes without pickling: {missing}"
    exported = [getattr(refracta, name) for name in refracta.__all__]
    python_classes = [
        obj
        for obj in exported
        if inspect.isclass(obj) and obj.__module__ != "refracta._core" and not issubclass(obj, BaseException)
    ]
    assert {c.__name__ for c in python_classes} >= {
        "RayBatch",
        "ElevationTable",
        "SceneFile",
        "SweepResult",
        "SweepFailure",
    }
    for cls in python_classes:  # each is a dataclass, NamedTuple or defines __reduce__
        assert hasattr(cls, "__dataclass_fields__") or hasattr(cls, "_fields") or "__reduce__" in vars(cls), cls
