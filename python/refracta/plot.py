"""Plots of curved rays and the atmospheres that bend them (matplotlib).

Every ray drawn here is traced by the library's integrators (refracta.trace_ray); nothing is
re-computed in Python.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from refracta import _core
from refracta._checks import is_number, real_array
from refracta._warn import deprecated

_UNSET = object()  # a deprecated keyword not given


def _renamed(old: str, old_value: object, new: str, value):
    """`value`, or the deprecated keyword `old`'s value (one release) with a DeprecationWarning."""
    if old_value is _UNSET:
        return value
    deprecated(f"ray_fan: {old}= is deprecated; call it {new}=")
    return old_value


def _profile_heights(field, low: float, high: float, count: int = 400) -> np.ndarray:
    if high <= low:
        high = low + 1.0
    return np.linspace(low, high, count)


def ray_fan(
    field: _core.IndexField,
    eye_height: float,
    elevations: Sequence[float],
    max_length: float,
    stop_height: float | None = 0.0,
    trace: str | None = None,
    tol: float | None = None,
    title: str | None = None,
    figsize=(11.0, 4.2),
    *,
    ground: object = _UNSET,
    method: object = _UNSET,
):
    """Rays from one eye in their vertical plane, beside the temperature and index profiles.

    Args:
        field: any IndexField (height-only fields are traced exactly with trace='stratified').
        eye_height: height of the eye [m] (scene units for LogisticProfile).
        elevations: launch elevations [deg], negative below the horizon.
        max_length: arc length of each ray [m].
        stop_height: height where rays end on the ground [m], or None for no ground.
        trace: integrator; default 'stratified' for height-only fields, else 'rk45'.
        tol: integrator tolerance [m] (None: TraceOptions' default).
        ground, method: the deprecated spellings of stop_height and trace (one release, with a
            DeprecationWarning).

    Returns:
        A matplotlib Figure. The ray panel's vertical scale is exaggerated (its own y range);
        rays are coloured by elevation, those reaching the ground drawn dashed.
    """
    import matplotlib.pyplot as plt
    from matplotlib import cm, colors

    if not isinstance(field, _core.IndexField):
        raise ValueError(f"ray_fan: field must be a refracta IndexField (got {type(field).__name__})")
    angles = np.atleast_1d(real_array(elevations, "ray_fan: elevations"))  # [deg]; not "0.1", nor True
    if angles.ndim != 1 or angles.size == 0 or not np.all(np.isfinite(angles)) or np.any(np.abs(angles) > 90.0):
        raise ValueError(
            f"ray_fan: elevations must be a non-empty list of finite angles in [-90, 90] deg (got {elevations!r})"
        )
    stop_height = _renamed("ground", ground, "stop_height", stop_height)
    trace = _renamed("method", method, "trace", trace)
    if (
        not is_number(eye_height)
        or not np.isfinite(eye_height)
        or (stop_height is not None and eye_height < stop_height)
    ):
        raise ValueError(f"ray_fan: eye_height must be a finite number above the ground (got {eye_height!r})")
    trace = trace or ("stratified" if field.height_only else "rk45")

    # The air's own profiles: a CurvedEarth's base at true heights (its flat frame's index rises with
    # height by e^(y / R), which read as air growing denser upward).
    curved = field if isinstance(field, _core.CurvedEarth) else None
    air = curved.base if curved is not None else field
    temperature = getattr(air, "temperature", None)  # the models with a temperature profile
    has_temperature = temperature is not None
    fig, axes = plt.subplots(
        1,
        3 if has_temperature else 2,
        figsize=figsize,
        gridspec_kw={"width_ratios": [4, 1, 1] if has_temperature else [4, 1]},
        sharey=True,
        constrained_layout=True,
    )
    ax_rays = axes[0]
    norm = colors.Normalize(angles.min(), angles.max() if np.ptp(angles) > 0 else angles.min() + 1)
    cmap = cm.viridis
    low, high = eye_height, eye_height
    for elevation in angles:
        e = np.radians(elevation)
        path = _core.trace_ray(
            field,
            [0.0, eye_height, 0.0],
            [np.cos(e), np.sin(e), 0.0],
            trace=trace,
            tol=tol,
            max_length=max_length,
            stop_height=stop_height,
        )
        points = path.sample(max(200, 2 * len(path)))
        low, high = min(low, points[:, 1].min()), max(high, points[:, 1].max())
        ax_rays.plot(
            points[:, 0],
            points[:, 1],
            color=cmap(norm(elevation)),
            lw=1.0,
            ls="--" if path.stop == "stop_height" else "-",
        )
    if stop_height is not None:
        ax_rays.axhline(stop_height, color="0.35", lw=1.5)
        low = min(low, stop_height)
    ax_rays.plot([0.0], [eye_height], "o", color="crimson", ms=5, label="eye")
    ax_rays.set_xlabel("distance [m]")
    ax_rays.set_ylabel("height [m] (vertical scale exaggerated)")
    ax_rays.set_xlim(0, None)
    ax_rays.legend(loc="upper left")
    fig.colorbar(cm.ScalarMappable(norm=norm, cmap=cmap), ax=ax_rays, label="launch elevation [deg]", pad=0.01)
    ax_rays.set_title(title or f"{field.type_name}: rays from {eye_height:g} m")

    margin = 0.05 * (high - low if high > low else 1.0)
    # The profiles from the ground up (below it there is no air: a trial read the surface layer's
    # continuation under the road, 34 C, as the road's own excess).
    bottom = low - margin if stop_height is None else max(low - margin, stop_height)
    heights = _profile_heights(field, bottom, high + margin)
    true = np.asarray(curved.true_height(heights)) if curved is not None else heights
    points = np.stack([np.zeros_like(heights), true, np.zeros_like(heights)], axis=1)
    ax_index = axes[-1]
    ax_index.plot((air.ior(points) - 1.0) * 1e6, heights, color="tab:blue")
    ax_index.set_xlabel("(n - 1) x 1e6")
    ax_index.set_title("index")
    if temperature is not None:
        ax_t = axes[1]
        ax_t.plot(temperature(true) - 273.15, heights, color="tab:red")
        ax_t.set_xlabel("T [°C]")
        ax_t.set_title("temperature")
    ax_rays.set_ylim(low - margin, high + margin)
    return fig


_LISTED_PAIRS = 10  # edit_report's legend names each pair up to this many


def edit_report(result, figsize=(12.0, 4.2), figure=None):
    """An edit at a glance: each pair's light path before (dashed) and after (solid) the solve,
    seen from the side (distance from the eye vs height), with its source (x) and the eye; and
    the cost history on a log scale.

    Args:
        result: a refracta.edit.EditResult.
        figsize: (width, height) [inches] of a new figure (ignored when `figure` is given).
        figure: an empty matplotlib.figure.Figure to draw into, or None: a new pyplot figure (shown
            inline in a notebook). A Figure made with ``matplotlib.figure.Figure()`` never touches
            pyplot's global state, so it may be drawn and saved on any thread (the mirage editor
            draws its ray fan on a worker thread this way).

    Returns:
        The matplotlib Figure. Paths are traced by the library (EditResult.paths) with the options
        the solve used.
    """
    from matplotlib import colormaps

    from refracta.edit import EditResult

    if not isinstance(result, EditResult):
        raise ValueError(f"edit_report: result must be a refracta.edit.EditResult (got {type(result).__name__})")
    if figure is None:
        import matplotlib.pyplot as plt

        figure = plt.figure(figsize=figsize)
    elif figure.axes:
        raise ValueError(f"edit_report: figure must be empty (it has {len(figure.axes)} axes)")
    figure.set_layout_engine("constrained")
    ax_paths, ax_cost = figure.subplots(1, 2, gridspec_kw={"width_ratios": [3, 1.3]})
    eye = np.asarray(result.eye, dtype=float)
    colours = colormaps["tab10"](np.arange(len(result.pairs)) % 10)
    for which, style in (("start", "--"), ("solved", "-")):
        for path, colour in zip(result.paths(which), colours):
            points = path.sample(max(200, 2 * len(path)))
            along = np.hypot(points[:, 0] - eye[0], points[:, 2] - eye[2])
            ax_paths.plot(
                along,
                points[:, 1],
                style,
                color=colour,
                lw=1.0 if which == "start" else 1.6,
                alpha=0.6 if which == "start" else 1.0,
            )
    # A legend line per pair up to _LISTED_PAIRS; beyond, one line for them all (40 pairs' lines
    # covered the plot and ran off the figure, and constrained layout gave up with a warning).
    listed = len(result.pairs) <= _LISTED_PAIRS
    for i, (pair, colour) in enumerate(zip(result.pairs, colours)):
        source = np.asarray(pair.source)
        label: str | None
        if listed:
            label = f"pair {i}: miss {result.initial_distances[i]:.2g} -> {result.distances[i]:.2g} m"
        else:
            largest = (float(np.max(result.initial_distances)), float(np.max(result.distances)))
            label = (
                f"{len(result.pairs)} sources: largest miss {largest[0]:.2g} -> {largest[1]:.2g} m" if i == 0 else None
            )
        ax_paths.plot(
            np.hypot(source[0] - eye[0], source[2] - eye[2]), source[1], "x", color=colour, ms=9, mew=2, label=label
        )
    ax_paths.plot([0.0], [eye[1]], "o", color="crimson", ms=5, label="eye")
    ax_paths.set_xlabel("distance from the eye [m]")
    ax_paths.set_ylabel("height [m]")
    ax_paths.set_title(f"{result.field.type_name}: paths before (dashed) and after (solid)")
    ax_paths.legend(fontsize=8, loc="best")

    # The history is the run that gave the result (the last local solve of a staged one), in the
    # measure the solver minimised (with a robust loss, not the plain cost): the start's plain cost
    # is marked beside it, so the whole descent shows.
    tiny = np.finfo(float).tiny
    history = np.maximum(np.asarray(result.history, dtype=float), tiny)
    # Ceres records its iteration 0 (the local solve's start), nlopt each evaluation from the first.
    ceres = result.backend == "ceres"
    step = "iteration" if ceres else "evaluation"
    staged = len(result.stages) > 1
    steps = np.arange(len(history)) if ceres else np.arange(1, len(history) + 1)
    ax_cost.semilogy(steps, history, color="tab:blue", label=f"last local solve, per {step}" if staged else None)
    start = "the solve's start (plain cost)" if staged else "start (plain cost)"
    ax_cost.semilogy([0], [max(result.initial_cost, tiny)], "o", color="crimson", label=start)
    last = steps[-1] if len(steps) else 0
    ax_cost.semilogy([last], [max(result.cost, tiny)], "s", color="tab:green", mfc="none", label="result (plain)")
    ax_cost.legend(fontsize=8, loc="best")
    ax_cost.set_xlabel(f"{step} of the last local solve" if staged else step)
    loss = result.settings.loss
    ax_cost.set_ylabel("cost [m²]" if loss == "none" else f"cost [m²] ({loss} loss in the curve)")
    ax_cost.set_title(f"{result.backend}: {'success' if result.success else 'failed'}")
    ax_cost.grid(True, which="both", alpha=0.3)
    return figure


def readouts_figure(image, aovs: dict, exposure: float | None = None, figsize=(9.0, 4.0)):
    """A matplotlib figure of a render's image whose status bar, as the pointer moves over it, shows
    the readouts at that pixel (render(aovs=[...])'s second result; the text of
    refracta.widgets.readout_text, through the axes' format_coord). Needs an interactive backend
    (``%matplotlib widget`` with ipympl, Qt, Tk); in plain Jupyter use
    refracta.widgets.show_readouts, which hovers in the browser. exposure: as refracta.io.to_display
    (None: automatic)."""
    import matplotlib.pyplot as plt

    from refracta import io
    from refracta._readout_text import checked_planes, readout_text

    pixels, _ = checked_planes(aovs, image, "readouts_figure")
    figure, axes = plt.subplots(figsize=figsize)
    axes.imshow(io.to_display(pixels[..., :3], exposure=exposure), interpolation="nearest")
    # imshow puts pixel (i, j)'s centre at (i, j): the image point is (x + 0.5, y + 0.5).
    axes.format_coord = lambda x, y: readout_text(aovs, x + 0.5, y + 0.5).replace("\n", "; ")  # type: ignore[method-assign]
    axes.set_axis_off()
    return figure
