"""
refracta's C++ core (private; use the refracta package)
"""
from __future__ import annotations
import collections.abc
import numpy
import numpy.typing
import typing
__all__: list[str] = ['Camera', 'CurvedEarth', 'CustomField', 'IndexField', 'IoError', 'LinearSquaredProfile', 'LogisticProfile', 'NumericalError', 'PhysicalAtmosphere', 'RayPath', 'Scene', 'TemperatureProfile', 'trace_ray']
class NumericalError(RuntimeError):
    pass
class IoError(OSError):
    pass
class IndexField:
    """
    A refractive-index field n(x). Points are (N, 3) or (3,) float arrays in metres, y up.
    
    ior(points) -> n, shape (N,) (float for one point); grad_ior(points) -> grad n [1/m], (N, 3).
    params: dict of parameter values; param_names; bounds: dict name -> (lower, upper), the box an
    optimiser searches; with_params(**values) -> a new field; height_only: n depends on y alone;
    gauge_params: parameters an optimiser holds fixed by default (a joint scaling leaves rays unchanged).
    Raises refracta.NumericalError where n <= 0 or is not finite.
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
    def with_params(self, **kwargs) -> IndexField:
        """
        A new field of the same model with the given parameters changed.
        """
    @property
    def bounds(self) -> dict:
        ...
    @property
    def gauge_params(self) -> list[str]:
        ...
    @property
    def height_only(self) -> bool:
        ...
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
        ...
    @property
    def type_name(self) -> str:
        ...
class LogisticProfile(IndexField):
    """
    The original mirage editor's height profile (Choi 2017), in scene units:
    n(h) = 1 + 0.003 k_s (f(n_bg, 10 a_bg, 0, h) + f(n_inv, -0.1 a_inv, h_ciso, h)
           + f(n_hot, 0.3 a_hot, 0, h)) / (|n_bg| + |n_inv| + |n_hot|),  f(L, w, x0, x) = L/(1 + e^((x0-x)/w)).
    Scaling n_bg, n_inv, n_hot together changes nothing (gauge freedom): editing fixes n_bg by default.
    
    Parameters (name [unit] default, optimiser bounds: meaning):
        n_bg [1] 3, [-10, 10]: background amplitude
        n_inv [1] 0.1, [-10, 10]: inversion-layer amplitude
        n_hot [1] 0.1, [-10, 10]: hot-spot amplitude
        h_ciso [scene units] 1, [-10, 100]: height of the inversion layer
        a_bg [1] 1, [0.01, 100]: background width (logistic width 10 a_bg)
        a_inv [1] 1, [0.01, 100]: inversion width (logistic width 0.1 a_inv)
        a_hot [1] 1, [0.01, 100]: hot-spot width (logistic width 0.3 a_hot)
        k_s [1] 10, [-300, 300]: overall strength: n - 1 reaches 0.003 k_s
    """
    def __init__(self, *args, **kwargs) -> None:
        ...
class LinearSquaredProfile(IndexField):
    """
    n^2 = n0^2 + alpha y: rays are parabolas y = y0 + t0 x + alpha x^2 / (4 beta^2), beta = n(y0) cos(e0).
    
    Parameters (name [unit] default, optimiser bounds: meaning):
        n0 [1] 1.00028, [0.5, 3]: index at y = 0
        alpha [1/m] 0, [-0.001, 0.001]: d(n^2)/dy
    """
    def __init__(self, *args, **kwargs) -> None:
        ...
class PhysicalAtmosphere(IndexField):
    """
    Real air: U.S. Standard Atmosphere 1976 temperature + a smooth inversion layer + a surface layer
    surface_dt * exp(-h / surface_depth) (h >= 0), hydrostatic pressure, and the index of air from
    Edlen's formula revised by Birch & Downs (1993/94) at `wavelength`, optional relative humidity.
    Defaults give n - 1 = 2.7784e-4 at the ground (15 C, 101325 Pa, 550 nm). Modelled for heights in
    [-1000, 32000] m.
    
    Parameters (name [unit] default, optimiser bounds: meaning):
        t_ground [K] 288.15, [220, 330]: air temperature at h = 0 without the surface layer
        lapse_rate [K/m] 0.0065, [-0.02, 0.02]: tropospheric dT/dh is -lapse_rate
        pressure [Pa] 101325, [50000, 110000]: pressure at h = 0
        inversion_dt [K] 0, [-30, 30]: temperature rise across the inversion layer
        inversion_base [m] 100, [-100, 5000]: bottom of the inversion layer
        inversion_thickness [m] 10, [0.1, 2000]: thickness of the inversion layer
        surface_dt [K] 0, [-30, 60]: surface-layer excess temperature at h = 0
        surface_depth [m] 0.1, [0.005, 10]: e-folding depth of the surface layer
        humidity [1] 0, [0, 1]: relative humidity
        wavelength [nm] 550, [380, 780]: vacuum wavelength
    """
    def __init__(self, *args, **kwargs) -> None:
        ...
    def pressure(self, heights: typing.Any) -> typing.Any:
        """
        Hydrostatic pressure [Pa] at the given heights [m].
        """
    def temperature(self, heights: typing.Any) -> typing.Any:
        """
        Air temperature [K] at the given heights [m] (scalar or 1-D array).
        """
class TemperatureProfile(IndexField):
    """
    A measured sounding: temperatures [K] at strictly increasing heights [m], joined by a monotone C1
    cubic (pchip) and levelling off smoothly beyond the ends; hydrostatic pressure from `pressure` [Pa]
    at the lowest height; n from the same air formula as PhysicalAtmosphere. The temperatures are the
    parameters t0, t1, ... (with pressure, humidity, wavelength).
    """
    def __init__(self, heights: typing.Any, temperatures: typing.Any, pressure: typing.SupportsFloat | typing.SupportsIndex = 101325.0, humidity: typing.SupportsFloat | typing.SupportsIndex = 0.0, wavelength: typing.SupportsFloat | typing.SupportsIndex = 550.0) -> None:
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
    def __init__(self, base: IndexField, radius: typing.SupportsFloat | typing.SupportsIndex = 6371000.0) -> None:
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
    Slow: the integrators call back into Python at every evaluation.
    """
    def __init__(self, ior: typing.Any, grad_ior: typing.Any, height_only: bool = False) -> None:
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
    ray_vectors (N,3) the integrated v (|v| = n); stop: why the path ended ('max_length',
    'stop_height'); evaluations: field evaluations used.
    """
    def __len__(self) -> int:
        ...
    def __repr__(self) -> str:
        ...
    def at_height(self, y: typing.SupportsFloat | typing.SupportsIndex) -> numpy.typing.NDArray[numpy.float64]:
        """
        Every point where the path crosses height y [m], in path order, (K, 3).
        """
    def closest_point(self, q: typing.Any) -> tuple[numpy.ndarray, float, float]:
        """
        (point, distance, s): the point of the continuous path closest to q, its distance [m] and its arc length [m].
        """
    def crossings(self, normal: typing.Any, offset: typing.SupportsFloat | typing.SupportsIndex) -> list:
        """
        Crossings of the plane normal . x = offset: a list of (point, s, unit direction).
        """
    def point_at(self, s: typing.SupportsFloat | typing.SupportsIndex) -> tuple[numpy.ndarray, numpy.ndarray]:
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
class _ElevationTable:
    def __init__(self, field: IndexField, eye_height: typing.SupportsFloat | typing.SupportsIndex, min_elevation: typing.SupportsFloat | typing.SupportsIndex, max_elevation: typing.SupportsFloat | typing.SupportsIndex, tol: typing.SupportsFloat | typing.SupportsIndex, max_length: typing.SupportsFloat | typing.SupportsIndex, stop_height: typing.SupportsFloat | typing.SupportsIndex | None, step: typing.SupportsFloat | typing.SupportsIndex | None, trace_tol: typing.SupportsFloat | typing.SupportsIndex | None, progress: typing.Any) -> None:
        ...
    def ends(self, elevations: typing.Any, azimuths: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
        ...
    @property
    def elevations(self) -> numpy.typing.NDArray[numpy.float64]:
        ...
    @property
    def evaluations(self) -> int:
        ...
    @property
    def exact_intervals(self) -> int:
        ...
    @property
    def size(self) -> int:
        ...
class Scene:
    """
    Geometry (Embree) with Blinn-Phong materials, a sun and a sky. Materials: kd (diffuse albedo,
    RGB in [0, 1]), ks (specular albedo), ns (Phong exponent). Units: metres, y up.
    """
    shadows: bool
    def __init__(self) -> None:
        ...
    def add_billboard(self, centre: typing.Any, width: typing.SupportsFloat | typing.SupportsIndex, height: typing.SupportsFloat | typing.SupportsIndex, texture: str, facing: typing.Any = (-1.0, 0.0, 0.0), kd: typing.Any = (1.0, 1.0, 1.0)) -> int:
        """
        Add a vertical textured rectangle (a photo standing in the scene: a ship, a building) centred at
        `centre`, width x height [m], its picture facing `facing` (default -x, toward a camera on the
        -x side), upright.
        """
    def add_box(self, centre: typing.Any, size: typing.Any, kd: typing.Any = (0.5, 0.5, 0.5), ks: typing.Any = (0.0, 0.0, 0.0), ns: typing.SupportsFloat | typing.SupportsIndex = 1.0, alpha: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> int:
        """
        Add an axis-aligned box: centre (3,) and size (3,) [m]; alpha < 1: transparent in render_raster.
        """
    def add_ground(self, height: typing.SupportsFloat | typing.SupportsIndex = 0.0, size: typing.SupportsFloat | typing.SupportsIndex = 20000.0, kd: typing.Any = (0.3, 0.3, 0.3), ks: typing.Any = (0.0, 0.0, 0.0), ns: typing.SupportsFloat | typing.SupportsIndex = 1.0, texture: str | None = None, texture_size: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> int:
        """
        Add a square ground of side `size` [m] at y = height, centred on the origin; an optional texture
        repeats every texture_size [m] (u along +x, v along -z).
        """
    def add_mesh(self, vertices: typing.Any, triangles: typing.Any, kd: typing.Any = (0.5, 0.5, 0.5), ks: typing.Any = (0.0, 0.0, 0.0), ns: typing.SupportsFloat | typing.SupportsIndex = 1.0, uvs: typing.Any = None, texture: str | None = None, alpha: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> int:
        """
        Add a triangle mesh: vertices (N, 3) [m], triangles (M, 3) indices; optional uvs (N, 2) texture
        coordinates (u right, v up) and a texture image file multiplying kd; alpha < 1 makes it transparent
        in render_raster. Returns its id.
        """
    def add_obj(self, path: str, offset: typing.Any = (0.0, 0.0, 0.0), scale: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> list:
        """
        Add a Wavefront OBJ (+ MTL: Kd, Ks, Ns, map_Kd with the file's texture coordinates) file, scaled
        then offset; returns the geometry ids. A missing OBJ, MTL or texture raises refracta.IoError.
        """
    def add_sphere(self, centre: typing.Any, radius: typing.SupportsFloat | typing.SupportsIndex, kd: typing.Any = (0.5, 0.5, 0.5), ks: typing.Any = (0.0, 0.0, 0.0), ns: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> int:
        """
        Add a sphere (exact, not tessellated).
        """
    def add_spot_light(self, position: typing.Any, direction: typing.Any, angle: typing.SupportsFloat | typing.SupportsIndex = 60.0, intensity: typing.Any = (100.0, 100.0, 100.0), radius: typing.SupportsFloat | typing.SupportsIndex = 0.0) -> int:
        """
        Add a spot light at `position` [m] shining along `direction` into a cone of full `angle` [deg] with
        `intensity` [W/sr per channel] (irradiance I cos / d^2); radius > 0 makes it a disc (area light) whose
        shadows are sampled soft. Returns its index.
        """
    def intersect(self, origin: typing.Any, direction: typing.Any) -> typing.Any:
        """
        First hit of a straight ray: (point, distance, geometry id), or None.
        """
    def set_sky(self, horizon: typing.Any = None, zenith: typing.Any = None, environment: str | None = None, scale: typing.SupportsFloat | typing.SupportsIndex = 1.0) -> None:
        """
        Sky radiance toward the horizon (and below) and straight up (default: same, a constant sky), or an
        equirectangular environment map file (y up, top row the zenith, centre column along +x, radiance
        times `scale`; 8/16-bit files are sRGB-decoded).
        """
    def set_sun(self, direction: typing.Any, radiance: typing.Any, angular_diameter: typing.SupportsFloat | typing.SupportsIndex = 0.53) -> None:
        """
        The sun: direction toward it, disc radiance (RGB), angular diameter [deg].
        """
    @property
    def geometry_count(self) -> int:
        ...
class Camera:
    """
    Pinhole camera. Camera(position, look_at, up=(0, 1, 0), vfov=45, width=640, height=360): vfov is the
    vertical field of view [deg]. Pixel coordinates (u, v): u right, v down, pixel (i, j) centred at
    (i + 0.5, j + 0.5).
    """
    def __init__(self, position: typing.Any, look_at: typing.Any, up: typing.Any = (0.0, 1.0, 0.0), vfov: typing.SupportsFloat | typing.SupportsIndex = 45.0, width: typing.SupportsInt | typing.SupportsIndex = 640, height: typing.SupportsInt | typing.SupportsIndex = 360) -> None:
        ...
    def __repr__(self) -> str:
        ...
    def pick(self, scene: Scene, u: typing.SupportsFloat | typing.SupportsIndex, v: typing.SupportsFloat | typing.SupportsIndex) -> typing.Any:
        """
        The scene point seen at pixel (u, v) without atmosphere (straight ray), or None.
        """
    def project(self, points: typing.Any) -> typing.Any:
        """
        (u, v, depth) per point (N, 3); depth [m] along the view axis, <= 0 behind.
        """
    def ray(self, u: typing.SupportsFloat | typing.SupportsIndex, v: typing.SupportsFloat | typing.SupportsIndex) -> tuple[numpy.ndarray, numpy.ndarray]:
        """
        (origin, unit direction) of the ray through pixel coordinates (u, v).
        """
    def resized(self, width: typing.SupportsInt | typing.SupportsIndex, height: typing.SupportsInt | typing.SupportsIndex) -> Camera:
        """
        The same view at another image size (vertical field of view kept).
        """
    @property
    def height(self) -> int:
        ...
    @property
    def position(self) -> numpy.ndarray:
        ...
    @property
    def vfov(self) -> float:
        ...
    @property
    def width(self) -> int:
        ...
class _PairOptions:
    def __init__(self, method: str, tol: typing.SupportsFloat | typing.SupportsIndex, step: typing.SupportsFloat | typing.SupportsIndex | None, ground: typing.SupportsFloat | typing.SupportsIndex | None, distance: str, reach: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
class _SolveSettings:
    backend: str
    loss: str
    def __init__(self) -> None:
        ...
    def validate(self) -> None:
        ...
    @property
    def accept_angle(self) -> float:
        ...
    @accept_angle.setter
    def accept_angle(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def function_tolerance(self) -> float:
        ...
    @function_tolerance.setter
    def function_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def gradient_tolerance(self) -> float:
        ...
    @gradient_tolerance.setter
    def gradient_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def loss_scale(self) -> float:
        ...
    @loss_scale.setter
    def loss_scale(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def max_evaluations(self) -> int:
        ...
    @max_evaluations.setter
    def max_evaluations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_iterations(self) -> int:
        ...
    @max_iterations.setter
    def max_iterations(self, arg0: typing.SupportsInt | typing.SupportsIndex) -> None:
        ...
    @property
    def max_time(self) -> float:
        ...
    @max_time.setter
    def max_time(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def parameter_tolerance(self) -> float:
        ...
    @parameter_tolerance.setter
    def parameter_tolerance(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def target_cost(self) -> float:
        ...
    @target_cost.setter
    def target_cost(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
    @property
    def trust_region(self) -> float:
        ...
    @trust_region.setter
    def trust_region(self, arg0: typing.SupportsFloat | typing.SupportsIndex) -> None:
        ...
def _canonical_bound(moments: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex], z_f: typing.SupportsFloat | typing.SupportsIndex) -> tuple[float, float, bool]:
    ...
def _composite(depths: typing.Any, alphas: typing.Any, colors: typing.Any, background: typing.Any, method: str, moments: typing.SupportsInt | typing.SupportsIndex, kind: str, beta: typing.SupportsFloat | typing.SupportsIndex, bias: typing.SupportsFloat | typing.SupportsIndex | None, z_range: tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex] | None, layers: typing.SupportsInt | typing.SupportsIndex | None, weight: str) -> numpy.ndarray:
    ...
def _display(image: typing.Any, exposure: typing.SupportsFloat | typing.SupportsIndex, tonemap: str, gamma: str) -> numpy.typing.NDArray[numpy.float32]:
    ...
def _pair_distances(field: IndexField, origins: typing.Any, directions: typing.Any, sources: typing.Any, options: _PairOptions) -> numpy.typing.NDArray[numpy.float64]:
    ...
def _pair_jacobian(field: IndexField, origins: typing.Any, directions: typing.Any, sources: typing.Any, weights: typing.Any, free: collections.abc.Sequence[str], derivatives: str, options: _PairOptions) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], list[str]]:
    ...
def _quantize_moments(moments: typing.Any, signed: bool, inverse: bool) -> numpy.typing.NDArray[numpy.float64]:
    ...
def _rasterize(scene: Scene, camera: Camera, guard_band: typing.SupportsFloat | typing.SupportsIndex, tile: typing.SupportsInt | typing.SupportsIndex) -> dict:
    ...
def _read_image(path: str) -> numpy.typing.NDArray[numpy.float32]:
    ...
def _render(scene: Scene, camera: Camera, field: IndexField, method: str, spp: typing.SupportsInt | typing.SupportsIndex, seed: typing.SupportsInt | typing.SupportsIndex, max_length: typing.SupportsFloat | typing.SupportsIndex, chord: typing.SupportsFloat | typing.SupportsIndex, sagitta: typing.SupportsFloat | typing.SupportsIndex, tol: typing.SupportsFloat | typing.SupportsIndex, table: bool, integrator: str | None, march: str, step: typing.SupportsFloat | typing.SupportsIndex, max_steps: typing.SupportsInt | typing.SupportsIndex, guard_band: typing.SupportsFloat | typing.SupportsIndex, texture_filter: bool, progress: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float32], dict]:
    ...
def _render_raster(scene: Scene, camera: Camera, shadows: str, resolution: typing.SupportsInt | typing.SupportsIndex, kernel: typing.SupportsInt | typing.SupportsIndex, signed_depth: bool, bias: typing.SupportsFloat | typing.SupportsIndex | None, bias_vector: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] | None, storage: str, depth_bias: typing.SupportsFloat | typing.SupportsIndex, normal_offset: typing.SupportsFloat | typing.SupportsIndex, bleeding_reduction: typing.SupportsFloat | typing.SupportsIndex, shadow_centre: typing.Any, shadow_half_size: typing.SupportsFloat | typing.SupportsIndex | None, shadow_distance: typing.SupportsFloat | typing.SupportsIndex | None, output_shadow: bool, transparency: str | None, moments: typing.SupportsInt | typing.SupportsIndex, kind: str, beta: typing.SupportsFloat | typing.SupportsIndex, layers: typing.SupportsInt | typing.SupportsIndex, weight: str, shadow_light: typing.SupportsInt | typing.SupportsIndex, use_sun: bool, spots: collections.abc.Sequence[typing.SupportsInt | typing.SupportsIndex] | None, progress: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float32], dict]:
    ...
def _shadow_intensity(moments: typing.Any, z_f: typing.Any, method: str, signed: bool, bias: typing.SupportsFloat | typing.SupportsIndex | None, bias_vector: collections.abc.Sequence[typing.SupportsFloat | typing.SupportsIndex] | None, storage: str) -> numpy.typing.NDArray[numpy.float64]:
    ...
def _solve_edit(field: IndexField, origins: typing.Any, directions: typing.Any, sources: typing.Any, weights: typing.Any, free: collections.abc.Sequence[str], bounds: collections.abc.Mapping[str, tuple[typing.SupportsFloat | typing.SupportsIndex, typing.SupportsFloat | typing.SupportsIndex]], derivatives: str, pair_options: _PairOptions, settings: _SolveSettings, progress: typing.Any) -> dict:
    ...
def _trace_batch(field: IndexField, origins: typing.Any, directions: typing.Any, method: str, tol: typing.SupportsFloat | typing.SupportsIndex, step: typing.SupportsFloat | typing.SupportsIndex | None, max_length: typing.SupportsFloat | typing.SupportsIndex, stop_height: typing.SupportsFloat | typing.SupportsIndex | None, progress: typing.Any) -> tuple[numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64], numpy.typing.NDArray[numpy.float64]]:
    ...
def _write_image(path: str, image: typing.Any, exposure: typing.SupportsFloat | typing.SupportsIndex, tonemap: str, gamma: str) -> None:
    ...
def trace_ray(field: IndexField, origin: typing.Any, direction: typing.Any, method: str = 'rk45', tol: typing.SupportsFloat | typing.SupportsIndex = 1e-06, step: typing.SupportsFloat | typing.SupportsIndex | None = None, max_length: typing.SupportsFloat | typing.SupportsIndex = 1000.0, stop_height: typing.SupportsFloat | typing.SupportsIndex | None = None) -> RayPath:
    """
    Trace one curved ray through `field` and return its RayPath.
    
    The ray equations dx/ds = v/n, dv/ds = grad n are launched with v0 = n(origin) * direction/|direction|.
    method: 'rk45' (adaptive Dormand-Prince; tol is the target position error [m] over the path),
    'rk4' (fixed step `step`, default 0.3 m, the original editor's), or 'stratified' (height-only
    fields: exact paths from n(h) cos(e) = const by quadrature to `tol`; `step` is the largest node
    spacing, default 100 m). max_length [m]: arc length at which the path ends. stop_height [m]: the
    path ends where it descends through this height (a ground). Raises ValueError for bad arguments
    and refracta.NumericalError where n <= 0 or is not finite.
    """
_stop_names: tuple = ('max_length', 'stop_height', 'stopped')
