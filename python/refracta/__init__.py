"""refracta: physically based mirages -- curved light rays through air of varying refractive index.

Fields (n(x) and grad n): LogisticProfile, PhysicalAtmosphere, TemperatureProfile,
LinearSquaredProfile, CustomField. Rays: trace_ray (one RayPath), trace_rays (a batch, in
parallel). Plots: refracta.plot. Units: metres, kelvin, pascal, nanometres; y is up.
"""

from refracta._core import (
    CustomField,
    IndexField,
    IoError,
    LinearSquaredProfile,
    LogisticProfile,
    NumericalError,
    PhysicalAtmosphere,
    RayPath,
    TemperatureProfile,
    trace_ray,
)
from refracta._rays import ElevationTable, RayBatch, trace_rays

__version__ = "0.1.0"

__all__ = [
    "CustomField",
    "ElevationTable",
    "IndexField",
    "IoError",
    "LinearSquaredProfile",
    "LogisticProfile",
    "NumericalError",
    "PhysicalAtmosphere",
    "RayBatch",
    "RayPath",
    "TemperatureProfile",
    "trace_ray",
    "trace_rays",
]
