"""
refracta's C++ core (private; use the refracta package)
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import os
import typing
__all__: list[str] = ['AerialPerspective', 'AreaLight', 'Beckmann', 'BlinnPhong', 'BsdfSample', 'Camera', 'Conductor', 'ConstantEnvironment', 'CurvedEarth', 'CustomField', 'DEFAULT_TURBULENCE_YAW_DEG', 'Dielectric', 'Diffuse', 'DispersedField', 'DisplaySettings', 'EDIT_CAMERA_PARAMETERS', 'ElevationTableOptions', 'EnvironmentLight', 'HotSpot', 'INNER_SCALE_FACTOR', 'IndexField', 'IoError', 'Ior', 'Light', 'LightSampler', 'LinearSquaredProfile', 'LogisticProfile', 'Material', 'MboitSettings', 'MissingFileError', 'MomentShadowSettings', 'NumericalError', 'ObjOptions', 'OceanWaves', 'OitSettings', 'PairOptions', 'PhysicalAtmosphere', 'PhysicalSky', 'Plastic', 'PointLight', 'Principled', 'RasterRenderOptions', 'RasterRenderStats', 'RayPath', 'RenderOptions', 'RenderStats', 'RoughConductor', 'RoughDielectric', 'SPECTRUM_CONSTANT', 'ScaledLight', 'Scene', 'ShadowMapOptions', 'SolveSettings', 'SolveSummary', 'SphereLight', 'SpotLight', 'SunLight', 'TemperatureProfile', 'TerrainShading', 'TextureNotFoundError', 'ThinDielectric', 'ThinFilm', 'TraceOptions', 'TrowbridgeReitz', 'TurbulenceGrid', 'TurbulenceLayer', 'TurbulenceSettings', 'Water', 'air_dispersion_scale', 'bessel_j1', 'cox_munk_mean_square_slope', 'dispersed_field', 'field_reference_wavelength', 'fresnel_conductor', 'fresnel_dielectric', 'fresnel_diffuse_reflectance', 'get_threads', 'physical_memory_bytes', 'set_threads', 'synthesise_turbulence', 'thin_film_reflectance', 'trace_ray', 'turbulence_memory_needed', 'von_karman_spectrum', 'water_absorption', 'water_backscattering', 'water_body_reflectance', 'water_density', 'water_ior']
class NumericalError(RuntimeError):
    pass
class IoError(OSError):
    pass
class MissingFileError(IoError, FileNotFoundError):
    """
    A file that is not there: a refracta.IoError and a FileNotFoundError.
    """
class HotSpot:
    """
    An areal hot (dt > 0) or cold (dt < 0) patch of ground centred at (x, z) [m]: the air above it is
    warmer by dt * exp(-h / depth) * F(r), r the horizontal distance from the centre, with footprint
    'gaussian' F = exp(-r^2 / (2 radius^2)) or 'compact' F = (1 - r/R)^4 (4 r/R + 1) for r < R = radius
    (Wendland's C2 function: exactly zero outside). Give it to PhysicalAtmosphere(hot_spots=[...]) (dt
    [K]; depth [m], None: the atmosphere's surface_depth as the field is made) or
    LogisticProfile(hot_spots=[...]) (dt: strength of the profile's hot-spot term there, 1 = the whole
    term; depth must be None: the term's width is a_hot). The fields expose each spot's numbers as
    parameters hot_spot<i>_x, _z, _radius, _dt (, _depth), so refracta.edit.solve can move, resize and
    heat them; a spot's depth is then its own parameter, which with_params or a solve of surface_depth
    leaves where it is (change hot_spot<i>_depth with it to move both).
    """
    def __eq__(self, arg0: HotSpot) -> bool:
        ...
    def __getstate__(self) -> tuple:
        ...
    def __hash__(self) -> int:
        ...
    def __init__(self, x: typing.SupportsFloat | typing.SupportsIndex, z: typing.SupportsFloat | typing.SupportsIndex, radius: typing.SupportsFloat | typing.SupportsIndex, dt: typing.SupportsFloat | typing.SupportsIndex, depth: typing.SupportsFloat | typing.SupportsIndex | None = None, footprint: str = 'gaussian') -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def depth(self) -> float | None:
        ...
    @property
    def dt(self) -> float:
        ...
    @property
    def footprint(self) -> str:
        ...
    @property
    def radius(self) -> float:
        ...
    @property
    def reach(self) -> float:
        """
        Distance [m] beyond which the footprint is below 1e-6 (compact: exactly 0).
        """
    @property
    def x(self) -> float:
        ...
    @property
    def z(self) -> float:
        ...
class TurbulenceSettings:
    """
    The settings of a turbulence pattern and its placement (refracta.Turbulence), with the hot road's
    defaults (defined once, here, with their reasons). validate() reports every bad value at once, and a
    grid too large for max_bytes. Pickles through its fields.
    """
    __hash__: typing.ClassVar[None] = None
    @staticmethod
    def from_fields(**kwargs) -> TurbulenceSettings:
        """
        Settings with the given fields set (the rest at their defaults), validated.
        """
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def cell_count(self) -> int:
        """
        N: cells, or from size and spacing, or 256.
        """
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def cells(self) -> int | None:
        """
        N (the grid is N^3, one period N * spacing wide), or size [m] (N = ceil(size / spacing)); unset
        both: 256, whose inertial range spans over a decade (x16 within 15 %), where 128 reaches x8. (default: None)
        """
    @cells.setter
    def cells(self, arg0: typing.SupportsInt | typing.SupportsIndex | None) -> None:
        ...
    @property
    def cn2(self) -> float:
        """
        C_n^2 [m^(-2/3)] at the ground, >= 0 (the pattern is weighted by E(h): C_n^2(h) = cn2 E(h)^2).
        1e-10: within centimetres of sun-heated asphalt (C_n^2 ~ 1e-13..1e-12 at 1-2 m in daytime, Andrews &
        Phillips 2005 ch. 12, rising as h^(-4/3) toward the ground in free convection, Wyngaard et al.
        1971). (default: 1e-10)
        """
    @cn2.setter
    def cn2(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def depth(self) -> float | None:
        """
        The height envelope E(h) = e^(-h/depth) [m]; unset (None): uniform. 0.1 m: the examples' surface
        layer. (default: 0.1)
        """
    @depth.setter
    def depth(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def inner_scale(self) -> float:
        """
        The inner scale l0 [m]: the Gaussian cutoff kappa_m = 5.92 / l0; 5 mm near hot ground. (default: 0.005)
        """
    @inner_scale.setter
    def inner_scale(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_bytes(self) -> float | None:
        """
        The largest FFT work arrays allowed [bytes] (a grid needing more is refused); unset (None): half
        this machine's memory (inf: no limit). (default: None)
        """
    @max_bytes.setter
    def max_bytes(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def outer_scale(self) -> float:
        """
        The von Karman outer scale L0 [m]; inf: the periodic tile is the outer scale, which keeps the widest
        inertial range. (default: inf)
        """
    @outer_scale.setter
    def outer_scale(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def seed(self) -> int:
        """
        the random pattern (same seed and grid, same pattern) (default: 0)
        """
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def size(self) -> float | None:
        """
        [m] the tile, cells = ceil(size / spacing) (None: from cells) (default: None)
        """
    @size.setter
    def size(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def spacing(self) -> float:
        """
        The grid's cell [m], in [1e-6, 1e4]: the renderer steps half a cell through the layer, so a pixel's
        cost grows as path length / spacing (benchmarks/bench_realism.py). (default: 0.05)
        """
    @spacing.setter
    def spacing(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def wind(self) -> tuple[float, float]:
        """
        (u, w) [m/s] along x and z: the pattern at time t is shifted by (u t, 0, w t) (Taylor's frozen
        flow). (0, 2): a light breeze across the examples' line of sight (+x). (default: (0.0, 2.0))
        """
    @wind.setter
    def wind(self, arg1: typing.Any) -> None:
        ...
    @property
    def yaw_deg(self) -> float:
        """
        The lattice's turn about the vertical [deg], as every angle users give
        (default_turbulence_yaw_deg()); turbulence_layer turns it into the layer's radians, the one
        conversion. (default: 31.71747441146101)
        """
    @yaw_deg.setter
    def yaw_deg(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class TurbulenceGrid:
    """
    A periodic uniform cubic B-spline over an nx x ny x nz grid (index (i ny + j) nz + k, x = axis 0, y
    up = axis 1, z = axis 2) of cells `spacing` [m] wide; one period is nx * spacing along x, etc. In
    Python TurbulenceGrid(coefficients (nx, ny, nz) float32, spacing [m]), built by refracta.Turbulence;
    evaluate(points) gives the spline's values and gradients (for tests and plots).
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, coefficients: typing.Any, spacing: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def evaluate(self, points: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
        """
        (values (N,), gradients (N, 3) [1/m]) at points (N, 3) [m].
        """
    @property
    def bound(self) -> float:
        """
        max |coefficient|: a bound of |values|.
        """
    @property
    def coefficients(self) -> numpy.ndarray:
        ...
    @property
    def shape(self) -> tuple[int, int, int]:
        ...
    @property
    def spacing(self) -> float:
        ...
class TurbulenceLayer:
    """
    A grid placed in the air (Python's TurbulenceLayer): delta_n = scale * E(h) * grid(R_yaw (p -
    offset)), E(h) = e^(-h/depth) above the ground (none for depth = inf): scaled, shifted by the wind,
    the lattice turned by yaw [rad] about the vertical (the layer's internal unit: refracta.Turbulence
    takes yaw_deg [deg]). Made by refracta.Turbulence (its `layer`).
    """
    @staticmethod
    def of(settings: TurbulenceSettings, grid: TurbulenceGrid, time: typing.SupportsFloat | typing.SupportsIndex) -> TurbulenceLayer:
        """
        The layer of `settings` over `grid`: scaled by sqrt(cn2), carried by the wind to time [s].
        """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, grid: TurbulenceGrid, scale: typing.SupportsFloat | typing.SupportsIndex, offset: typing.Any, depth: typing.SupportsFloat | typing.SupportsIndex, yaw: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def evaluate(self, points: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
        """
        (delta_n (N,), its gradient (N, 3) [1/m]) at points (N, 3) [m].
        """
    @property
    def depth(self) -> float:
        ...
    @property
    def grid(self) -> TurbulenceGrid:
        ...
    @property
    def offset(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def scale(self) -> float:
        ...
    @property
    def yaw(self) -> float:
        """
        The lattice's turn about the vertical [rad].
        """
class _TurbulenceSpectrum:
    def __init__(self, cells: typing.SupportsInt | typing.SupportsIndex, spacing: typing.SupportsFloat | typing.SupportsIndex, inner_scale: typing.SupportsFloat | typing.SupportsIndex, outer_scale: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def variances(self, i: typing.SupportsInt | typing.SupportsIndex, j: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex], k: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex]) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        sigma^2 at lattice indices (i, j[a], k[b]) as a (len(j), len(k)) array (C_n^2 = 1).
        """
class IndexField:
    """
    A refractive-index field n(x). Points are (N, 3) or (3,) float arrays in metres, y up.
    
    ior(points) -> n, shape (N,) (float for one point); grad_ior(points) -> grad n [1/m], (N, 3).
    params: dict of parameter values; param_names; bounds: dict name -> (lower, upper), the box an
    optimiser searches; ``with_params(**values)`` -> a new field; height_only: n depends on y alone;
    gauge_params: parameters an optimiser holds fixed by default (a joint scaling leaves rays
    unchanged). Raises refracta.NumericalError where n <= 0 or is not finite.
    """
    def __repr__(self) -> str:
        ...
    def grad_ior(self, points: typing.Any) -> typing.Any:
        """
        Gradient of n [1/m] at points (N, 3) -> (N, 3).
        """
    def ior(self, points: typing.Any) -> typing.Any:
        """
        Refractive index at points (N, 3) -> (N,).
        """
    def with_params(self, *args, **kwargs) -> IndexField:
        """
        A new field of the same model with the given parameters changed.
        """
    def with_turbulence(self, turbulence: typing.Any) -> IndexField:
        """
        The same air (parameters, hot spots) with `turbulence` (a refracta.Turbulence, a TurbulenceLayer, or None: calm) in place of its own; PhysicalAtmosphere and LogisticProfile (ValueError for other fields).
        """
    @property
    def bounds(self) -> dict:
        """
        Each parameter's (low, high) bounds by name, as edit.solve keeps them (a new dict at each access).
        """
    @property
    def earth_radius(self) -> float:
        """
        The radius [m] of the spherical Earth whose coordinates this field flattens (CurvedEarth's radius; inf: a flat-Earth field).
        """
    @property
    def gauge_params(self) -> list[str]:
        ...
    @property
    def height_only(self) -> bool:
        ...
    @property
    def height_only_part(self) -> IndexField:
        """
        A field that depends on height alone except in local regions (hot spots): the height-only field that holds outside them; None for other fields.
        """
    @property
    def local_regions(self) -> list:
        """
        Where the field differs from height_only_part: vertical cylinders (x, z, radius [m]) below `top` [m]; `scale` [m]: the feature's horizontal size.
        """
    @property
    def param_info(self) -> list:
        """
        One dict per parameter: name, default, lower, upper, unit, doc.
        """
    @property
    def param_names(self) -> list[str]:
        ...
    @property
    def params(self) -> dict:
        """
        The parameters' values by name: a new dict at each access, so changing it changes no field;
        field.with_params(name=value) makes a field with new values.
        """
    @property
    def type_name(self) -> str:
        ...
class LogisticProfile(IndexField):
    """
    The original mirage editor's height profile (Choi 2017), in scene units::
    
        n(h) = 1 + 0.003 k_s (f(n_bg, 10 a_bg, 0, h) + f(n_inv, -0.1 a_inv, h_ciso, h)
               + f(n_hot, 0.3 a_hot, 0, h)) / (|n_bg| + |n_inv| + |n_hot|)
        f(L, w, x0, x) = L / (1 + e^((x0 - x) / w))
    
    Scaling n_bg, n_inv, n_hot together changes nothing (gauge freedom): editing fixes n_bg by default.
    hot_spots=[refracta.HotSpot(x, z, radius, strength), ...] localise the hot term: its deficit near
    the ground, n_hot * sigma(-h / (0.3 a_hot)), is scaled by sum_i dt_i F_i(r_i), so the hot layer lies
    only over the spots (parameters hot_spot<i>_x, _z, _radius, _dt).
    
    Parameters (name [unit] default, optimiser bounds: meaning):
        n_bg [1] 3, [-10, 10]: background amplitude
        n_inv [1] 0.1, [-10, 10]: inversion-layer amplitude
        n_hot [1] 0.1, [-10, 10]: hot-spot amplitude
        h_ciso [scene units] 1, [-10, 100]: height of the inversion layer
        a_bg [1] 1, [0.01, 100]: background width (logistic width 10 a_bg)
        a_inv [1] 1, [0.01, 100]: inversion width (logistic width 0.1 a_inv)
        a_hot [1] 1, [0.01, 100]: hot-spot width (logistic width 0.3 a_hot)
        k_s [1] 10, [-300, 300]: overall strength: n - 1 reaches 0.003 k_s
    
    The optimiser bounds are where edit.solve searches; the model itself takes any physical value (a value it refuses is named).
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, n_bg: float = 3.0, n_inv: float = 0.1, n_hot: float = 0.1, h_ciso: float = 1.0, a_bg: float = 1.0, a_inv: float = 1.0, *, a_hot: float = 1.0, k_s: float = 10.0, hot_spots: HotSpot | collections.abc.Sequence[HotSpot] | None = None, turbulence: typing.Any = None) -> None:
        """
        The first 6 parameters by position or name, the rest by name; see the class for units and bounds.
        """
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def hot_spots(self) -> list[HotSpot]:
        """
        The hot spots with their current parameter values (a list of HotSpot).
        """
    @property
    def turbulence(self) -> TurbulenceLayer:
        """
        The TurbulenceLayer this air carries (None: calm).
        """
class LinearSquaredProfile(IndexField):
    """
    n^2 = n0^2 + alpha y: rays are parabolas y = y0 + t0 x + alpha x^2 / (4 beta^2), beta = n(y0)
    cos(e0).
    
    Parameters (name [unit] default, optimiser bounds: meaning):
        n0 [1] 1.000277, [0.5, 3]: index at y = 0
        alpha [1/m] 0, [-0.001, 0.001]: d(n^2)/dy
    
    The optimiser bounds are where edit.solve searches; the model itself takes any physical value (a value it refuses is named).
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, n0: float = 1.000277, alpha: float = 0.0) -> None:
        """
        Parameters in the order above (positional or by name); see the class for units and bounds.
        """
    def __setstate__(self, arg0: tuple) -> None:
        ...
class PhysicalAtmosphere(IndexField):
    """
    Real air: U.S. Standard Atmosphere 1976 temperature (its seven layers to 86 km, geometric heights,
    gravity falling with height) + a smooth inversion layer + a surface layer surface_dt * exp(-h /
    surface_depth) (h >= 0) + areal hot spots (hot_spots=[refracta.HotSpot, ...]), hydrostatic pressure,
    and the index of air from Edlen's formula revised by Birch & Downs (1993/94) at `wavelength`,
    optional relative humidity. The humidity is relative to the local temperature, so warmer air holds
    more vapour: a heated surface layer too, as if the road gave off water (at 50 %, 30 C air over a
    road 15 K warmer, the layer's index step is 7.9 % larger than with the air's vapour pressure carried
    down into it: a trial); a vapour pressure not below the air's is refused. The hydrostatic pressure
    takes dry air's gas constant (1.6 % in dP/dh in saturated air at 30 C, ~0.003 in k). Defaults give n
    - 1 = 2.7784e-4 at the ground (15 C, 101325 Pa, 550 nm). Modelled for heights in [-1000, 86000] m
    (uniform above). With hot spots the field is no longer height-only: its parameters gain
    hot_spot<i>_x, _z, _radius, _dt, _depth (a spot made with depth None takes surface_depth's value
    then, and keeps it when with_params or a solve changes surface_depth), and height_only_part is the
    same air without them.
    
    Parameters (name [unit] default, optimiser bounds: meaning):
        t_ground [K] 288.15, [220, 330]: air temperature at h = 0 without the surface layer (the 1976 layers above shift with it)
        lapse_rate [K/m] 0.0065, [-0.02, 0.02]: tropospheric dT/dh is -lapse_rate
        pressure [Pa] 101325, [50000, 110000]: pressure at h = 0
        inversion_dt [K] 0, [-30, 30]: temperature rise across the inversion layer
        inversion_base [m] 100, [-100, 5000]: bottom of the inversion layer
        inversion_thickness [m] 10, [0.1, 2000]: thickness of the inversion layer
        surface_dt [K] 0, [-30, 60]: surface-layer excess temperature at h = 0
        surface_depth [m] 0.1, [0.005, 10]: e-folding depth of the surface layer
        humidity [1] 0, [0, 1]: relative humidity
        wavelength [nm] 550, [380, 780]: vacuum wavelength
    
    The optimiser bounds are where edit.solve searches; the model itself takes any physical value (a value it refuses is named).
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, t_ground: float = 288.15, lapse_rate: float = 0.0065, pressure: float = 101325.0, inversion_dt: float = 0.0, inversion_base: float = 100.0, inversion_thickness: float = 10.0, *, surface_dt: float = 0.0, surface_depth: float = 0.1, humidity: float = 0.0, wavelength: float = 550.0, hot_spots: HotSpot | collections.abc.Sequence[HotSpot] | None = None, turbulence: typing.Any = None) -> None:
        """
        The first 6 parameters by position or name, the rest by name; see the class for units and bounds.
        """
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def pressure(self, heights: typing.Any) -> typing.Any:
        """
        Hydrostatic pressure [Pa] at the given heights [m].
        """
    def temperature(self, heights: typing.Any) -> typing.Any:
        """
        Air temperature [K] at the given heights [m] (scalar or 1-D array).
        """
    @property
    def hot_spots(self) -> list[HotSpot]:
        """
        The hot spots with their current parameter values (a list of HotSpot).
        """
    @property
    def turbulence(self) -> TurbulenceLayer:
        """
        The TurbulenceLayer this air carries (None: calm).
        """
class TemperatureProfile(IndexField):
    """
    A measured sounding: temperatures [K] at strictly increasing heights [m], joined by a monotone C1
    cubic (pchip) and levelling off smoothly beyond the ends, as T_end + s w tanh(dh / w) (s: the end
    slope, w: the end interval): up to one more interval's worth of the end gradient (a coarse top
    interval of 10 K over 10 m goes on to ~10 K more; add a level where the air is known to turn);
    hydrostatic pressure from `pressure` [Pa] at the lowest height; n from the same air formula as
    PhysicalAtmosphere. The temperatures are the parameters t0, t1, ... (with pressure, humidity,
    wavelength).
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, heights: typing.Any, temperatures: typing.Any, pressure: typing.SupportsFloat | typing.SupportsIndex = 101325.0, humidity: typing.SupportsFloat | typing.SupportsIndex = 0.0, wavelength: typing.SupportsFloat | typing.SupportsIndex = 550.0) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def pressure(self, heights: typing.Any) -> typing.Any:
        """
        Hydrostatic pressure [Pa] at the given heights [m].
        """
    def temperature(self, heights: typing.Any) -> typing.Any:
        """
        Air temperature [K] at the given heights [m] (scalar or 1-D array).
        """
    @property
    def heights(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
class CurvedEarth(IndexField):
    """
    A height-only atmosphere over a spherical Earth, in flat coordinates (conformal Earth-flattening
    transform): x' = distance along the surface, y' = R ln(r/R), n' = n(h) e^(y'/R). Exact for rays in
    their vertical plane; scene heights y' differ from true heights by h^2/(2R) (0.8 mm at 100 m):
    true_height(y') and flat_height(h) convert. Use it for anything seen over kilometres (horizons,
    looming, Fata Morgana).
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, base: IndexField, radius: typing.SupportsFloat | typing.SupportsIndex = 6371000.0) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def flat_height(self, h: typing.Any) -> typing.Any:
        """
        Flat-frame height y' of true heights h [m].
        """
    def true_height(self, y: typing.Any) -> typing.Any:
        """
        True height h [m] of flat-frame heights y'.
        """
    @property
    def base(self) -> IndexField:
        ...
    @property
    def radius(self) -> float:
        ...
class CustomField(IndexField):
    """
    A field written in Python: ior(points (N,3)) -> (N,) and grad_ior(points (N,3)) -> (N,3), both
    vectorised. height_only=True promises n depends on y alone (enables method='stratified').
    Slow: the integrators call back into Python at every evaluation. Its first evaluation checks it
    there: height_only=True against n and grad_ior 1 m aside (ValueError if either changes), and
    grad_ior against ior's central differences 1 mm apart (a RuntimeWarning beyond 1e-3 of it).
    A field whose callables refer back to it (methods of an object holding it) is garbage-collected
    while Python alone holds it; one a CurvedEarth, scene or other field also holds stays alive with
    its callables, so a cycle through that holder too is kept until the holder is dropped.
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, ior: typing.Any, grad_ior: typing.Any, height_only: bool = False) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def grad_function(self) -> typing.Any:
        ...
    @property
    def ior_function(self) -> typing.Any:
        ...
class RayPath:
    """
    A traced light path. Arrays are per node (the integrator's steps; the path between nodes is the
    quintic Hermite interpolant of positions, tangents and curvatures, accurate to O(step^6)).
    
    points (N,3) [m]; directions (N,3) unit tangents; arc_length (N,) [m]; ior (N,) n at each node;
    ray_vectors (N,3) the integrated v (``|v| = n``); stop: why the path ended ('max_length',
    'stop_height'); evaluations: field evaluations used.
    """
    def __getstate__(self) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 11]"], int, int]:
        ...
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple[typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 11]"], typing.SupportsInt | typing.SupportsIndex, typing.SupportsInt | typing.SupportsIndex]) -> None:
        ...
    def at_height(self, y: typing.SupportsFloat | typing.SupportsIndex) -> numpy.typing.NDArray[numpy.float64]:
        """
        Every point where the path crosses height y [m], in path order, (K, 3).
        """
    def closest_point(self, q: typing.Any) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], float, float]:
        """
        (point, distance, s): the point of the continuous path closest to q (within 1e7 m of the origin), its distance [m] and its arc length [m].
        """
    def crossings(self, normal: typing.Any, offset: typing.SupportsFloat | typing.SupportsIndex) -> list[tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], float, typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]]]:
        """
        Crossings of the plane normal . x = offset: a list of (point, s, unit direction).
        """
    def point_at(self, s: typing.SupportsFloat | typing.SupportsIndex) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]]:
        """
        (point, unit tangent) at arc length s [m] on the continuous path.
        """
    def sample(self, count: typing.SupportsInt | typing.SupportsIndex = 200) -> numpy.typing.NDArray[numpy.float64]:
        """
        count points (count, 3) evenly spaced in arc length on the continuous path.
        """
    @property
    def arc_length(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def directions(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def evaluations(self) -> int:
        ...
    @property
    def ior(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def length(self) -> float:
        """
        Arc length of the whole path [m].
        """
    @property
    def points(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def ray_vectors(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def stop(self) -> str:
        ...
class TraceOptions:
    """
    Options of refracta.trace_ray and trace_rays, with their defaults (defined once, here). Set any
    field by name; validate() reports every bad value at once. Pickles through its fields.
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def ior_floor(self) -> float | None:
        """
        stratified: a lower bound of n over every height the path can reach (None: unknown). A ray
        whose invariant beta = n cos e stays clearly below it can never turn, so its heights are not scanned
        metre by metre for turning points (a path climbing 100 km: 70 000 nodes, else ~1 000). (default: None)
        """
    @ior_floor.setter
    def ior_floor(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def max_length(self) -> float:
        """
        arc length at which the path ends [m] (default: 1000.0)
        """
    @max_length.setter
    def max_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_steps(self) -> int:
        """
        A guard against runaway step-size collapse: a path needing more steps is refused up front. (default: 10000000)
        """
    @max_steps.setter
    def max_steps(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def step(self) -> float:
        """
        [m] rk4: the fixed step (0: 0.3 m, the original editor's); rk45: the largest step (0: none); stratified: the largest node spacing (0: 100 m) (default: 0.0)
        """
    @step.setter
    def step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def stop_height(self) -> float | None:
        """
        The path ends where it descends through this height [m] (a ground); unset (None): no ground. (default: None)
        """
    @stop_height.setter
    def stop_height(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def tol(self) -> float:
        """
        rk45 and stratified: target error of positions along the path [m]. rk45 holds each step's local
        error to its share of it, which in smooth air keeps the global error within tol (measured 0.002-0.5
        tol); a thin hot layer or a duct amplifies errors (a trial: 10x tol at 1e-4 over 30 km in a duct,
        1.6x at 1e-5), and at a tol near the layer's own scale (1e-2 m and looser over a 0.1 m road layer) a
        step can cross the layer unseen: keep tol well below the thinnest layer. stratified meets tol down
        to about 1e-11 of max_length, its floor. (default: 1e-06)
        """
    @tol.setter
    def tol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def trace(self) -> str:
        """
        the integrator: 'rk45' (adaptive Dormand-Prince; tol is the target position error [m] over the path), 'rk4' (fixed step `step`), or 'stratified' (height-only fields: exact paths from n(h) cos(e) = const by quadrature to tol; `step` is the largest node spacing) (default: 'rk45')
        """
    @trace.setter
    def trace(self, arg1: str) -> None:
        ...
class ElevationTableOptions:
    """
    Options of refracta.ElevationTable beside its eye height and elevation range, with their defaults
    (defined once, here). `trace` holds the exact traces' TraceOptions (their integrator is always
    'stratified'; their tol is trace_tol, or tol when None). Pickles through its fields.
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def initial_rays(self) -> int:
        """
        exact traces before refining (default: 65)
        """
    @initial_rays.setter
    def initial_rays(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_rays(self) -> int:
        """
        Beyond this many exact traces, unresolved intervals stay exact (traced exactly per query). (default: 200000)
        """
    @max_rays.setter
    def max_rays(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def tol(self) -> float:
        """
        interpolation tolerance along the whole path [m] (renders add angular_tol) (default: 0.001)
        """
    @tol.setter
    def tol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def trace(self) -> TraceOptions:
        """
        TraceOptions of the exact traces (max_length, stop_height, step): their integrator is forced to
        stratified, and their tol is trace_tol, or the table's tol when unset (the traces then as accurate
        as the interpolation asks). (default: TraceOptions(ior_floor=None, max_length=1000.0, max_steps=10000000, step=0.0, stop_height=None, tol=1e-06, trace='rk45'))
        """
    @trace.setter
    def trace(self, arg0: TraceOptions) -> None:
        ...
    @property
    def trace_tol(self) -> float | None:
        """
        the exact traces' tolerance [m]; unset (None): tol (default: None)
        """
    @trace_tol.setter
    def trace_tol(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
class _ElevationTable:
    def __init__(self, field: IndexField, eye_height: typing.SupportsFloat | typing.SupportsIndex, min_elevation: typing.SupportsFloat | typing.SupportsIndex, max_elevation: typing.SupportsFloat | typing.SupportsIndex, options: typing.Any, progress: typing.Any, **kwargs) -> None:
        ...
    def _ends(self, elevations: typing.Any, azimuths: typing.Any) -> tuple:
        """
        (points, directions, lengths, stops, evaluations) [deg].
        """
    @property
    def elevations(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        The traced elevations [deg].
        """
    @property
    def evaluations(self) -> int:
        """
        Field evaluations spent building the table.
        """
    @property
    def exact_intervals(self) -> int:
        """
        Elevation intervals where queries are traced exactly (unresolved kind changes).
        """
    @property
    def eye_height(self) -> float:
        """
        [m]
        """
    @property
    def options(self) -> ElevationTableOptions:
        """
        The options the table was built with (a copy), as a caller gives them: without the build's cancel
        flag and the ior_floor the table found from its field.
        """
    @property
    def size(self) -> int:
        """
        Number of exactly traced elevations.
        """
    @property
    def tol(self) -> float:
        """
        The interpolation tolerance [m].
        """
class TextureNotFoundError(MissingFileError):
    """
    A texture an MTL file names is in none of the folders searched (a refracta.IoError and a FileNotFoundError).
    """
class ObjOptions:
    """
    How add_obj (Scene.add_obj) places an OBJ file and finds its textures.
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def missing_textures(self) -> str:
        """
        'error' (raise refracta.TextureNotFoundError) or 'warn' (a UserWarning once per texture name,
        through the `warn` callback; the material keeps Kd) (default: 'error')
        """
    @missing_textures.setter
    def missing_textures(self, arg1: str) -> None:
        ...
    @property
    def offset(self) -> tuple[float, float, float]:
        """
        [m] added to every vertex after scaling (default: (0.0, 0.0, 0.0))
        """
    @offset.setter
    def offset(self, arg1: typing.Any) -> None:
        ...
    @property
    def scale(self) -> float:
        """
        every vertex is multiplied by this (> 0), then offset (default: 1.0)
        """
    @scale.setter
    def scale(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def texture_dirs(self) -> list[str]:
        """
        folders searched, in order, after the MTL's own for each map_Kd and map_d (one folder or a sequence) (default: [])
        """
    @texture_dirs.setter
    def texture_dirs(self, arg1: typing.Any) -> None:
        ...
class Scene:
    """
    Geometry (Embree), materials (refracta.shading) and lights. Scene() starts empty: no sun, no sky,
    black. Every add_* takes material= (any refracta.shading material); without it the Blinn-Phong
    shorthand kd (diffuse albedo, RGB in [0, 1]), ks (specular albedo), ns (Phong exponent) applies.
    Meshes and spheres with emission= [W/(m^2 sr), RGB] are area lights (one-sided on the triangles'
    counter-clockwise front unless two_sided). Units: metres, y up.
    """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def _add_terrain_grid(self, positions: typing.Annotated[numpy.typing.ArrayLike, numpy.float32], material: typing.Any, uv_from_index: typing.Annotated[numpy.typing.ArrayLike, numpy.float64]) -> int:
        """
        Terrain as Embree grid geometry (private: use Scene.add_terrain). positions: (rows, cols, 3) [m]
        float32, row-major, rows along +z and columns along +x so the front is up; a sample with a NaN
        coordinate is a hole. uv_from_index (2, 3): (u, v) = A (col, row, 1). Returns the geometry id.
        """
    def _dark_enclosure(self, eye: typing.Any) -> int | None:
        """
        The geometry that keeps every light from `eye`, if one does: every light of the scene is at infinity
        (sun, sky, environment) and one opaque geometry lies around the eye (256 rays spread over the sphere
        each cross it an odd number of times; a material that transmits, water or glass, is seen through,
        and a ray through an opening finds none). No surface in view is then lit: render()'s "camera inside
        an object" hint (a trial's eye 1 mm up inside the hot road's 2 mm road slab). A room lit from
        within, or a furnace whose walls glow, has a light that is not at infinity, and is no mistake; an
        opening narrower than the rays' spacing (~0.2 rad) can be missed.
        """
    def add_billboard(self, centre: typing.Any, width: typing.SupportsFloat | typing.SupportsIndex, height: typing.SupportsFloat | typing.SupportsIndex, texture: os.PathLike | str | bytes, facing: typing.Any = (-1.0, 0.0, 0.0), kd: typing.Any = None) -> int:
        """
        Add a vertical textured rectangle (a photo standing in the scene: a ship, a building) centred at
        `centre`, width x height [m], its picture facing `facing` (default -x, toward a camera on the -x
        side), upright; kd (default 1: the picture's own colours) multiplies the texture. Where the picture
        has alpha (an RGBA or grey-alpha image) it is a cut-out: rays and shadows pass through its clear
        parts (a ray meets a point of alpha a with probability a; render_raster draws where a >= 1/2).
        """
    def add_box(self, centre: typing.Any, size: typing.Any, material: typing.Any = None, emission: typing.Any = None, *, kd: typing.Any = None, ks: typing.Any = None, ns: typing.Any = None, alpha: typing.Any = None) -> int:
        """
        Add an axis-aligned box (faces outward): centre (3,) and size (3,) [m]. Without `material`, the
        kd/ks/ns/alpha shorthand: BlinnPhong(kd (default 0.5 grey), ks (default 0), ns (default 1), alpha
        (default 1; < 1: transparent in render_raster)).
        """
    def add_ground(self, height: typing.SupportsFloat | typing.SupportsIndex = 0.0, size: typing.SupportsFloat | typing.SupportsIndex = 20000.0, material: typing.Any = None, kd: typing.Any = None, ks: typing.Any = None, ns: typing.Any = None, *, texture: os.PathLike | str | bytes | None = None, texture_size: typing.SupportsFloat | typing.SupportsIndex | None = None) -> int:
        """
        Add a square ground of side `size` [m] at y = height, centred on the origin, facing up. Without
        `material`, the kd/ks/ns shorthand (BlinnPhong; kd default 0.3 grey) and a texture multiplying kd; a
        texture (or a textured material's) repeats every texture_size [m] (u along +x, v along -z;
        None: 1 m).
        """
    @typing.overload
    def add_light(self, light: ...) -> int:
        """
        Add a refracta.lights light (not area lights: their geometry takes emission=). Returns its index.
        """
    @typing.overload
    def add_light(self, light: ...) -> int:
        """
        Add a refracta.spectrum.PhysicalSky (as Scene.lights gives it). Returns its index.
        """
    def add_mesh(self, vertices: typing.Any, triangles: typing.Any, material: typing.Any = None, emission: typing.Any = None, two_sided: bool = False, normals: typing.Any = None, *, uvs: typing.Any = None, kd: typing.Any = None, ks: typing.Any = None, ns: typing.Any = None, texture: os.PathLike | str | bytes | None = None, alpha: typing.Any = None) -> int:
        """
        Add a triangle mesh: vertices (N, 3) [m], triangles (M, 3) indices (front: counter-clockwise);
        optional per-vertex normals (N, 3) (shading normals, interpolated; any length but 0) and uvs (N, 2)
        texture coordinates (u right, v up); emission makes it an area light. Without `material`, the
        kd/ks/ns/alpha shorthand: BlinnPhong(kd (default 0.5 grey), ks (default 0), ns (default 1), alpha
        (default 1; < 1: transparent in render_raster)). A texture (an image file) multiplies kd. A light
        reflects by its material too (as pbrt-v4's area lights do; Mitsuba 3's emitters are black unless
        given a BSDF): material=Diffuse(0.0) for a black lamp. Returns its id.
        """
    def add_obj(self, path: os.PathLike | str | bytes, offset: typing.Any = None, scale: typing.Any = None, *, options: typing.Any = None, texture_dirs: typing.Any = None, missing_textures: typing.Any = None, progress: typing.Any = True) -> list[int]:
        """
        Add a Wavefront OBJ file with its MTL materials, scaled then offset.
        
        The settings are a refracta.ObjOptions (``options``; None: its defaults) changed by the keywords
        offset, scale, texture_dirs and missing_textures (None: left as they are).
        
        Kd, Ks, Ns, d, map_Kd become BlinnPhong; Pr/Pm (PBR extension) Principled; illum 4/6/7 with d < 1
        and Ni > 1 Dielectric(Ni); Ke an area light. Vertex normals are kept as shading normals. map_d is a
        cut-out mask (its alpha channel, else its first; Scene::set_cutout): leaves and fences on cards,
        clear where the mask is 0. A grey mask is data, read as stored (its 128 of 255 is opacity 0.502); a
        map_d found nowhere is a missing texture.
        
        A texture the MTL names (map_Kd) is looked for in the MTL's folder, then in each of ``texture_dirs``
        in order (relative folders from the working directory), as written and by its file name alone (a
        path from the author's machine). A texture found nowhere raises refracta.TextureNotFoundError (a
        refracta.IoError and a FileNotFoundError) naming it and the folders searched
        (``missing_textures='error'``), or, with ``missing_textures='warn'``, issues a UserWarning (Python's
        warnings) and its material uses Kd.
        
        Each texture is prepared once (MIP-mapped, linear) into the texture cache folder
        ($REFRACTA_TEXTURE_CACHE, else refracta-textures in the temporary folder); a model with hundreds of
        textures takes seconds the first time. progress: True shows a bar on stderr once preparing has taken
        over a second, a callable gets progress(done, total) textures, False shows nothing.
        
        Returns the geometry ids, one per part. A missing OBJ or MTL raises refracta.IoError.
        """
    def add_point_light(self, position: typing.Any, intensity: typing.Any) -> int:
        """
        Add a point light at `position` [m] of `intensity` [W/sr, RGB] (irradiance I cos / d^2). Returns its
        index.
        """
    def add_sea(self, waves: OceanWaves | None = None, height: typing.SupportsFloat | typing.SupportsIndex = 0.0, size: typing.SupportsFloat | typing.SupportsIndex = 200000.0, material: typing.Any = None, detail_radius: typing.SupportsFloat | typing.SupportsIndex = 50.0, centre: typing.Any = (0.0, 0.0)) -> list[int]:
        """
        Add a sea at y = height with waves near `centre` (x, z) [m] (put it under the camera).
        
        Within detail_radius [m] of centre: the waves (an OceanWaves; default OceanWaves(wind_speed=the
        material's), whose 100 m patch holds a fully developed sea up to ~12 m/s: above, pass
        OceanWaves(wind_speed, patch_size=10 U^2/g), which warns when too small) tiled on a mesh of their
        nodes with shading normals from their slopes; over the outer 30 % of the radius they blend into a
        coarse level, the same sea at a quarter of the resolution (exactly its longer waves) on nodes 4
        cells apart, which reaches 4 detail_radius and fades to flat over its outer 30 %; beyond, a flat
        square of side `size` [m] centred on the origin (as add_ground). The levels meet without a crack.
        (Waves with resolution < 32 have no coarse level.)
        
        material: default shading.Water(wind_speed=waves.wind_speed). With a Water (its wind_speed must
        equal the waves'), every displaced band (per level the full waves, then 3 fade rings) gets a copy
        with resolved_slope_variance set to the mean-square slope its mesh's normals show, so that resolved
        + microfacet = Cox & Munk's total and the statistical roughness grows with distance as the resolved
        slopes fall; the flat plane keeps the full Water. Any other material is used as given everywhere.
        
        Returns the geometry ids: the displaced meshes (fine full waves, its fade rings, coarse full waves,
        its fade rings; empty ones left out), then the flat plane. A null `waves` is set to the default sea
        it made (whose patch_caveat the binding warns with).
        """
    def add_sphere(self, centre: typing.Any, radius: typing.SupportsFloat | typing.SupportsIndex, material: typing.Any = None, emission: typing.Any = None, *, kd: typing.Any = None, ks: typing.Any = None, ns: typing.Any = None) -> int:
        """
        Add a sphere (exact, not tessellated); emission makes it a spherical light (reflecting by its
        material too, as add_mesh's). Without `material`, the kd/ks/ns shorthand: BlinnPhong(kd (default 0.5
        grey), ks (default 0), ns (default 1)). Its shading tangent (an anisotropic material's u, e.g.
        RoughConductor's alpha_u) runs around the +y axis, along the lines of latitude.
        """
    def add_spot_light(self, position: typing.Any, direction: typing.Any, angle: typing.SupportsFloat | typing.SupportsIndex = 60.0, intensity: typing.Any = (100.0, 100.0, 100.0), radius: typing.SupportsFloat | typing.SupportsIndex = 0.0, *, inner_angle: typing.SupportsFloat | typing.SupportsIndex | None = None) -> int:
        """
        Add a spot light at `position` [m] shining along `direction` into a cone of full `angle` [deg] (in
        (0, 360]) with `intensity` [W/sr per channel] (irradiance I cos / d^2); radius > 0 gives
        render_raster's 'embree' reference soft shadows of a disc that size. inner_angle [deg] in (0,
        angle]: a smooth falloff from it to angle (lights.SpotLight's, pbrt-v4's smoothstep); none: a hard
        edge. Returns its index among the spot lights.
        """
    def add_terrain(self, heights, origin = None, spacing = None, material = None, *, frame = None, earth_radius = None, orthophoto = None, water_level = None, water = None) -> TerrainGeometry:
        """
        Add terrain from elevation data to the Scene ``self`` (bound as ``Scene.add_terrain``); see the
            module's docstring.
        
            heights: a (rows, cols) array of heights [m] (NaN: a hole), with ``origin`` (x0, z0) [m] and
            ``spacing`` (dx, dz) [m] > 0 (rows along +z, columns along +x) and, for a curved Earth,
            ``earth_radius`` [m] (or a CurvedEarth); or the path of an SRTM .hgt tile or a GeoTIFF, or a list of them, with
            ``frame`` a :class:`refracta.geo.LocalFrame` placing them.
            material: a refracta.shading material, or None for TerrainShading (elevation, slope, snow line).
            orthophoto: an image file draped over the terrain (a georeferenced GeoTIFF for the file forms).
            water_level: a true height [m]: a water surface (``water``, default refracta.shading.Water)
            over the terrain's extent at that height.
            Returns a :class:`TerrainGeometry` (the geometry ids). Bad input raises ValueError naming the
            argument; a missing file refracta.IoError (ElevationFileNotFoundError, also a
            FileNotFoundError), a FIFO or folder refracta.IoError. Terrain is traced (refracta.render); render_raster
            draws only triangle meshes and does not show it.
            
        """
    def intersect(self, origin: typing.Any, direction: typing.Any) -> typing.Any:
        """
        First hit of a straight ray: (point, distance, geometry id), or None.
        """
    def material(self, geometry: typing.SupportsInt | typing.SupportsIndex) -> ...:
        """
        The material of a geometry (an id returned by add_*), as a refracta.shading object (a material
        with a texture file: the scene's copy, its file registered here).
        """
    def remove(self, geometry: typing.SupportsInt | typing.SupportsIndex) -> None:
        """
        Remove a geometry (an id returned by add_*, e.g. an OBJ's terrain) and the area light it emits.
        The other ids stay valid (a removed id is not reused; geometry_count still counts it); the
        acceleration structure is rebuilt before the next render. Not while a render of this scene runs.
        """
    def set_aerial_perspective(self, enabled: bool) -> None:
        """
        Turn aerial perspective on (from the scene's physical sky; ValueError without one) or off, keeping the sky.
        """
    def set_environment(self, source: typing.Any, rotation: typing.Any = None, scale: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> None:
        """
        The environment (replacing any sky): an RGB radiance (a constant environment), an equirectangular
        map file (EXR/HDR through OpenImageIO as linear radiance; an 8- or 16-bit PNG/JPEG decoded from
        sRGB, as textures are) or a float array of linear radiance, (H, W) grey or (H, W, 1, 3 or 4; alpha
        ignored), times `scale`, turned by `rotation` (degrees about y, or a 3 x 3 matrix). Orientation:
        refracta.lights.EnvironmentLight.
        """
    def set_material(self, geometry: typing.SupportsInt | typing.SupportsIndex, material: typing.Any) -> None:
        """
        Give a geometry (an id returned by add_*, e.g. one part of add_obj) another refracta.shading material.
        Its emission, if any, stays. Not while a render of this scene runs (RuntimeError).
        """
    def set_physical_sky(self, sun_direction: typing.Any, aerosol: typing.SupportsFloat | typing.SupportsIndex | None = None, ozone_du: typing.SupportsFloat | typing.SupportsIndex = 300.0, ground_albedo: typing.SupportsFloat | typing.SupportsIndex = 0.0, sun_angular_diameter: typing.SupportsFloat | typing.SupportsIndex = 0.53, limb_darkening: typing.SupportsFloat | typing.SupportsIndex = 0.0, *, scale: typing.SupportsFloat | typing.SupportsIndex = 1.0, altitude: typing.SupportsFloat | typing.SupportsIndex = 0.0, below_horizon: str = 'horizon', aerial_perspective: bool = True, visibility: typing.SupportsFloat | typing.SupportsIndex | None = None) -> None:
        """
        The physical sky (replacing every environment, sky and sun): refracta.spectrum.PhysicalSky's single
        scattering (Nishita et al. 1993) plus Hillaire 2020's multiple scattering, for the sun toward
        `sun_direction` (normalised, y up), `aerosol` (Mie density scale; None: 1, a clear sky), `ozone_du`
        [Dobson units, at most 10 000; the Earth's column is 100-600], observer `altitude` [m]. Below the
        horizon `below_horizon`: 'horizon' (default) continues the sky from the horizon at each azimuth
        (Scene.set_sky's convention: the ground is geometry, and a ray ending its max_length still heading
        slightly down sees the horizon sky, importance-sampled over the whole sphere); 'ground' shows the
        Lambertian ground of `ground_albedo` (which must be 0 with 'horizon'). And the sun: a disc of
        `sun_angular_diameter` [deg] with linear limb darkening u, its radiance the 5778 K solar spectrum
        through the atmosphere's extinction (reddened toward the horizon; within the horizon's refraction,
        33', below the planet's limb the grazing column's, as the render's curved rays still reach it; none
        further below). Units: spectral radiance W/(m^2 sr nm) in spectral renders, its CIE-Y-weighted mean
        in RGB (linear sRGB of XYZ / integral ybar, as Color.illuminant: times 106.86 nm gives W/(m^2 sr));
        RGB and spectral renders agree. `scale` multiplies sky and sun (e.g. an exposure). Builds the sky's
        table (1-3 s; `build_sky`). aerial_perspective (default True): the same air dims and lights every
        segment the renderers cast (refracta.spectrum.AerialPerspective: transmittance and scattered
        sunlight, the sky's multiple scattering included), so distant objects grey and blue into the sky;
        False keeps surfaces as seen through empty space. visibility [km, at least 0.001]: meteorological
        visibility at the ground (Koschmieder: extinction at 550 nm = 3.912 / V), setting the aerosol in its
        place (give one of them; an aerosol thicker than 1 m of visibility is refused too). The scene's y =
        0 lies `altitude` above the sky's sea level.
        """
    def set_sky(self, horizon: typing.Any = None, zenith: typing.Any = None, environment: os.PathLike | str | bytes | None = None, scale: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> None:
        """
        A sky (replacing any environment): radiance toward the horizon (and below) and straight up, linear
        in the sine of the elevation (zenith default: the horizon's, a constant sky), or an equirectangular
        environment map file (refracta.lights.EnvironmentLight's orientation), times `scale`.
        """
    def set_sun(self, direction: typing.Any, radiance: typing.Any, angular_diameter: typing.SupportsFloat | typing.SupportsIndex = 0.53, limb_darkening: typing.SupportsFloat | typing.SupportsIndex = 0.0, wavelengths: typing.Any = None) -> None:
        """
        The sun (replacing any): direction toward it, disc radiance [W/(m^2 sr), RGB], angular diameter
        [deg], limb darkening u (I(mu) = 1 - u (1 - mu)). Seen through the air along curved rays. With
        wavelengths (M,) [nm, increasing], radiance is a spectrum (M,) [W/(m^2 sr nm)] instead (e.g.
        refracta.spectrum.PhysicalSky(...).sun_radiance(wavelengths): the sun through the air's extinction).
        """
    def terrain_height(self, x: typing.SupportsFloat | typing.SupportsIndex, z: typing.SupportsFloat | typing.SupportsIndex) -> float | None:
        """
        The scene height y [m] of the highest terrain surface (add_terrain's) over scene point (x, z), or
        None where none lies there; other geometry above it is looked through. An eye 1.7 m above the
        ground there, in scene coordinates: Camera((x, scene.terrain_height(x, z) + 1.7, z), ...). Over a
        geo.LocalFrame's curved Earth y is the flat frame's, short of the height above the ellipsoid by
        h^2 / R (3.9 m at 5 000 m) that frame.camera and Camera.geographic take: use
        frame.ground_height(scene, (lat, lon)) there.
        """
    @property
    def aerial_perspective(self) -> typing.Any:
        """
        The scene's refracta.spectrum.AerialPerspective (set_physical_sky(aerial_perspective=True)), or None.
        """
    @property
    def bounds(self) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
        """
        (lower, upper): corners (3,) [m] of the axis-aligned box around every geometry (spheres
        exact; a ground counts at its full size). ValueError for an empty scene.
        """
    @property
    def geometry_count(self) -> int:
        ...
    @property
    def ground_bounds(self) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]] | None:
        """
        (lower, upper) of the scene's ground or sea: its flat horizontal surfaces when they reach outside
        the other geometry or are all it holds, else None (a floor inside a room's walls, a scene of
        objects alone); surfaces that emit light are no ground.
        """
    @property
    def lights(self) -> list[...]:
        """
        The scene's lights. add_light puts its non-area lights into another scene; the air's own light is the scene's, not a light's: there, set_aerial_perspective(True) turns it on from its physical sky.
        """
    @property
    def object_bounds(self) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
        """
        (lower, upper) of the scene's objects, as Camera.framing frames them: flat horizontal surfaces
        (a ground, a sea) count only when there is nothing else. ValueError for an empty scene.
        """
class Camera:
    """
    Pinhole camera. Camera(position, look_at, up=(0, 1, 0), vfov=45, width=640, height=360; one side
    given alone, the other follows that 16:9 shape): vfov is the vertical field of view [deg], from 1e-6
    to under 180. Pixel coordinates (u, v): u right, v down, pixel (i, j) centred at (i + 0.5, j + 0.5).
    A photographer's camera with depth of field: Camera.photographic(..., f_number=) or
    Camera.eye_level(..., f_number=); any camera through a thin lens: with_lens.
    """
    max_side: typing.ClassVar[int] = 16777216
    @staticmethod
    def eye_level(eye: typing.Any, target: typing.Any, eye_height: typing.SupportsFloat | typing.SupportsIndex = 1.6, focal_length_mm: typing.SupportsFloat | typing.SupportsIndex = 50.0, sensor_mm: tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex] = (36.0, 24.0), *, width: typing.SupportsInt | typing.SupportsIndex | None = None, height: typing.SupportsInt | typing.SupportsIndex | None = None, f_number: typing.SupportsFloat | typing.SupportsIndex | None = None, focus_distance: typing.SupportsFloat | typing.SupportsIndex | None = None) -> Camera:
        """
        A photographer's view: standing at ``eye`` (the ground point under the feet [m]) with the lens
        eye_height [m] above it (1.6: a standing adult), the camera level, aimed at the horizon in the
        horizontal direction of ``target`` (the target's own height does not tilt it). Over flat ground the
        horizon runs through the image's centre row, where mirages are: a hot road's "wet" band and the
        inverted images under cars sit just below it (Camera.framing's 45 deg aerial view shows none of
        them). Over a curved Earth the sea horizon dips sqrt(2 h / R) below it (0.041 deg at 1.6 m). Lens,
        sensor, f_number and focus_distance as for Camera.photographic (focus by default at the target's
        horizontal distance). ValueError for an eye height <= 0 or not finite, or a target straight above or
        below the eye:
        
            camera = refracta.Camera.eye_level((0, 0, 0), (0, 0, -200), eye_height=1.6, focal_length_mm=200)
        """
    @staticmethod
    def framing(scene_or_bounds: typing.Any, direction: typing.Any = (-1.0, -0.5, -1.0), vfov: typing.SupportsFloat | typing.SupportsIndex = 45.0, width: typing.SupportsInt | typing.SupportsIndex | None = None, height: typing.SupportsInt | typing.SupportsIndex | None = None, up: typing.Any = (0.0, 1.0, 0.0)) -> Camera:
        """
        A camera that shows a whole scene (or box): it looks along ``direction`` (default: down onto the box
        from its +x, +y, +z side) at the centre of the scene's box, from the distance at which the bounding
        sphere fills the narrower of the two fields of view (the whole box is in the image, touching its
        border only if the box is a cube seen along an axis). A scene's box holds its objects: flat
        horizontal surfaces (add_ground's 20 km square, a water plane) count only when the scene has nothing
        else.
        
            scene.add_obj("city.obj", texture_dirs=["textures"]) camera = refracta.Camera.framing(scene,
            width=800, height=450)
        
        scene_or_bounds: a Scene or (lower, upper) corners (3,) [m]; vfov [deg]. ValueError for an
        empty, non-finite or single-point box.
        """
    @staticmethod
    def geographic(lat, lon, height, azimuth = None, elevation = None, *, target = None, vfov = None, focal_length_mm = None, sensor_mm = None, image_width = None, image_height = None, roll = 0.0, earth_radius = None, **unknown) -> Camera:
        """
        A camera at latitude ``lat``, longitude ``lon`` [deg], ``height`` [m] above the WGS84
            ellipsoid (the eye's height: the ground's height plus the eye above it), looking at ``azimuth``
            [deg clockwise from north] and ``elevation`` [deg above the horizontal] -- or, instead of those
            two, at ``target`` = (lat, lon[, height above the ellipsoid, default 0]): its bearing and its
            elevation with no air (``LocalFrame.aim``; refraction then lifts it a little above the centre).
        
            It sits at the origin of ``refracta.geo.LocalFrame(lat, lon, earth_radius=R)``, at scene
            position (0, R ln(1 + height / R), 0): build the rest of the scene with that frame
            (``to_scene``) and give the same R to CurvedEarth. earth_radius: R [m] (or a CurvedEarth, or
            math.inf for a flat-Earth scene); None: the ellipsoid's radius of curvature along
            ``azimuth``, ``geo.radius_of_curvature(lat, azimuth)`` (issue 20's convention for a
            geographic scene).
        
            Give exactly one of vfov [deg] (the vertical field of view) or focal_length_mm with sensor_mm
            = (width, height) [mm] (Camera.photographic's lens and sensor; None: its full-frame default).
            image_width, image_height [pixels]: the image's size (None: the bound constructor's default;
            named so as not to clash with the eye's height). roll [deg]: the camera turned clockwise about
            its view direction as seen from behind (the image's right side dips), 0 level. For a camera
            elsewhere in an existing frame use ``LocalFrame.camera``. Example::
        
                R = refracta.geo.radius_of_curvature(47.0, 120.0)
                camera = refracta.Camera.geographic(47.0, 8.0, 450.0, 120.0, 0.0, focal_length_mm=300.0,
                                                    image_width=960, image_height=640, earth_radius=R)
                air = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius=R)
            
        """
    @staticmethod
    def photographic(position: typing.Any, look_at: typing.Any, focal_length_mm: typing.SupportsFloat | typing.SupportsIndex, sensor_mm: tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex] = (36.0, 24.0), width: typing.SupportsInt | typing.SupportsIndex | None = None, height: typing.SupportsInt | typing.SupportsIndex | None = None, *, up: typing.Any = (0.0, 1.0, 0.0), f_number: typing.SupportsFloat | typing.SupportsIndex | None = None, focus_distance: typing.SupportsFloat | typing.SupportsIndex | None = None) -> Camera:
        """
        A camera described by its lens and sensor: focal_length_mm on a sensor of sensor_mm = (width,
        height) [mm] (full frame 36 x 24; APS-C about 23.5 x 15.6). The image spans the sensor's width when
        it is relatively wider than the sensor, else its height (a crop of the other side, Blender's "auto"
        sensor fit); vfov follows as 2 atan(h / 2f). A 300 mm telephoto on full frame at 960 x 640 sees 4.58
        deg vertically:
        
            camera = refracta.Camera.photographic((0, 5, 0), (28000, 5, 0), 300.0, width=960, height=640)
        
        position, look_at [m]; up as for Camera.
        
        Depth of field: with f_number N a thin lens of aperture diameter A = f / N, focused at
        focus_distance [m] (None: the distance to look_at); None: a pinhole, everything sharp. A point at
        depth d [m] then blurs to the thin-lens circle of confusion ``c = A f abs(d - d_f) / (d (d_f - f))``
        on the sensor; the image keeps the field of view of focus at infinity (no focus breathing, as
        Blender, Mitsuba and pbrt), so in pixels c (d_f - f) / d_f x width / (sensor width used) [mm]. Each
        pixel sample takes its own lens point; through a field those rays are traced from the lens (not
        served by the eye's table), which costs what table=False costs. Only the ray-traced methods
        ('straight', 'curved') render it. ValueError for a focal length outside [0.1, 100000] mm, a sensor
        side outside [0.1, 2000] mm, an f_number or focus_distance <= 0 or NaN, or a focus_distance without
        an f_number (a pinhole has no focus).
        """
    @staticmethod
    def photographic_vfov(focal_length_mm: typing.SupportsFloat | typing.SupportsIndex, sensor_mm: tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex] = (36.0, 24.0), width: typing.SupportsInt | typing.SupportsIndex = 960, height: typing.SupportsInt | typing.SupportsIndex = 640) -> float:
        """
        The vertical field of view [deg] Camera.photographic gives an image of width x height pixels (the
        image spans the sensor's width when relatively wider than the sensor, else its height).
        """
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        """
        The same view, image size, jitter and lens (what a pickle keeps: their rays are bit-identical).
        """
    def __getstate__(self) -> tuple:
        ...
    def __hash__(self) -> int:
        ...
    def __init__(self, position: typing.Any, look_at: typing.Any, up: typing.Any = (0.0, 1.0, 0.0), vfov: typing.SupportsFloat | typing.SupportsIndex = 45.0, width: typing.SupportsInt | typing.SupportsIndex | None = None, height: typing.SupportsInt | typing.SupportsIndex | None = None) -> None:
        """
        width, height [pixels]: the image, 640 x 360 by default; one given alone, the other follows that
        16:9 shape (square pixels).
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def jittered(self, angles: typing.Any) -> Camera:
        """
        The same camera with every ray turned by small angles [rad] toward the image's right and up: a map
        (height, width, 2) at the pixel centres, bilinear between them (held at the border). Non-physical
        "geometric noise" (the follow-up editor's cheap shimmer); project() ignores it. ValueError for a map
        of another size or with non-finite angles.
        """
    def pick(self, scene: Scene, u: typing.SupportsFloat | typing.SupportsIndex, v: typing.SupportsFloat | typing.SupportsIndex, field: IndexField | None = None, max_length: typing.SupportsFloat | typing.SupportsIndex | None = None) -> typing.Any:
        """
        The scene point [m] seen at film position (u, v) [pixels; a pixel's centre at +0.5; in [0, width]
        x [0, height], else ValueError], or None.
        field=None: along the straight ray of the scene's own frame. With a field: along the path through
        it, at most max_length [m] long (None: as far as scene coordinates go; curved paths by the
        render's default options). Over a CurvedEarth's flat frame the point seen without the air is
        pick(scene, u, v, refracta.without_refraction(field)): the scene's own straight ray would
        cross a flat Earth.
        """
    def project(self, points: typing.Any, earth_radius: typing.SupportsFloat | typing.SupportsIndex = ...) -> typing.Any:
        """
        (u, v, depth) per point (N, 3) through the pinhole; depth [m] along the view axis, <= 0 behind.
        earth_radius [m]: the scene is the flat frame of a CurvedEarth of this radius; the points are
        projected along the true geometry's straight lines, where pick(scene, u, v,
        refracta.without_refraction(field)) finds them (inf: the scene's own straight lines).
        """
    def ray(self, u: typing.Any, v: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
        """
        (origin, unit direction) of the ray through pixel coordinates (u, v), the pixel's corner at its integers (its centre at x + 0.5); u and v numbers, or (N,) arrays (either may be a number): then (N, 3) origins and directions. Beyond [0, width] x [0, height] the pinhole's rays go on past the frame (overscan), as far as the view's half-space.
        """
    def resized(self, width: typing.SupportsInt | typing.SupportsIndex, height: typing.SupportsInt | typing.SupportsIndex) -> Camera:
        """
        The same view and lens at another image size (vertical field of view kept). A jittered camera keeps
        its angle map at the same size; at another, ValueError (resize the map, then call jittered; or
        camera.without_jitter().resized(...)).
        """
    def with_lens(self, aperture_diameter: typing.SupportsFloat | typing.SupportsIndex, focus_distance: typing.SupportsFloat | typing.SupportsIndex) -> Camera:
        """
        The same view through a thin lens of aperture_diameter [m] (0: a pinhole) focused on the plane at
        depth focus_distance [m] along forward() (Camera.photographic's f_number gives f / N). ValueError
        for a negative or non-finite diameter, or a focus distance <= 0 or not finite.
        """
    def without_jitter(self) -> Camera:
        """
        The same camera without its jitter map (None: unchanged; a preview at another size, say).
        """
    @property
    def aperture_diameter(self) -> float:
        """
        The thin lens's aperture diameter [m] (f / N), 0 for a pinhole.
        """
    @property
    def focus_distance(self) -> float:
        """
        The depth [m] of the plane in focus, 0 for a pinhole.
        """
    @property
    def height(self) -> int:
        ...
    @property
    def jitter(self) -> typing.Any:
        """
        The angle map (height, width, 2) [rad] of a jittered camera, or None.
        """
    @property
    def look_at(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def pixel_angle(self) -> float:
        """
        The angle [rad] one pixel subtends at the image centre (vertical field of view / height).
        """
    @property
    def position(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def up(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        The up vector given to the constructor.
        """
    @property
    def vfov(self) -> float:
        ...
    @property
    def width(self) -> int:
        ...
class DisplaySettings:
    """
    How refracta.io turns linear radiance into display values (shading/tonemap.h; the formulas: the
    refracta.io module). Exposure: automatic (no manual field set: the image's log-average luminance
    goes to `key`), or manual, at most one of `exposure`, `ev100`, or `shutter` with `f_number` (and
    `iso`); a `key` given overrides a manual exposure. The white balance `white_balance` (none by
    default), then the tone curve `tonemap` and the transfer curve `gamma`. validate() lists every bad
    field.
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def ev100(self) -> float | None:
        """
        manual exposure as EV100: c = K / (1.2 x 2^EV100); None: not this way (default: None)
        """
    @ev100.setter
    def ev100(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def exposure(self) -> float | None:
        """
        c > 0 multiplying the radiance (manual); None: not this way (default: None)
        """
    @exposure.setter
    def exposure(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def f_number(self) -> float | None:
        """
        a camera's f-number N (with shutter) (default: None)
        """
    @f_number.setter
    def f_number(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def gamma(self) -> str | float:
        """
        the transfer curve: 'srgb', 'linear' or a gamma g in [1, 3] (default: 'srgb')
        """
    @gamma.setter
    def gamma(self, arg1: str | typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def iso(self) -> float | None:
        """
        a camera's ISO with shutter and f_number; None: ISO 100 (kDefaultIso) (default: None)
        """
    @iso.setter
    def iso(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def key(self) -> float | None:
        """
        Automatic exposure's key a (eq. 2: c = a / Lw_bar, Lw_bar = exp(mean ln(delta + Lw)) over the image,
        delta = kReinhardDelta times the mean luminance: exactly scale-free); given, it overrides any manual
        exposure; none: kAutoKey (0.18) when there is no manual exposure, else none. (default: None)
        """
    @key.setter
    def key(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def luminous_efficacy(self) -> float:
        """
        K: luminance [cd/m^2] of an image value of 1 (EV100 and camera settings only): 683 lm/W for
        radiance in W/(m^2 sr). (default: 683.0)
        """
    @luminous_efficacy.setter
    def luminous_efficacy(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def shutter(self) -> float | None:
        """
        [s] a camera's shutter time (with f_number); None: not this way (default: None)
        """
    @shutter.setter
    def shutter(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def tonemap(self) -> str:
        """
        'aces' (filmic), 'reinhard', 'film' (1 - e^(-cL)) or 'linear' (min(cL, 1)) (default: 'aces')
        """
    @tonemap.setter
    def tonemap(self, arg1: str) -> None:
        ...
    @property
    def white(self) -> float | None:
        """
        Reinhard: L_white of eq. 4, Ld = min(1, L (1 + L / L_white^2) / (1 + L)), the smallest scaled
        luminance mapped to display luminance 1 (in the colour's own hue: Ld / Lw scales its channels);
        none: infinite, Ld = L / (1 + L) (eq. 3). Reinhard's only (other tone curves refuse it). (default: None)
        """
    @white.setter
    def white(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def white_balance(self) -> typing.Any:
        """
        the light shown white: 'none' (the render's D65 white), 'auto' (grey world), 'daylight' (D55), 'cloudy' (D65), 'shade' (D75), 'tungsten' (3200 K), a colour temperature [K] in [1000, 40000] (Planckian) or an RGB white (r, g, b) in linear sRGB with X, Y, Z and its cone responses > 0; Bradford adaptation to D65 (default: 'none')
        """
    @white_balance.setter
    def white_balance(self, arg1: str | typing.SupportsFloat | typing.SupportsIndex | typing.Annotated[collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], "FixedSize(3)"]) -> None:
        ...
class OceanWaves:
    """
    A wind sea's waves on a periodic square patch (scene/ocean_waves.h): a height field synthesised by
    FFT from the Phillips spectrum, as Tessendorf 2001 ("Simulating Ocean Water") does,
    
        Phi(k) = A exp(-1 / (k L_w)^2) / k^4 |k^.w^|^2 [m^4],   L_w = wind_speed^2 / g,
    
    with A = 2 (0.21 / 4)^2 / pi = 1.755e-3 fixed by the significant wave height of a fully developed
    sea, H_s = 4 sigma_h = 0.21 U^2 / g (Pierson & Moskowitz 1964; Phillips 1957 for the k^-4 form).
    Each mode is a complex normal with E|h~(k)|^2 = Phi(k) dk^2 (dk = 2 pi / patch_size), Hermitian so
    the field is real; slopes by the FFT of i k h~ (exact on the nodes). Modes run up to the patch's
    Nyquist wavenumber pi resolution / patch_size (shorter waves are the Water material's microfacets)
    and down to 2 pi / patch_size (longer waves are missing). Deterministic from seed (each mode's
    numbers depend only on seed and its integer wavenumber, so a finer resolution keeps the long waves);
    time [s] moves the waves by deep-water dispersion w = sqrt(g k), every one of them downwind. A patch
    too small for the wind warns (its longer waves missing: patch_size of 10 U^2/g keeps ~92 % of the
    sea's variance). No choppy displacement.
    
    wind_speed [m/s] in (0, 30] (12.5 m above the sea, as Water's); wind_direction (x, z) horizontal,
    any non-zero length; patch_size [m] in [0.01, 1e7]; resolution a power of two in [8, 1024]. Arrays
    are indexed [j, i] at node x = i * spacing, z = j * spacing (rows along z).
    """
    phillips_a: typing.ClassVar[float] = 0.0017546832475881459
    def __getstate__(self) -> tuple[float, tuple[float, float], float, int, int, float]:
        ...
    def __init__(self, wind_speed: typing.SupportsFloat | typing.SupportsIndex = 5.0, wind_direction: typing.Any = (1.0, 0.0), patch_size: typing.SupportsFloat | typing.SupportsIndex = 100.0, resolution: typing.SupportsInt | typing.SupportsIndex = 256, seed: typing.SupportsInt | typing.SupportsIndex = 0, time: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def heights(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (N, N) heights [m], [j, i].
        """
    def slopes(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        (N, N, 2) (dh/dx, dh/dz), [j, i].
        """
    def spectrum(self, kx: typing.Any, kz: typing.Any) -> typing.Any:
        """
        Phi(k) [m^4] at wavenumbers kx, kz [rad/m] (vectorised).
        """
    @property
    def expected_height_variance(self) -> float:
        """
        sum of Phi dk^2 over the synthesised modes [m^2]: the field's expected variance.
        """
    @property
    def expected_slope_variance(self) -> float:
        """
        sum of k^2 Phi dk^2 over the synthesised modes: the expected mean-square slope.
        """
    @property
    def height_variance(self) -> float:
        """
        This field's variance over the nodes [m^2].
        """
    @property
    def patch_size(self) -> float:
        """
        [m]
        """
    @property
    def resolution(self) -> int:
        ...
    @property
    def seed(self) -> int:
        ...
    @property
    def significant_wave_height(self) -> float:
        """
        Pierson-Moskowitz H_s = 0.21 U^2 / g [m] (the spectrum's 4 sigma_h)
        """
    @property
    def slope_variance(self) -> float:
        """
        This field's mean of (dh/dx)^2 + (dh/dz)^2 over the nodes.
        """
    @property
    def spacing(self) -> float:
        """
        patch_size / resolution [m]
        """
    @property
    def spectrum_height_variance(self) -> float:
        """
        The whole spectrum's integral (H_s / 4)^2 [m^2].
        """
    @property
    def time(self) -> float:
        """
        [s]
        """
    @property
    def wind_direction(self) -> tuple[float, float]:
        """
        Unit (x, z).
        """
    @property
    def wind_length(self) -> float:
        """
        L_w = U^2 / g [m]
        """
    @property
    def wind_speed(self) -> float:
        """
        [m/s]
        """
class MomentShadowSettings:
    """
    How a moment shadow map keeps its four power moments and biases them (Peters & Klein 2015; Peters et
    al. 2017): depth_range 'unit' ([0, 1], Peters & Klein I3D 2015) or 'signed' ([-1, 1], Peters et al.
    JCGT 2017); storage 'fp64', 'fp32' or 'unorm16' (16 bits through the optimised quantisation
    transforms); bias (alpha) and bias_vector (b*): None means the published value for the depth range
    and storage (published_bias, published_bias_vector).
    """
    __hash__: typing.ClassVar[None] = None
    @staticmethod
    def published_bias(depth_range: str, storage: str) -> float:
        """
        The published strengths: 3e-6 (unit) / 3e-7 (signed) for fp32 and fp64 (Peters & Klein 2015 sec. 5;
        Peters et al. 2017 sec. 3.2); unorm16 needs ~10x more: 3e-5 / 6e-5.
        """
    @staticmethod
    def published_bias_vector(depth_range: str, storage: str = 'fp32') -> typing.Any:
        """
        (0.5, 0.5, 0.5, 0.5) for unit depths; for signed ones (0, 0.375, 0, 0.375), and with 16-bit storage
        (the sparse quantisation) (0, 0.628, 0, 0.628) (Peters et al. 2017).
        """
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def bias(self) -> float | None:
        """
        alpha, the weight of bias_vector (Peters & Klein's alpha) in [0, 1); unset (None) gives
        published_bias(depth_range, storage). (default: None)
        """
    @bias.setter
    def bias(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def bias_vector(self) -> typing.Any:
        """
        b*, the 4 moments biased toward; unset (None): published_bias_vector(depth_range, storage). (default: None)
        """
    @bias_vector.setter
    def bias_vector(self, arg1: typing.Any) -> None:
        ...
    @property
    def depth_range(self) -> str:
        """
        'unit' ([0, 1]) or 'signed' ([-1, 1]) (default: 'unit')
        """
    @depth_range.setter
    def depth_range(self, arg1: str) -> None:
        ...
    @property
    def storage(self) -> str:
        """
        'fp64', 'fp32' or 'unorm16': how a GPU would keep the moments (default: 'fp32')
        """
    @storage.setter
    def storage(self, arg1: str) -> None:
        ...
class ShadowMapOptions:
    """
    The shadow maps of render_raster (an orthographic map for the sun, a perspective one per spot
    light): method 'hard' (one depth compare), 'pcf' (kernel x kernel compares), 'vsm', 'msm_hamburger',
    'msm_hausdorff' (four moments box-filtered kernel x kernel, read through `moments`).
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def bleeding_reduction(self) -> float:
        """
        VSM light-bleeding reduction (Lauritzen) in [0, 1): intensities below this amount of light become 0. (default: 0.0)
        """
    @bleeding_reduction.setter
    def bleeding_reduction(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def depth_bias(self) -> float:
        """
        hard / pcf: compare against z - depth_bias (normalised depth) (default: 0.0002)
        """
    @depth_bias.setter
    def depth_bias(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def kernel(self) -> int:
        """
        k x k filter (odd) of PCF and of the moment map (default: 1)
        """
    @kernel.setter
    def kernel(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def method(self) -> str:
        """
        'hard', 'pcf', 'vsm', 'msm_hamburger' or 'msm_hausdorff' (default: 'msm_hamburger')
        """
    @method.setter
    def method(self, arg1: str) -> None:
        ...
    @property
    def moments(self) -> MomentShadowSettings:
        """
        MomentShadowSettings of the moment methods (vsm, msm_*): depth range, storage, bias (default: MomentShadowSettings(bias=None, bias_vector=None, depth_range='unit', storage='fp32'))
        """
    @moments.setter
    def moments(self, arg0: MomentShadowSettings) -> None:
        ...
    @property
    def normal_offset(self) -> float:
        """
        receivers are moved this many texels along their normal (default: 1.5)
        """
    @normal_offset.setter
    def normal_offset(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def resolution(self) -> int:
        """
        texels per side, in [2, 8192] (default: 1024)
        """
    @resolution.setter
    def resolution(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
class MboitSettings:
    """
    Moment-based order-independent transparency (Muenstermann et al., I3D 2018): basis 'power' (moments
    4, 6 or 8) or 'trigonometric' (2, 3 or 4); overestimation beta; bias None: the published value for
    the basis, moment count and storage; storage 'fp32', 'unorm16' (the 16-bit ROV variant, re-quantised
    after every fragment) or 'fp64' (the method itself); log-depth warp over [z_near, z_far] [m] (both
    0: the fragments' own range, in render_raster the frame's).
    """
    __hash__: typing.ClassVar[None] = None
    @staticmethod
    def published_bias(basis: str, moments: typing.SupportsInt | typing.SupportsIndex, storage: str) -> float:
        """
        fp32: 5e-7 / 5e-6 / 5e-5 for 4 / 6 / 8 power moments; unorm16: 6e-5 (the Unity HDRP port),
        5e-5, 5e-4; trigonometric: 4e-4 for 2 moments, 2e-4 for 3 and 4.
        """
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def basis(self) -> str:
        """
        'power' or 'trigonometric' (default: 'power')
        """
    @basis.setter
    def basis(self, arg1: str) -> None:
        ...
    @property
    def beta(self) -> float:
        """
        overestimation in [0, 1]: the share of the fragment's own layer in front (default: 0.25)
        """
    @beta.setter
    def beta(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def bias(self) -> float | None:
        """
        alpha, the weight of the bias vector in [0, 1); unset (None) gives the published value for the
        basis, the moment count and the storage (published_bias). (default: None)
        """
    @bias.setter
    def bias(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def moments(self) -> int:
        """
        4, 6 or 8 power moments; 2, 3 or 4 trigonometric (default: 4)
        """
    @moments.setter
    def moments(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def storage(self) -> str:
        """
        'fp32', 'unorm16' (a GPU's storage) or 'fp64' (the method itself) (default: 'fp32')
        """
    @storage.setter
    def storage(self, arg1: str) -> None:
        ...
    @property
    def z_far(self) -> float:
        """
        far end of the log-depth warp [m]; both 0: the fragments' own range (default: 0.0)
        """
    @z_far.setter
    def z_far(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def z_near(self) -> float:
        """
        near end of the log-depth warp [m] (default: 0.0)
        """
    @z_near.setter
    def z_near(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class OitSettings:
    """
    How surfaces with alpha < 1 are composited: method 'exact' (sorted: depth peeling with enough
    layers), 'peel' (the `layers` nearest), 'wboit' (McGuire & Bavoil, JCGT 2013, depth weight 'eq7' or
    'eq9') or 'mboit' (moment-based, settings in `mboit`).
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def bytes_per_pixel(self, fragments_per_pixel: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        Bytes per pixel a GPU would keep: sorted lists 20 per fragment (depth, alpha, RGB fp32); peeling 12
        per layer (RGBA16F + depth fp32); WBOIT 10 (RGBA16F + R16F); MBOIT b0 in fp32 and the moments in
        fp32 or 16 bits, plus the RGBA16F accumulation. ValueError unless fragments_per_pixel is finite and
        >= 0.
        """
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def layers(self) -> int:
        """
        peel: layers kept (default: 4)
        """
    @layers.setter
    def layers(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def mboit(self) -> MboitSettings:
        """
        MboitSettings (method 'mboit') (default: MboitSettings(basis='power', beta=0.25, bias=None, moments=4, storage='fp32', z_far=0.0, z_near=0.0))
        """
    @mboit.setter
    def mboit(self, arg0: MboitSettings) -> None:
        ...
    @property
    def method(self) -> str:
        """
        'exact', 'peel', 'wboit' or 'mboit' (default: 'mboit')
        """
    @method.setter
    def method(self, arg1: str) -> None:
        ...
    @property
    def weight(self) -> str:
        """
        wboit: 'eq7' or 'eq9' (default: 'eq7')
        """
    @weight.setter
    def weight(self, arg1: str) -> None:
        ...
class RasterRenderOptions:
    """
    Options of refracta.render_raster, with their defaults (defined once, here). Set any field by name,
    nested ones through .shadow_map (ShadowMapOptions) and .transparency (OitSettings or None);
    validate() reports every bad value at once.
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def light_strata(self) -> int:
        """
        Samples (n^2, n = 1 .. 64) of each light with extent other than the spots (environment, sky, area
        lights; the sun where its disc is wider than 1 deg or cut by a surface's horizon), and as many of
        the BSDF (not of the sun), combined by MIS, deterministic per
        pixel: the same n^2 quasi-random points everywhere, so their quadrature error is a bias, not
        noise. Measured at n = 8 (16, 32): a panel 0.2 m over a floor -0.9 % (+1.2 %, +0.4 %) of its form
        factor, an environment map with a small bright sun -0.3 % (-2.5 %, -1.2 %) of its integral, a sphere
        lamp 7e-4; a lobe taking a share F of the samples (water's reflection, F ~ 0.03) gets about F n^2 of
        them: raise it for glossy or dielectric surfaces under bright skies. (default: 8)
        """
    @light_strata.setter
    def light_strata(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def output(self) -> str:
        """
        'radiance' (linear RGB) or 'shadow' ((shadow intensity, 1, 0) where shadow_light reaches the surface) (default: 'radiance')
        """
    @output.setter
    def output(self, arg1: str) -> None:
        ...
    @property
    def shadow_centre(self) -> typing.Any:
        """
        The region the sun's map covers, seen from the sun: its centre [m]; unset (None): fitted to the
        visible points closer than shadow_distance to the camera. (default: None)
        """
    @shadow_centre.setter
    def shadow_centre(self, arg1: typing.Any) -> None:
        ...
    @property
    def shadow_distance(self) -> float:
        """
        [m] the sun's map covers the visible points closer than this to the camera (default: inf)
        """
    @shadow_distance.setter
    def shadow_distance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def shadow_half_size(self) -> float | None:
        """
        half the side of the sun's map [m]; None: fitted to the visible points (default: None)
        """
    @shadow_half_size.setter
    def shadow_half_size(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def shadow_light(self) -> int:
        """
        output shadow: -1 the sun, k >= 0 the scene's spot light k (default: -1)
        """
    @shadow_light.setter
    def shadow_light(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def shadow_map(self) -> ShadowMapOptions:
        """
        ShadowMapOptions of the sun's and the spot lights' maps (shadows 'map') (default: ShadowMapOptions(bleeding_reduction=0.0, depth_bias=0.0002, kernel=1, method='msm_hamburger', moments=MomentShadowSettings(bias=None, bias_vector=None, depth_range='unit', storage='fp32'), normal_offset=1.5, resolution=1024))
        """
    @shadow_map.setter
    def shadow_map(self, arg0: ShadowMapOptions) -> None:
        ...
    @property
    def shadows(self) -> str:
        """
        'map' (shadow maps: shadow_map), 'embree' (shadow rays: the reference) or 'none' (default: 'map')
        """
    @shadows.setter
    def shadows(self, arg1: str) -> None:
        ...
    @property
    def spots(self) -> list[int] | None:
        """
        Indices of the spot lights that shine (spot k is the k-th spot light in the scene's order); unset
        (None): all. Other lights (point, area, environment) shade with Embree shadow rays. (default: None)
        """
    @spots.setter
    def spots(self, arg0: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex] | None) -> None:
        ...
    @property
    def tile(self) -> int:
        """
        tile size [pixels] of the parallel loop (default: 16)
        """
    @tile.setter
    def tile(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def transparency(self) -> OitSettings:
        """
        Surfaces with material alpha < 1 are composited over the opaque ones with this method (fragments
        from the rasterizer, culled by the opaque depth); without it they are opaque. MBOIT's log-depth
        range, when not set, is fitted to the frame's fragments. None: every surface opaque. (default: None)
        """
    @transparency.setter
    def transparency(self, arg1: typing.Any) -> None:
        ...
    @property
    def use_sun(self) -> bool:
        """
        the scene's sun shines (default: True)
        """
    @use_sun.setter
    def use_sun(self, arg0: bool) -> None:
        ...
class RasterRenderStats:
    """
    What render_raster measured (read-only).
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> tuple[float, float, int, int, float]:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex, typing.SupportsInt | typing.SupportsIndex, typing.SupportsInt | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def bytes_per_texel(self) -> int:
        """
        what the shadow method reads per texel
        """
    @property
    def oit_bytes_per_pixel(self) -> float:
        """
        what the transparency method keeps per pixel (mean)
        """
    @property
    def seconds(self) -> float:
        """
        the whole render [s]
        """
    @property
    def shadow_build_seconds(self) -> float:
        """
        rasterizing, filtering and storing the shadow maps [s]
        """
    @property
    def transparent_fragments(self) -> int:
        """
        transparent fragments in front of the opaque surfaces
        """
class RenderOptions:
    """
    Options of refracta.render, with their defaults (defined once, here). Set any field by name;
    validate() reports every bad value at once.
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def bounds_in(self, width: typing.SupportsInt | typing.SupportsIndex, height: typing.SupportsInt | typing.SupportsIndex) -> tuple[int, int, int, int]:
        """
        The pixels to render of a width x height image, (x0, y0, x1, y1): pixel_bounds (checked to lie
        inside, non-empty; std::invalid_argument otherwise) or the whole image.
        """
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def adaptive(self) -> bool:
        """
        Adaptive sampling at the same budget (render/adaptive_sampling.h): a pilot of
        AdaptiveSampling::first_pass(spp) samples per pixel (2 at 16 spp) chooses how the rest of its 32 x
        32 block's budget is shared: every pixel at least half of spp, the others where the pilot's samples
        vary most (edges, noise); each pixel is one pattern of its count, the pilot is not averaged in
        (unbiased); the image's total is still width x height x spp. 'straight' and 'curved' only; spp >= 6
        (AdaptiveSampling::min_spp; below, a ValueError: the pilot would leave no samples to move). (default: False)
        """
    @adaptive.setter
    def adaptive(self, arg0: bool) -> None:
        ...
    @property
    def chord(self) -> float:
        """
        longest straight chord tested against the geometry [m] (default: 1000.0)
        """
    @chord.setter
    def chord(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def differentials(self) -> bool:
        """
        A camera ray's footprint on a textured surface from ray differentials through the air
        (Caster::footprint: the paths of its neighbours, as squeezed or stretched by a mirage); false: the
        ray cone (pixel angle x path length), as for every later bounce. (default: True)
        """
    @differentials.setter
    def differentials(self, arg0: bool) -> None:
        ...
    @property
    def edge_spp(self) -> int:
        """
        Edge refinement (render/film.h EdgeRefinement): when above spp, every pixel at an edge between
        surfaces -- its first hits' mean albedo or normal differs from a neighbour's -- is rendered again as
        one pattern of edge_spp samples, so its coverage is weighed as a sensor's pixel integrates it; the
        other pixels keep spp. The edges' pixels are few (7-13 % on the demo scenes): the cost is that share
        x edge_spp. 0 (or at most spp): off. Not with adaptive. (default: 0)
        """
    @edge_spp.setter
    def edge_spp(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def guard_band(self) -> float:
        """
        Extra raster view on each side, as a fraction of the image size: rays that bend out of the camera's
        view can still find geometry there. What is in no raster pixel cannot appear. (default: 0.1)
        """
    @guard_band.setter
    def guard_band(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def guide_spp(self) -> int:
        """
        With surface_aovs: when above spp, the albedo and normal come from a pass of their own with this
        many samples per pixel that stops at each path's first non-specular surface (no lighting: a camera
        ray, its mirror and glass chain and the surface's albedo), so they carry the pixel's edge coverage
        to guide_spp samples' accuracy (render(denoise=True)'s guided filter rebuilds the image's edges from
        them, python/refracta/_denoise.py). Non-adaptive, RGB (a spectral render's guides follow the air at
        its reference wavelength); 0 or at most spp: the image's own samples. Off by default: 64 guide
        samples cost 0.7-1.7x the CPU of 16 'direct' RGB ones on the demo scenes (about what 32 spp cost,
        and 32 spp denoised gain as much or more; 0.2x of the spectral green flash's, where they find no
        surface: benchmarks/bench_denoise.py). (default: 0)
        """
    @guide_spp.setter
    def guide_spp(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def march(self) -> str:
        """
        raster_march: 'rk45' to tol, or 'rk4' with step (the original) (default: 'rk45')
        """
    @march.setter
    def march(self, arg1: str) -> None:
        ...
    @property
    def max_depth(self) -> int:
        """
        Scattering events along a path (0: emitters only, 1: direct lighting; Mitsuba's max_depth is this +
        1). 'direct' uses it for specular chains only. (default: 5)
        """
    @max_depth.setter
    def max_depth(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_length(self) -> float:
        """
        Curved rays end here and show the sky in their last direction [m]; so do straight rays over a field
        with an Earth radius (the sphere's straight lines, render/picking.h straight_air). Over such a field
        a camera ray that ends in the air above every object goes on to where it leaves the air and shows
        the sky there (Caster::continue_to_sky): the scene is met within max_length, the sky's refraction
        wherever it happens. (default: 5000.0)
        """
    @max_length.setter
    def max_length(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_steps(self) -> int:
        """
        raster_march 'rk4': steps at most (default: 1000)
        """
    @max_steps.setter
    def max_steps(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def method(self) -> str:
        """
        'curved' (exact curved rays), 'straight' (no refraction) or 'raster_march' (the original editor's method) (default: 'curved')
        """
    @method.setter
    def method(self, arg1: str) -> None:
        ...
    @property
    def pixel_bounds(self) -> tuple[int, int, int, int] | None:
        """
        Render only these pixels of the camera's image, (x0, y0, x1, y1): pixels [x0, x1) x [y0, y1) (the
        result has the bounds' size); each pixel exactly as in the whole image (its seed and the eye's
        ElevationTable are the whole image's: distributed tiles). Unset (None): the whole image. Checked
        against the camera's image by bounds_in(width, height). (default: None)
        """
    @pixel_bounds.setter
    def pixel_bounds(self, arg1: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex] | None) -> None:
        ...
    @property
    def readouts(self) -> bool:
        """
        Also render the per-pixel readouts (readouts.h: distance, position, object id, apparent and true
        elevation, apparent azimuth, hidden heights) after those 9 channels: 19 in all. Implies
        surface_aovs. 'straight' and 'curved' only. (default: False)
        """
    @readouts.setter
    def readouts(self, arg0: bool) -> None:
        ...
    @property
    def rr_depth(self) -> int:
        """
        Russian roulette from this many scattering events on (survival min(0.95, max throughput)). (default: 3)
        """
    @rr_depth.setter
    def rr_depth(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def sagitta(self) -> float:
        """
        largest distance between a chord and the curved path [m] (default: 0.001)
        """
    @sagitta.setter
    def sagitta(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sagitta_pixels(self) -> float:
        """
        Camera rays may stray this fraction of a pixel's footprint (pixel angle x path length) from their
        path when that is more than `sagitta`: what a pixel cannot resolve need not be traced. (default: 0.25)
        """
    @sagitta_pixels.setter
    def sagitta_pixels(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def sample_counts(self) -> bool:
        """
        Also write each pixel's number of camera samples (the ones its value averages: spp, edge_spp at a
        refined edge, the adaptive count; a pilot's samples only choose that count) as one more, last
        channel (renderer.h). 'straight' and 'curved' only. (default: False)
        """
    @sample_counts.setter
    def sample_counts(self, arg0: bool) -> None:
        ...
    @property
    def seed(self) -> int:
        """
        seed of the per-pixel random streams (default: 0)
        """
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def spectral(self) -> bool:
        """
        Spectral rendering: 4 hero wavelengths per sample (Wilkie et al. 2014) instead of RGB. (default: False)
        """
    @spectral.setter
    def spectral(self, arg0: bool) -> None:
        ...
    @property
    def spp(self) -> int:
        """
        samples per pixel (1: the pixel centre; more: correlated multi-jittered, film.h) (default: 1)
        """
    @spp.setter
    def spp(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def step(self) -> float:
        """
        raster_march 'rk4': the step [m] (default: 0.3)
        """
    @step.setter
    def step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def surface_aovs(self) -> bool:
        """
        Also render the albedo and normal of each sample's first non-specular hit (averaged over the pixel's
        samples): the image then has 9 channels, radiance, albedo, normal (Intel Open Image Denoise's
        auxiliary features; renderer.h; Python's render returns them as aovs=["albedo", "normal"] and the
        image's 3). 'straight' and 'curved' only. (default: False)
        """
    @surface_aovs.setter
    def surface_aovs(self, arg0: bool) -> None:
        ...
    @property
    def table(self) -> bool:
        """
        Height-only fields: serve every pixel from one ElevationTable for the camera's eye height
        (interpolated to `tol`) instead of tracing each pixel (over a CurvedEarth, paths over 150 km end in
        the table where they leave the air; spectral renders of 8 spp or more: one table per dispersion
        scale; renderer.cpp). (default: True)
        """
    @table.setter
    def table(self, arg0: bool) -> None:
        ...
    @property
    def texture_filter(self) -> bool:
        """
        Filter textures over each sample's footprint (OIIO MIP-mapping, anisotropic; bilinear between
        texels); false reads the finest level at the sample's point, bilinearly (aliases: only for
        references and tests). Magnified, both are that bilinear lookup. (default: True)
        """
    @texture_filter.setter
    def texture_filter(self, arg0: bool) -> None:
        ...
    @property
    def tile(self) -> int:
        """
        tile size [pixels] of the parallel loop (default: 16)
        """
    @tile.setter
    def tile(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def tol(self) -> float:
        """
        Curved-ray integration tolerance [m] (the integrator, `trace`: 'stratified' for height-only fields,
        'rk45' for others). (default: 0.0001)
        """
    @tol.setter
    def tol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def trace(self) -> str | None:
        """
        ray integrator for curved rays: None (stratified for height-only fields, rk45 otherwise), 'rk45', 'stratified' (default: None)
        """
    @trace.setter
    def trace(self, arg1: str | None) -> None:
        ...
    @property
    def transport(self) -> str:
        """
        'direct' (direct lighting with MIS, mirror/glass chains) or 'path' (path tracing) (default: 'direct')
        """
    @transport.setter
    def transport(self, arg1: str) -> None:
        ...
    @property
    def turbulence_step(self) -> float:
        """
        'perturbed': the step through the layer, in the turbulence's cells. The cubic B-spline's gradient
        varies on the cell's scale, and a step h samples the path integral's spectrum aliased from
        wavenumbers 2 pi / h along the path: at 1 cell that is where the spline's response has its zeros
        (along the lattice axes), at 2 cells the grid's Nyquist, where it carries full power. In [0.01, 16]:
        below a hundredth of a cell nothing changes but the cost (1e-300 overflowed the step count and meant
        one step through the layer). (default: 1.0)
        """
    @turbulence_step.setter
    def turbulence_step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def turbulence_trace(self) -> str:
        """
        camera rays through turbulence: 'auto' (default: 'perturbed' where it applies, else 'strict'),
        'strict' (the full field, rk45) or 'perturbed' (deviations from each ray's calm path, traced
        exactly to tol, in steps of the turbulence's cells; those samples' shadow and bounce rays through
        the calm air; rays turned by more than 5 mrad traced strictly). 'perturbed' serves RGB curved
        renders through height-only calm air, or hot spots over it, from a pinhole camera; elsewhere the
        render traces strictly, and render() warns where 'perturbed' was asked for
        """
    @turbulence_trace.setter
    def turbulence_trace(self, arg1: str) -> None:
        ...
class RenderStats:
    """
    What refracta.render counted, summed over its samples (read-only; tiles add up with +).
    """
    __hash__: typing.ClassVar[None] = None
    def __add__(self, arg0: RenderStats) -> RenderStats:
        ...
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> tuple[int, int, int]:
        ...
    def __init__(self) -> None:
        """
        All counts 0.
        """
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple[typing.SupportsInt | typing.SupportsIndex, typing.SupportsInt | typing.SupportsIndex, typing.SupportsInt | typing.SupportsIndex]) -> None:
        ...
    @property
    def chords(self) -> int:
        """
        Embree queries along camera paths (straight rays count one each)
        """
    @property
    def invalid_samples(self) -> int:
        """
        samples whose radiance was not finite (dropped; should stay 0)
        """
    @property
    def samples(self) -> int:
        """
        camera samples traced
        """
class SolveSettings:
    """
    Settings of refracta.edit.solve, with their defaults (defined once, in C++'s SolveSettings). Set any
    field by name, or pass them to solve() as keywords; validate() reports every bad value at once.
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def accept_angle(self) -> float:
        """
        A pair is met when its miss beyond its margin is at most accept_angle * (eye-to-source distance)
        [rad], or its tolerance if larger (PointPair::allowed_miss): 1e-6 rad is far below a pixel of any
        camera. (default: 1e-06)
        """
    @accept_angle.setter
    def accept_angle(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def backend(self) -> str:
        """
        'ceres' (Levenberg-Marquardt, automatic derivatives) or 'nlopt:<ALGORITHM>' (any nlopt name) (default: 'ceres')
        """
    @backend.setter
    def backend(self, arg1: str) -> None:
        ...
    @property
    def design_per_param(self) -> int:
        """
        auto: points per free parameter of the global stage (scan points on its axis; as many again
        quasi-random points, half over the box, half near the start), at most 100000 (kMostDesignPerParam). (default: 16)
        """
    @design_per_param.setter
    def design_per_param(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def function_tolerance(self) -> float:
        """
        relative change of the cost that ends the solve (default: 1e-14)
        """
    @function_tolerance.setter
    def function_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gradient_tolerance(self) -> float:
        """
        ceres: max-norm of the projected gradient (default: 1e-16)
        """
    @gradient_tolerance.setter
    def gradient_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def local_starts(self) -> int:
        """
        auto: local solves from the global stage's best points, at most. (default: 4)
        """
    @local_starts.setter
    def local_starts(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def loss(self) -> str:
        """
        ceres robust loss on each pair's squared miss: 'none', 'huber', 'soft_l1', 'cauchy', 'arctan' (default: 'none')
        """
    @loss.setter
    def loss(self, arg1: str) -> None:
        ...
    @property
    def loss_scale(self) -> float:
        """
        [m] the miss where the robust loss starts to down-weight (default: 1.0)
        """
    @loss_scale.setter
    def loss_scale(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_evaluations(self) -> int:
        """
        Cost evaluations of the whole solve, each tracing every pair (ceres: residual and Jacobian passes;
        nlopt: every call of the objective; the global stage: every design point). (default: 3000)
        """
    @max_evaluations.setter
    def max_evaluations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_iterations(self) -> int:
        """
        LM iterations of the whole solve (ceres); nlopt has none: max_evaluations stops it (default: 200)
        """
    @max_iterations.setter
    def max_iterations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def parameter_tolerance(self) -> float:
        """
        relative change of the parameters that ends the solve (default: 1e-12)
        """
    @parameter_tolerance.setter
    def parameter_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def pixel_tolerance(self) -> float:
        """
        [pixels] a pair with a pixel destination is met when its miss is within its margin plus this
        fraction of the pixel's footprint at the source (the camera's pixel angle times the source's range;
        PointPair::tolerance), when that exceeds accept_angle times its range. A tenth of a pixel cannot be
        seen in the image, and it spares an edit from failing on a miss of 0.01 px (issue 23: 5.9 mm at 1.9
        km). It judges the result only: the cost still pulls every pair onto its source. refracta.edit.solve
        converts it to metres per pair (C++ sees metres only). (default: 0.1)
        """
    @pixel_tolerance.setter
    def pixel_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def quick_iterations(self) -> int:
        """
        auto: iterations of the first local solve (and of each continuation). Measured on
        benchmarks/bench_edit.py: LM meets, or is still closing in on, every case it solves from its start
        at all within 15 iterations. (default: 15)
        """
    @quick_iterations.setter
    def quick_iterations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def seed(self) -> int:
        """
        seed of the random starts (default: 0)
        """
    @seed.setter
    def seed(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def starts(self) -> int:
        """
        Starts of the whole strategy: the first from the field as given, the others uniformly random within
        the free parameters' bounds (seeded by `seed`); the best result is kept (every pair met first, then
        the lowest cost). All starts share the budget above; a start whose field cannot trace every pair is
        skipped. (default: 1)
        """
    @starts.setter
    def starts(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def strategy(self) -> str:
        """
        'auto' (a short local solve; if not every pair is met, the global stage and local solves from its best points) or 'local' (the back-end from the start only) (default: 'auto')
        """
    @strategy.setter
    def strategy(self, arg1: str) -> None:
        ...
    @property
    def target_cost(self) -> float:
        """
        [m^2] stop once the cost is <= this (0: never early) (default: 0.0)
        """
    @target_cost.setter
    def target_cost(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def time_limit(self) -> float:
        """
        [s] wall-clock limit of the solve from its call; 0: none. A trace running when it expires is
        interrupted (EvaluationContext's flag, polled every step), and the solve then measures the best
        point found (its misses: one or two evaluations more, not interrupted -- seconds where that point
        itself ducts a long ray: 28 s over the limit for the issue's 1e7 m pair, before its residuals were
        reused; a fraction of a second for ordinary pairs). 300 s is generous: the slowest edit of
        benchmarks/bench_edit.py takes under a second, while a trial atmosphere that ducts a ray over a long
        path costs seconds per evaluation (issue 23: 7.7 M steps for 150 km). (default: 300.0)
        """
    @time_limit.setter
    def time_limit(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def trust_region(self) -> float:
        """
        ceres: initial trust-region radius of Levenberg-Marquardt in the unit box of the free
        parameters (1 = each parameter's whole bound range). Cautious first steps keep LM out of the flat
        regions of narrow layers (a logistic inversion far from every ray) that a bold first step lands in;
        measured on benchmarks/bench_edit.py: 1e4 (Ceres' default) fails the 16-pair logistic case, 0.1
        solves every case. (default: 0.1)
        """
    @trust_region.setter
    def trust_region(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class PairOptions:
    """
    How an edit's pairs are traced and measured (refracta.edit.solve, distances, jacobian and
    EditResult.paths take these fields as keywords), with their defaults (defined once, in C++'s
    PairOptions). validate() reports every bad value at once.
    """
    __hash__: typing.ClassVar[None] = None
    def __eq__(self, arg0: typing.Any) -> typing.Any:
        ...
    def __getstate__(self) -> dict:
        ...
    def __init__(self, **kwargs) -> None:
        """
        The defaults, with any field set by keyword (then validated).
        """
    def __repr__(self) -> str:
        ...
    def __setattr__(self, arg0: str, arg1: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def validate(self) -> None:
        """
        Raises ValueError listing every bad field (nested options included).
        """
    @property
    def distance(self) -> str:
        """
        'continuous' (closest approach of the continuous path) or 'vertex' (nearest integrator node) (default: 'continuous')
        """
    @distance.setter
    def distance(self, arg1: str) -> None:
        ...
    @property
    def max_steps(self) -> int:
        """
        Integration steps a trace may take (TraceOptions::max_steps): beyond them the evaluation fails. (default: 10000000)
        """
    @max_steps.setter
    def max_steps(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def reach(self) -> float:
        """
        The path is traced to reach x (the eye-to-source distance) + 1 m (reach in [1, 100]), and stops
        early once it is past the source. (default: 1.5)
        """
    @reach.setter
    def reach(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def step(self) -> float:
        """
        rk4 step [m] (0: 0.3, the original editor's) (default: 0.0)
        """
    @step.setter
    def step(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def stop_height(self) -> float | None:
        """
        Paths end where they descend through it (a ground) [m]; unset (None): no ground. (default: None)
        """
    @stop_height.setter
    def stop_height(self, arg0: typing.SupportsFloat | typing.SupportsIndex | None) -> None:
        ...
    @property
    def tol(self) -> float:
        """
        rk45 target position error [m] (at least 1e-13 per metre of path) (default: 1e-09)
        """
    @tol.setter
    def tol(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def trace(self) -> str:
        """
        the ray integrator: 'rk45' (to tol) or 'rk4' (fixed step); 'stratified' has no derivatives (default: 'rk45')
        """
    @trace.setter
    def trace(self, arg1: str) -> None:
        ...
class SolveSummary:
    """
    What an edit solve returned (read-only; refracta.edit.EditResult forwards its fields, values
    aside: there the solved field, EditResult.field, holds them).
    """
    def __getstate__(self) -> dict:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def at_bounds(self) -> list[str]:
        """
        free parameters the result left on a bound of the search (the message says which bound): the best fit may lie beyond it
        """
    @property
    def backend(self) -> str:
        """
        'ceres' or 'nlopt:<ALGORITHM>'
        """
    @property
    def camera(self) -> Camera | None:
        """
        with camera parameters free: the solved Camera; else None
        """
    @property
    def camera_values(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        with camera parameters free: camera_yaw, camera_pitch, camera_roll (offsets from the start camera) and camera_vfov [deg] at the result; else empty
        """
    @property
    def condition(self) -> float:
        """
        the Jacobian's condition number at a result meeting every pair (else 0)
        """
    @property
    def converged(self) -> bool:
        """
        the back-end ended normally
        """
    @property
    def cost(self) -> float:
        """
        [m^2] the same at the result
        """
    @property
    def derivatives(self) -> str:
        """
        'automatic' or 'numeric'
        """
    @property
    def distances(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        [m] each pair's miss at the result
        """
    @property
    def evaluations(self) -> int:
        """
        cost evaluations of the whole solve
        """
    @property
    def free(self) -> list[str]:
        """
        the parameters that were optimised
        """
    @property
    def history(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        cost per iteration (ceres) or best cost per evaluation (nlopt)
        """
    @property
    def initial_cost(self) -> float:
        """
        [m^2] 1/2 sum weight * (miss - margin)^2 at the start
        """
    @property
    def insensitive(self) -> list[str]:
        """
        requested free, but no pair depends on them: held fixed
        """
    @property
    def iterations(self) -> int:
        """
        iterations of the start that gave the result
        """
    @property
    def message(self) -> str:
        """
        what happened, and why a pair is not met
        """
    @property
    def met(self) -> numpy.typing.NDArray[numpy.bool]:
        """
        per pair: its miss is within its margin plus its met tolerance
        """
    @property
    def pair_traces(self) -> int:
        """
        traced pairs, derivative passes included
        """
    @property
    def rank(self) -> int:
        """
        its numerical rank (else 0)
        """
    @property
    def solver_report(self) -> str:
        """
        the back-end's own report of the run that gave the result
        """
    @property
    def stages(self) -> list[str]:
        """
        what the strategy did, one line per stage
        """
    @property
    def starts(self) -> int:
        """
        starts asked for
        """
    @property
    def stopped_by(self) -> str:
        """
        'iteration limit', 'evaluation limit', 'time limit' or ''
        """
    @property
    def strategy(self) -> str:
        """
        'auto' or 'local'
        """
    @property
    def success(self) -> bool:
        """
        every pair met (strategy 'local': and converged)
        """
    @property
    def time(self) -> float:
        """
        [s] solving, set-up excluded
        """
    @property
    def unique(self) -> bool:
        """
        every pair met, and the pairs fix every free parameter (condition <= 1e6, and a quarter of the search box along the least-determined combination meets them no longer)
        """
    @property
    def values(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        every parameter of the solved field, in param_names order
        """
class BsdfSample:
    """
    What Material.sample returns, one row per sample (read-only arrays; bsdf.h's BsdfSample fields): wi
    (N, 3), weight (N, C), f (N, C), pdf (N,), flags (N,) uint32, is_delta (N,), eta (N,), valid (N,),
    terminated (N,); C = 3 (RGB) or 4 (spectral). See Material.sample. s['wi'] (the former dict) still
    works and iteration over the names are deprecated (DeprecationWarning).
    """
    fields: typing.ClassVar[tuple] = ('wi', 'weight', 'f', 'pdf', 'flags', 'is_delta', 'eta', 'valid', 'terminated')
    def __getitem__(self, key: str) -> typing.Any:
        ...
    def __getstate__(self) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.uint32], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]]:
        ...
    def __iter__(self) -> collections.abc.Iterator:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple[typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 3]"], typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"], typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, n]"], typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], typing.Annotated[numpy.typing.ArrayLike, numpy.uint32, "[m, 1]"], typing.Annotated[numpy.typing.ArrayLike, numpy.bool, "[m, 1]"], typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], typing.Annotated[numpy.typing.ArrayLike, numpy.bool, "[m, 1]"], typing.Annotated[numpy.typing.ArrayLike, numpy.bool, "[m, 1]"]]) -> None:
        ...
    @property
    def eta(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        The relative index crossed (N,), 1 for reflection (and where invalid).
        """
    @property
    def f(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        The BSDF value (N, C) [1/sr] (delta lobes: as weight's numerator).
        """
    @property
    def flags(self) -> typing.Annotated[numpy.typing.NDArray[numpy.uint32], "[m, 1]"]:
        """
        1 reflection, 2 transmission, 4 diffuse, 8 glossy, 16 specular (N,).
        """
    @property
    def is_delta(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        """
        Whether a delta lobe was sampled (N,).
        """
    @property
    def pdf(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Density (N,) [1/sr] (delta lobes: the lobe's selection probability).
        """
    @property
    def terminated(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        """
        True where a dispersive refraction kept the hero wavelength only (N,).
        """
    @property
    def valid(self) -> typing.Annotated[numpy.typing.NDArray[numpy.bool], "[m, 1]"]:
        """
        False where no direction was produced (N,).
        """
    @property
    def weight(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        ``f |cos theta_i| / pdf`` (N, C) (delta lobes: albedo / probability).
        """
    @property
    def wi(self) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        Sampled unit directions (N, 3), 0 where invalid.
        """
class Material:
    """
    A surface material (shading/material.h): builds a BSDF at a hit. Evaluate it in
    the local shading frame with f, pdf and sample (z along the shading normal).
    """
    def __repr__(self) -> str:
        ...
    def describe(self) -> str:
        ...
    def f(self, wo: typing.Any, wi: typing.Any, wavelengths: typing.Any = None, eta_outside: typing.SupportsFloat | typing.SupportsIndex = 1.0, mode: str = 'radiance') -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        The BSDF value f(wo, wi) without the cosine [1/sr]: (N, 3) linear RGB, or (N, 4) per wavelength.
        Delta lobes give 0.
        wo, wi: unit directions in the local shading frame (z = shading normal), shape (N, 3) or (3,)
        (one side may be a single direction, broadcast), wo toward the viewer, wi toward the light.
        wavelengths: None for RGB rendering, or (4,) / (N, 4) hero wavelengths [nm] for spectral.
        eta_outside: index of the medium on the normal's side; mode: 'radiance' or 'importance'.
        """
    def interior_ior(self, wavelength: typing.SupportsFloat | typing.SupportsIndex | None = None) -> float | None:
        """
        Index of refraction of the medium a dielectric bounds, at the given wavelength [nm] (None: RGB
        rendering's 550 nm), or None for materials that bound no medium.
        """
    def pdf(self, wo: typing.Any, wi: typing.Any, wavelengths: typing.Any = None, eta_outside: typing.SupportsFloat | typing.SupportsIndex = 1.0, mode: str = 'radiance') -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        Density [1/sr] with which sample(wo, u) produces wi: (N,). It includes the lobe selection
        probabilities; delta lobes contribute 0.
        wo, wi: unit directions in the local shading frame (z = shading normal), shape (N, 3) or (3,)
        (one side may be a single direction, broadcast), wo toward the viewer, wi toward the light.
        wavelengths: None for RGB rendering, or (4,) / (N, 4) hero wavelengths [nm] for spectral.
        eta_outside: index of the medium on the normal's side; mode: 'radiance' or 'importance'.
        """
    def sample(self, wo: typing.Any, u: typing.Any, wavelengths: typing.Any = None, eta_outside: typing.SupportsFloat | typing.SupportsIndex = 1.0, mode: str = 'radiance') -> BsdfSample:
        """
        Sample incident directions for wo (N, 3) from uniform numbers u (N, 3) in [0, 1): u[:, 0] picks the
        lobe, u[:, 1:] the direction; wo or u may be a single row. Returns a BsdfSample of arrays: wi (N, 3)
        (0 where invalid), weight (N, C) = ``f |cos theta_i| / pdf`` (delta lobes: the lobe's albedo over
        its probability), f (N, C), pdf (N,) (delta lobes: the lobe's selection probability), flags (N,)
        uint32 (1 reflection, 2 transmission, 4 diffuse, 8 glossy, 16 specular/delta), is_delta (N,), eta
        (N,) the relative index crossed (1 for reflection), valid (N,) False where no direction was
        produced, terminated (N,) True where a dispersive refraction kept the hero wavelength only. C = 3
        (RGB) or 4 (spectral). Other arguments as for f.
        """
    @property
    def alpha(self) -> float:
        """
        Opacity for raster transparency, in [0, 1] (BlinnPhong's alpha=; 1 for the others). Not a
        roughness: the alpha= of RoughDielectric, RoughConductor, Plastic and ThinFilm is their
        microfacet roughness, read back as parameters['alpha_u'] and ['alpha_v'].
        """
    @property
    def priority(self) -> int:
        """
        Nested-dielectric priority (larger wins).
        """
class Dielectric(Material):
    """
    Smooth glass: reflect with probability F, refract with 1 - F (TIR: reflect), radiance scaled by
    (eta_i / eta_t)^2 on refraction. ior: a number > 0 or 'bk7' (None: 1.5); or, instead, sellmeier=(B1,
    B2, B3, C1, C2, C3), C in um^2 (dispersive: spectral rendering keeps the hero wavelength on
    refraction).
    priority: nested dielectrics (larger wins). Model a glass of water with the water overlapping
    the glass by more than the ray offset (offset_point: 1e-5 m + 5e-7 x the coordinates; 2e-4 m near
    the origin holds), or sharing its surface exactly as triangles: surfaces 2e-6 to 2e-5 m apart, or
    coincident exact spheres, are not told apart and the medium record goes wrong (a
    trial: 27-63 % of the light lost; Mitsuba 3's larger offset, 9e-5 x (1 + the largest
    coordinate), has the same limit).
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, ior: typing.Any = None, sellmeier: typing.Any = None, priority: typing.SupportsInt | typing.SupportsIndex = 0) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class RoughDielectric(Material):
    """
    Rough glass (Walter et al. 2007): GGX alpha (or alpha_u, alpha_v), ior as for Dielectric, priority.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, alpha: typing.SupportsFloat | typing.SupportsIndex | None = None, ior: typing.Any = None, sellmeier: typing.Any = None, priority: typing.SupportsInt | typing.SupportsIndex = 0, alpha_u: typing.SupportsFloat | typing.SupportsIndex | None = None, alpha_v: typing.SupportsFloat | typing.SupportsIndex | None = None) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class ThinDielectric(Material):
    """
    A thin pane (window): reflection R' = R + T^2 R / (1 - R^2), transmission 1 - R' straight through
    (no offset, no medium inside: interior_ior is None). ior as for Dielectric.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, ior: typing.Any = None, sellmeier: typing.Any = None) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class Diffuse(Material):
    """
    Lambertian reflection f = R / pi (two-sided). reflectance: a number or (r, g, b) in [0, 1] (> 1 is
    refused: it would create energy). texture: an image file (str or os.PathLike;
    any format OpenImageIO reads, 8/16-bit files decoded from sRGB) whose linear RGB, clamped to [0, 1],
    multiplies the colour at the surface's uvs (OBJ texcoords, add_mesh(uvs=), add_ground's repeat);
    relative paths are from the working directory when the material is made. Each scene the material
    is added to registers the file (prepared once into the texture cache). An int is the id of a
    texture the scene already holds. f/pdf/sample evaluate the untextured colour.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, reflectance: typing.Any = 0.5, texture: typing.Any = None) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class BlinnPhong(Material):
    """
    Normalised Blinn-Phong: f = kd / pi + ks (ns + 8) / (8 pi) (n.h)^ns (the MTL model). kd, ks in [0,
    1] (numbers or (r, g, b)), ns >= 0; alpha in [0, 1] is the raster opacity (MTL d). Sampled by a
    mixture of the cosine hemisphere and the (n.h)^ns lobe; pdf exact. A texture multiplies kd. texture: an image file (str or os.PathLike;
    any format OpenImageIO reads, 8/16-bit files decoded from sRGB) whose linear RGB, clamped to [0, 1],
    multiplies the colour at the surface's uvs (OBJ texcoords, add_mesh(uvs=), add_ground's repeat);
    relative paths are from the working directory when the material is made. Each scene the material
    is added to registers the file (prepared once into the texture cache). An int is the id of a
    texture the scene already holds. f/pdf/sample evaluate the untextured colour.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, kd: typing.Any = 0.5, ks: typing.Any = 0.0, ns: typing.SupportsFloat | typing.SupportsIndex = 1.0, texture: typing.Any = None, alpha: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class Conductor(Material):
    """
    A smooth metal mirror with the exact complex Fresnel reflectance of eta + i k (numbers or (r, g, b),
    relative to vacuum). eta and k unset: a perfect mirror, F = 1; eta without k: k = 0.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, eta: typing.Any = None, k: typing.Any = None) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class RoughConductor(Material):
    """
    A rough metal: GGX microfacets (alpha, or alpha_u along the tangent and alpha_v along the bitangent;
    >= 0, raised to 1e-4), height-correlated Smith masking, exact complex Fresnel of eta + i k (unset: F
    = 1), visible-normal sampling.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, alpha: typing.SupportsFloat | typing.SupportsIndex | None = None, alpha_u: typing.SupportsFloat | typing.SupportsIndex | None = None, alpha_v: typing.SupportsFloat | typing.SupportsIndex | None = None, eta: typing.Any = None, k: typing.Any = None) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class Plastic(Material):
    """
    Coated diffuse (Weidlich & Wilkie 2007): a dielectric coat of index ior over a Lambertian base of
    reflectance in [0, 1]; alpha = 0: smooth coat (a delta lobe), > 0: GGX (or alpha_u, alpha_v). A
    texture multiplies the reflectance. The base's light enters and leaves through the smooth coat's
    Fresnel terms at any alpha, (1 - F(wi)) (1 - F(wo)) R / (pi eta^2 (1 - R Fdr_internal)) (internal
    reflections at the coat summed). Smooth: Mitsuba 3's plastic with nonlinear=True (its default,
    False, divides by 1 - Fdr_internal instead: brighter by (1 - R Fdr_internal) / (1 - Fdr_internal),
    35 % at R 0.77 and 2.5x as R -> 0 for ior 1.5). Rough: roughplastic's specular lobe; its diffuse
    part differs from roughplastic's, which takes the rough interface's tabulated transmittance and
    internal reflectance (a trial's directional albedos, alpha 0.3, white base, ior 1.5: 11.8 % above
    roughplastic's at normal incidence, 4.4 % below at 80 deg, 0.54 against 0.62 at 85 deg and 0.28
    against 0.60 at 89 deg). The rough lobe's Fresnel at grazing can outgrow the smooth coat's F that
    the diffuse part leaves room for: a white base under a coat of ior 10 reflects 1.05 of what arrives
    at 85 deg (1.29 at ior 50); at a polymer's 1.5 it never exceeds 1. ior in (0, 100]: beyond,
    Fdr_internal rounds to 1 and a white base's 1 / (1 - R Fdr_internal) to infinity. texture: an image file (str or os.PathLike;
    any format OpenImageIO reads, 8/16-bit files decoded from sRGB) whose linear RGB, clamped to [0, 1],
    multiplies the colour at the surface's uvs (OBJ texcoords, add_mesh(uvs=), add_ground's repeat);
    relative paths are from the working directory when the material is made. Each scene the material
    is added to registers the file (prepared once into the texture cache). An int is the id of a
    texture the scene already holds. f/pdf/sample evaluate the untextured colour.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, reflectance: typing.Any = 0.5, ior: typing.SupportsFloat | typing.SupportsIndex = 1.5, alpha: typing.SupportsFloat | typing.SupportsIndex | None = None, alpha_u: typing.SupportsFloat | typing.SupportsIndex | None = None, alpha_v: typing.SupportsFloat | typing.SupportsIndex | None = None, texture: typing.Any = None) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class Principled(Material):
    """
    Burley 2012's principled BRDF (disney.brdf without subsurface): base_color (r, g, b) in [0, 1], and
    metallic, roughness (alpha = roughness^2), anisotropic, specular, specular_tint, sheen, sheen_tint,
    clearcoat, clearcoat_gloss, all in [0, 1]. A texture multiplies base_color. Not energy conserving,
    as Burley's model is not: its lobes are summed (the diffuse is not reduced by the specular's
    reflectance) and the diffuse's retro-reflective rim exceeds 1 at grazing angles. A white base_color,
    the other parameters at their defaults, reflects 1.04 of the light at normal incidence and 1.19 at
    89 deg (1.05 and 1.21 with clearcoat 1; the mean of sample() weights): a white furnace renders it
    about 4 % bright. texture: an image file (str or os.PathLike;
    any format OpenImageIO reads, 8/16-bit files decoded from sRGB) whose linear RGB, clamped to [0, 1],
    multiplies the colour at the surface's uvs (OBJ texcoords, add_mesh(uvs=), add_ground's repeat);
    relative paths are from the working directory when the material is made. Each scene the material
    is added to registers the file (prepared once into the texture cache). An int is the id of a
    texture the scene already holds. f/pdf/sample evaluate the untextured colour.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, base_color: typing.Any = 0.5, metallic: typing.SupportsFloat | typing.SupportsIndex = 0.0, roughness: typing.SupportsFloat | typing.SupportsIndex = 0.5, anisotropic: typing.SupportsFloat | typing.SupportsIndex = 0.0, specular: typing.SupportsFloat | typing.SupportsIndex = 0.5, specular_tint: typing.SupportsFloat | typing.SupportsIndex = 0.0, *, sheen: typing.SupportsFloat | typing.SupportsIndex = 0.0, sheen_tint: typing.SupportsFloat | typing.SupportsIndex = 0.5, clearcoat: typing.SupportsFloat | typing.SupportsIndex = 0.0, clearcoat_gloss: typing.SupportsFloat | typing.SupportsIndex = 1.0, texture: typing.Any = None) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class ThinFilm(Material):
    """
    Thin-film iridescence (Belcour & Barla 2017): a film of thickness [nm] and index film_ior on a base
    of complex index eta + i k, with GGX roughness alpha (or alpha_u, alpha_v; 0 = smooth mirror). The
    Fresnel term is the film's exact Airy reflectance (RGB: at 630, 532, 465 nm). Reflection only.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, thickness: typing.SupportsFloat | typing.SupportsIndex, film_ior: typing.SupportsFloat | typing.SupportsIndex = 1.33, eta: typing.Any = 1.5, k: typing.Any = 0.0, alpha: typing.SupportsFloat | typing.SupportsIndex | None = None, *, alpha_u: typing.SupportsFloat | typing.SupportsIndex | None = None, alpha_v: typing.SupportsFloat | typing.SupportsIndex | None = None) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class Water(Material):
    """
    The sea: a wind-roughened water surface over a deep water body (water_surface.h).
    
    The interface is a Beckmann microfacet dielectric (Walter et al. 2007; Mitsuba 3's roughdielectric
    with distribution='beckmann') whose alpha^2 is Cox & Munk 1954's total mean-square slope 0.003 +
    5.12e-3 wind_speed (alpha = 0.17 at 5 m/s) and whose index is water_ior(lambda, temperature_c,
    salinity): per wavelength in spectral rendering, at 630, 532 and 465 nm per RGB channel (directions
    sampled at 550 nm). body=True (default): the deep water under it absorbs (Pope & Fry 1997) and
    backscatters (Morel 1974) the light refracted in and returns R = 0.33 b_b / (a + b_b) of it as
    isotropic light leaving through the rough interface, T(cos_i) T(cos_o) R / (pi eta^2 (1 - R
    Fbar_int)) (T = transmittance(mu), Fbar_int = internal_reflectance()); reflection-only and two-
    sided, nothing continues below. body=False: the bare interface, reflecting and transmitting,
    bounding a medium of the water's index (priority for nested dielectrics).
    Defaults: wind_speed 5 m/s (a gentle breeze), temperature_c 20 deg C, salinity 35 g/kg (the open
    ocean). resolved_slope_variance: the mean-square slope a displaced wave mesh under it already
    resolves (Scene.add_sea sets it): alpha^2 = Cox-Munk's total - it, so that resolved + unresolved =
    total. wind_speed in [0, 30] m/s, temperature_c in [-2, 40] (a cold sea at its freezing point),
    salinity in [0, 40] g/kg.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, wind_speed: typing.Any = 5.0, temperature_c: typing.Any = 20.0, salinity: typing.Any = 35.0, body: bool = True, priority: typing.SupportsInt | typing.SupportsIndex = 0, resolved_slope_variance: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def internal_reflectance(self, wavelength_nm: typing.SupportsFloat | typing.SupportsIndex = 550.0) -> float:
        """
        Fbar_int = 1 - 2 int T(mu) mu dmu / eta^2: what of isotropic light under the rough surface is sent
        back down, at wavelength_nm (the flat surface's fresnel_diffuse_reflectance(1 / eta) when alpha ->
        0).
        """
    def ior(self, wavelength_nm: typing.Any) -> typing.Any:
        """
        The water's index relative to vacuum at wavelength_nm [nm] (a number or an array).
        """
    def transmittance(self, mu: typing.Any, wavelength_nm: typing.SupportsFloat | typing.SupportsIndex = 550.0) -> typing.Any:
        """
        The rough interface's directional transmittance T(mu) from above (the share of the energy arriving
        at cos theta = mu that crosses into the water), as the water body's term uses it, at the water's
        index at wavelength_nm under vacuum, mu in [-1, 1] (std::invalid_argument naming them otherwise).
        Tabulated (33 mu x 5 eta nodes).
        """
    @property
    def alpha(self) -> float:
        """
        Deprecated: the roughness (use Water.roughness); Material.alpha, the raster's opacity, is 1 for water.
        """
    @property
    def body(self) -> bool:
        """
        Whether a deep water body is under the surface.
        """
    @property
    def mean_square_slope(self) -> float:
        """
        Cox & Munk's total sigma^2.
        """
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
    @property
    def resolved_slope_variance(self) -> float:
        """
        [-] the mean-square slope a displaced mesh under this material already shows (Scene.add_sea: the
        Tessendorf waves it resolves); the microfacets keep the rest, alpha^2 = sigma^2 - this, so that
        resolved + unresolved = Cox & Munk's total. In [0, sigma^2 - kMinUnresolvedSlopeVariance].
        """
    @property
    def roughness(self) -> float:
        """
        The Beckmann roughness alpha = sqrt(mean_square_slope - resolved_slope_variance).
        """
    @property
    def salinity(self) -> float:
        """
        [g/kg]
        """
    @property
    def temperature_c(self) -> float:
        """
        [deg C]
        """
    @property
    def wind_speed(self) -> float:
        """
        [m/s] 12.5 m above the sea
        """
class Beckmann:
    """
    The isotropic Beckmann microfacet distribution: D, Lambda (exact, with erf), G1 and the height-
    correlated G. alpha^2 is the total mean-square slope. Directions: (N, 3) unit vectors.
    """
    def D(self, m: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def G(self, wo: typing.Any, wi: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def G1(self, w: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def __getstate__(self) -> tuple[float]:
        ...
    def __init__(self, alpha: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple[typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    @property
    def alpha(self) -> float:
        ...
class TrowbridgeReitz:
    """
    The GGX microfacet distribution: D, Lambda, G1, height-correlated G, the visible-normal density and
    sampler. Directions: (N, 3) unit vectors in the local frame.
    """
    def D(self, m: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def D_visible(self, w: typing.Any, m: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def G(self, wo: typing.Any, wi: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def G1(self, w: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        ...
    def __getstate__(self) -> tuple[float, float]:
        ...
    def __init__(self, alpha_x: typing.SupportsFloat | typing.SupportsIndex, alpha_y: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    def sample_wm(self, w: typing.Any, u: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        ...
    @property
    def alpha_x(self) -> float:
        ...
    @property
    def alpha_y(self) -> float:
        ...
class Ior:
    """
    An index of refraction: constant or Sellmeier (C in um^2).
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, ior: typing.Any = None, sellmeier: typing.Any = None) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def at(self, wavelength: typing.Any) -> typing.Any:
        """
        n at wavelength(s) [nm] in the rendered range [360, 830].
        """
    @property
    def dispersive(self) -> bool:
        ...
class TerrainShading(Material):
    """
    Terrain coloured by elevation, slope and snow line (shading/terrain_shading.h), the default of
    Scene.add_terrain: Lambertian, its reflectance ``vegetation`` below ``tree_line`` [m], ``rock``
    above it and wherever the ground is steeper than ``rock_slope`` [deg], ``snow`` above ``snow_line``
    [m] on slopes under 55 deg (snow slides off steeper ones); the covers blend over 100 m of height and
    5 deg of slope. Heights are true heights above sea level: with ``earth_radius`` R > 0 (the scene's
    CurvedEarth radius) the scene's y is the flat height y' = R ln(1 + h/R) and h = R (exp(y'/R) - 1);
    inf (or 0) means a flat Earth (h = y). The slope is the shading normal's angle from +y (the Earth-
    flattening map is conformal: it keeps angles). Colours are linear RGB albedos in [0, 1]: conifer
    forest ~0.08, rock 0.2-0.3, old snow ~0.8.
    """
    def __getstate__(self) -> dict:
        ...
    def __init__(self, snow_line: typing.SupportsFloat | typing.SupportsIndex = 3000.0, tree_line: typing.SupportsFloat | typing.SupportsIndex = 2000.0, rock_slope: typing.SupportsFloat | typing.SupportsIndex = 35.0, earth_radius: typing.SupportsFloat | typing.SupportsIndex = ..., *, vegetation: typing.Any = (0.06, 0.09, 0.04), rock: typing.Any = (0.25, 0.23, 0.21), snow: typing.Any = (0.8, 0.8, 0.83)) -> None:
        ...
    def __setstate__(self, arg0: dict) -> None:
        ...
    def reflectance(self, height: typing.SupportsFloat | typing.SupportsIndex, slope: typing.SupportsFloat | typing.SupportsIndex) -> tuple:
        """
        The linear RGB albedo at true height `height` [m] on ground sloping `slope` [deg] in [0, 90].
        """
    @property
    def parameters(self) -> dict:
        """
        The constructor's keyword arguments that rebuild this material (pickling uses them).
        """
class Light:
    """
    A light. In Python its methods evaluate RGB rendering, vectorised over N points.
    """
    def L(self, points: typing.Any, normals: typing.Any, dirs: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        Area lights: RGB radiance (N, 3) leaving points (N, 3) with the light's front normals (N, 3) toward
        unit dirs (N, 3).
        """
    def Le(self, dirs: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        Infinite lights: RGB radiance (N, 3) seen looking along unit dirs (N, 3); 0 for others.
        """
    def __repr__(self) -> str:
        ...
    def pdf_li(self, points: typing.Any, normals: typing.Any, wi: typing.Any, p_light: typing.Any = None, n_light: typing.Any = None) -> numpy.typing.NDArray[numpy.float64]:
        """
        The solid-angle density (N,) with which sample_li picks unit wi (N, 3) at points (N, 3). Area lights
        need the point p_light (N, 3) where the ray along wi hits the light and its normal n_light (N, 3)
        (each empty: zeros; else one per point).
        """
    def preprocess(self, centre: typing.Any, radius: typing.SupportsFloat | typing.SupportsIndex) -> None:
        """
        Tells the light the scene's bounding sphere (centre [m], radius [m]).
        """
    def sample_li(self, points: typing.Any, normals: typing.Any, u: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
        """
        Samples a direction toward the light from each point (Light.sample_li).
        
        points: (N, 3) [m]; normals: (N, 3) unit geometric normals (rows may be 0) or None; u: (N, 2) in
        [0, 1). Returns (wi (N, 3) unit toward the light, L (N, 3) RGB radiance arriving [W/(m^2 sr)] (point
        and spot: I/r^2), pdf (N,) per steradian (delta lights: 1), distance (N,) [m] (infinite
        lights: inf)). A point the light cannot reach gets wi = 0, L = 0, pdf = 0, distance = 0.
        """
    @property
    def is_delta(self) -> bool:
        ...
    @property
    def is_infinite(self) -> bool:
        ...
    @property
    def power(self) -> float:
        """
        Emitted power [W] as luminance Y of the RGB power (infinite lights: through the disc of the scene radius given to preprocess, 1 m until then).
        """
    @property
    def type(self) -> str:
        """
        'delta_position' (point, spot), 'area' (meshes, spheres) or 'infinite' (sun, environments).
        """
class LightSampler:
    """
    Chooses one light per sample, in proportion to power ('power'), by kind ('kind') or uniformly
    ('uniform'). Build it after preprocess() of infinite lights.
    """
    def __getstate__(self) -> tuple[list[Light], int]:
        ...
    def __init__(self, lights: collections.abc.Sequence[Light], strategy: str = 'power') -> None:
        ...
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def pmf(self, index: typing.SupportsInt | typing.SupportsIndex) -> float:
        ...
    def sample(self, u: typing.Any) -> tuple[numpy.typing.NDArray[numpy.int64], numpy.typing.NDArray[numpy.float64]]:
        """
        (index (N,) int, probability (N,)) for u (N,) in [0, 1).
        """
class PointLight(Light):
    """
    A point light: intensity I [W/sr] (a colour: one number or RGB) in every direction from position
    [m]; irradiance at distance r on a surface tilted by theta E = I cos(theta) / r^2; power 4 pi I.
    """
    def __getstate__(self) -> tuple[tuple, tuple]:
        ...
    def __init__(self, position: typing.Any, intensity: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def position(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
class SpotLight(Light):
    """
    A spot light at position [m] shining along direction into a cone of full angle [deg] with intensity
    I [W/sr] (a colour). A hard edge by default (full intensity inside the cone, nothing outside); with
    inner_angle [deg] < angle a smoothstep falloff (pbrt-v4 SpotLight::I): I(w) = I
    smoothstep(cos(angle/2), cos(inner_angle/2), cos theta), theta from the axis.
    """
    def __getstate__(self) -> tuple[tuple, tuple, float, tuple, float]:
        ...
    def __init__(self, position: typing.Any, direction: typing.Any, angle: typing.SupportsFloat | typing.SupportsIndex, intensity: typing.Any, inner_angle: typing.Any = None) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def angle(self) -> float:
        ...
    @property
    def inner_angle(self) -> float:
        ...
class SunLight(Light):
    """
    The sun: a disc at infinity toward direction, mean radiance [W/(m^2 sr)] (a colour) over the disc,
    angular_diameter [deg], linear limb darkening u in [0, 1] (I(mu) = 1 - u (1 - mu)).
    """
    def __getstate__(self) -> tuple[tuple, tuple, float, float]:
        ...
    def __init__(self, direction: typing.Any, radiance: typing.Any, angular_diameter: typing.SupportsFloat | typing.SupportsIndex = 0.53, limb_darkening: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def direction(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def irradiance(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        RGB irradiance [W/m^2] on a surface facing the sun.
        """
    @property
    def solid_angle(self) -> float:
        """
        Of the disc [sr].
        """
class AreaLight(Light):
    """
    An emissive triangle mesh: vertices (V, 3) [m], triangles (T, 3) of vertex indices, uniform emission
    radiance L_e [W/(m^2 sr)] (a colour) from the counter-clockwise front of every triangle (front
    normal normalize((v1 - v0) x (v2 - v0))) or from both sides when two_sided.
    """
    def __getstate__(self) -> tuple[tuple, tuple, bool]:
        ...
    def __init__(self, vertices: typing.Any, triangles: typing.Any, emission: typing.Any, two_sided: bool = False) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def normal(self, triangle: typing.SupportsInt | typing.SupportsIndex) -> numpy.typing.NDArray[numpy.float64]:
        """
        The front normal of an area light's triangle (unit; 0 for a zero-area one; ValueError for an index
        past its triangles).
        """
    @property
    def area(self) -> float:
        """
        Total area [m^2] (zero-area triangles count 0).
        """
    @property
    def two_sided(self) -> bool:
        ...
class SphereLight(Light):
    """
    An emissive sphere: centre [m], radius [m], uniform emission radiance L_e [W/(m^2 sr)] (a colour)
    leaving its surface outward; power 4 pi^2 r^2 Y(L_e).
    """
    def __getstate__(self) -> tuple[tuple, float, tuple]:
        ...
    def __init__(self, centre: typing.Any, radius: typing.SupportsFloat | typing.SupportsIndex, emission: typing.Any) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def radius(self) -> float:
        ...
class EnvironmentLight(Light):
    """
    An equirectangular environment map (H, W, 3) of float linear RGB, rows top (up, +y) to
    bottom: radiance [W/(m^2 sr)] = scale x the map, rotated by rotation (degrees about +y or a
    3 x 3 map-to-world matrix). Mitsuba 3's envmap orientation and interpolation
    (src/emitters/envmap.cpp): in the map's frame d = rotation^T x world direction, u = atan2(d.x, -d.z)
    / (2 pi) wrapped into [0, 1), v = acos(d.y) / pi; back: theta = pi v, phi = 2 pi u, d = (sin phi sin
    theta, cos theta, -cos phi sin theta). So u = 0 looks along -z, u = 1/4 along +x, u = 1/2 (the
    centre column) along +z. Column i is centred at u = (i + 1/2) / W and wraps around; row j is at v =
    j / (H - 1) (the first and last rows are the poles); radiance is bilinear between the four
    surrounding texels.
    """
    @staticmethod
    def rotation_about_y(degrees: typing.SupportsFloat | typing.SupportsIndex) -> numpy.typing.NDArray[numpy.float64]:
        """
        The 3 x 3 rotation about +y by degrees (right-handed: +x turns toward -z).
        """
    def __getstate__(self) -> tuple:
        ...
    def __init__(self, image: typing.Any, scale: typing.SupportsFloat | typing.SupportsIndex = 1.0, rotation: typing.Any = None) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    def direction_to_uv(self, dirs: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        (u, v) (N, 2) of directions (N, 3) (normalised here).
        """
    def uv_to_direction(self, uv: typing.Any) -> numpy.typing.NDArray[numpy.float64]:
        """
        World directions (N, 3) of (u, v) (N, 2), each in [0, 1].
        """
    @property
    def rotation(self) -> numpy.typing.NDArray[numpy.float64]:
        """
        The 3 x 3 rotation, map frame -> world.
        """
    @property
    def scale(self) -> float:
        ...
class ConstantEnvironment(Light):
    """
    Uniform radiance L_e [W/(m^2 sr)] (a colour) from every direction; sampling 'cosine' (about the
    point's normal, when given) or 'uniform' (the sphere, pdf 1/(4 pi)). Irradiance pi L_e.
    """
    def __getstate__(self) -> tuple[tuple, int]:
        ...
    def __init__(self, radiance: typing.Any, sampling: str = 'cosine') -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
class ScaledLight(Light):
    """
    An infinite light (a sky or an environment, not the sun) times a constant factor `scale`:
    Scene.set_physical_sky's `scale` on its sky. Pickles through its light and scale.
    """
    def __getstate__(self) -> tuple[typing.Any, float]:
        ...
    def __init__(self, light: typing.Any, scale: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def light(self) -> typing.Any:
        ...
    @property
    def scale(self) -> float:
        ...
class PhysicalSky:
    """
    A physical sky through a spherical standard atmosphere: single scattering (Nishita et al. 1993)
    plus, with multiple_scattering (default True), the higher orders by Hillaire 2020's isotropic
    multiple-scattering table (orders 2-13 explicit, then a geometric series): Rayleigh (lambda^-4, 8
    km, tau(550 nm) = 0.097), Mie (1.2 km, Cornette-Shanks g = 0.76, scaled by `aerosol`, or set by a
    meteorological `visibility` [km] instead: the total extinction at the ground at 550 nm is 3.912 /
    visibility, Koschmieder), ozone absorption (`ozone_du` Dobson units), a 5778 K sun scaled to 1361
    W/m^2.
    sun_direction: toward the sun (normalised), y up. Radiance in W/(m^2 sr nm); below the horizon, by
    below_horizon: 'ground' (default) the ground's Lambertian radiance (ground_albedo), reached by
    BSDF sampling only (pdf_li 0); 'horizon' the radiance at the horizon at the same azimuth
    (ground_albedo must be 0), sample_li/pdf_li then cover the whole sphere (Scene.set_physical_sky's
    default). Light sampling draws directions in proportion to a table of the sky's luminance (the upper
    hemisphere; the whole sphere with 'horizon').
    """
    @staticmethod
    def solar_irradiance(wavelengths: typing.Any) -> typing.Any:
        """
        Extraterrestrial solar spectral irradiance [W/(m^2 nm)] at a wavelength [nm] (a 5778 K black body
        scaled to the solar constant, 1361 W/m^2).
        """
    def __getstate__(self) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], float, float, float, float, float, int, bool]:
        ...
    def __init__(self, sun_direction: typing.Any, aerosol: typing.SupportsFloat | typing.SupportsIndex | None = None, ozone_du: typing.SupportsFloat | typing.SupportsIndex = 300.0, ground_albedo: typing.SupportsFloat | typing.SupportsIndex = 0.0, altitude: typing.SupportsFloat | typing.SupportsIndex = 0.0, rayleigh_scale: typing.SupportsFloat | typing.SupportsIndex = 1.0, *, below_horizon: str = 'ground', visibility: typing.SupportsFloat | typing.SupportsIndex | None = None, multiple_scattering: bool = True) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple[typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex, typing.SupportsInt | typing.SupportsIndex, bool]) -> None:
        ...
    def optical_depth(self, wavelength: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        The whole optical depth (Rayleigh + Mie + ozone) from the observer straight up to the top at a
        wavelength [nm].
        """
    def pdf_li(self, dirs: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
        """
        The light-sampling density [1/sr] of sample_li in each unit direction (dirs (N, 3) or (3,)).
        """
    def power(self) -> float:
        ...
    def preprocess(self, centre: typing.Any, radius: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def radiance(self, dirs: typing.Any, wavelengths: typing.Any, direct: bool = False) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
        """
        The sky's radiance [W/(m^2 sr nm)] in each unit direction (dirs (N, 3) or (3,)) at each wavelength
        [nm] in [360, 830]: an array (directions, wavelengths). direct: integrated along each direction
        without the sky's table (slower; the table's reference).
        """
    def rayleigh_optical_depth(self, wavelength: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        The Rayleigh optical depth from the observer straight up to the top at a wavelength [nm] (a
        numerical integral of the profile).
        """
    def rgb_radiance(self, dirs: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
        """
        The sky's radiance in each unit direction (dirs (N, 3) or (3,)) as RGB renders see it, (N, 3):
        linear sRGB of the spectrum's XYZ / integral ybar, i.e. a luminance-weighted spectral radiance
        [W/(m^2 sr nm)] (times 106.86 nm: W/(m^2 sr)).
        """
    def sample_li(self, u: typing.Any) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]]:
        """
        Light sampling at each row (u1, u2) of u (N, 2) in [0, 1): (directions (N, 3), pdf [1/sr] (N,), RGB
        radiance (N, 3)), 0 where nothing was sampled.
        """
    def sun_radiance(self, wavelengths: typing.Any, angular_diameter_deg: typing.SupportsFloat | typing.SupportsIndex = 0.53) -> typing.Any:
        """
        The sun's radiance at the observer [W/(m^2 sr nm)] at a wavelength [nm] in [360, 830]: its
        irradiance (solar_irradiance x sun_transmittance) spread uniformly over a disc of
        `angular_diameter_deg`.
        """
    def sun_radiance_rgb(self, angular_diameter_deg: typing.SupportsFloat | typing.SupportsIndex = 0.53) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
        """
        The sun's radiance at the observer as RGB renders see it: linear sRGB of its XYZ / integral ybar, a
        luminance-weighted spectral radiance [W/(m^2 sr nm)] (times 106.86 nm: W/(m^2 sr)).
        """
    def sun_transmittance(self, wavelengths: typing.Any) -> typing.Any:
        """
        Beer-Lambert transmittance of the sunlight from the top of the atmosphere to the observer at a
        wavelength [nm] in [360, 830].
        """
    @property
    def aerosol(self) -> float:
        """
        The Mie density scale (set from `visibility` when that was given).
        """
    @property
    def build_seconds(self) -> float:
        ...
class AerialPerspective:
    """
    Aerial perspective of a physical sky: along a segment of air from a viewer at `a` to a point `b` [m]
    (scene coordinates; y = 0 lies the sky's `altitude` above sea level), the transmittance T and the
    scattered sunlight S the air adds (the sky's coefficients, densities, phase functions, ozone, sun
    and multiple-scattering table): what arrives at a is T L(b) + S. The chord is integrated in pieces
    in closed form (cpp/refracta/shading/aerial_perspective.h).
    earth_radius: a CurvedEarth's radius when the scene is its flat frame (y is then the height above
    the curved ground), inf for a flat scene (the sky's planet touches y = 0 under the origin).
    Scene.set_physical_sky(aerial_perspective=True) makes the renderers apply it to every segment.
    """
    def __getstate__(self) -> tuple[tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], float, float, float, float, float, int, bool], float]:
        ...
    def __init__(self, sky: PhysicalSky, scale: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def __setstate__(self, arg0: tuple[tuple[typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[3, 1]"], typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex, typing.SupportsInt | typing.SupportsIndex, bool], typing.SupportsFloat | typing.SupportsIndex]) -> None:
        ...
    def along(self, a: typing.Any, b: typing.Any, wavelength: typing.SupportsFloat | typing.SupportsIndex, earth_radius: typing.SupportsFloat | typing.SupportsIndex = ...) -> tuple[float, float]:
        """
        (transmittance, in-scatter [W/(m^2 sr nm)] x scale) at one wavelength [nm] in [360, 830].
        """
    def along_rgb(self, a: typing.Any, b: typing.Any, earth_radius: typing.SupportsFloat | typing.SupportsIndex = ...) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]]:
        """
        (transmittance, in-scatter) as RGB renders apply them: linear sRGB, the sky's Le convention.
        """
    def inscatter_reference(self, a: typing.Any, b: typing.Any, wavelength: typing.SupportsFloat | typing.SupportsIndex, steps: typing.SupportsInt | typing.SupportsIndex = 4096, earth_radius: typing.SupportsFloat | typing.SupportsIndex = ...) -> float:
        """
        The same in-scatter by brute force: `steps` midpoints on the chord, each point's sun column traced.
        """
    def sun_transmittance(self, height: typing.SupportsFloat | typing.SupportsIndex, elevation_deg: typing.SupportsFloat | typing.SupportsIndex, wavelength: typing.SupportsFloat | typing.SupportsIndex) -> float:
        """
        The sun's transmittance to `height` [m] above sea level where it stands `elevation_deg` above the local horizon.
        """
    @property
    def scale(self) -> float:
        ...
class DispersedField(IndexField):
    """
    A field at another wavelength: n' = 1 + scale (n - 1), grad n' = scale grad n, height-only as its
    base; for dry air scale = K(lambda)/K(lambda_ref) (air_dispersion_scale). Its parameters are the
    base's. Spectral renders through a field build these per sample (each hero wavelength); build one
    with dispersed_field(field, wavelength).
    
    Built by dispersed_field, it knows its wavelength: its `wavelength` parameter (where its base has
    one: PhysicalAtmosphere, TemperatureProfile) is that wavelength, not the base's, so that
    field_reference_wavelength, a second dispersed_field (which scales from it) and the repr see the air
    it is (a trial: a field dispersed to 450 nm said 550, and dispersing it again scaled from 550);
    with_param_values then reads a new wavelength as a new scale over the base. Over a base without one
    (550 nm by convention) the parameters stay the base's.
    """
    def __getstate__(self) -> tuple[IndexField, float, float]:
        ...
    def __init__(self, base: IndexField, scale: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    def __setstate__(self, arg0: tuple) -> None:
        ...
    @property
    def base(self) -> IndexField:
        ...
    @property
    def scale(self) -> float:
        ...
def _astronomical_refraction(field: IndexField, elevations: typing.Any, eye_height: typing.SupportsFloat | typing.SupportsIndex | None, top: typing.SupportsFloat | typing.SupportsIndex | None, earth_radius: typing.SupportsFloat | typing.SupportsIndex | None, tol: typing.SupportsFloat | typing.SupportsIndex | None) -> numpy.typing.NDArray[numpy.float64]:
    """
    Refraction [rad] at apparent elevations [rad] (refracta.astronomical_refraction).
    """
def _build_options(cls: type, options: typing.Any, owner: str, fields: dict, paths: dict = {}) -> typing.Any:
    """
    A validated copy of options (a cls, or None) with fields set (paths: keyword -> dotted nested field): refracta._options.build's rule.
    """
def _cancel_thread_work(thread_ids: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex]) -> int:
    """
    Cancels the refracta calls of the given Python threads (threading.get_ident()): those running and those they start until _end_thread_cancel; returns how many were running.
    """
def _canonical_bound(moments: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], z_f: typing.SupportsFloat | typing.SupportsIndex) -> tuple[float, float, bool]:
    """
    (lower, at_query, fallback) of the canonical bound.
    """
def _channel_names(path: str) -> list[str]:
    """
    The channel names of an image file (OIIO's).
    """
def _check_derivatives(derivatives: str, field: IndexField) -> None:
    """
    "automatic", "numeric", or "auto" (automatic when `field` has a templated model, else numeric).
    """
def _check_image_format(path: str) -> None:
    """
    IoError unless an image of path's format (its extension) can be written.
    """
def _check_writable(path: str) -> None:
    """
    IoError if `path` exists and is not a regular file: opening a FIFO to write waits for a reader that
    may never come, so writers refuse it (and devices, folders) before opening.
    """
def _cmj_pattern(count: typing.SupportsInt | typing.SupportsIndex, seed: typing.SupportsInt | typing.SupportsIndex) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 2]"]:
    """
    (count, 2) sample positions in [0, 1)^2 of the film's correlated multi-jittered pattern (core/sample_patterns.h,
    Kensler 2013) with the shuffles of `seed`, jittered by the generator Rng(seed, 0).
    """
def _composite(depths: typing.Any, alphas: typing.Any, colors: typing.Any, background: typing.Any, settings: OitSettings) -> numpy.typing.NDArray[numpy.float64]:
    """
    One pixel's fragments composited over the background.
    """
def _display(image: typing.Any, display: DisplaySettings) -> numpy.typing.NDArray[numpy.float32]:
    """
    Display values of an image (refracta.io.to_display).
    """
def _display_exposure(image: typing.Any, display: DisplaySettings) -> tuple[float, bool]:
    """
    (c, metered_nothing): the exposure c the display settings give this image (io.exposure_of), and whether
    automatic exposure found no light to meter.
    """
def _end_thread_cancel(thread_id: typing.SupportsInt | typing.SupportsIndex) -> None:
    """
    Lets the thread's refracta calls run again after _cancel_thread_work.
    """
def _ev100(f_number: typing.SupportsFloat | typing.SupportsIndex, shutter: typing.SupportsFloat | typing.SupportsIndex, iso: typing.SupportsFloat | typing.SupportsIndex = 100.0) -> float:
    """
    EV100 = log2(N^2 / t) - log2(ISO / 100) of a camera's f-number, shutter time [s] and ISO.
    """
def _is_float_format(path: str) -> bool:
    """
    Whether write_image keeps path's format linear.
    """
def _mboit_unorm16(b: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex]) -> list[float]:
    """
    6 or 8 normalised power moments after MBOIT's 16-bit storage (transform, rounding, inverse).
    """
def _mirage_images(true_elevation: typing.Annotated[numpy.typing.ArrayLike, numpy.float32, "[m, n]"], object_id: typing.Annotated[numpy.typing.ArrayLike, numpy.float32, "[m, n]"]) -> typing.Annotated[numpy.typing.NDArray[numpy.int32], "[m, n]"]:
    """
    Mirage multiplicity per pixel (render's aovs 'images'; render/readouts.h mirage_images): (H, W) int32.
    """
def _pair_distances(field: IndexField, origins: typing.Any, directions: typing.Any, sources: typing.Any, options: PairOptions) -> numpy.typing.NDArray[numpy.float64]:
    ...
def _pair_jacobian(field: IndexField, origins: typing.Any, directions: typing.Any, sources: typing.Any, *, weights: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] | None, margins: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] | None, free: collections.abc.Sequence[str], derivatives: str, options: PairOptions, camera: Camera | None = None, pixels: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 2]"] | None = None) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"], list[str]]:
    ...
def _pair_paths(field: IndexField, origins: typing.Any, directions: typing.Any, sources: typing.Any, options: PairOptions) -> list[RayPath]:
    """
    Each pair's path, traced by PairOptions' rule for it (what its miss is measured on).
    """
def _perturbed_trace_refusal(field: IndexField, options: RenderOptions, camera: Camera) -> str | None:
    """
    Why options.turbulence_trace 'perturbed' cannot serve a render through `field` from `camera` (empty:
    it can, or 'strict' or 'auto' was asked, or the field has no turbulence): the fast path follows the
    eye table's calm paths (renderer.cpp eye_table: calm air that is height-only or hot spots over such
    air, RGB, curved rays, the table on and stratified, a pinhole camera, paths over a spherical Earth
    no longer than kTableLongestPath). ShimmerCaster::make's rule; render() and animate() (Python) warn
    with it, as the render then traces strictly.
    """
def _power_moment_bound(moments: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], z_f: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"]) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]]:
    """
    MBOIT's per-pixel fast path: (lower, at_query, fallback) at every z_f.
    """
def _quantize_moments(moments: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 4]"], depth_range: str, inverse: bool) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 4]"]:
    """
    The optimised quantisation transform of (N, 4) moments, or its inverse.
    """
def _rasterize(scene: Scene, camera: Camera, guard_band: typing.SupportsFloat | typing.SupportsIndex, tile: typing.SupportsInt | typing.SupportsIndex | None) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float32], "[m, n]"], typing.Annotated[numpy.typing.NDArray[numpy.int64], "[m, n]"], typing.Annotated[numpy.typing.NDArray[numpy.int64], "[m, n]"], typing.Annotated[numpy.typing.NDArray[numpy.float32], "[m, n]"], tuple[int, int], int, int, int]:
    """
    (depth, geometry, primitive, barycentric (H * W, 3), offset, triangles, screen triangles, fragments).
    """
def _read_image(path: typing.Any, linear: bool) -> numpy.typing.NDArray[numpy.float32]:
    ...
def _render(scene: Scene, camera: Camera, field: IndexField, options: RenderOptions, progress: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float32], RenderStats]:
    ...
def _render_raster(scene: Scene, camera: Camera, options: RasterRenderOptions, progress: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float32], RasterRenderStats]:
    """
    (image, RasterRenderStats) of refracta.render_raster.
    """
def _shadow_intensity(moments: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 4]"], z_f: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 1]"], method: str, settings: MomentShadowSettings) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    Shadow intensities of (N, 4) moments at N receiver depths.
    """
def _shutdown_running_work(timeout_seconds: typing.SupportsFloat | typing.SupportsIndex = 10.0) -> None:
    ...
def _solve_edit(field: IndexField, origins: typing.Any, directions: typing.Any, sources: typing.Any, *, weights: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] | None, margins: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] | None, tolerances: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] | None, free: collections.abc.Sequence[str], bounds: collections.abc.Mapping[str, tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex]], derivatives: str, pair_options: PairOptions, settings: SolveSettings, progress: typing.Any, camera: Camera | None = None, pixels: typing.Annotated[numpy.typing.ArrayLike, numpy.float64, "[m, 2]"] | None = None) -> SolveSummary:
    ...
def _spectrum_blackbody(temperature: typing.SupportsFloat | typing.SupportsIndex, wavelengths: typing.Any, luminance: typing.SupportsFloat | typing.SupportsIndex | None) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    Planck's law (spectrum.py).
    """
def _spectrum_cie_xyz(wavelengths: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    The CIE 1931 functions (spectrum.py).
    """
def _spectrum_cie_y_integral() -> float:
    """
    integral y (spectrum.py).
    """
def _spectrum_coefficients(rgb: typing.Any, method: str) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 4]"]:
    """
    Rows of (c0, c1, c2, residual) (spectrum.py).
    """
def _spectrum_d65(wavelengths: typing.Any, normalised: bool) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 1]"]:
    """
    D65 (spectrum.py).
    """
def _spectrum_measure_table(resolution: typing.SupportsInt | typing.SupportsIndex, quadrature_step_nm: typing.SupportsInt | typing.SupportsIndex, polish_steps: typing.SupportsInt | typing.SupportsIndex, samples: typing.SupportsInt | typing.SupportsIndex, seed: typing.SupportsInt | typing.SupportsIndex) -> dict:
    """
    Builds and measures a coefficient table (spectrum.py).
    """
def _spectrum_rgb_to_spectrum(rgb: typing.Any, wavelengths: typing.Any, kind: str, method: str) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, n]"]:
    """
    Rows of spectra (spectrum.py).
    """
def _spectrum_sample_wavelengths(u: typing.Any, terminate: bool) -> tuple[typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 4]"], typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 4]"]]:
    """
    Hero wavelengths and pdfs (spectrum.py).
    """
def _spectrum_tabulated_to_rgb(wavelengths: typing.Any, values: typing.Any, kind: str) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[3, 1]"]:
    """
    RGB of a tabulated spectrum (spectrum.py).
    """
def _spectrum_to_linear_srgb(radiance: typing.Any, wavelengths: typing.Any, pdf: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    The spectral estimate's RGB (spectrum.py).
    """
def _spectrum_xyz_to_linear_srgb(xyz: typing.Any) -> typing.Annotated[numpy.typing.NDArray[numpy.float64], "[m, 3]"]:
    """
    XYZ rows to linear sRGB (spectrum.py).
    """
def _tabulate_heights(field: IndexField, lo: typing.SupportsFloat | typing.SupportsIndex, hi: typing.SupportsFloat | typing.SupportsIndex) -> IndexField:
    """
    A height-only field tabulated over [lo, hi] m (cubic Hermite to 1e-12 in n); other fields unchanged.
    """
def _trace_batch(field: IndexField, origins: typing.Any, directions: typing.Any, options: typing.Any, progress: typing.Any, **kwargs) -> tuple:
    ...
def _white_balance_matrix(image: typing.Any, display: DisplaySettings) -> numpy.typing.NDArray[numpy.float64]:
    """
    The white balance's linear sRGB matrix for this image (io.white_balance_of).
    """
def _write_image(path: typing.Any, image: typing.Any, display: DisplaySettings) -> None:
    """
    Write an image as refracta.io.write_image.
    """
def _write_image_channels(path: str, image: typing.Any, names: collections.abc.Sequence[str]) -> None:
    """
    Write (H, W, C) float pixels as they are to a float file (EXR) with one name per channel (io.write_layers).
    """
def air_dispersion_scale(wavelength: typing.SupportsFloat | typing.SupportsIndex, reference: typing.SupportsFloat | typing.SupportsIndex = 550.0) -> float:
    """
    K(wavelength)/K(reference) of dry air (Birch & Downs 1993 Edlen formula at 101325 Pa, 288.15 K):
    the factor of n - 1 from the reference wavelength to `wavelength` [nm], both in [230, 2000].
    """
def bessel_j1(x: typing.Any) -> numpy.ndarray:
    """
    The Bessel function J1 (std::cyl_bessel_j), element by element.
    """
def cox_munk_mean_square_slope(wind_speed: typing.Any) -> typing.Any:
    """
    Total (upwind + crosswind) mean-square slope of a clean sea surface at wind speed U [m/s], 12.5 m
    above the sea: sigma^2 = 0.003 + 5.12e-3 U (Cox & Munk 1954, "Measurement of the roughness of the
    sea surface from photographs of the sun's glitter", JOSA 44(11), 838-850, eq. for sigma_u^2 +
    sigma_c^2, +-0.004). U in [0, 30]; ValueError naming wind_speed otherwise.
    Vectorised: numbers or arrays of them (numpy broadcasting).
    """
def dispersed_field(field: IndexField, wavelength: typing.SupportsFloat | typing.SupportsIndex, reference: typing.SupportsFloat | typing.SupportsIndex | None = None) -> IndexField:
    """
    The field at `wavelength` [nm] (dry-air dispersion, n - 1 scaled by air_dispersion_scale from
    `reference`, default field_reference_wavelength(field)); CurvedEarth is rebuilt over its
    dispersed base; the field itself when nothing changes.
    """
def field_reference_wavelength(field: IndexField) -> float:
    """
    The wavelength [nm] a field's n stands for: its `wavelength` parameter (PhysicalAtmosphere,
    TemperatureProfile, CurvedEarth over them), else 550.
    """
def fresnel_conductor(cos_i: typing.Any, eta: typing.Any, k: typing.Any) -> typing.Any:
    """
    Unpolarised Fresnel reflectance of a conductor of relative complex index eta + i k at ``|cos_i|`` (exact). Vectorised.
    """
def fresnel_dielectric(cos_i: typing.Any, eta: typing.Any) -> typing.Any:
    """
    Unpolarised Fresnel reflectance of a dielectric interface, eta = eta_t / eta_i on the side cos_i > 0
    (cos_i < 0: from inside, 1 / eta). Total internal reflection gives 1. Vectorised.
    """
def fresnel_diffuse_reflectance(eta: typing.SupportsFloat | typing.SupportsIndex) -> float:
    """
    Hemispherical reflectance 2 int F(mu) mu dmu of a dielectric seen from the side where eta = eta_t / eta_i.
    """
def get_threads() -> int:
    """
    The number of threads refracta's parallel work may use (see set_threads).
    """
def physical_memory_bytes() -> float:
    """
    This machine's physical memory [bytes] (0 if unknown), by which refracta refuses work too large to allocate.
    """
def set_threads(n: typing.SupportsInt | typing.SupportsIndex | None) -> None:
    """
    Limit refracta's parallel work (oneTBB: render, trace_rays, render_raster, solve's pair traces,
    Embree's BVH builds; OpenImageIO's image and texture work) to n threads, n in [0, 256]; n = None or 0 restores the default, every core. Results do
    not depend on it: every parallel loop writes each item's result to its own slot.
    """
def synthesise_turbulence(settings: TurbulenceSettings, progress: typing.Any = None) -> TurbulenceGrid:
    """
    The spline coefficients of the pattern for C_n^2 = 1 (a TurbulenceGrid); GIL released, Ctrl-C stops it.
    """
def thin_film_reflectance(cos_i: typing.Any, n1: typing.Any, n2: typing.Any, eta: typing.Any, k: typing.Any, *, thickness: typing.Any, wavelength: typing.Any) -> typing.Any:
    """
    Airy reflectance of a film (index n2, thickness [nm]) between n1 and a base eta + i k at a wavelength [nm]. Vectorised.
    """
def trace_ray(field: IndexField, origin: typing.Any, direction: typing.Any, options: typing.Any = None, **kwargs) -> RayPath:
    """
    Trace one curved ray through `field` and return its RayPath (the whole path recorded).
    
    The ray equations dx/ds = v/n, dv/ds = grad n are launched with ``v0 = n(origin) * direction /
    |direction|``. options: a refracta.TraceOptions, or None for its defaults; any of its fields may
    also be given as keywords (trace, tol, step, max_length, stop_height, max_steps, ior_floor), e.g.
    ``trace_ray(field, o, d, trace='rk4', step=0.1)``; ``method=`` is the deprecated name of ``trace=``.
    Raises ValueError for bad arguments (a path needing more than max_steps nodes is refused up front),
    refracta.NumericalError where n <= 0 or is not finite; Ctrl-C (KeyboardInterrupt) stops it.
    """
def turbulence_memory_needed(cells: typing.SupportsInt | typing.SupportsIndex) -> float:
    """
    Bytes the synthesis of a cells^3 grid holds at its peak (a bound).
    """
def von_karman_spectrum(kappa: typing.Any, cn2: typing.SupportsFloat | typing.SupportsIndex = 1.0, inner_scale: typing.SupportsFloat | typing.SupportsIndex = 0.0, outer_scale: typing.SupportsFloat | typing.SupportsIndex = ...) -> numpy.ndarray:
    """
    The von Karman spectrum with a Gaussian inner cutoff, Phi_n(kappa) [m^3]: 0.033005 C_n^2 (kappa^2 +
    kappa0^2)^(-11/6) exp(-kappa^2 / kappa_m^2), kappa0 = 2 pi / L0, kappa_m = 5.92 / l0 (Andrews &
    Phillips 2005, eq. 3.27). kappa [rad/m] (array); inner_scale l0 = 0: no cutoff; outer_scale L0 =
    inf: Kolmogorov at small kappa (infinite at kappa = 0).
    """
def water_absorption(wavelength_nm: typing.Any) -> typing.Any:
    """
    Absorption coefficient of pure water [1/m] at a wavelength [nm] in [360, 830], linear between 5 nm
    nodes: Pope & Fry 1997 ("Absorption spectrum (380-700 nm) of pure water. II. Integrating cavity
    measurements", Applied Optics 36(33), 8710-8723) from 380 to 725 nm; Smith & Baker 1981 ("Optical
    properties of the clearest natural waters (200-800 nm)", Applied Optics 20(2), 177-184) below; Kou,
    Labrie & Chylek 1993 (Applied Optics 32(19)) above, as NASA's ocean-colour processing joins them
    (0.00635 at 440 nm, 0.0565 at 550, 0.624 at 700). The small temperature and salinity dependence of
    absorption is left out. Outside the range: std::invalid_argument (ValueError in Python).
    Vectorised: numbers or arrays of them (numpy broadcasting).
    """
def water_backscattering(wavelength_nm: typing.Any, salinity: typing.Any = 0.0) -> typing.Any:
    """
    Backscattering coefficient of pure (sea) water [1/m]: half the molecular scattering b_w(lambda) =
    b_w(500) (lambda / 500)^-4.32 of Morel 1974 ("Optical properties of pure water and pure sea water",
    in Optical Aspects of Oceanography, Jerlov & Steemann Nielsen eds.), whose phase function is
    symmetric front-to-back; b_w(500) = 0.00222 1/m for pure water, and sea water (S = 35-39 g/kg)
    scatters 30 % more: b_w(500) = 0.00222 (1 + 0.3 S / 37). Zhang et al. 2009 (Optics Express 17(7))
    derive the same lambda^-4.32 slope from fluctuation theory. Wavelength in [360, 830] nm
    (water_absorption's range, with which it makes the water body's colour), salinity in [0,
    kWaterMaxSalinity = 40] g/kg; outside: std::invalid_argument (ValueError in Python).
    Vectorised: numbers or arrays of them (numpy broadcasting).
    """
def water_body_reflectance(wavelength_nm: typing.Any, salinity: typing.Any = 0.0) -> typing.Any:
    """
    Irradiance reflectance R = E_u / E_d just beneath the surface of an optically deep, homogeneous
    water body: R = 0.33 b_b / (a + b_b) (Morel & Prieur 1977, "Analysis of variations in ocean color",
    Limnology and Oceanography 22(4), R = 0.33 b_b / a; written with Gordon, Brown & Jacobs 1975's
    variable X = b_b / (a + b_b), Applied Optics 14(2), so that R stays below 0.33 where backscattering
    rivals absorption). Pure water of the given salinity: blue (0.13 at 420 nm), 0.0054 at 550 nm,
    4.4e-4 at 650 nm for S = 35). Throws outside 360-830 nm or 0-40 g/kg.
    Vectorised: numbers or arrays of them (numpy broadcasting).
    """
def water_density(temperature_c: typing.Any) -> typing.Any:
    """
    Density of air-free pure water at 101 325 Pa [kg/m^3], temperature [deg C] in [-2, 40] (above):
    Tanaka, Girard, Davis, Peuto & Bignell 2001, "Recommended table for the density of water between 0 C
    and 40 C", Metrologia 38, eq. 1 (999.97495 kg/m^3 at its maximum near 4 C, 998.2067 at 20 C).
    Outside the range: std::invalid_argument (ValueError in Python).
    Vectorised: numbers or arrays of them (numpy broadcasting).
    """
def water_ior(wavelength_nm: typing.Any, temperature_c: typing.Any = 20.0, salinity: typing.Any = 0.0) -> typing.Any:
    """
    Refractive index of water relative to vacuum at a vacuum wavelength [nm] in [200, 1100], temperature
    [deg C] in [-2, 40] and salinity [g/kg, ~PSU] in [0, 40], at atmospheric pressure. Pure water by
    IAPWS R9-97, "Release on the Refractive Index of Ordinary Water Substance as a Function of
    Wavelength, Temperature and Pressure" (the Lorentz-Lorenz form (n^2 - 1)/(n^2 + 2) = rho_bar
    A(rho_bar, T_bar, lambda_bar), eq. A1), at water_density(t); sea water plus the salinity terms of
    Quan & Fry 1995, Applied Optics 34(18), eq. 3, (n1 + n2 t + n3 t^2) S + n6 S / lambda (fitted 0-35
    g/kg, 0-30 C, 400-700 nm, relative to air: the 3e-4 difference from vacuum in the increment is far
    below the fit's accuracy). Outside the ranges: std::invalid_argument (ValueError in Python) naming
    the argument.
    Vectorised: numbers or arrays of them (numpy broadcasting).
    """
DEFAULT_TURBULENCE_YAW_DEG: float = 31.71747441146101
EDIT_CAMERA_PARAMETERS: tuple = ('camera_yaw', 'camera_pitch', 'camera_roll', 'camera_vfov')
INNER_SCALE_FACTOR: float = 5.92
SPECTRUM_CONSTANT: float = 0.03300539063636137
_READOUT_CHANNELS: dict = {'distance': (9, 1), 'position': (10, 3), 'object_id': (13, 1), 'apparent_elevation': (14, 1), 'apparent_azimuth': (15, 1), 'true_elevation': (16, 1), 'hidden_height': (17, 2)}
_SCENE_REACH: float = 10000000.0
_stop_names: tuple = ('max_length', 'stop_height', 'stopped')
