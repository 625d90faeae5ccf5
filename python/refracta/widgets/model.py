"""The mirage editor's state and behaviour, without any user interface (MirageEditor is its view).

EditorModel holds the scene, camera, atmosphere and point pairs, turns pointer events into pairs
and camera moves, keeps undo/redo history, and runs renders and solves in the background
(refracta.widgets.jobs). The view forwards the browser's events to the same methods the tests
call, and redraws when the model tells it what changed.

Coordinates: pointer events and destinations are in image pixels of the editor's (full
resolution) camera -- u right, v down, pixel (i, j) centred at (i + 0.5, j + 0.5), as Camera.ray,
Camera.pick and Camera.project use them. Sources are scene points [m].

Pointer gestures in mode 'points':

- a press on nothing, first: the source -- the scene point the pixel shows without atmosphere
  (Camera.pick); on the sky (no hit) a message says so and nothing changes;
- a press on nothing, second: the destination -- where that point's mirage image should appear;
  the pair is added (weight 1, margin 0);
- a press on a marker, then moving: drags that source (picked again under the pointer) or
  destination; the secondary button drops a source still waiting for its destination.

In mode 'camera' a primary drag orbits, a secondary or shift drag pans; the wheel dollies in both
modes (refracta.widgets.camera_moves).

Rendering: every change of camera, atmosphere or scene renders the image again, first at
1 / preview_scale of the resolution in each direction, then at full resolution; a newer request
cancels the one still running (JobRunner slot 'render'). The straight view (no atmosphere) renders
in its own slot when shown. Solving (slot 'solve') calls refracta.edit.solve with the pairs, the
free parameters and the solve options; its result becomes the atmosphere (undoable), and the ray
fan of the pairs (refracta.plot.edit_report: paths before and after) is drawn as a PNG.

Hot spots: an atmosphere with areal hot spots (refracta.HotSpot) shows each spot's footprint on the
ground (spot_outlines); its parameters hot_spot<i>_x, _z, _radius, _dt (, _depth) are free
parameters like any other (set_free), so a solve can move, resize and heat it.

Observers registered with observe(callback) are called as callback(what) after each change, with
what one of CHANGES, on the thread that made it (the caller's for events, a worker's for renders
and solves).
"""

from __future__ import annotations

import io as _io
import logging
import math
import os
import threading
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Callable, cast

import numpy as np

from refracta import _checks, _core
from refracta import io as _image_io
from refracta._rays import without_refraction
from refracta._render import SceneWarning, _check_scene, render
from refracta._warn import deprecated
from refracta.scene_file import relocate
from refracta.widgets import camera_moves, files
from refracta.widgets.jobs import Job, JobRunner

if TYPE_CHECKING:
    from refracta.edit import EditResult
    from refracta.turbulence import Turbulence

__all__ = [
    "CHANGES",
    "DisplayImage",
    "EditorModel",
    "GRAB_RADIUS",
    "MAX_HISTORY",
    "SPOT_SEGMENTS",
    "check_margin",
    "check_weight",
    "ground_circle",
    "make_pair",
    "unmet_pairs",
]

log = logging.getLogger("refracta.widgets")

#: What observers are told changed.
CHANGES = (
    "image",
    "straight",
    "pairs",
    "camera",
    "field",
    "free",
    "message",
    "progress",
    "result",
    "history",
    "busy",
    "mode",
    "fan",
)
MAX_HISTORY = 100  # undo steps kept: each holds references to immutable objects, not copies
SPOT_SEGMENTS = 96  # chords per drawn footprint circle: a spot seen at a grazing angle is an ellipse
# flattened ~50x, whose ends 96 chords still round (each 3.75 deg of the circle)
GRAB_RADIUS = 8.0  # [display pixels] a press this close to a marker drags it (about a fingertip)
DEFAULT_DISPLAY: dict = {}  # refracta.io.to_display's defaults: automatic exposure (key 0.18), ACES


@dataclass(frozen=True)
class DisplayImage:
    """A tone-mapped image ready to show. pixels: uint8 (H, W, 3) sRGB; level: 'preview' or
    'full'; linear: the renderer's float32 (H, W, 3) radiance."""

    pixels: np.ndarray
    level: str
    linear: np.ndarray


@dataclass(frozen=True)
class _Snapshot:
    """What undo restores: references to the immutable scene, camera and field, the pairs tuple, the
    solve's free parameters, stop height and options."""

    label: str
    scene: _core.Scene
    scene_text: str | None
    scene_folder: Path | None
    camera: _core.Camera
    field: _core.IndexField
    turbulence: Turbulence | None
    pairs: tuple
    free: tuple[str, ...] | None
    stop_height: float | None
    solve_options: dict  # replaced, never changed in place
    result: EditResult | None
    fan_png: bytes | None


def _finite(value, name: str) -> float:
    number = _checks.number(value, name)  # not True, nor '2'
    if not math.isfinite(number):
        raise ValueError(f"{name} must be a finite number (got {value!r})")
    return number


def _check_options(
    render_options: dict, solve_options: dict, camera: _core.Camera, field: _core.IndexField, preview_scale: int
) -> None:
    """Builds the options every render and solve will, and checks render's and solve's own keywords
    as they would (tiles at the preview's size too), so a bad one fails here, not later in the
    background (where it would only be a message)."""
    from refracta import edit
    from refracta._render import check_render_keywords, own_keywords, tile_bounds
    from refracta._render import render_options as build_render_options

    named = own_keywords()  # render's own arguments, not RenderOptions fields (aovs, denoise, ...)
    own = {k: v for k, v in render_options.items() if k in named}
    try:
        check_render_keywords(camera, render_options.get("method"), **own)
        if own.get("tiles") is not None:
            small = camera.width // preview_scale, camera.height // preview_scale
            tile_bounds(max(1, small[0]), max(1, small[1]), own["tiles"])
        build_render_options(**{k: v for k, v in render_options.items() if k not in named})
    except (ValueError, TypeError) as error:  # TypeError: a keyword render does not take
        raise ValueError(f"render_options: {error}") from None
    solve_named = ("bounds", "derivatives")  # edit.solve's own arguments, not options
    edit.solve_options(where="solve_options", **{k: v for k, v in solve_options.items() if k not in solve_named})
    edit.check_solve_keywords(field, solve_options.get("bounds"), solve_options.get("derivatives"))


def _check_scene_text(text) -> None:
    """scene_text: None or a scene file's TOML text (exported later with the editor's camera and air)."""
    if text is None:
        return
    if not isinstance(text, str):
        raise ValueError(f"scene_text must be a scene file's text or None (got {type(text).__name__})")
    from refracta.scene_file import _loads, tomllib

    try:
        _loads(text)
    except (tomllib.TOMLDecodeError, ValueError) as error:
        raise ValueError(f"scene_text is not a scene file's TOML text: {error}") from None


def check_weight(weight, name: str = "weight") -> float:
    """`weight` as a float; ValueError naming `name` unless finite and > 0."""
    value = _finite(weight, name)
    if not value > 0.0:
        raise ValueError(f"{name} must be > 0 (got {weight!r})")
    return value


def check_margin(margin, name: str = "margin") -> float:
    """`margin` as a float; ValueError naming `name` unless finite and >= 0."""
    value = _finite(margin, name)
    if value < 0.0:
        raise ValueError(f"{name} must be >= 0 (got {margin!r})")
    return value


def make_pair(destination, source, weight=None, margin=None):
    """A refracta.edit.PointPair, weight and margin checked first (ValueError naming them; None:
    PointPair's defaults).

    margin [pixels for a pixel destination, m for a 3D one]: the pair counts as met once its miss
    is within it."""
    from refracta.edit import PointPair

    weight = check_weight(PointPair.weight if weight is None else weight)
    margin = check_margin(PointPair.margin if margin is None else margin)
    # PointPair checks that the source has three values.
    point = cast("tuple[float, float, float]", tuple(float(x) for x in source))
    return PointPair(tuple(float(x) for x in destination), point, weight, margin=margin)


def _camera_names() -> tuple[str, ...]:
    """The camera parameters a solve may free beside the field's (refracta.edit.CAMERA_PARAMETERS)."""
    from refracta.edit import CAMERA_PARAMETERS

    return CAMERA_PARAMETERS


def _deprecated_ground(ground: float | None, stop_height: float | None, where: str) -> float | None:
    """stop_height, or the deprecated ground= (one release) with a DeprecationWarning naming it."""
    if ground is None:
        return stop_height
    if stop_height is not None:
        raise ValueError(f"{where}: pass stop_height= only (ground= is its deprecated spelling)")
    deprecated(f"{where}: ground= is deprecated; call it stop_height=")
    return ground


def ground_circle(
    camera: _core.Camera,
    centre_x: float,
    centre_z: float,
    radius: float,
    segments: int = SPOT_SEGMENTS,
    earth_radius: float = math.inf,
) -> list[tuple[float, float] | None]:
    """The circle of `radius` [m] about (centre_x, 0, centre_z) on the ground plane y = 0, as image
    pixels (u, v) of `camera` (Camera.project: where the camera sees the ground without
    atmosphere, over a CurvedEarth of earth_radius along its true straight lines): segments + 1
    points, the last the first again (a closed outline); None for a point behind the camera (the
    outline breaks there)."""
    angles = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    angles[-1] = 0.0  # exactly the first point: the outline closes
    points = np.stack(
        [centre_x + radius * np.cos(angles), np.zeros_like(angles), centre_z + radius * np.sin(angles)], axis=1
    )
    projected = np.asarray(camera.project(points, earth_radius=earth_radius), dtype=float)
    return [(float(u), float(v)) if depth > 0.0 else None for u, v, depth in projected]


def unmet_pairs(result) -> list[int]:
    """Indices of the pairs an EditResult did not meet (its `met`: miss within margin)."""
    return [i for i, ok in enumerate(result.met) if not ok]


class EditorModel:
    """The mirage editor without its user interface (see the module doc for gestures and units).

    Args:
        scene, camera, field: what to edit: a refracta.Scene, the full-resolution refracta.Camera
            and the atmosphere (an IndexField with parameters, e.g. PhysicalAtmosphere).
        free: names of the field parameters a solve may change (None: solve()'s default).
        stop_height: height [m] where the pairs' paths end on the ground (solve's stop_height;
            None: none). ground= is its deprecated spelling (one release, with a DeprecationWarning).
        max_length: [m] rays end after this length in renders (None: RenderOptions' default).
        render_options: further refracta.render keywords (spp, transport, ...).
        solve_options: further refracta.edit.solve keywords (backend, accept_angle, ...).
        scene_text: the TOML text the scene was loaded from (export keeps everything in it).
        scene_folder: the folder its file names are relative to (the file's): export_scene rewrites
            them for the folder it writes to (None: they are written as they are).
        turbulence: the refracta.Turbulence whose layer `field` carries (field.turbulence), or None:
            exports write its settings (a field keeps only the layer; refracta.scene_file).
        preview_scale: the preview renders 1/preview_scale of the width and height (4: a quarter).
        display: refracta.io.to_display keywords (default: none, its automatic exposure and ACES curve).
        autorender: render at once (False: only when render() is called; for tests).

    Raises:
        ValueError: wrong types, unknown free parameter names, preview_scale < 1.
    """

    def __init__(
        self,
        scene: _core.Scene,
        camera: _core.Camera,
        field: _core.IndexField,
        free: Sequence[str] | None = None,
        *,
        stop_height: float | None = None,
        max_length: float | None = None,
        render_options: dict | None = None,
        solve_options: dict | None = None,
        scene_text: str | None = None,
        scene_folder: str | os.PathLike | None = None,
        turbulence: Turbulence | None = None,
        preview_scale: int = 4,
        display: dict | None = None,
        autorender: bool = True,
        ground: float | None = None,
    ):
        stop_height = _deprecated_ground(ground, stop_height, "refracta.widgets")
        if not isinstance(scene, _core.Scene):
            raise ValueError(f"scene must be a refracta.Scene (got {type(scene).__name__})")
        if not isinstance(camera, _core.Camera):
            raise ValueError(f"camera must be a refracta.Camera (got {type(camera).__name__})")
        if not isinstance(field, _core.IndexField):
            raise ValueError(f"field must be a refracta IndexField (got {type(field).__name__})")
        scale = preview_scale
        whole = _checks.is_number(scale) and math.isfinite(scale) and int(scale) == scale
        if not whole or scale < 1:
            raise ValueError(f"preview_scale must be a whole number >= 1 (got {preview_scale!r})")
        _check_scene_text(scene_text)
        from refracta.turbulence import Turbulence  # at runtime (the module-level import is for typing)

        if turbulence is not None and not isinstance(turbulence, Turbulence):
            raise ValueError(f"turbulence must be a refracta.Turbulence or None (got {type(turbulence).__name__})")
        self._lock = threading.RLock()
        self._observers: list[Callable[[str], None]] = []
        self.scene, self.scene_text, self.camera, self.field = scene, scene_text, camera, field
        self.scene_folder = None if scene_folder is None else Path(os.fspath(scene_folder)).absolute()
        self.turbulence = turbulence
        self.free: tuple[str, ...] | None = None
        self.set_free(free)
        self.stop_height = None if stop_height is None else _finite(stop_height, "stop_height")
        self.render_options = dict(render_options or {})
        if max_length is not None:
            self.render_options["max_length"] = _finite(max_length, "max_length")
        # Each render job passes its own, and shows one image: a tuple (aovs, return_stats) or a
        # second scene would break the jobs in the background; the previews render whole images at
        # a quarter of the size, where a full image's pixel_bounds fall outside (a trial).
        reserved_names = ("progress", "method", "aovs", "return_stats", "stats", "frame", "scene", "camera", "field")
        for reserved in (*reserved_names, "pixel_bounds"):
            if reserved in self.render_options:
                raise ValueError(f"render_options: {reserved!r} is the editor's to choose")
        self.solve_options = dict(solve_options or {})
        for reserved in ("free", "ground", "stop_height", "progress"):
            if reserved in self.solve_options:
                raise ValueError(f"solve_options: pass {reserved!r} as the editor's own argument")
        _check_options(self.render_options, self.solve_options, camera, field, int(preview_scale))
        self.preview_scale = int(preview_scale)
        if display is not None and not isinstance(display, dict):
            raise ValueError(f"display must be a dict of refracta.io.to_display keywords (got {display!r})")
        self.display = dict(DEFAULT_DISPLAY if display is None else display)
        _image_io.settings(**self.display)  # here, not in every render job: a bad one fails now (ValueError)
        self.pairs: tuple = ()
        self.pending_source: np.ndarray | None = None  # a source waiting for its destination [m]
        self.selected: int | None = None
        self.mode = "points"
        self.show_straight = False
        self.result: EditResult | None = None  # the last EditResult applied
        self.fan_png: bytes | None = None  # its ray fan (refracta.plot.edit_report) as PNG
        self.message, self.message_kind = "", "info"
        self.messages_said = 0  # say() calls so far (the view tells a handler that said nothing)
        self.images: dict[str, DisplayImage | None] = {"curved": None, "straight": None}
        self.progress: dict[str, tuple[str, float]] = {}
        self._undo: list[_Snapshot] = []
        self._redo: list[_Snapshot] = []
        self._drag: dict | None = None
        self.runner = JobRunner(
            on_progress=self._on_progress, on_error=self._on_job_error, on_finished=self._on_job_finished
        )
        if autorender:
            self.render()

    # ---------------------------------------------------------------- observers and messages
    def observe(self, callback: Callable[[str], None]) -> None:
        """Call callback(what) after each change (what: one of CHANGES)."""
        self._observers.append(callback)

    def _notify(self, *changes: str) -> None:
        for what in changes:
            for callback in list(self._observers):
                try:
                    callback(what)
                except Exception:  # a view's failure must not break the model
                    log.exception("refracta.widgets: observer failed on %r", what)

    def say(self, message: str, kind: str = "info") -> None:
        """Show `message` (kind 'info', 'success' or 'error') in the editor."""
        self.message, self.message_kind = message, kind
        self.messages_said += 1
        self._notify("message")

    # ---------------------------------------------------------------- history
    def _snapshot(self, label: str) -> _Snapshot:
        return _Snapshot(
            label,
            self.scene,
            self.scene_text,
            self.scene_folder,
            self.camera,
            self.field,
            self.turbulence,
            self.pairs,
            self.free,
            self.stop_height,
            self.solve_options,
            self.result,
            self.fan_png,
        )

    def _record(self, before: _Snapshot) -> None:
        """Push `before` (the state before an edit) on the undo stack; clears redo. Called with the
        lock held: the caller notifies 'history' after releasing it (observers never run under the
        model's lock, so a view may call the model from them)."""
        self._undo.append(before)
        del self._undo[:-MAX_HISTORY]
        self._redo.clear()

    @property
    def can_undo(self) -> bool:
        return bool(self._undo)

    @property
    def can_redo(self) -> bool:
        return bool(self._redo)

    def undo(self) -> bool:
        """Restore the state before the last edit (pairs, camera, atmosphere, scene); False if none."""
        return self._step(self._undo, self._redo, "undo", "Undid")

    def redo(self) -> bool:
        """Restore the state the last undo left; False if none."""
        return self._step(self._redo, self._undo, "redo", "Redid")

    def _step(self, source: list[_Snapshot], target: list[_Snapshot], action: str, verb: str) -> bool:
        with self._lock:
            state = source.pop() if source else None
            if state is not None:
                target.append(self._snapshot(state.label))
                camera_changed = state.camera is not self.camera or state.scene is not self.scene
                view_changed = camera_changed or state.field is not self.field
                self.scene, self.scene_text, self.camera, self.field = (
                    state.scene,
                    state.scene_text,
                    state.camera,
                    state.field,
                )
                self.turbulence, self.scene_folder = state.turbulence, state.scene_folder
                self.pairs, self.free, self.result, self.fan_png = state.pairs, state.free, state.result, state.fan_png
                self.stop_height, self.solve_options = state.stop_height, state.solve_options
                self.pending_source, self._drag = None, None
                if self.selected is not None and self.selected >= len(self.pairs):
                    self.selected = None
        if state is None:
            self.say(f"Nothing to {action}.")
            return False
        self._notify("pairs", "camera", "field", "result", "fan", "history")
        self.say(f"{verb}: {state.label}.")
        if view_changed:
            self.render(straight=camera_changed)
        return True

    # ---------------------------------------------------------------- pairs
    @property
    def result_matches_pairs(self) -> bool:
        """Whether the last solve's result was solved for the pairs as they are now (its misses
        and met flags describe them)."""
        result = self.result
        return result is not None and tuple(result.pairs) == self.pairs

    def markers(self, scale: float = 1.0) -> list[dict]:
        """What to draw over the image, in image pixels: per pair its source (projected by the camera,
        without atmosphere) and destination, and a source waiting for its destination. Each marker:
        {'kind': 'source'|'destination'|'pending', 'pair': index or -1, 'u', 'v', 'selected', 'met'
        (True/False after a solve of these pairs, else None)}."""
        with self._lock:
            camera, pairs, selected = self.camera, self.pairs, self.selected
            unmet = set(unmet_pairs(self.result)) if self.result_matches_pairs else None
            pending, earth_radius = self.pending_source, float(self.field.earth_radius)
        out = []
        for i, pair in enumerate(pairs):
            met = None if unmet is None else i not in unmet
            for kind, uv in (
                ("source", self._project(camera, pair.source, earth_radius)),
                ("destination", self._destination_pixel(camera, pair)),
            ):
                if uv is not None:
                    out.append({"kind": kind, "pair": i, "u": uv[0], "v": uv[1], "selected": i == selected, "met": met})
        if pending is not None:
            uv = self._project(camera, pending, earth_radius)
            if uv is not None:
                out.append({"kind": "pending", "pair": -1, "u": uv[0], "v": uv[1], "selected": True, "met": None})
        return out

    @property
    def hot_spots(self) -> list:
        """The atmosphere's hot spots with their current values (refracta.HotSpot, spot i's
        parameters are hot_spot<i>_*); [] for an atmosphere without."""
        return list(getattr(self.field, "hot_spots", None) or [])

    def spot_outlines(self) -> list[dict]:
        """The hot spots' footprints to draw over the image, in image pixels of the camera: each
        spot's circles on the ground plane y = 0 (ground_circle: where the camera sees the ground
        without atmosphere). Per spot: {'spot': index, 'footprint': 'gaussian'|'compact', 'hot': dt
        > 0, 'centre': (u, v) or None (behind the camera), 'rings': [{'kind', 'radius' [m],
        'points': [(u, v) or None, ...]}]} with rings 'radius' (gaussian: 1 sigma; compact: the
        support, where the spot ends) and, for a gaussian, 'reach' (where its footprint falls
        below 1e-6: HotSpot.reach)."""
        with self._lock:
            camera, spots, earth_radius = self.camera, self.hot_spots, float(self.field.earth_radius)
        out = []
        for index, spot in enumerate(spots):
            rings = [("radius", spot.radius)] + ([("reach", spot.reach)] if spot.footprint == "gaussian" else [])
            out.append(
                {
                    "spot": index,
                    "footprint": spot.footprint,
                    "hot": spot.dt > 0.0,
                    "centre": self._project(camera, (spot.x, 0.0, spot.z), earth_radius),
                    "rings": [
                        {
                            "kind": kind,
                            "radius": float(radius),
                            "points": ground_circle(camera, spot.x, spot.z, radius, earth_radius=earth_radius),
                        }
                        for kind, radius in rings
                    ],
                }
            )
        return out

    @staticmethod
    def _project(camera, point, earth_radius: float = math.inf) -> tuple[float, float] | None:
        """Where the camera sees a scene point without air: over a CurvedEarth (earth_radius) along
        the true straight lines, where a click picks it (camera.pick through without_refraction)."""
        point = np.asarray(point, dtype=float)[None, :]
        u, v, depth = np.asarray(camera.project(point, earth_radius=earth_radius), dtype=float)[0]
        return (float(u), float(v)) if depth > 0.0 else None

    def _destination_pixel(self, camera, pair):
        if len(pair.destination) == 2:
            return float(pair.destination[0]), float(pair.destination[1])
        return self._project(camera, pair.destination)

    def add_pair(self, destination, source, weight: float | None = None, margin: float | None = None) -> int:
        """Add a pair: destination a pixel (u, v) of the camera or a 3D point [m], source a scene
        point [m]; returns its index. Raises ValueError naming a bad weight (finite, > 0) or margin
        (finite, >= 0) or point."""
        pair = make_pair(destination, source, weight, margin)
        self._check_in_image(pair)
        with self._lock:
            before = self._snapshot("add pair")
            self.pairs = self.pairs + (pair,)
            self.selected = len(self.pairs) - 1
            self._record(before)
        self._notify("pairs", "history")
        return self.selected

    def _replace_pair(self, index: int, label: str, record: bool = True, **changes) -> None:
        with self._lock:
            self._check_index(index)
            old = self.pairs[index]
            values = dict(destination=old.destination, source=old.source, weight=old.weight, margin=old.margin)
            values.update(changes)
            new = make_pair(values["destination"], values["source"], values["weight"], values["margin"])
            self._check_in_image(new)
            before = self._snapshot(label)
            self.pairs = self.pairs[:index] + (new,) + self.pairs[index + 1 :]
            if record:
                self._record(before)
        self._notify("pairs", "history")

    def _check_in_image(self, pair, camera: _core.Camera | None = None) -> None:
        """A pixel destination must lie on the camera's image (`camera`, default the editor's), as
        solve requires (a pair added off it failed only later, as a failed solve job)."""
        camera = camera or self.camera
        if len(pair.destination) == 2 and not _checks.on_image(camera, *pair.destination):
            raise ValueError(f"pixel {pair.destination} lies outside the {camera.width} x {camera.height} image")

    def _check_index(self, index: int) -> None:
        if isinstance(index, bool) or not isinstance(index, (int, np.integer)) or not 0 <= index < len(self.pairs):
            raise ValueError(f"pair index must be in [0, {len(self.pairs)}) (got {index!r})")

    def set_weight(self, index: int, weight: float) -> None:
        """Set pair `index`'s weight (finite, > 0; ValueError naming it otherwise)."""
        check_weight(weight, f"pair {index} weight")
        self._replace_pair(index, f"weight of pair {index}", weight=weight)

    def set_margin(self, index: int, margin: float) -> None:
        """Set pair `index`'s margin (finite, >= 0 [pixels]; ValueError naming it otherwise)."""
        check_margin(margin, f"pair {index} margin")
        self._replace_pair(index, f"margin of pair {index}", margin=margin)

    def delete_pair(self, index: int) -> None:
        """Remove pair `index`."""
        with self._lock:
            self._check_index(index)
            before = self._snapshot(f"delete pair {index}")
            self.pairs = self.pairs[:index] + self.pairs[index + 1 :]
            if self.selected is not None:
                self.selected = None if self.selected == index else self.selected - (self.selected > index)
            self._record(before)
        self._notify("pairs", "history")

    def select(self, index: int | None) -> None:
        """Highlight pair `index` (None: none)."""
        if index is not None:
            self._check_index(index)
        self.selected = index
        self._notify("pairs")

    def set_pairs(self, pairs: Sequence, label: str = "set pairs") -> None:
        """Replace every pair (refracta.edit.PointPair objects; undoable)."""
        self._replace_pairs(pairs, label)

    def _replace_pairs(self, pairs: Sequence, label: str, **state) -> None:
        """Every pair replaced, with other attributes (`state`: free, stop_height, solve_options,
        already checked) in the same undo step."""
        made = tuple(make_pair(p.destination, p.source, p.weight, p.margin) for p in pairs)
        for index, pair in enumerate(made):  # as add_pair checks it (imported pairs were let through)
            try:
                self._check_in_image(pair)
            except ValueError as error:
                raise ValueError(f"pair {index}: {error}") from None
        with self._lock:
            before = self._snapshot(label)
            self.pairs, self.selected, self.pending_source = made, None, None
            for name, value in state.items():
                setattr(self, name, value)
            self._record(before)
        self._notify("pairs", *(["free"] if "free" in state else []), "history")

    def set_free(self, free: Sequence[str] | None) -> None:
        """The parameters a solve may change (None or empty: solve()'s default). ValueError naming
        unknown names."""
        self.free = self._checked_free(free)
        self._notify("free")

    def _checked_free(self, free: Sequence[str] | None) -> tuple[str, ...] | None:
        if isinstance(free, str):
            free = [free]
        if free is not None and not (isinstance(free, (list, tuple)) and all(isinstance(n, str) for n in free)):
            raise ValueError(f"free must be a parameter name or a list of them (got {free!r})")
        free = tuple(free or ())
        valid = list(self.field.param_names) + list(_camera_names())
        unknown = [name for name in free if name not in valid]
        if unknown:
            raise ValueError(f"free: unknown parameter(s) {unknown} of {self.field.type_name}; valid names: {valid}")
        return free or None

    # ---------------------------------------------------------------- pointer events
    def set_mode(self, mode: str) -> None:
        """'points' (place and drag pairs) or 'camera' (orbit, pan, dolly)."""
        if mode not in ("points", "camera"):
            raise ValueError(f"mode must be 'points' or 'camera' (got {mode!r})")
        self.mode, self._drag = mode, None
        self._notify("mode")

    def _nearest_marker(self, u: float, v: float, scale: float) -> dict | None:
        radius = GRAB_RADIUS / max(scale, 1e-9)
        best, best_distance = None, radius
        for marker in self.markers():
            if marker["kind"] == "pending":
                continue
            distance = math.hypot(marker["u"] - u, marker["v"] - v)
            if distance <= best_distance:
                best, best_distance = marker, distance
        return best

    def pointer_down(self, u: float, v: float, button: int = 0, shift: bool = False, scale: float = 1.0) -> None:
        """A press at pixel (u, v): button 0 primary, 2 secondary; scale: display pixels per image
        pixel (markers are grabbed within GRAB_RADIUS display pixels; with shift in points mode
        none is: the press places a point however close to a marker)."""
        u, v = _finite(u, "u"), _finite(v, "v")
        if not _finite(scale, "scale") > 0.0:
            raise ValueError(f"scale must be > 0 display pixels per image pixel (got {scale!r})")
        if self.mode == "camera":
            kind = "pan" if (button == 2 or shift) else "orbit"
            self._drag = {"kind": kind, "start": (u, v), "camera": self.camera, "before": self._snapshot(kind)}
            return
        if button == 2:
            if self.pending_source is not None:
                self.pending_source = None
                self._notify("pairs")
                self.say("Source dropped.")
            return
        marker = None if shift else self._nearest_marker(u, v, scale)
        if marker is not None:
            self._drag = {
                "kind": marker["kind"],
                "pair": marker["pair"],
                "start": (u, v),
                "marker": (marker["u"], marker["v"]),  # moves by the pointer's offset, no jump
                "before": self._snapshot(f"move {marker['kind']} of pair {marker['pair']}"),
                "moved": False,
            }
            self.select(marker["pair"])
            self.say(
                f"Pair {marker['pair']}'s {marker['kind']} selected: drag it to move it. To place a point "
                "this close to a marker, hold Shift."
            )
            return
        if not _checks.on_image(self.camera, u, v):  # a source or destination off the image
            width, height = self.camera.width, self.camera.height
            self.say(f"Pixel ({u:.1f}, {v:.1f}) lies outside the {width} x {height} image: click on it.", "error")
            return
        if self.pending_source is None:
            point = self.camera.pick(self.scene, u, v, without_refraction(self.field))
            if point is None:
                self.say(
                    f"Nothing at pixel ({u:.1f}, {v:.1f}) to be a source (sky, or beyond the scene): click an object.",
                    "error",
                )
                return
            self.pending_source = np.asarray(point, dtype=float)
            self._notify("pairs")
            self.say(
                f"Source at ({point[0]:.2f}, {point[1]:.2f}, {point[2]:.2f}) m; now click where its "
                "mirage image should appear."
            )
            return
        source, self.pending_source = self.pending_source, None
        index = self.add_pair((u, v), source)
        self.say(f"Pair {index} added: destination ({u:.1f}, {v:.1f}).", "success")

    def pointer_move(self, u: float, v: float) -> None:
        """The pointer moved to (u, v) with a button held (ignored when nothing is dragged)."""
        drag = self._drag
        if drag is None:
            return
        u, v = _finite(u, "u"), _finite(v, "v")
        du, dv = u - drag["start"][0], v - drag["start"][1]
        if drag["kind"] in ("orbit", "pan"):
            if du == 0.0 and dv == 0.0:
                return  # a click without a move: no new camera, render or undo step (a trial's "orbit" did)
            move = camera_moves.orbit if drag["kind"] == "orbit" else camera_moves.pan
            self._set_camera(move(drag["camera"], du, dv))
            return
        if du == 0.0 and dv == 0.0 and not drag["moved"]:
            return  # a press on a marker without a move selects it and changes nothing
        index = drag["pair"]
        # Held on the image, as a pointer leaving it does: solve refuses destinations off it, and a
        # source is a point the image shows, as a click places it (one dragged to u = -20 was picked
        # off the image, its marker beyond reach).
        mu = min(max(drag["marker"][0] + du, 0.0), self.camera.width)
        mv = min(max(drag["marker"][1] + dv, 0.0), self.camera.height)
        if drag["kind"] == "destination":
            self._replace_pair(index, drag["before"].label, record=False, destination=(mu, mv))
        else:
            point = self.camera.pick(self.scene, mu, mv, without_refraction(self.field))
            if point is None:
                self.say(
                    f"Nothing at pixel ({mu:.1f}, {mv:.1f}) to be a source; the source stays where it was.", "error"
                )
                return
            self._replace_pair(index, drag["before"].label, record=False, source=point)
        drag["moved"] = True

    def pointer_up(self, u: float | None = None, v: float | None = None) -> None:
        """The button was released (at (u, v), if given): ends a drag, one undo step per drag."""
        if u is not None and v is not None:
            self.pointer_move(u, v)
        drag, self._drag = self._drag, None
        if drag is None:
            return
        if drag["kind"] in ("orbit", "pan"):
            if drag["camera"] is not self.camera:
                with self._lock:
                    self._record(drag["before"])
                self._notify("history")
        else:
            if drag.get("moved"):
                with self._lock:
                    self._record(drag["before"])
            self._notify("pairs", "history")

    @property
    def dragging(self) -> bool:
        """Whether a pointer drag (marker or camera) is under way."""
        return self._drag is not None

    def click(self, u: float, v: float, button: int = 0, shift: bool = False) -> None:
        """A press and release at (u, v) (as a browser click sends them)."""
        self.pointer_down(u, v, button, shift)
        self.pointer_up()

    def wheel(self, steps: float) -> None:
        """Dolly by `steps` wheel steps (> 0: toward the look-at point); one undo step."""
        steps = _finite(steps, "steps")
        if steps == 0.0:
            return
        camera = camera_moves.dolly(self.camera, steps)  # first: a move that fails records no undo step
        with self._lock:
            self._record(self._snapshot("dolly"))
        self._notify("history")
        self._set_camera(camera)

    # ---------------------------------------------------------------- camera
    def set_camera(self, position=None, look_at=None, vfov=None) -> None:
        """Move the camera to `position` / `look_at` [m] / `vfov` [deg] (None keeps each); one undo
        step. ValueError naming the bad field."""
        camera = camera_moves.with_pose(self.camera, position, look_at, vfov)
        with self._lock:
            self._record(self._snapshot("camera"))
        self._notify("history")
        self._set_camera(camera)

    def _set_camera(self, camera: _core.Camera) -> None:
        with self._lock:
            self.camera = camera
        self._notify("camera", "pairs")
        self.render(straight=True)

    # ---------------------------------------------------------------- rendering
    def set_show_straight(self, show: bool) -> None:
        """Show (and render) the straight view, without atmosphere, beside the image."""
        self.show_straight = bool(show)
        self._notify("straight")
        if self.show_straight:
            self.render(curved=False, straight=True)

    def render(self, curved: bool = True, straight: bool = True) -> None:
        """Render again in the background (the curved image progressively; the straight view if
        shown and `straight`), superseding the renders still running."""
        with self._lock:
            scene, camera, field = self.scene, self.camera, self.field
            options = dict(self.render_options)
        if curved:
            previews = (
                []
                if self.preview_scale == 1
                else [
                    (
                        "preview",
                        # A jitter map is per pixel of the full image: the preview goes without it.
                        camera.without_jitter().resized(
                            max(1, camera.width // self.preview_scale), max(1, camera.height // self.preview_scale)
                        ),
                    )
                ]
            )
            stages = previews + [("full", camera)]

            def curved_work(job: Job):
                for k, (level, view) in enumerate(stages):
                    progress = job.progress(f"rendering ({level})", k / len(stages), (k + 1) / len(stages))
                    image = render(scene, view, field, method="curved", progress=progress, **options)
                    job.check()
                    self._publish(job, "curved", level, image)

            self.runner.submit("render", curved_work, "rendering")
        if straight and self.show_straight:

            def straight_work(job: Job):
                # The same Earth without the air's bending (a CurvedEarth still hides what its bulge hides).
                reference = without_refraction(field)
                image = render(
                    scene,
                    camera,
                    reference,
                    method="curved" if reference else "straight",
                    progress=job.progress("straight view"),
                    **options,
                )
                job.check()
                self._publish(job, "straight", "full", image)

            self.runner.submit("straight", straight_work, "straight view")
        self._notify("busy")

    def _publish(self, job: Job, kind: str, level: str, image: np.ndarray) -> None:
        pixels = np.asarray(_image_io.to_display(image, **self.display))
        pixels = np.clip(np.rint(pixels[..., :3] * 255.0), 0, 255).astype(np.uint8)
        with self._lock:
            if job.cancelled:
                return
            self.images[kind] = DisplayImage(pixels, level, image)
        self._notify("image" if kind == "curved" else "straight")

    def _on_progress(self, job: Job, label: str, fraction: float) -> None:
        self.progress[job.slot] = (label, fraction)
        self._notify("progress")

    def _on_job_error(self, error: BaseException) -> None:
        log.debug("refracta.widgets: background job failed", exc_info=error)
        self.say(f"{type(error).__name__}: {error}", "error")

    def _on_job_finished(self, job: Job) -> None:
        # Superseded by a newer solve, it says nothing (it said "cancelled" while the next one ran).
        if job.state == "cancelled" and job.slot == "solve" and not self.runner.busy("solve"):
            self.say("Solve cancelled; nothing changed.")
        if not self.runner.busy(job.slot):
            self.progress.pop(job.slot, None)
        self._notify("progress", "busy")

    @property
    def busy(self) -> bool:
        """Whether a render or solve is running or queued."""
        return self.runner.busy()

    def wait(self, timeout: float | None = None) -> bool:
        """Block until every render and solve has finished; False if `timeout` [s] passed first."""
        return self.runner.wait(timeout)

    def cancel(self) -> None:
        """Stop the running solve and renders (the image keeps its last finished stage)."""
        self.runner.cancel()

    def close(self) -> None:
        """Stop the background threads (the model is unusable afterwards)."""
        self.runner.close()

    # ---------------------------------------------------------------- solving
    def solve(self) -> Job | None:
        """Solve for the atmosphere that meets the pairs, in the background (a solve still running
        is superseded). Returns the Job, or None (with a message) when there are no pairs."""
        from refracta import edit

        with self._lock:
            field, camera, pairs, free = self.field, self.camera, self.pairs, self.free
            options = dict(self.solve_options)
        if not pairs:
            self.say("Add at least one pair first: click a scene point, then where its image should appear.", "error")
            return None
        if self.stop_height is not None:
            options["stop_height"] = self.stop_height

        def work(job: Job):
            result = edit.solve(
                field,
                camera,
                list(pairs),
                free=list(free) if free else None,
                progress=job.progress("solving"),
                **options,
            )
            job.check()
            return result

        def done(result):
            with self._lock:
                # Pairs, atmosphere or camera changed (undo, an edit) while it ran: its answer is to
                # another question (a trial's 2-pair result landed after undo had left one pair).
                stale = (self.field, self.camera, tuple(self.pairs)) != (field, camera, tuple(pairs))
                if not stale:
                    before = self._snapshot("solve")
                    self.field, self.result, self.fan_png = result.field, result, None
                    if result.summary.camera is not None:  # camera parameters were free: the solved camera
                        self.camera = result.camera
                    self._record(before)
            if stale:
                self.say(
                    "The pairs, atmosphere or camera changed while the solve ran: its result is dropped; solve again."
                )
                return
            self._notify("field", "result", "fan", "pairs", "history", "camera")
            unmet = unmet_pairs(result)
            if result.success:
                # The solve's own word when the pairs fix fewer combinations than there are free parameters.
                unique = result.message.find("The solution is not unique")
                caveat = " " + result.message[unique:].split(". ")[0] + "." if unique >= 0 else ""
                self.say(
                    f"Solved: every pair met ({result.iterations} iterations, {result.time:.2g} s).{caveat}", "success"
                )
            elif unmet:
                self.say(
                    f"Not every image can be put there: pair(s) {', '.join(map(str, unmet))} missed. " + result.message,
                    "error",
                )
            else:
                self.say("Solve stopped: " + result.message, "error")
            self.render(straight=result.summary.camera is not None)  # a solved camera changes both views
            # The ray fan last (matplotlib: ~0.3 s), while the new image renders.
            fan = _fan_png(result)
            with self._lock:
                if self.result is not result:  # undone meanwhile
                    return
                self.fan_png = fan
            self._notify("fan")

        self.say("Solving ...")
        job = self.runner.submit("solve", work, "solving", on_done=done)
        self._notify("busy")
        return job

    def changed_parameters(self) -> list[tuple[str, float, float, str]]:
        """(name, start, solved, unit) of the last solve's free parameters."""
        result = self.result
        if result is None:
            return []
        return result.parameter_changes()

    # ---------------------------------------------------------------- files
    def _solve_file_options(self) -> dict:
        options: dict[str, object] = dict(self.solve_options)
        options["free"] = list(self.free) if self.free else None
        options["stop_height"] = self.stop_height
        return options

    def pairs_json(self) -> str:
        """The pairs in the JSON format of `refracta edit --pairs` (refracta.edit.load_pairs)."""
        return files.pairs_json(self.pairs, self._solve_file_options())

    def scene_toml(self, folder=None) -> str:
        """The scene as TOML with the editor's camera and atmosphere (refracta.load_scene), its file
        names relative to `folder` (where it will be saved; None: the scene's own folder)."""
        text = files.scene_toml(self.scene_text, self.camera, self.field, self.turbulence)
        if folder is None or self.scene_folder is None:
            return text
        return relocate(text, self.scene_folder, folder)

    def export_pairs(self, path) -> Path:
        """Write pairs_json() to `path`; returns it. refracta.IoError if it cannot be written."""
        return self._write(path, self.pairs_json(), "pairs")

    def export_scene(self, path) -> Path:
        """Write scene_toml() to `path`, its file names (objects, textures, environment maps)
        rewritten to name the same files from there; returns it. refracta.IoError if it cannot be
        written."""
        written = self._write(path, self.scene_toml(Path(os.fspath(path)).absolute().parent), "scene")
        if self.scene_text is None:  # a Scene built in Python: no file describes its objects and lights
            self.say(
                f"Wrote {written} with the camera and atmosphere only: the scene was built in Python, not "
                "loaded from a scene file, so its objects and lights are not in it (loading it gives an empty scene).",
                "error",
            )
        return written

    def _write(self, path, text: str, what: str) -> Path:
        path = Path(path)
        try:
            path.write_text(text, encoding="utf-8")  # as scene files are read
        except OSError as error:
            raise _core.IoError(f"cannot write {what} file {path}: {error.strerror}") from None
        self.say(f"Wrote {path}.", "success")
        return path

    def import_pairs(self, path) -> None:
        """Replace the pairs by those of a pairs file (sources given as pixels are picked with the
        editor's camera); its 'free' and 'stop_height' become the editor's. Undoable. Raises what
        refracta.edit.load_pairs raises (IoError, ValueError naming the file and pair)."""
        from refracta.edit import load_pairs

        pairs, options = load_pairs(path, self.scene, self.camera, self.field)
        # Everything checked before anything changes: a bad option fails here, not in a later solve.
        free = self._checked_free(options.pop("free")) if "free" in options else self.free
        stop_height = self.stop_height
        if "stop_height" in options:
            given = options.pop("stop_height")
            stop_height = None if given is None else _finite(given, "stop_height")
        solve_options = {**self.solve_options, **options}
        _check_options(self.render_options, solve_options, self.camera, self.field, self.preview_scale)
        label = f"load pairs from {Path(path).name}"
        self._replace_pairs(pairs, label, free=free, stop_height=stop_height, solve_options=solve_options)
        self.say(f"Loaded {len(pairs)} pair(s) from {path}.", "success")

    def import_scene(self, path) -> None:
        """Replace scene, camera and atmosphere by a scene file's (refracta.load_scene); undoable.
        A file without [atmosphere] keeps the editor's."""
        from refracta.scene_file import load_scene, read_scene_text

        path = Path(path)
        loaded = load_scene(path)
        scene, camera, field = loaded
        text = read_scene_text(path)
        for index, pair in enumerate(self.pairs):  # the pairs stay: their destinations must fit the new image
            try:
                self._check_in_image(pair, camera)
            except ValueError as error:
                raise ValueError(f"{path.name}: pair {index}: {error}: remove or move that pair first") from None
        # render's own hints (no light, a camera under the ground, ...), said in the editor: from its
        # render jobs they reached only the worker's stderr (a trial's scene saved without its objects).
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always", SceneWarning)
            _check_scene(scene, camera, field if field is not None else self.field, "curved", "load scene")
        with self._lock:
            before = self._snapshot(f"load scene {path.name}")
            self.scene, self.scene_text, self.camera = scene, text, camera
            self.scene_folder = path.absolute().parent
            if field is not None:
                self.field, self.turbulence = field, loaded.turbulence
                if self.free and any(n not in field.param_names and n not in _camera_names() for n in self.free):
                    self.free = None
            self.pending_source, self.selected = None, None
            self._record(before)
        self._notify("camera", "field", "pairs", "history")
        notes = [str(w.message) for w in caught if issubclass(w.category, SceneWarning)]
        self.say(f"Loaded {path}." + "".join(f" {note}" for note in notes), "error" if notes else "success")
        self.render()


def _fan_png(result) -> bytes:
    """refracta.plot.edit_report's figure (paths before and after, cost history) as PNG bytes.

    Drawn into a matplotlib.figure.Figure, not a pyplot one: it is made on a solve's worker thread,
    and a Figure outside pyplot shares no state with the notebook's figures or its backend."""
    from matplotlib.figure import Figure

    from refracta import plot

    figure = plot.edit_report(result, figure=Figure(figsize=(9.0, 3.2)))
    buffer = _io.BytesIO()
    figure.savefig(buffer, format="png", dpi=80)
    return buffer.getvalue()
