"""Leftovers of earlier trials: a CustomField in a reference cycle through its own callables was
never collected, and the scaled sky `set_physical_sky(..., scale=)` puts in `Scene.lights` could not
be pickled; astronomical refraction from above the air was refused."""

import gc
import pickle
import weakref

import numpy as np
import pytest

import refracta
from refracta import lights


class _AirOfAnObject:
    """The usual way to write a field with state: its callables are methods of an object that holds it."""

    def __init__(self):
        self.field = refracta.CustomField(self.ior, self.grad, height_only=True)

    def ior(self, points):
        return 1.0003 - 1e-6 * np.asarray(points)[:, 1]

    def grad(self, points):
        out = np.zeros((len(points), 3))
        out[:, 1] = -1e-6
        return out


def _dropped(owner_factory):
    """A weak reference to an owner dropped by every Python name, after a collection."""
    owner = owner_factory()
    ref = weakref.ref(owner)
    del owner
    gc.collect()
    return ref


def test_a_custom_field_in_a_cycle_through_its_callables_is_collected():
    # Before: the cycle owner -> field -> bound method -> owner was invisible to the collector.
    assert _dropped(_AirOfAnObject)() is None


def test_a_custom_field_held_by_the_library_stays_alive_and_callable():
    owner = _AirOfAnObject()
    earth = refracta.CurvedEarth(owner.field, 6371000.0)
    ref = weakref.ref(owner)
    del owner
    gc.collect()
    # The CurvedEarth still uses the field: its callables (and their object) must live.
    assert ref() is not None
    ray = refracta.trace_ray(earth, (0.0, 2.0, 0.0), (1.0, 0.0, 0.0), max_length=50.0)
    assert np.all(np.isfinite(ray.points))
    del earth, ray
    gc.collect()
    # Once only Python held it, the cycle goes.
    assert ref() is None


def test_a_field_kept_after_its_owner_is_dropped_still_evaluates():
    owner = _AirOfAnObject()
    field = owner.field
    del owner
    gc.collect()
    # n = 1.0003 - 1e-6 y exactly as the callable computes it (one subtraction, no tolerance needed).
    assert field.ior([[0.0, 2.0, 0.0]])[0] == 1.0003 - 2e-6


def _scaled_sky_scene():
    scene = refracta.Scene()
    # The air's own light is the scene's, not a light's: off, so that the lights are all there is.
    scene.set_physical_sky((0.0, 0.6, 0.8), scale=2.0, aerial_perspective=False)
    return scene


def test_the_scaled_sky_of_a_scene_pickles_and_keeps_its_light():
    sky = _scaled_sky_scene().lights[0]
    assert isinstance(sky, lights.ScaledLight) and sky.scale == 2.0
    copy = pickle.loads(pickle.dumps(sky))
    dirs = np.array([[0.0, 0.6, 0.8], [0.6, 0.8, 0.0], [0.0, 1.0, 0.0]])
    # The sky's table is rebuilt from its settings: the same numbers bit for bit.
    np.testing.assert_array_equal(copy.Le(dirs), sky.Le(dirs))
    # Twice the unscaled sky, exactly (a power-of-two factor).
    np.testing.assert_array_equal(copy.Le(dirs), 2.0 * sky.light.rgb_radiance(dirs))


def test_the_lights_of_one_scene_light_another_identically():
    source = _scaled_sky_scene()
    source.add_box((0.0, 0.5, -5.0), (1.0, 1.0, 1.0))
    target = refracta.Scene()
    target.add_box((0.0, 0.5, -5.0), (1.0, 1.0, 1.0))
    for light in source.lights:
        target.add_light(light)
    camera = refracta.Camera((0.0, 1.0, 0.0), (0.0, 0.8, -5.0), vfov=40.0, width=16, height=12)
    first, second = (refracta.render(s, camera, None, spp=2, progress=False) for s in (source, target))
    np.testing.assert_array_equal(first, second)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: lights.ScaledLight(lights.PointLight((0.0, 0.0, 0.0), 1.0), 2.0), "must be infinite"),
        (lambda: lights.ScaledLight(3, 2.0), "must be a refracta.lights.Light"),
        (lambda: lights.ScaledLight(lights.ConstantEnvironment(1.0), float("nan")), "finite and >= 0"),
        (lambda: lights.ScaledLight(lights.ConstantEnvironment(1.0), -1.0), "finite and >= 0"),
    ],
)
def test_a_scaled_light_refuses_what_it_cannot_scale(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_a_star_setting_through_the_limb_seen_from_above_the_air():
    # From 400 km, looking at the limb 5 km up (straight line): the default top (86 km, below the
    # eye) used to be refused. The air above 86 km is uniform, so the answer is the path's bending.
    air, radius, eye = refracta.PhysicalAtmosphere(), 6371e3, 400e3
    elevation = -np.degrees(np.arccos((radius + 5e3) / (radius + eye)))
    seen = refracta.astronomical_refraction(air, elevation, eye_height=eye)
    # Any top above the eye gives the same path: equal to the tracer's tolerance (4e-8 measured).
    assert seen == pytest.approx(refracta.astronomical_refraction(air, elevation, eye_height=eye, top=500e3), rel=1e-6)

    # The limb ray is symmetric about its lowest point, found by Bouguer's invariant n r cos e;
    # it bends there twice what a level ray from that height bends on its way out.
    def n(h):
        return float(air.ior([0.0, h, 0.0]))

    invariant = n(86e3) * (radius + eye) * np.cos(np.radians(elevation))
    low, high = 0.0, 1e4
    for _ in range(60):
        mid = 0.5 * (low + high)
        low, high = (mid, high) if n(mid) * (radius + mid) < invariant else (low, mid)
    half = refracta.astronomical_refraction(air, 0.0, eye_height=low)
    # 1.1e-6 apart measured: the two traces' tolerances and their vacuum steps at the top.
    assert seen == pytest.approx(2.0 * half, rel=5e-6)


def test_astronomical_refraction_names_what_the_caller_gave():
    # A 1e11 m Earth (a flat Earth's stand-in) gave a message about TraceOptions and a max_length
    # the caller never set; an eye beyond the scene's reach is refused by its name.
    with pytest.raises(
        ValueError, match=r"tol must be at least .* for earth_radius 1e\+11 m and top 86000 m \(the default\)"
    ):
        refracta.astronomical_refraction(refracta.PhysicalAtmosphere(), 10.0, earth_radius=1e11)
    with pytest.raises(ValueError, match="eye_height must be >= 0 m and below"):
        refracta.astronomical_refraction(refracta.PhysicalAtmosphere(), 10.0, eye_height=2e7)


def test_every_light_of_a_scene_goes_into_another_or_is_refused_by_name():
    # A round-trip trial: the unscaled physical sky came back as a PhysicalSky that add_light
    # refused ("must be a refracta.Light"), and an emissive sphere's SphereLight was taken without
    # its sphere: it lit the ground but no camera ray saw it (5.05 where the source scene shows it).
    source = refracta.Scene()
    source.set_physical_sky((0.0, 0.6, 0.8), aerial_perspective=False)
    source.add_sphere((20.0, 1.0, 0.0), 1.0, emission=(5.0, 5.0, 5.0))
    target = refracta.Scene()
    added = []
    for light in source.lights:
        if isinstance(light, lights.SphereLight):
            with pytest.raises(
                ValueError, match=r"an area light \(AreaLight, SphereLight\) must be emitted by a surface"
            ):
                target.add_light(light)
        else:
            index = target.add_light(light)
            added.append(type(target.lights[index]).__name__)
    assert added == ["PhysicalSky", "SunLight"]
    with pytest.raises(refracta.ArgumentError, match=r"Scene.add_light: light must be a refracta.Light \(got 'sun'\)"):
        target.add_light("sun")


def test_reprs_tell_apart_what_behaves_differently():
    calm = refracta.PhysicalAtmosphere()
    turbulent = calm.with_turbulence(refracta.Turbulence(cn2=1e-10, depth=0.1, cells=16))
    assert "turbulence=<layer" in repr(turbulent) and "turbulence" not in repr(calm)
    texels = np.ones((4, 8, 3), np.float32)
    assert repr(lights.EnvironmentLight(texels, rotation=90.0)) != repr(lights.EnvironmentLight(texels))
    ggx = refracta.shading.TrowbridgeReitz(0.1, 0.3)
    assert eval(repr(ggx), {"TrowbridgeReitz": refracta.shading.TrowbridgeReitz}).alpha_y == 0.3


def test_objects_holding_arrays_compare_by_identity_not_by_an_ambiguous_truth(tmp_path):
    # photo.load(p) == photo.load(p) raised "The truth value of an array ... is ambiguous".
    path = tmp_path / "p.png"
    refracta.io.write_image(path, np.full((4, 4, 3), 0.5, np.float32), tonemap="linear", exposure=1.0)
    first, second = refracta.photo.load(path), refracta.photo.load(path)
    assert first == first and first != second and first in [first]


def test_a_physical_sky_takes_its_sun_direction_as_the_scene_does():
    # spectrum.PhysicalSky refused a direction that set_physical_sky normalises ("must be a unit
    # vector (got norm 0.4387)"): one rule for both.
    given = np.array([-0.3, 0.25, 0.2])
    scene = refracta.Scene()
    scene.set_physical_sky(given, aerial_perspective=False)
    sky = refracta.spectrum.PhysicalSky(given, below_horizon="horizon")
    dirs = np.array([[0.0, 1.0, 0.0], [0.6, 0.8, 0.0]])
    # The same settings (the scene's sky is the first of its lights): the same table, bit for bit.
    np.testing.assert_array_equal(sky.rgb_radiance(dirs), scene.lights[0].rgb_radiance(dirs))
    with pytest.raises(ValueError, match="sun_direction must be non-zero and finite"):
        refracta.spectrum.PhysicalSky((0.0, 0.0, 0.0))


@pytest.mark.parametrize(
    "slip",
    [
        lambda: refracta.PhysicalAtmosphere(pressure=1013.25),
        lambda: refracta.TemperatureProfile([0.0, 10.0], [288.15, 288.0], pressure=337.0),
    ],
)
def test_a_pressure_in_hectopascals_is_refused(slip):
    # 1013.25 "Pa" gave n - 1 = 2.8e-6, a hundredth of the real air's, and no mirage, without a word.
    with pytest.raises(ValueError, match=r"pressure must be in pascals .* hPa is"):
        slip()


def test_thin_air_outside_the_hectopascal_range_is_still_taken():
    # Near-vacuum (a test of straight rays) and a high plateau's 60 kPa stay valid: n - 1 scales
    # with P, 2.78e-4 at 101 325 Pa, so 2.7e-12 at 1e-3 Pa (bound 1e-10) ...
    assert refracta.PhysicalAtmosphere(pressure=1e-3).ior([0.0, 1.0, 0.0]) < 1.0 + 1e-10
    # ... and 1.6e-4 at 60 kPa (bound 1e-4).
    assert refracta.PhysicalAtmosphere(pressure=6e4).ior([0.0, 1.0, 0.0]) > 1.0001


def test_the_collector_meets_a_python_subclass_of_custom_field_before_pybind11_lays_it_out():
    # The first instance of a new subclass is tracked from its allocation, and laying it out makes
    # objects the collector tracks: with a collection at every allocation, the traverse read a
    # holder table not yet there (a segfault, exit code 139). In a child: a crash must not take pytest.
    import subprocess
    import sys

    child = (
        "import gc, numpy as np, refracta\n"
        "class Sub(refracta.CustomField): pass\n"
        "gc.set_threshold(1)\n"
        "f = Sub(lambda p: np.ones(len(p)), lambda p: np.zeros((len(p), 3)))\n"
        "gc.set_threshold(700)\n"
        "print(f.ior([0.0, 1.0, 0.0]))\n"
    )
    done = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == "1.0"


def test_a_scaled_light_of_a_scaled_light_is_one_and_the_sun_is_refused():
    environment = lights.ConstantEnvironment(1.0)
    twice = lights.ScaledLight(lights.ScaledLight(environment, 2.0), 3.0)
    # .light gave the pickle's tuple form for a nested one.
    assert isinstance(twice.light, lights.ScaledLight) and twice.light.scale == 2.0
    # The scene finds its sun by type: a scaled sun it would not bend, replace or render as the sun.
    sun = lights.SunLight((0.0, 1.0, 0.0), 1.0)
    with pytest.raises(ValueError, match=r"scale the sun by its radiance"):
        lights.ScaledLight(sun, 2.0)
    # The scene pickle's old tuple form is not a light.
    with pytest.raises(ValueError, match=r"a light must be a refracta.lights.Light .* \(got <class 'tuple'>\)"):
        lights.ScaledLight(("scaled", environment, 2.0), 3.0)
