"""The public functions whose keywords mirror a bound options class write no numeric default of
their own: a number lives once, in the C++ struct's initialiser (REVIEW.md P3), and the Python
signature says None (or leaves the keyword to **fields) for "C++'s default"."""

import inspect
import numbers

import pytest

import refracta
from refracta import edit, moments, oit

# (function, the bound class its keywords mirror, parameters that are not options: inputs with a
# natural value of their own, kept in the signature on purpose).
MIRRORS = [
    (refracta.render, refracta.RenderOptions, ()),
    (refracta.render_raster, refracta.RasterRenderOptions, ()),
    (oit.composite, refracta.OitSettings, ("background",)),  # the colour behind the fragments: an input
    (moments.shadow_intensity, refracta.MomentShadowSettings, ()),
    (edit.solve, None, ()),
    (refracta.trace_rays, refracta.TraceOptions, ()),
    (refracta.ElevationTable, refracta.ElevationTableOptions, ()),
    (refracta.Turbulence, None, ()),
]


def numeric(value) -> bool:
    """A literal number (True / False are switches, not numbers), or a tuple or list holding one."""
    if isinstance(value, bool):
        return False
    if isinstance(value, numbers.Number):
        return True
    return isinstance(value, (tuple, list)) and any(numeric(v) for v in value)


@pytest.mark.parametrize("function, mirrored, inputs", MIRRORS, ids=lambda v: getattr(v, "__qualname__", ""))
def test_no_numeric_default_in_the_signature(function, mirrored, inputs):
    signature = inspect.signature(function)
    written = {p.name: p.default for p in signature.parameters.values() if p.name not in inputs and numeric(p.default)}
    assert written == {}, f"{function.__qualname__} writes defaults that belong to C++: {written}"


def test_the_check_itself_sees_a_numeric_default():
    def mirrors(spp=1, seed=None, spectral=False, speed=(10.0, 0.0), method="curved"):
        return spp, seed, spectral, speed, method

    flagged = [p.name for p in inspect.signature(mirrors).parameters.values() if numeric(p.default)]
    assert flagged == ["spp", "speed"]


@pytest.mark.parametrize(
    "function, mirrored, inputs", [m for m in MIRRORS if m[1] is not None], ids=lambda v: getattr(v, "__qualname__", "")
)
def test_the_mirrored_class_has_documented_fields(function, mirrored, inputs):
    # The class the keywords go to carries the defaults and their documentation.
    fields = [
        name
        for name in dir(mirrored)
        if isinstance(getattr(mirrored, name, None), property) and not name.startswith("_")
    ]
    assert fields, mirrored
    for name in fields:
        assert getattr(mirrored, name).__doc__, f"{mirrored.__name__}.{name} has no docstring"


# Every numeric default a public Python function writes, each an input with a natural value of
# its own that no C++ struct holds (C++'s defaults reach Python as None), with the reason. A new
# one fails the walk below until it is listed here or left to C++.
PYTHON_OWN_DEFAULTS = {
    # Example scenes: their image sizes and set-ups are the examples' own.
    "refracta.examples.cold_sea": {"width", "height"},
    "refracta.examples.fata_morgana": {"width", "height"},
    "refracta.examples.green_flash": {"width", "height", "sun_elevation"},
    "refracta.examples.hot_road": {"width", "height"},
    "refracta.examples.hot_spot": {"width", "height"},
    "refracta.examples.real_place": {"width", "height"},
    "refracta.examples.set_physical_sky": {"scale"},  # the examples' radiance unit, RADIANCE_SCALE
    "refracta.examples_chroma.chroma_filter": {"sigma", "range_sigma"},  # the demo's colour filter
    "refracta.examples_meshes.Mesh.moved": {"scale"},  # 1: unscaled
    "refracta.examples_meshes.cones": {"points"},
    "refracta.examples_meshes.ellipse": {"points"},
    "refracta.examples_meshes.prism": {"top_shift", "top_scale"},  # no shift, unscaled: a prism
    "refracta.examples_meshes.ship_hull": {"length", "beam", "freeboard", "draught"},
    "refracta.examples_town.cliff_faces": {"z_range"},
    "refracta.cli.green_flash_frame": {"size", "spp"},  # the command's frame
    # Plots and comparisons: figure sizes, the kernels compared.
    "refracta.plot.edit_report": {"figsize"},
    "refracta.plot.ray_fan": {"stop_height", "figsize"},  # the ground at height 0
    "refracta.plot.readouts_figure": {"figsize"},
    "refracta.compare.shadows": {"kernels"},
    # Neutral values: no noise at t = 0, no offset, no roll, no scaling, a point aperture.
    "refracta._animate.geometric_noise": {"seed", "time", "speed"},
    "refracta._animate.geometric_noise_map": {"seed", "time", "speed"},  # geometric_noise's
    "refracta._geo_camera.geographic_camera": {"roll"},
    "refracta.widgets.model.ground_circle": {"segments", "earth_radius"},  # a flat Earth (inf) unless given
    "refracta._rays.ElevationTable.ends": {"azimuths"},  # the table's own plane
    "refracta.edit.PointPair.__init__": {"weight", "margin"},  # 1 and 0: the pair as given
    "refracta.geo.LocalFrame.__init__": {"height"},  # on the ellipsoid
    "refracta.geo.LocalFrame.camera": {"roll"},
    "refracta.raster.rasterize": {"guard_band"},  # the camera's view exactly
    "refracta.turbulence.Turbulence.angle_of_arrival_scatter": {"aperture", "direction"},
    "refracta.turbulence.Turbulence.angle_of_arrival_variance": {"aperture", "direction"},
    "refracta.turbulence.Turbulence.separations_within": {"tolerance"},
    "refracta.turbulence.tilt_variance": {"inner_scale", "outer_scale", "aperture"},  # Kolmogorov's limits
    "refracta.moments.power_moments": {"count"},  # 4: Hamburger MSM's
    "refracta.oit.composite": {"background"},  # black behind the fragments
    "refracta.photo.Exif.__init__": {"orientation"},  # EXIF's 1: as stored
    "refracta.photo.Photo.camera": {"up"},
    "refracta.photo.overlay": {"alpha", "threshold", "color"},  # the drawing's look
    # The editor's own interaction: the mouse's button, the preview's size and the markers' scale.
    "refracta.widgets.model.EditorModel.__init__": {"preview_scale"},
    "refracta.widgets.model.EditorModel.click": {"button"},
    "refracta.widgets.model.EditorModel.markers": {"scale"},
    "refracta.widgets.model.EditorModel.pointer_down": {"button", "scale"},
    "refracta.widgets.jobs.Job.progress": {"start", "end"},  # a job's share of the bar: all of it
    # Infrastructure: a bar's silence for quick work.
    "refracta._progress.ProgressBar.__init__": {"quiet_seconds"},
}


def public_python_functions():
    """(qualified name, function) of every public function and method defined in refracta's Python
    modules (not the bound _core: its defaults are C++'s)."""
    import importlib
    import pkgutil

    modules = ["refracta"] + [
        f"refracta.{m.name}" for m in pkgutil.iter_modules(refracta.__path__) if m.name not in ("testing", "__main__")
    ]
    modules += ["refracta.widgets.model", "refracta.widgets.view"]
    seen = set()
    for module_name in modules:
        module = importlib.import_module(module_name)
        for name, value in vars(module).items():
            if inspect.isclass(value) and value.__module__.startswith("refracta") and "_core" not in value.__module__:
                members = [(f"{name}.{k}", v) for k, v in vars(value).items() if inspect.isfunction(v)]
                members = [(q, v) for q, v in members if not q.split(".")[-1].startswith("_") or q.endswith("__init__")]
            elif inspect.isfunction(value) and not name.startswith("_"):
                members = [(name, value)]
            else:
                continue
            for qualname, function in members:
                if function.__module__.startswith("refracta") and id(function) not in seen:
                    seen.add(id(function))
                    yield f"{function.__module__}.{qualname}", function


def test_every_public_python_function_writes_only_its_own_numeric_defaults():
    written = {}
    for name, function in public_python_functions():
        try:
            parameters = inspect.signature(function).parameters.values()
        except ValueError:  # a wrapper of a bound C++ function (functools.wraps): C++'s defaults
            continue
        numbers_written = {p.name for p in parameters if numeric(p.default)}
        if numbers_written:
            written[name] = numbers_written
    unlisted = {n: sorted(v - PYTHON_OWN_DEFAULTS.get(n, set())) for n, v in written.items()}
    assert {n: v for n, v in unlisted.items() if v} == {}, "numeric defaults that belong to C++ (or to the list)"
    gone = {n: sorted(v - written.get(n, set())) for n, v in PYTHON_OWN_DEFAULTS.items()}
    assert {n: v for n, v in gone.items() if v} == {}, "listed defaults no longer written: drop them from the list"
