"""refracta.edit: find the atmosphere that puts a mirage image where an artist wants it.

The original mirage editor (Choi 2017) let an artist click point pairs: a *destination* (where the
image should appear: a pixel of a camera, or a 3D point the eye looks toward) and a *source* (the
scene point to be seen there). The light path launched from the eye toward the destination should
pass through the source. refracta measures each pair by the closest approach of the continuous
path to the source (the miss vector, perpendicular to the path) and minimises the weighted sum of
squared misses over the field's parameters:

* ``backend='ceres'``: Levenberg-Marquardt with one residual block per pair and exact derivatives
  by automatic differentiation (ceres::Jet) through the same integrator that renders;
* ``backend='nlopt:<ALGORITHM>'``: any nlopt algorithm (LN_BOBYQA was the original editor's
  choice; LD_LBFGS and LD_MMA get the automatic derivatives), for comparison.

Example::

    import refracta
    from refracta.edit import PointPair, solve

    field = refracta.LogisticProfile()
    pairs = [PointPair(destination=(1000.0, 1.2, 0.0), source=(1000.0, 3.0, 0.0))]
    result = solve(field, eye_or_camera=(0.0, 1.5, 0.0), pairs=pairs, free=["k_s", "h_ciso"])
    print(result)            # the report: costs, distances, parameters before and after
    solved = result.field

Matching a photograph: with a Camera as eye_or_camera, ``free`` may also name the camera's
CAMERA_PARAMETERS -- ``camera_yaw``, ``camera_pitch``, ``camera_roll`` (degrees about the camera's own
up, right and forward: offsets from the camera given; positive yaw turns the view right, positive
pitch up, positive roll turns the camera's up toward its right) and ``camera_vfov`` (its vertical
field of view [deg]) -- and the pairs' pixel destinations then follow the solved camera
(result.camera). Their default bounds: yaw within half the horizontal field of view, pitch half the
vertical one, roll 15 deg, vfov a factor of 2 either way (C++'s CameraRig).

Units: metres (scene units for LogisticProfile); cost is 1/2 sum weight * miss^2 [m^2].
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import Any, Callable

import numpy as np

from refracta import _core, _options
from refracta._checks import is_number, number, on_image, real_array
from refracta._progress import progress_callback
from refracta._rays import without_refraction
from refracta._warn import deprecated

# The options and summary of a solve, bound from C++ (edit_settings.h, point_pair.h).
SolveSettings = _core.SolveSettings
PairOptions = _core.PairOptions
SolveSummary = _core.SolveSummary

#: The camera's parameters solve() can free beside the field's (C++'s CameraRig::names()).
CAMERA_PARAMETERS: tuple[str, ...] = tuple(_core.EDIT_CAMERA_PARAMETERS)

__all__ = [
    "CAMERA_PARAMETERS",
    "EditResult",
    "PairOptions",
    "PointPair",
    "SolveSettings",
    "SolveSummary",
    "distances",
    "jacobian",
    "load_pairs",
    "solve",
    "NLOPT_ALGORITHMS",
]

#: nlopt algorithms known to work on edits (any other nlopt name is accepted too).
NLOPT_ALGORITHMS = ("LN_BOBYQA", "LN_NELDERMEAD", "LN_SBPLX", "LN_COBYLA", "GN_DIRECT_L", "LD_LBFGS", "LD_MMA")


def _vector(value, sizes, what: str) -> np.ndarray:
    wanted = " or ".join(str(s) for s in sizes)
    try:
        array = real_array(value, what)
    except ValueError:
        raise ValueError(f"{what} must be {wanted} finite numbers (got {value!r})") from None
    if array.ndim != 1 or array.size not in sizes or not np.all(np.isfinite(array)):
        raise ValueError(f"{what} must be {wanted} finite numbers (got {value!r})")
    return array


def _number(value, what: str) -> float:
    """A finite number, not a bool or a string (True and '2' were weights)."""
    value = number(value, what)
    if not np.isfinite(value):
        raise ValueError(f"{what} must be finite (got {value!r})")
    return value


@dataclass(frozen=True)
class PointPair:
    """One constraint of an edit.

    Attributes:
        destination: where the image should appear -- a pixel ``(u, v)`` of the camera passed to
            solve(), or a 3D point [m] the eye looks toward (only its direction from the eye
            matters).
        source: the 3D scene point [m] that should be seen there
            (``camera.pick(scene, u, v, refracta.without_refraction(field))`` finds the point a
            pixel shows without atmosphere; over a CurvedEarth without the field it would be a
            flat Earth's).
        weight: importance (> 0); the pair's miss is scaled by sqrt(weight) in the cost.
        margin: how far (>= 0) the path may pass from the source at no cost: metres, or pixels
            for a pixel destination (converted at the source's distance). The cost is a dead zone,
            zero inside the margin and 1/2 weight (miss - margin)^2 outside, so less important
            points get larger margins; a pair is met once its miss is within its margin (plus
            solve's accept_angle times its range, or for a pixel destination solve's
            pixel_tolerance, a tenth of the pixel's footprint at the source, if that is larger).
    """

    destination: tuple[float, ...]
    source: tuple[float, float, float]
    weight: float = 1.0
    margin: float = 0.0

    def __post_init__(self):
        destination = _vector(self.destination, (2, 3), "PointPair destination")
        source = _vector(self.source, (3,), "PointPair source")
        weight = _number(self.weight, "PointPair weight")
        if not weight > 0.0:
            raise ValueError(f"PointPair weight must be > 0 (got {self.weight!r})")
        margin = _number(self.margin, "PointPair margin")
        if not margin >= 0.0:
            raise ValueError(f"PointPair margin must be >= 0 (got {self.margin!r})")
        # Plain floats, not np.float64: the repr reads (1.0, 2.0) and the pair compares and
        # serialises like the tuples it was given.
        object.__setattr__(self, "destination", tuple(float(x) for x in destination))
        object.__setattr__(self, "source", tuple(float(x) for x in source))
        object.__setattr__(self, "weight", weight)
        object.__setattr__(self, "margin", margin)

    @property
    def is_pixel(self) -> bool:
        return len(self.destination) == 2


def _pair_pixels(pairs: Sequence[PointPair]) -> np.ndarray:
    """(N, 2): each pair's destination pixel (u, v), NaN for a 3D destination."""
    return np.array([p.destination if p.is_pixel else (np.nan, np.nan) for p in pairs], dtype=float).reshape(-1, 2)


def _refuse_several_cameras(eye_or_camera) -> None:
    if isinstance(eye_or_camera, (list, tuple)) and any(isinstance(item, _core.Camera) for item in eye_or_camera):
        raise ValueError(
            "eye_or_camera must be one Camera or one eye point (x, y, z) (got a sequence holding Cameras): an edit "
            "sees through one camera; solve for each camera in turn"
        )


def _pair_rays(eye_or_camera, pairs: Sequence[PointPair], pixel_tolerance: float | None = None):
    """(pairs, eye, camera or None, origins, directions, sources, weights, margins [m], tolerances [m])
    of the pairs.

    pixel_tolerance [pixels]: a pixel destination's pair is met within this many pixels' footprint
    at its source (default: the C++ default, SolveSettings().pixel_tolerance); 3D destinations: 0.
    """
    if isinstance(pairs, PointPair):
        pairs = [pairs]
    try:
        pairs = list(pairs)
    except TypeError:
        raise ValueError(f"pairs must be a PointPair or a list of them (got {type(pairs).__name__})") from None
    if not pairs:
        raise ValueError("pairs is empty: give at least one PointPair")
    for i, pair in enumerate(pairs):
        if not isinstance(pair, PointPair):
            raise ValueError(f"pairs[{i}] must be a PointPair (got {type(pair).__name__})")
    _refuse_several_cameras(eye_or_camera)
    camera = eye_or_camera if isinstance(eye_or_camera, _core.Camera) else None
    eye = camera.position if camera is not None else _vector(eye_or_camera, (3,), "eye_or_camera")
    directions = []
    for i, pair in enumerate(pairs):
        if pair.is_pixel:
            if camera is None:
                raise ValueError(
                    f"pairs[{i}] gives a pixel destination {pair.destination}; pass a Camera "
                    "as eye_or_camera (or give the destination as a 3D point)"
                )
            u, v = pair.destination
            if not on_image(camera, u, v):
                raise ValueError(
                    f"pairs[{i}]: pixel {pair.destination} lies outside the camera's {camera.width} x "
                    f"{camera.height} image (u in [0, {camera.width}], v in [0, {camera.height}]); pixels of a "
                    "photograph need a camera of its size (refracta.photo: Photo.camera)"
                )
            directions.append(camera.ray(u, v)[1])
        else:
            direction = np.asarray(pair.destination) - eye
            if not np.linalg.norm(direction) > 0.0:
                raise ValueError(f"pairs[{i}]: the destination is at the eye")
            directions.append(direction)
    origins = np.tile(eye, (len(pairs), 1))
    sources = np.array([p.source for p in pairs])
    weights = np.array([p.weight for p in pairs])
    # A pixel destination's margin and tolerance are in pixels: their footprint at the source's
    # distance (the angle they subtend times the range).
    if pixel_tolerance is None:
        pixel_tolerance = _core.SolveSettings().pixel_tolerance
    ranges = np.linalg.norm(sources - eye, axis=1)
    pixel_angle = camera.pixel_angle if camera is not None else 0.0  # a pixel pair has a camera (checked above)
    footprints = np.array([pixel_angle * r if p.is_pixel else 0.0 for p, r in zip(pairs, ranges)])
    margins = np.array([p.margin * (f if p.is_pixel else 1.0) for p, f in zip(pairs, footprints)])
    return pairs, eye, camera, origins, np.array(directions), sources, weights, margins, pixel_tolerance * footprints


# Deprecated keyword spellings (one release): the ray integrator is `trace`, the ground `stop_height`,
# as in refracta.trace_ray and refracta.render.
_RENAMED = {"integrator": "trace", "ground": "stop_height"}


def _pair_options(where: str, given: _core.PairOptions | None, options: dict) -> _core.PairOptions:
    """PairOptions from `given` (None: the defaults) and PairOptions fields as keywords (deprecated
    spellings renamed with a warning; any other keyword raises ValueError naming it)."""
    options = _options.renamed(dict(options), _RENAMED, where)
    return _options.build(_core.PairOptions, given, where=where, **options)


# Fields of EditResult read from its SolveSummary (documented on EditResult and _core.SolveSummary).
_SUMMARY_FIELDS = frozenset(_options.fields(_core.SolveSummary)) - {"values"}


@dataclass(frozen=True, eq=False)  # its fields (index fields, arrays) have no value equality: by identity
class EditResult:
    """What solve() found. ``print(result)`` shows the report. Compared and hashed by identity (a
    pickled copy is a different result; compare its fields).

    field: the solved field; start: the field it started from. cost / initial_cost: 1/2 sum of
    weight * (miss - margin)^2 over the pairs outside their margins [m^2]; distances: each pair's
    miss [m] after solving (initial_distances before); margins: each pair's margin [m] (pixel
    margins converted at the source's distance); tolerances: each pair's met tolerance beyond its
    margin [m] (pixel destinations: solve's pixel_tolerance of the pixel's footprint at the source;
    3D destinations 0); met: per pair, whether its miss is within its margin plus the larger of
    its tolerance and accept_angle times its range. success: every pair met (strategy 'local': and the
    back-end converged). strategy: 'auto' or 'local'; stages: what the strategy did, one line per
    stage (local solves, the global stage's design; several starts: then 'starts: k of n run');
    solver_report: the back-end's own report of the run that gave the result (Ceres' full summary).
    stopped_by: the limit that cut the solve short ('iteration limit', 'evaluation limit', 'time
    limit'; '' if none). condition, rank: of the Jacobian in the free parameters' unit box at a
    result meeting every pair (else 0, 0); above 1e6 the message says the solution is not unique,
    and unique is False (True: every pair met and the pairs fix every free parameter -- condition
    <= 1e6, and a quarter of the search box either way along the least-determined combination
    meets them no longer; a success with one landmark and five free parameters is not unique).
    history: cost per iteration (ceres) or best cost per evaluation (nlopt) of that run. free: the
    optimised parameters; insensitive: requested free parameters no pair depends on (held fixed, or
    when no pair depends on any, left free where the solver cannot move them);
    at_bounds: free parameters the result left on a bound of the search (the best fit may lie
    beyond: widen bounds=).
    iterations (of the start that gave the result), evaluations (cost evaluations, the global
    stage's design points and every start included), pair_traces (traced pairs, derivative passes
    included), time [s] (solving only), starts, backend, derivatives. These are read from
    `summary` (a _core.SolveSummary); `settings` and `pair_options` are what the solve ran with.
    camera: the solved camera when camera parameters were free (summary.camera; camera_values: their
    values, yaw/pitch/roll offsets and vfov [deg]), else the camera given (None for an eye point);
    start_camera: the camera given.
    """

    field: _core.IndexField
    start: _core.IndexField
    pairs: list[PointPair]
    eye: np.ndarray
    camera: _core.Camera | None
    initial_distances: np.ndarray
    margins: np.ndarray
    tolerances: np.ndarray
    summary: _core.SolveSummary
    settings: _core.SolveSettings
    pair_options: _core.PairOptions
    start_camera: _core.Camera | None = None

    def __getattr__(self, name: str) -> Any:
        # Only reached for names that are not attributes: the summary's fields (not while
        # unpickling, before `summary` is set).
        summary = self.__dict__.get("summary")
        if name not in _SUMMARY_FIELDS or summary is None:
            raise AttributeError(f"{type(self).__name__!r} object has no attribute {name!r}")
        return getattr(summary, name)

    def __dir__(self) -> list[str]:
        return sorted(set(super().__dir__()) | _SUMMARY_FIELDS)

    def paths(self, which: str = "solved") -> list[_core.RayPath]:
        """Each pair's light path through the solved field ('solved') or the start ('start'),
        traced by the rule its miss is measured with (PairOptions in C++)."""
        if which not in ("solved", "start"):
            raise ValueError(f"which must be 'solved' or 'start' (got {which!r})")
        field = self.field if which == "solved" else self.start
        camera = self.camera if which == "solved" or self.start_camera is None else self.start_camera
        eye_or_camera = camera if camera is not None else self.eye
        _, _, _, origins, directions, sources, _, _, _ = _pair_rays(eye_or_camera, self.pairs)
        return _core._pair_paths(field, origins, directions, sources, self.pair_options)

    def parameter_changes(self) -> list[tuple[str, float, float, str]]:
        """(name, start, solved, unit) of each free parameter: the field's, and the camera's
        (CAMERA_PARAMETERS: yaw, pitch, roll offsets from start_camera and vfov, in deg)."""
        info = {p["name"]: p["unit"] for p in self.start.param_info}
        start, solved = dict(self.start.params), dict(self.field.params)
        if len(self.camera_values) == len(CAMERA_PARAMETERS) and self.start_camera is not None:
            start |= dict(zip(CAMERA_PARAMETERS, (0.0, 0.0, 0.0, self.start_camera.vfov)))
            solved |= dict(zip(CAMERA_PARAMETERS, (float(v) for v in self.camera_values)))
            info |= dict.fromkeys(CAMERA_PARAMETERS, "deg")
        return [(name, float(start[name]), float(solved[name]), info[name]) for name in self.free]

    def uncertainty(self, pixel_sigma: float) -> dict[str, float]:
        """The standard deviation of each free parameter [its unit] that random errors of
        `pixel_sigma` pixels (each direction) in reading the destinations off a picture leave in
        the solved values: the linearised least-squares spread (J^T J)^-1 J^T C J (J^T J)^-1 of the
        pairs' miss Jacobian at the result (refracta.edit.jacobian, margins taken as 0: a dead zone
        has no derivative), C the pairs' weights times their pixel footprints at the source
        squared. ``unique`` only says whether the pairs fix the parameters within the search box;
        this says how well, for a given reading error (a trial: four skyline pairs 'unique', but
        0.3 px of picking error left inversion_base +-46 m). inf for parameters the pairs do not
        fix (a rank-deficient Jacobian). Pixel destinations only (ValueError otherwise); a
        linearisation: trust it while pixel_sigma moves the result little."""
        sigma = number(pixel_sigma, "pixel_sigma")
        if not (sigma > 0.0 and math.isfinite(sigma)):
            raise ValueError(f"uncertainty: pixel_sigma must be > 0 and finite (got {pixel_sigma!r})")
        if not all(pair.is_pixel for pair in self.pairs):
            raise ValueError(
                "uncertainty: every pair's destination must be a pixel (u, v); 3D destinations have no pixel"
            )
        pairs = [replace(pair, margin=0.0) for pair in self.pairs]
        eye_or_camera = self.camera if self.camera is not None else self.eye
        _, matrix, names = jacobian(self.field, eye_or_camera, pairs, self.free, pair_options=self.pair_options)
        if not names:
            return {}
        if np.linalg.matrix_rank(matrix) < len(names):
            return dict.fromkeys(names, math.inf)
        # A pixel's footprint at the source [m]: the pair's met tolerance over pixel_tolerance (edit.h).
        footprint = np.asarray(self.tolerances) / self.settings.pixel_tolerance
        weights = np.array([pair.weight for pair in pairs])
        noise = np.repeat(weights * (sigma * footprint) ** 2, 3)  # per miss component, as the Jacobian's rows
        inverse = np.linalg.inv(matrix.T @ matrix)
        covariance = inverse @ (matrix.T * noise) @ matrix @ inverse
        return {name: float(math.sqrt(max(value, 0.0))) for name, value in zip(names, np.diag(covariance))}

    def report(self) -> str:
        """A readable summary: outcome, costs, per-pair distances, parameters before and after."""
        verdict = ("success" if self.unique else "success, not unique") if self.success else "FAILED"
        lines = [
            f"Edit of {self.field.type_name} with {self.backend} ({self.derivatives} derivatives): {verdict}",
            f"  cost {self.initial_cost:.4g} -> {self.cost:.4g} m^2 in {self.iterations} iterations, "
            f"{self.evaluations} evaluations, {self.pair_traces} pair traces, {self.time:.3g} s"
            + (f" ({self.starts} starts)" if self.starts > 1 else ""),
            "  pair  weight  miss before [m]  miss after [m]  margin [m]  met  range [m]",
        ]
        if self.settings.loss != "none":  # two measures: say which is which
            lines.insert(
                2,
                f"  (cost: plain, 1/2 sum w (miss - margin)^2; the solver minimised its {self.settings.loss} loss "
                f"at scale {self.settings.loss_scale:g} m, which `history` holds)",
            )
        margins = self.margins if len(self.margins) == len(self.pairs) else np.zeros(len(self.pairs))
        met = self.met if len(self.met) == len(self.pairs) else np.zeros(len(self.pairs), dtype=bool)
        for i, pair in enumerate(self.pairs):
            distance = float(np.linalg.norm(np.asarray(pair.source) - self.eye))
            lines.append(
                f"  {i:4d}  {pair.weight:6.3g}  {self.initial_distances[i]:15.4g}  "
                f"{self.distances[i]:14.4g}  {margins[i]:10.4g}  {'yes' if met[i] else 'NO ':3s}  "
                f"{distance:9.4g}"
            )
        lines.append("  parameter            start          solved         unit")
        for name, before, after, unit in self.parameter_changes():
            lines.append(f"  {name:18s} {before:14.8g} {after:14.8g}  {unit}")
        start = self.start.params
        fixed = [n for n in start if n not in self.free]
        if fixed:
            lines.append("  held fixed: " + ", ".join(fixed))
        if self.insensitive:
            lines.append("  no pair depends on: " + ", ".join(self.insensitive))
        if self.stages:
            lines.append(f"  strategy {self.strategy}:")
            lines += ["    " + stage for stage in self.stages]
        if self.rank:
            lines.append(
                f"  Jacobian at the result: rank {self.rank} of {len(self.free)}, condition {self.condition:.3g}"
            )
        lines.append("  " + self.message)
        lines += self._ground_note()
        return "\n".join(lines)

    def _ground_note(self) -> list[str]:
        """A line when a met pair's path dips below height 0 with stop_height None: over water or land
        it ran through the ground to its source (a photo-fitting trial's 'success' for a source under
        the sea, its inversion base at -3.8 m)."""
        if self.pair_options.stop_height is not None or not self.success:
            return []
        lowest = [float(np.min(path.points[:, 1])) for path in self.paths()]
        below = [(i, y) for i, y in enumerate(lowest) if y < 0.0]
        if not below:
            return []
        i, y = min(below, key=lambda item: item[1])
        return [
            f"  note: stop_height is None, so no ground stops the paths: pair {i}'s dips to {y:.4g} m, below "
            f"height 0 ({len(below)} of {len(lowest)} pairs below it); over water or land give stop_height=0.0"
        ]

    __str__ = report

    def __repr__(self) -> str:
        return (
            f"EditResult(success={self.success}, unique={self.unique}, cost={self.cost:.3g}, "
            f"max miss={np.max(self.distances):.3g} m, "
            f"backend={self.backend!r}, iterations={self.iterations}, time={self.time:.3g} s)"
        )


def solve_options(
    settings: _core.SolveSettings | None = None,
    pair_options: _core.PairOptions | None = None,
    *,
    where: str = "refracta.edit.solve",
    **options: Any,
) -> tuple[_core.SolveSettings, _core.PairOptions]:
    """The (SolveSettings, PairOptions) that solve builds from its settings, pair_options and option
    keywords (each a field of one of them; old names renamed with a DeprecationWarning), validated:
    ValueError naming a keyword that is no option or every bad value. For checking options before
    a solve runs (the editor's solve_options)."""
    options = _options.renamed(dict(options), _RENAMED, where)
    settings_keywords, pair_keywords = _options.split(options, _core.SolveSettings, _core.PairOptions)
    _options.unknown(options, where, _options.fields(_core.SolveSettings) + _options.fields(_core.PairOptions))
    for name, given, cls in (
        ("settings", settings, _core.SolveSettings),
        ("pair_options", pair_options, _core.PairOptions),
    ):
        if given is not None and not isinstance(given, cls):
            raise ValueError(
                f"{where}: {name} must be a refracta.edit.{cls.__name__} or None (got {type(given).__name__})"
            )
    return (
        _options.build(_core.SolveSettings, settings, where=where, **settings_keywords),
        _options.build(_core.PairOptions, pair_options, where=where, **pair_keywords),
    )


def solve(
    field: _core.IndexField,
    eye_or_camera,
    pairs: Sequence[PointPair],
    free: Sequence[str] | None = None,
    backend: str | None = None,
    *,
    settings: _core.SolveSettings | None = None,
    pair_options: _core.PairOptions | None = None,
    bounds: dict[str, tuple[float, float]] | None = None,
    derivatives: str = "auto",
    progress: bool | Callable[[int, int], None] = False,
    **options: Any,
) -> EditResult:
    """Solve for the parameters of `field` that make each pair's light path pass its source.

    Args:
        field: any IndexField (PhysicalAtmosphere, LogisticProfile, LinearSquaredProfile, ...);
            CurvedEarth-wrapped fields edit the wrapped model's parameters.
        eye_or_camera: the eye position (x, y, z) [m], or a Camera (needed for pixel
            destinations; its position is the eye).
        pairs: PointPairs.
        free: names of the parameters to optimise; default: every parameter except the model's
            gauge ones (LogisticProfile's n_bg: a common scale of the amplitudes changes nothing).
            With a Camera, also CAMERA_PARAMETERS (module docstring): the pairs' pixel
            destinations then follow the solved camera, result.camera.
            Free parameters on which no pair depends are held fixed and listed in
            result.insensitive.
        backend: 'ceres' or 'nlopt:<ALGORITHM>' (see NLOPT_ALGORITHMS; any nlopt name works);
            a SolveSettings field, also accepted here by position.
        settings: a refracta.edit.SolveSettings (copied); keywords below override its fields.
        pair_options: a refracta.edit.PairOptions (copied); keywords override its fields.
        bounds: {name: (lower, upper)} overriding the model's (or the camera's) search box.
        derivatives: 'auto', 'automatic' (ceres::Jet) or 'numeric' (central differences).
        progress: True for a bar on stderr, or a callable progress(done, total): done of total
            is the largest fraction used of the iteration, evaluation and time limits (shared by
            every start), reaching total when the solve ends.
        **options: any field of refracta.edit.SolveSettings or refracta.edit.PairOptions by name; their
            defaults are the C++ structs' (``help(refracta.edit.SolveSettings)``). SolveSettings:
            strategy ('auto': a short local solve from `field`, quick_iterations, continued while
            LM's cost still falls; if it does not meet every pair, a global stage -- scans along
            each free parameter's axis and quasi-random points over the bounds and near the
            start, costs in parallel -- and local solves from its best points, at most
            local_starts, until one meets every pair; 'local': the back-end from `field` only),
            starts and seed (the strategy from `field`, then from uniform random points in the
            bounds; the best result is kept), max_iterations, max_evaluations, time_limit [s]
            (limits of the whole solve, shared by its stages and starts; a trace running at the
            time limit is interrupted; result.stopped_by names what stopped it), target_cost,
            function/parameter/gradient_tolerance, trust_region (ceres' first radius in the unit
            box), loss and loss_scale (ceres robust loss: 'huber', 'soft_l1', 'cauchy',
            'arctan'), accept_angle [rad] and pixel_tolerance [pixels] (when a pair counts as
            met). PairOptions: trace ('rk45' to `tol` [m], or 'rk4' with `step` [m]),
            stop_height [m] (paths end on the ground there; default none), distance
            ('continuous' closest approach, or 'vertex': the nearest integrator node, the
            original editor's measure, with trace='rk4' only), reach (paths are traced to ``reach * |source - eye| + 1``
            m), max_steps. Deprecated spellings: integrator= (trace), ground= (stop_height).

    Returns:
        EditResult. Not converging, or an image no atmosphere within the bounds can make, is a
        result with success False and a message, not an exception.

    Raises:
        ValueError: bad pairs (NaN, pixel without camera), unknown parameter names or nlopt
            algorithm, bounds not containing the start, bad option values (every one listed), a
            keyword that is no option. refracta.NumericalError: the start field cannot trace the
            pairs. KeyboardInterrupt on Ctrl-C.
    """
    where = "refracta.edit.solve"
    if backend is not None:
        options["backend"] = backend
    if not isinstance(field, _core.IndexField):
        raise ValueError(f"field must be an IndexField (got {type(field).__name__})")
    _refuse_several_cameras(eye_or_camera)
    free = _free_names(free)
    if free is not None:
        valid = list(field.param_names) + list(CAMERA_PARAMETERS)
        unknown = [n for n in free if n not in valid]
        if unknown:
            raise ValueError(f"unknown parameter(s) {unknown} for {field.type_name}; valid names: {valid}")
        if not isinstance(eye_or_camera, _core.Camera) and any(n in CAMERA_PARAMETERS for n in free):
            raise ValueError(
                f"free names camera parameters {[n for n in free if n in CAMERA_PARAMETERS]}: pass a Camera as "
                "eye_or_camera (the camera whose pixels the destinations are)"
            )
    settings, pair_options = solve_options(settings, pair_options, where=where, **options)
    check_solve_keywords(field, bounds)  # bounds where the model is defined (a trial's humidity in [-1, 3])
    if "max_iterations" in options and settings.backend.startswith("nlopt"):
        warnings.warn(
            f"{where}: max_iterations counts Ceres' iterations; {settings.backend} has none and stops on "
            "max_evaluations (every call of its objective) and time_limit",
            RuntimeWarning,
            stacklevel=2,
        )
    pairs, eye, camera, origins, directions, sources, weights, margins, tolerances = _pair_rays(
        eye_or_camera, pairs, settings.pixel_tolerance
    )
    bounds = _bounds_of(bounds)
    callback = progress_callback(progress, f"editing ({settings.backend})", share=True)  # the budget's share used
    initial = _core._pair_distances(field, origins, directions, sources, pair_options)
    summary = _core._solve_edit(
        field,
        origins,
        directions,
        sources,
        weights=weights,
        margins=margins,
        tolerances=tolerances,
        free=free or [],
        bounds=bounds,
        derivatives=derivatives,
        pair_options=pair_options,
        settings=settings,
        progress=callback,
        camera=camera,
        pixels=_pair_pixels(pairs),
    )
    solved = field.with_params(**dict(zip(field.param_names, (float(v) for v in summary.values))))
    return EditResult(
        field=solved,
        start=field,
        pairs=list(pairs),
        eye=np.asarray(eye),
        camera=summary.camera if summary.camera is not None else camera,
        initial_distances=initial,
        margins=margins,
        tolerances=tolerances,
        summary=summary,
        settings=settings,
        pair_options=pair_options,
        start_camera=camera,
    )


def distances(
    field: _core.IndexField,
    eye_or_camera,
    pairs: Sequence[PointPair],
    *,
    pair_options: _core.PairOptions | None = None,
    **options: Any,
) -> np.ndarray:
    """Each pair's miss [m]: how far the path launched toward its destination passes its source.
    pair_options, ``**options``: a refracta.edit.PairOptions and its fields by name (trace, tol, step,
    stop_height, distance, reach, max_steps), as solve() takes them."""
    pair_options = _pair_options("refracta.edit.distances", pair_options, options)
    _, _, _, origins, directions, sources, _, _, _ = _pair_rays(eye_or_camera, pairs)
    return _core._pair_distances(field, origins, directions, sources, pair_options)


def _free_names(free) -> list[str] | None:
    """solve()'s and jacobian()'s `free` as a list of names (None stays None: the default)."""
    if free is None:
        return None
    try:
        names = [free] if isinstance(free, str) else list(free)  # any iterable of names: a list, dict keys, ...
    except TypeError:
        names = None
    if names is None or not all(isinstance(n, (str, np.str_)) for n in names):
        raise ValueError(f"free must be a parameter name or a list of names (got {free!r})")
    if not names:
        raise ValueError("free is empty: name at least one parameter (or pass None for the default)")
    return [str(n) for n in names]


def check_solve_keywords(field: _core.IndexField, bounds=None, derivatives: str | None = None) -> None:
    """solve()'s bounds= and derivatives= checked before any work (the editor's solve_options):
    bounds of the field's or the camera's parameters, a derivatives name the field takes."""
    names = list(field.param_names) + list(CAMERA_PARAMETERS)
    for name, (lower, upper) in _bounds_of(bounds).items():
        if name not in names:
            raise ValueError(f"bounds given for {name!r}, which is not a parameter of {field.type_name} ({names})")
        if not (math.isfinite(lower) and math.isfinite(upper) and lower < upper and math.isfinite(upper - lower)):
            raise ValueError(  # as the solve's own check (edit_problem.cpp) says it
                f"bounds of {name!r} must be finite with lower < upper and a finite width upper - lower "
                f"(got [{lower:g}, {upper:g}])"
            )
        for bound in (lower, upper) if name in field.param_names else ():
            try:  # the model's own rule (as solve's EditProblem checks it)
                field.with_params(**{name: bound})
            except ValueError as error:
                raise ValueError(
                    f"bounds of {name!r} must lie where {field.type_name} is defined: at {bound:g}, {error}"
                ) from None
    if derivatives is not None:
        _core._check_derivatives(derivatives, field)


def _bounds_of(bounds) -> dict[str, tuple[float, float]]:
    """solve()'s `bounds` as {name: (lower, upper)} of numbers (None: no bounds of the caller's)."""
    if bounds is None:
        return {}
    if not isinstance(bounds, dict):
        raise ValueError(f"bounds must be a dict {{name: (lower, upper)}} (got {type(bounds).__name__})")
    out = {}
    for name, pair in bounds.items():
        if not isinstance(pair, (list, tuple, np.ndarray)) or len(pair) != 2 or not all(is_number(v) for v in pair):
            raise ValueError(f"bounds[{name!r}] must be a (lower, upper) pair of numbers (got {pair!r})")
        out[name] = (float(pair[0]), float(pair[1]))
    return out


def jacobian(
    field: _core.IndexField,
    eye_or_camera,
    pairs: Sequence[PointPair],
    free: Sequence[str] | None = None,
    *,
    derivatives: str = "auto",
    pair_options: _core.PairOptions | None = None,
    **options: Any,
) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """(residuals (3P,), Jacobian (3P, F), free names) at `field`: the weighted miss vectors an
    edit minimises and their derivatives in the free parameters (for sensitivity studies; with a
    Camera, free may name CAMERA_PARAMETERS too, derivatives per degree). pair_options,
    ``**options``: as distances()."""
    pair_options = _pair_options("refracta.edit.jacobian", pair_options, options)
    pairs, _, camera, origins, directions, sources, weights, margins, _ = _pair_rays(eye_or_camera, pairs)
    free = _free_names(free) or []  # None: every parameter
    return _core._pair_jacobian(
        field,
        origins,
        directions,
        sources,
        weights=weights,
        margins=margins,
        free=free,
        derivatives=derivatives,
        options=pair_options,
        camera=camera,
        pixels=_pair_pixels(pairs),
    )


def _file_option_names() -> set[str]:
    """The keys a pairs file may hold besides 'pairs': solve()'s options (its keywords that are not
    the call's own objects, every SolveSettings and PairOptions field, their deprecated spellings)."""
    import inspect

    objects = {"field", "eye_or_camera", "pairs", "settings", "pair_options", "progress", "options"}
    keywords = set(inspect.signature(solve).parameters) - objects
    return keywords | set(_options.fields(_core.SolveSettings) + _options.fields(_core.PairOptions)) | set(_RENAMED)


def load_pairs(
    path, scene: _core.Scene | None = None, camera: _core.Camera | None = None, field: _core.IndexField | None = None
) -> tuple[list[PointPair], dict]:
    """Point pairs from a JSON file, and the solve options it carries.

    Format::

        {"pairs": [{"destination": [u, v] or [x, y, z], "source": [x, y, z] or {"pixel": [u, v]},
                    "weight": 1.0, "margin": 0.0}, ...],
         "free": ["surface_dt"], "backend": "ceres", "stop_height": 0.0}  # optional solve() options

    A source given as a pixel is the scene point the camera sees there without atmosphere
    (camera.pick), so `scene` and `camera` are needed for it, and over a CurvedEarth the `field`
    the pairs are for: its Earth's straight lines (refracta.without_refraction(field)) pick the
    point; without it the scene's flat frame would be a flat Earth. The key "ground" is the deprecated
    spelling of "stop_height" (read for one release, with a DeprecationWarning). Raises
    refracta.MissingFileError for a missing file and ValueError naming the file and the pair for anything
    malformed.
    """
    import json
    import stat
    from pathlib import Path

    if field is not None and not isinstance(field, _core.IndexField):
        raise ValueError(f"load_pairs: field must be a refracta index field or None (got {type(field).__name__})")
    path = Path(path)
    try:
        if not path.exists():
            raise _core.MissingFileError(f"cannot read pairs file {path}: no such file")
        # Refused before opening: reading a FIFO (or a device) waits for a writer that may never come.
        if not stat.S_ISREG(path.stat().st_mode):
            raise _core.IoError(f"cannot read pairs file {path}: not a regular file")
        text = path.read_text(encoding="utf-8")
    except _core.IoError:
        raise
    except OSError as error:
        raise _core.IoError(f"cannot read pairs file {path}: {error.strerror}") from None
    except UnicodeDecodeError as error:
        raise ValueError(f"{path}: not a pairs file (JSON is UTF-8 text; byte {error.start} is not)") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        raise ValueError(f"{path}:{error.lineno}: not valid JSON: {error.msg}") from None
    except RecursionError:
        raise ValueError(f"{path}: not a pairs file (JSON nested too deeply)") from None
    if not isinstance(data, dict) or not isinstance(data.get("pairs"), list):
        raise ValueError(f"{path}: expected an object with a list 'pairs'")
    pairs = []
    for i, entry in enumerate(data["pairs"]):
        where = f"{path}: pairs[{i}]"
        if not isinstance(entry, dict) or "destination" not in entry or "source" not in entry:
            raise ValueError(f"{where}: needs 'destination' and 'source'")
        unknown = set(entry) - {"destination", "source", "weight", "margin"}
        if unknown:
            raise ValueError(f"{where}: unknown key '{sorted(unknown)[0]}'")
        source = entry["source"]
        if isinstance(source, dict):
            if set(source) != {"pixel"}:
                strangers = sorted(set(source) - {"pixel"})
                detail = f"unknown key '{strangers[0]}' in" if strangers else "no 'pixel' in"
                raise ValueError(f"{where}: {detail} source (a source is [x, y, z] or {{'pixel': [u, v]}})")
            if scene is None or camera is None:
                raise ValueError(f"{where}: a source given as {{'pixel': [u, v]}} needs the scene and camera")
            u, v = _vector(source["pixel"], (2,), f"{where} source pixel")
            if not on_image(camera, u, v):  # pick would extrapolate the ray
                raise ValueError(
                    f"{where}: source pixel ({u:g}, {v:g}) lies outside the camera's {camera.width} x "
                    f"{camera.height} image (u in [0, {camera.width}], v in [0, {camera.height}])"
                )
            source = camera.pick(scene, u, v, without_refraction(field))
            if source is None:
                raise ValueError(f"{where}: the camera sees no scene object at pixel ({u:g}, {v:g})")
        try:
            pairs.append(PointPair(entry["destination"], source, entry.get("weight", 1.0), entry.get("margin", 0.0)))
        except ValueError as error:
            raise ValueError(f"{where}: {error}") from None
    options = {k: v for k, v in data.items() if k != "pairs"}
    known = _file_option_names()
    strangers = sorted(set(options) - known)
    if strangers:
        raise ValueError(
            f"{path}: unknown key{'s' if len(strangers) > 1 else ''} {', '.join(repr(k) for k in strangers)} "
            f"(besides 'pairs', the file holds solve()'s options: {', '.join(sorted(known))})"
        )
    if "ground" in options:
        if "stop_height" in options:
            raise ValueError(f'{path}: give "stop_height" only ("ground" is its deprecated spelling)')
        deprecated(f'{path}: the key "ground" is deprecated; call it "stop_height"')
        options["stop_height"] = options.pop("ground")
    return pairs, options
