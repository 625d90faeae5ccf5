"""refracta: physically based mirages -- curved light rays through air of varying refractive index.

Fields (n(x) and grad n): LogisticProfile, PhysicalAtmosphere, TemperatureProfile,
LinearSquaredProfile, CustomField. Rays: trace_ray (one RayPath), trace_rays (a batch, in
parallel), ElevationTable. Images: Scene, Camera, render, refracta.io. Shading: refracta.shading
(BSDFs), refracta.lights, refracta.spectrum (spectral colour), refracta.testing (chi-square
sampler tests). Plots: refracta.plot. Units: metres, kelvin, pascal, nanometres; y is up.

Submodules not imported here (edit, examples, geo, photo, plot, compare, moments, oit, raster, cli, widgets:
the interactive editor in Jupyter) load on first use (PEP 562), so ``import refracta`` stays cheap
and does not import matplotlib.
"""

import importlib as _importlib

# _arguments first (it wraps _core as it loads, before any module takes a name from it): a refused
# argument is named (refracta/_arguments.py).
from refracta import _arguments, io, lights, shading, spectrum, terrain, testing  # noqa: F401 (_arguments)
from refracta._animate import animate, geometric_noise
from refracta._arguments import ArgumentError
from refracta._astronomy import astronomical_refraction
from refracta._core import (
    Camera,
    CurvedEarth,
    CustomField,
    DispersedField,
    DisplaySettings,
    ElevationTableOptions,
    HotSpot,
    IndexField,
    IoError,
    LinearSquaredProfile,
    LogisticProfile,
    MboitSettings,
    MissingFileError,
    MomentShadowSettings,
    NumericalError,
    ObjOptions,
    OceanWaves,
    OitSettings,
    PhysicalAtmosphere,
    RasterRenderOptions,
    RasterRenderStats,
    RayPath,
    RenderOptions,
    RenderStats,
    Scene,
    ShadowMapOptions,
    TemperatureProfile,
    TextureNotFoundError,
    TraceOptions,
    TurbulenceSettings,
    air_dispersion_scale,
    dispersed_field,
    field_reference_wavelength,
    get_threads,
    set_threads,
    trace_ray,
)
from refracta._denoise import denoise
from refracta._geo_camera import geographic_camera as _geographic_camera
from refracta._raster_render import render_raster
from refracta._rays import ElevationTable, RayBatch, trace_rays, without_refraction
from refracta._refraction_coefficient import RefractionCoefficient, refraction_coefficient
from refracta._render import SceneWarning, render
from refracta._sweep import SweepError, SweepFailure, SweepResult, sweep
from refracta.scene_file import SceneFile, load_scene
from refracta.turbulence import Turbulence

# The one place the version is written: pyproject.toml reads it (scikit-build-core's regex provider).
__version__ = "0.1.0"

# Submodules loaded on first attribute access (PEP 562): refracta.edit, refracta.plot, ...
_LAZY_SUBMODULES = (
    "cli",
    "compare",
    "edit",
    "examples",
    "geo",
    "moments",
    "oit",
    "photo",
    "plot",
    "raster",
    "widgets",
)

# Camera.geographic (issue 20): a Python static method on the bound class (refracta.geo's LocalFrame).
Camera.geographic = staticmethod(_geographic_camera)  # type: ignore[method-assign]


def __getattr__(name):
    if name in _LAZY_SUBMODULES:
        return _importlib.import_module(f"refracta.{name}")  # binds refracta.<name> as it imports
    raise AttributeError(f"module 'refracta' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_LAZY_SUBMODULES))


__all__ = [
    "ArgumentError",
    "Camera",
    "CurvedEarth",
    "CustomField",
    "DispersedField",
    "DisplaySettings",
    "ElevationTable",
    "ElevationTableOptions",
    "HotSpot",
    "IndexField",
    "IoError",
    "LinearSquaredProfile",
    "LogisticProfile",
    "MboitSettings",
    "MissingFileError",
    "MomentShadowSettings",
    "NumericalError",
    "ObjOptions",
    "OceanWaves",
    "OitSettings",
    "PhysicalAtmosphere",
    "RasterRenderOptions",
    "RasterRenderStats",
    "RayBatch",
    "RayPath",
    "RefractionCoefficient",
    "RenderOptions",
    "RenderStats",
    "Scene",
    "SceneFile",
    "SceneWarning",
    "ShadowMapOptions",
    "SweepError",
    "SweepFailure",
    "SweepResult",
    "TemperatureProfile",
    "TextureNotFoundError",
    "TraceOptions",
    "Turbulence",
    "TurbulenceSettings",
    "air_dispersion_scale",
    "animate",
    "astronomical_refraction",
    "denoise",
    "dispersed_field",
    "field_reference_wavelength",
    "geometric_noise",
    "get_threads",
    "set_threads",
    "io",
    "lights",
    "shading",
    "spectrum",
    "terrain",
    "testing",
    "load_scene",
    "render",
    "refraction_coefficient",
    "render_raster",
    "sweep",
    "trace_ray",
    "trace_rays",
    "without_refraction",
]
