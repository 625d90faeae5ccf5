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

Units: metres (scene units for LogisticProfile); cost is 1/2 sum weight * miss^2 [m^2].
"""

from __future__ import annotations

import time as _time
from collections.abc import Sequence
from dataclasses import dataclass
from dataclasses import field as _dataclass_field
from typing import Any, Callable

import numpy as np

from refracta import _core
from refracta._progress import ProgressBar

__all__ = ["EditResult", "PointPair", "distances", "jacobian", "load_pairs", "solve", "NLOPT_ALGORITHMS"]

#: nlopt algorithms known to work on edits (any other nlopt name is accepted too).
NLOPT_ALGORITHMS = ("LN_BOBYQA", "LN_NELDERMEAD", "LN_SBPLX", "LN_COBYLA", "GN_DIRECT_L", "LD_LBFGS", "LD_MMA")


def _vector(value, sizes, what: str) -> np.ndarray:
    array = np.asarray(value, dtype=float)
    if array.ndim != 1 or array.size not in sizes or not np.all(np.isfinite(array)):
        wanted = " or ".join(str(s) for s in sizes)
        raise ValueError(f"{what} must be {wanted} finite numbers (got {value!r})")
    return array


def _number(value, what: str) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a number (got {value!r})") from None
    if not np.isfinite(number):
        raise ValueError(f"{what} must be finite (got {value!r})")
    return number


@dataclass(frozen=True)
class PointPair:
    """One constraint of an edit.

    Attributes:
        destination: where the image should appear -- a pixel ``(u, v)`` of the camera passed to
            solve(), or a 3D point [m] the eye looks toward (only its direction from the eye
            matters).
        source: the 3D scene point [m] that should be seen there (``camera.pick(scene, u, v)``
            finds the point a pixel shows without atmosphere).
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


def _pair_rays(eye_or_camera, pairs: Sequence[PointPair], pixel_tolerance: float | None = None):
    """(pairs, eye, camera or None, origins, directions, sources, weights, margins [m], tolerances [m])
    of the pairs.

    pixel_tolerance [pixels]: a pixel destination's pair is met within this many pixels' footprint
    at its source (default: the C++ default, _SolveSettings().pixel_tolerance); 3D destinations: 0.
    """
    if isinstance(pairs, PointPair):
        pairs = [pairs]
    pairs = list(pairs)
    if not pairs:
        raise ValueError("pairs is empty: give at least one PointPair")
    for i, pair in enumerate(pairs):
        if not isinstance(pair, PointPair):
            raise ValueError(f"pairs[{i}] must be a PointPair (got {type(pair).__name__})")
    camera = eye_or_camera if isinstance(eye_or_camera, _core.Camera) else None
    eye = camera.position if camera is not None else _vector(eye_or_camera, (3,), "eye_or_camera")
    directions = []
    for i, pair in enumerate(pairs):
        if pair.is_pixel:
            if camera is None:
                raise ValueError(f"pairs[{i}] gives a pixel destination {pair.destination}; pass a Camera "
                                 "as eye_or_camera (or give the destination as a 3D point)")
            directions.append(camera.ray(*pair.destination)[1])
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
        pixel_tolerance = _core._SolveSettings().pixel_tolerance
    ranges = np.linalg.norm(sources - eye, axis=1)
    pixel_angle = camera.pixel_angle if camera is not None else 0.0  # a pixel pair has a camera (checked above)
    footprints = np.array([pixel_angle * r if p.is_pixel else 0.0 for p, r in zip(pairs, ranges)])
    margins = np.array([p.margin * (f if p.is_pixel else 1.0) for p, f in zip(pairs, footprints)])
    return pairs, eye, camera, origins, np.array(directions), sources, weights, margins, pixel_tolerance * footprints


def _pair_options(integrator: str, tol: float, step: float | None, ground: float | None,
                  distance: str, reach: float):
    if integrator not in ("rk45", "rk4"):
        raise ValueError(f"integrator must be 'rk45' or 'rk4' (got {integrator!r})")
    return _core._PairOptions(integrator, tol, step, ground, distance, reach)


@dataclass
class EditResult:
    """What solve() found. ``print(result)`` shows the report.

    field: the solved field; start: the field it started from. cost / initial_cost: 1/2 sum of
    weight * (miss - margin)^2 over the pairs outside their margins [m^2]; distances: each pair's
    miss [m] after solving (initial_distances before); margins: each pair's margin [m] (pixel
    margins converted at the source's distance); tolerances: each pair's met tolerance beyond its
    margin [m] (pixel destinations: solve's pixel_tolerance of the pixel's footprint at the source;
    3D destinations 0); met: per pair, whether its miss is within its margin plus the larger of
    its tolerance and accept_angle times its range. success: every pair met (strategy 'local': and the
    back-end converged). strategy: 'auto' or 'local'; stages: what the strategy did, one line per
    stage (local solves, the global stage's design); solver_report: the back-end's own report of
    the run that gave the result (Ceres' full summary). stopped_by: the limit that cut the solve
    short ('iteration limit', 'evaluation limit', 'time limit'; '' if none). condition, rank: of the
    Jacobian in the free parameters' unit box at a result meeting every pair (else 0, 0); above
    1e6 the message says the solution is not unique. history: cost per iteration (ceres) or best
    cost per evaluation (nlopt) of that run. free: the optimised parameters; insensitive: requested
    free parameters no pair depends on (held fixed). iterations, evaluations (cost evaluations,
    the global stage's design points included), pair_traces (traced pairs, derivative passes
    included), time [s] (solving only).
    """

    field: _core.IndexField
    start: _core.IndexField
    pairs: list[PointPair]
    eye: np.ndarray
    camera: _core.Camera | None
    cost: float
    initial_cost: float
    distances: np.ndarray
    initial_distances: np.ndarray
    iterations: int
    evaluations: int
    pair_traces: int
    time: float
    success: bool
    converged: bool
    message: str
    history: np.ndarray
    free: list[str]
    insensitive: list[str]
    backend: str
    derivatives: str
    starts: int = 1
    trace_options: dict[str, Any] = _dataclass_field(default_factory=dict)
    margins: np.ndarray = _dataclass_field(default_factory=lambda: np.zeros(0))
    tolerances: np.ndarray = _dataclass_field(default_factory=lambda: np.zeros(0))
    met: np.ndarray = _dataclass_field(default_factory=lambda: np.zeros(0, dtype=bool))
    strategy: str = "local"
    stages: list[str] = _dataclass_field(default_factory=list)
    solver_report: str = ""
    stopped_by: str = ""
    condition: float = 0.0
    rank: int = 0

    def paths(self, which: str = "solved") -> list[_core.RayPath]:
        """Each pair's light path through the solved field ('solved') or the start ('start')."""
        if which not in ("solved", "start"):
            raise ValueError(f"which must be 'solved' or 'start' (got {which!r})")
        field = self.field if which == "solved" else self.start
        _, _, _, origins, directions, sources, _, _, _ = _pair_rays(self.camera if self.camera is not None else self.eye, self.pairs)
        options = self.trace_options
        out = []
        for origin, direction, source in zip(origins, directions, sources):
            length = options["reach"] * float(np.linalg.norm(source - origin)) + 1.0
            out.append(_core.trace_ray(field, origin, direction, method=options["integrator"], tol=options["tol"],
                                       step=options["step"], max_length=length, stop_height=options["ground"]))
        return out

    def report(self) -> str:
        """A readable summary: outcome, costs, per-pair distances, parameters before and after."""
        verdict = "success" if self.success else "FAILED"
        lines = [
            f"Edit of {self.field.type_name} with {self.backend} ({self.derivatives} derivatives): {verdict}",
            f"  cost {self.initial_cost:.4g} -> {self.cost:.4g} m^2 in {self.iterations} iterations, "
            f"{self.evaluations} evaluations, {self.pair_traces} pair traces, {self.time:.3g} s"
            + (f" ({self.starts} starts)" if self.starts > 1 else ""),
            "  pair  weight  miss before [m]  miss after [m]  margin [m]  met  range [m]",
        ]
        margins = self.margins if len(self.margins) == len(self.pairs) else np.zeros(len(self.pairs))
        met = self.met if len(self.met) == len(self.pairs) else np.zeros(len(self.pairs), dtype=bool)
        for i, pair in enumerate(self.pairs):
            distance = float(np.linalg.norm(np.asarray(pair.source) - self.eye))
            lines.append(f"  {i:4d}  {pair.weight:6.3g}  {self.initial_distances[i]:15.4g}  "
                         f"{self.distances[i]:14.4g}  {margins[i]:10.4g}  {'yes' if met[i] else 'NO ':3s}  {distance:9.4g}")
        info = {p["name"]: p for p in self.start.param_info}
        start, solved = self.start.params, self.field.params
        lines.append("  parameter            start          solved         unit")
        for name in self.free:
            lines.append(f"  {name:18s} {start[name]:14.8g} {solved[name]:14.8g}  {info[name]['unit']}")
        fixed = [n for n in start if n not in self.free]
        if fixed:
            lines.append("  held fixed: " + ", ".join(fixed))
        if self.insensitive:
            lines.append("  no pair depends on (held fixed): " + ", ".join(self.insensitive))
        if self.stages:
            lines.append(f"  strategy {self.strategy}:")
            lines += ["    " + stage for stage in self.stages]
        if self.rank:
            lines.append(f"  Jacobian at the result: rank {self.rank} of {len(self.free)}, condition {self.condition:.3g}")
        lines.append("  " + self.message)
        return "\n".join(lines)

    __str__ = report

    def __repr__(self) -> str:
        return (f"EditResult(success={self.success}, cost={self.cost:.3g}, max miss={np.max(self.distances):.3g} m, "
                f"backend={self.backend!r}, iterations={self.iterations}, time={self.time:.3g} s)")


def solve(
    field: _core.IndexField,
    eye_or_camera,
    pairs: Sequence[PointPair],
    free: Sequence[str] | None = None,
    backend: str = "ceres",
    *,
    strategy: str = "auto",
    bounds: dict[str, tuple[float, float]] | None = None,
    starts: int = 1,
    seed: int = 0,
    derivatives: str = "auto",
    distance: str = "continuous",
    integrator: str = "rk45",
    tol: float = 1e-9,
    step: float | None = None,
    ground: float | None = None,
    reach: float = 1.5,
    loss: str = "none",
    loss_scale: float = 1.0,
    max_iterations: int = 200,
    max_evaluations: int = 3000,
    time_limit: float | None = None,
    target_cost: float | None = None,
    trust_region: float = 0.1,
    accept_angle: float = 1e-6,
    pixel_tolerance: float | None = None,
    function_tolerance: float = 1e-14,
    parameter_tolerance: float = 1e-12,
    gradient_tolerance: float = 1e-16,
    progress: bool | Callable[[int, int], None] = False,
    quick_iterations: int | None = None,
    design_per_param: int | None = None,
    local_starts: int | None = None,
) -> EditResult:
    """Solve for the parameters of `field` that make each pair's light path pass its source.

    Args:
        field: any IndexField. Built-in models (LogisticProfile, PhysicalAtmosphere,
            TemperatureProfile, LinearSquaredProfile, and CurvedEarth over them) get automatic
            derivatives; other fields (CustomField) central differences.
        eye_or_camera: a Camera (pixel destinations allowed) or the eye position (3,) [m].
        pairs: PointPairs.
        free: names of the parameters to optimise; default every parameter except the model's
            gauge ones (LogisticProfile's n_bg: a common scale of the amplitudes changes nothing).
            Free parameters on which no pair depends are held fixed and listed in
            result.insensitive.
        backend: 'ceres' or 'nlopt:<ALGORITHM>' (see NLOPT_ALGORITHMS; any nlopt name works).
        strategy: 'auto' (default) -- a short local solve from `field` (quick_iterations), with
            ceres continued while its cost still falls (LM closing in); if it does not meet
            every pair, a global stage (scans along each free parameter's axis and
            quasi-random points over the bounds and near the start, costs in parallel on all
            cores) and local solves from its best points (at most local_starts) until one meets
            every pair; result.stages says what ran. 'local' -- the back-end from `field` only.
        bounds: {name: (lower, upper)} overriding the model's search box.
        starts: number of starts; the first is `field`, the others uniform in the bounds (seeded by
            `seed`); the best result is returned with times and evaluations summed.
        derivatives: 'auto', 'automatic' (ceres::Jet) or 'numeric' (central differences).
        distance: 'continuous' (closest approach of the continuous path) or 'vertex' (nearest
            integrator node, the original editor's piecewise-constant measure).
        integrator, tol, step: 'rk45' to `tol` [m] (default 1e-9) or 'rk4' with `step` [m]
            (default 0.3, the original's).
        ground: height [m] where paths end on the ground (default: none).
        reach: paths are traced to ``reach * |source - eye| + 1`` m (and stop once past the source).
        loss, loss_scale: ceres robust loss ('huber', 'soft_l1', 'cauchy', 'arctan') on each
            pair's squared miss, quadratic below loss_scale [m].
        max_iterations (LM iterations, ceres), max_evaluations (cost evaluations, each tracing
            every pair: back-ends and the global stage's design points), time_limit [s] (0: none;
            default 300, the C++ SolveSettings'): limits of the whole solve, shared by its stages
            and its starts; a trace running at the time limit is interrupted. What stopped the
            solve is named in result.stages and result.stopped_by. target_cost [m^2] (stop once
            reached), function/parameter/gradient_tolerance: convergence criteria.
        trust_region: ceres' initial trust-region radius as a fraction of each free parameter's
            bound range (default 0.1: cautious first steps; narrow layers have flat regions a bold
            step lands in).
        accept_angle: a pair is met when its miss is at most its margin plus
            ``accept_angle * |source - eye|`` (accept_angle [rad]).
        pixel_tolerance: a pair with a pixel destination is met when its miss is within its
            margin plus this many pixels' footprint at its source (default 0.1 px, the C++
            SolveSettings::pixel_tolerance), if that exceeds accept_angle times its range. It
            judges the result only: the cost still pulls every pair onto its source.
        quick_iterations, design_per_param, local_starts: the 'auto' strategy's first local
            solve's iterations, design points per free parameter, local solves from the design
            (defaults: refracta's _core._SolveSettings()).
        progress: True for a bar on stderr, or a callable progress(done, total): done of total
            is the largest fraction used of the iteration, evaluation and time limits (and, with
            several starts, of the starts), reaching total when the solve ends.

    Returns:
        EditResult. Not converging, or an image no atmosphere within the bounds can make, is a
        result with success False and a message, not an exception.

    Raises:
        ValueError: bad pairs (NaN, pixel without camera), unknown parameter names or nlopt
            algorithm, bounds not containing the start. refracta.NumericalError: the start field
            cannot trace the pairs. KeyboardInterrupt on Ctrl-C.
    """
    if not isinstance(field, _core.IndexField):
        raise ValueError(f"field must be an IndexField (got {type(field).__name__})")
    if isinstance(starts, bool) or int(starts) != starts or starts < 1:
        raise ValueError(f"starts must be a whole number >= 1 (got {starts!r})")
    if free is not None:
        if isinstance(free, str):
            free = [free]
        free = list(free)
        if not free:
            raise ValueError("free is empty: name at least one parameter (or pass None for the default)")
        unknown = [n for n in free if n not in field.param_names]
        if unknown:
            raise ValueError(f"unknown parameter(s) {unknown} for {field.type_name}; "
                             f"valid names: {field.param_names}")
    options = _pair_options(integrator, tol, step, ground, distance, reach)
    settings = _core._SolveSettings()
    settings.backend = backend
    settings.strategy = strategy
    for name, value in (("quick_iterations", quick_iterations), ("design_per_param", design_per_param),
                        ("local_starts", local_starts)):
        if value is not None:
            if isinstance(value, bool) or int(value) != value:
                raise ValueError(f"{name} must be a whole number (got {value!r})")
            setattr(settings, name, int(value))
    settings.max_iterations = int(max_iterations)
    settings.max_evaluations = int(max_evaluations)
    if time_limit is not None:
        settings.time_limit = _number(time_limit, "time_limit")
    settings.function_tolerance = function_tolerance
    settings.parameter_tolerance = parameter_tolerance
    settings.gradient_tolerance = gradient_tolerance
    settings.target_cost = 0.0 if target_cost is None else float(target_cost)
    settings.trust_region = float(trust_region)
    settings.loss = loss
    settings.loss_scale = loss_scale
    settings.accept_angle = accept_angle
    if pixel_tolerance is not None:
        settings.pixel_tolerance = _number(pixel_tolerance, "pixel_tolerance")
    settings.validate()
    pairs, eye, camera, origins, directions, sources, weights, margins, tolerances = _pair_rays(
        eye_or_camera, pairs, settings.pixel_tolerance)
    bounds = {k: (float(v[0]), float(v[1])) for k, v in (bounds or {}).items()}
    callback = ProgressBar(f"editing ({backend})") if progress is True else (progress or None)
    # One budget for every start: each gets what the ones before it left (SolveSettings' limits).
    budget = dict(max_iterations=settings.max_iterations, max_evaluations=settings.max_evaluations,
                  time_limit=settings.time_limit)
    began = _time.perf_counter()

    def run(start_field, k):
        def report(done, total):  # start k's progress as its share of the whole
            if callback is not None:
                callback(k * total + done, starts * total)

        return _core._solve_edit(start_field, origins, directions, sources, weights, margins, tolerances, free or [],
                                 bounds, derivatives, options, settings, report if callback is not None else None)

    def left():
        """The budget's first exhausted limit, or None; settings set to what is left."""
        settings.max_iterations = budget["max_iterations"] - (used_iterations if backend == "ceres" else 0)
        settings.max_evaluations = budget["max_evaluations"] - total_evaluations
        if budget["time_limit"] > 0.0:
            settings.time_limit = budget["time_limit"] - (_time.perf_counter() - began)
            if settings.time_limit <= 0.0:
                return "time limit"
        if settings.max_evaluations < 1:
            return "evaluation limit"
        if settings.max_iterations < 1:
            return "iteration limit"
        return None

    initial = _core._pair_distances(field, origins, directions, sources, options)
    best = first = run(field, 0)
    total_time, total_evaluations, total_traces = best["time"], best["evaluations"], best["pair_traces"]
    used_iterations = best["iterations"]
    starts_run, stopped = 1, None
    if starts > 1:
        rng = np.random.default_rng(seed)
        box = field.bounds
        box.update(bounds)
        for k in range(1, starts):
            trial_start = field.with_params(**{n: float(rng.uniform(*box[n])) for n in best["free"]})
            stopped = left()
            if stopped:
                break
            try:
                trial = run(trial_start, k)
            except _core.NumericalError:
                continue  # this start cannot trace the pairs; try the next
            starts_run += 1
            total_time += trial["time"]
            total_evaluations += trial["evaluations"]
            total_traces += trial["pair_traces"]
            used_iterations += trial["iterations"]
            stopped = trial["stopped_by"] or None
            if (trial["success"], -trial["cost"]) > (best["success"], -best["cost"]):
                best = trial
        if callback is not None:
            callback(starts, starts)  # complete, also when the budget ended the starts early
    stages = list(best["stages"])
    if starts > 1:
        stages.append(f"starts: {starts_run} of {starts} run" + (f"; stopped by the {stopped}" if stopped else ""))
    elif best["stopped_by"]:
        stopped = best["stopped_by"]
    names = field.param_names
    solved = field.with_params(**dict(zip(names, (float(v) for v in best["values"]))))
    return EditResult(
        field=solved, start=field, pairs=list(pairs), eye=np.asarray(eye), camera=camera, cost=best["cost"],
        initial_cost=first["initial_cost"],
        distances=best["distances"], initial_distances=initial, iterations=best["iterations"],
        evaluations=total_evaluations, pair_traces=total_traces, time=total_time, success=best["success"],
        converged=best["converged"], message=best["message"], history=best["history"], free=best["free"],
        insensitive=best["insensitive"], backend=backend, derivatives=best["derivatives"], starts=int(starts),
        trace_options=dict(integrator=integrator, tol=tol, step=step, ground=ground, reach=reach),
        margins=margins, tolerances=tolerances, met=np.asarray(best["met"], dtype=bool), strategy=best["strategy"],
        stages=stages, solver_report=best["solver_report"], stopped_by=stopped or "",
        condition=best["condition"], rank=best["rank"],
    )


def distances(field: _core.IndexField, eye_or_camera, pairs: Sequence[PointPair], *, distance: str = "continuous",
              integrator: str = "rk45", tol: float = 1e-9, step: float | None = None,
              ground: float | None = None, reach: float = 1.5) -> np.ndarray:
    """Each pair's miss [m]: how far the path launched toward its destination passes its source."""
    _, _, _, origins, directions, sources, _, _, _ = _pair_rays(eye_or_camera, pairs)
    return _core._pair_distances(field, origins, directions, sources,
                                 _pair_options(integrator, tol, step, ground, distance, reach))


def jacobian(field: _core.IndexField, eye_or_camera, pairs: Sequence[PointPair], free: Sequence[str] | None = None,
             *, derivatives: str = "auto", distance: str = "continuous", integrator: str = "rk45", tol: float = 1e-9,
             step: float | None = None, ground: float | None = None,
             reach: float = 1.5) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """(residuals (3P,), Jacobian (3P, F), free names) at `field`: the weighted miss vectors an
    edit minimises and their derivatives in the free parameters (for sensitivity studies)."""
    _, _, _, origins, directions, sources, weights, margins, _ = _pair_rays(eye_or_camera, pairs)
    free = [free] if isinstance(free, str) else list(free or [])
    return _core._pair_jacobian(field, origins, directions, sources, weights, margins, free, derivatives,
                                _pair_options(integrator, tol, step, ground, distance, reach))


def load_pairs(path, scene: _core.Scene | None = None, camera: _core.Camera | None = None) -> tuple[list[PointPair], dict]:
    """Point pairs from a JSON file, and the solve options it carries.

    Format::

        {"pairs": [{"destination": [u, v] or [x, y, z], "source": [x, y, z] or {"pixel": [u, v]},
                    "weight": 1.0, "margin": 0.0}, ...],
         "free": ["surface_dt"], "backend": "ceres", "ground": 0.0}      # optional solve() options

    A source given as a pixel is the scene point the camera sees there without atmosphere
    (camera.pick), so `scene` and `camera` are needed for it. Raises refracta.IoError for a missing
    file and ValueError naming the file and the pair for anything malformed.
    """
    import json
    import stat
    from pathlib import Path

    path = Path(path)
    try:
        # Refused before opening: reading a FIFO (or a device) waits for a writer that may never come.
        if not stat.S_ISREG(path.stat().st_mode):
            raise _core.IoError(f"cannot read pairs file {path}: not a regular file")
        text = path.read_text()
    except _core.IoError:
        raise
    except OSError as error:
        raise _core.IoError(f"cannot read pairs file {path}: {error.strerror}") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as error:
        raise ValueError(f"{path}:{error.lineno}: not valid JSON: {error.msg}") from None
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
            if scene is None or camera is None or "pixel" not in source:
                raise ValueError(f"{where}: a source given as {{'pixel': [u, v]}} needs the scene and camera")
            u, v = _vector(source["pixel"], (2,), f"{where} source pixel")
            source = camera.pick(scene, u, v)
            if source is None:
                raise ValueError(f"{where}: the camera sees no scene object at pixel ({u:g}, {v:g})")
        try:
            pairs.append(PointPair(entry["destination"], source, entry.get("weight", 1.0), entry.get("margin", 0.0)))
        except ValueError as error:
            raise ValueError(f"{where}: {error}") from None
    options = {k: v for k, v in data.items() if k != "pairs"}
    return pairs, options
