"""refracta: physically based mirages -- curved light rays through air of varying refractive index.

Fields (n(x) and grad n): LogisticProfile, PhysicalAtmosphere, TemperatureProfile,
LinearSquaredProfile, CustomField. Rays: trace_ray (one RayPath), trace_rays (a batch, in
parallel), ElevationTable. Images: Scene, Camera, render, refracta.io. Shading: refracta.shading (BSDFs), refracta.lights,
refracta.spectrum (spectral colour), refracta.testing (chi-square sampler tests). Plots: refracta.plot. Units: metres, kelvin, pascal, nanometres; y is up.
"""

from refracta._core import (
    Camera,
    CurvedEarth,
    CustomField,
    DispersedField,
    IndexField,
    IoError,
    LinearSquaredProfile,
    LogisticProfile,
    NumericalError,
    PhysicalAtmosphere,
    RayPath,
    RenderOptions,
    Scene,
    TemperatureProfile,
    air_dispersion_scale,
    dispersed_field,
    field_reference_wavelength,
    trace_ray,
)
from refracta import io, lights, shading, spectrum, testing
from refracta._render import render
from refracta._raster_render import render_raster
from refracta.scene_file import SceneFile, load_scene
from refracta._rays import ElevationTable, RayBatch, trace_rays
from refracta._sweep import SweepError, SweepFailure, SweepResult, sweep

__version__ = "0.1.0"

__all__ = [
    "Camera",
    "CurvedEarth",
    "CustomField",
    "DispersedField",
    "ElevationTable",
    "IndexField",
    "IoError",
    "LinearSquaredProfile",
    "LogisticProfile",
    "NumericalError",
    "PhysicalAtmosphere",
    "RayBatch",
    "RayPath",
    "RenderOptions",
    "Scene",
    "SceneFile",
    "SweepError",
    "SweepFailure",
    "SweepResult",
    "TemperatureProfile",
    "air_dispersion_scale",
    "dispersed_field",
    "field_reference_wavelength",
    "io",
    "lights",
    "shading",
    "spectrum",
    "testing",
    "load_scene",
    "render",
    "render_raster",
    "sweep",
    "trace_ray",
    "trace_rays",
]
