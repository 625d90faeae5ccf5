"""MirageEditor: the interactive mirage editor in Jupyter (ipywidgets + an anywidget canvas), the view
of refracta.widgets.model.EditorModel.

Every control calls one model method; every model change redraws the controls it concerns. The
canvas's pointer messages go to EditorModel.pointer_down / pointer_move / pointer_up / wheel. A
user mistake (a click on the sky as a source, a NaN weight, a missing file) shows a message in
the editor instead of a traceback; the Python methods below raise as usual.
"""

from __future__ import annotations

import html
import logging
import os
import threading
from collections.abc import Sequence
from pathlib import Path

import ipywidgets as w
import numpy as np

from refracta import _core
from refracta.edit import CAMERA_PARAMETERS
from refracta.widgets.canvas import ImageCanvas
from refracta.widgets.model import EditorModel

__all__ = ["MirageEditor"]

log = logging.getLogger("refracta.widgets")

DISPLAY_WIDTH = 720  # [display pixels] the image is shown at least this wide (small renders scaled up)
MAX_SCALE = 4.0  # ... but never more than this many display pixels per image pixel
BESIDE = 0.6  # with the straight view shown, both images at this fraction of that size: two
# 720-pixel images side by side fit a notebook ~900 pixels wide
USER_ERRORS = (ValueError, OSError, _core.NumericalError)  # shown as a message (IoError is an OSError)
MESSAGE_COLOURS = {"info": "#333", "success": "#1a7f37", "error": "#c62828"}
TABLE_STYLE = "style='border-spacing: 14px 1px'"


def _free_choices(field) -> list[str]:
    """What the "free" list offers: the field's parameters, then the camera's (refracta.edit's
    CAMERA_PARAMETERS: a photograph's camera is solved with the air; offering only the field's made
    a camera parameter free in the model a TraitError in the widget)."""
    from refracta.edit import CAMERA_PARAMETERS

    return list(field.param_names) + list(CAMERA_PARAMETERS)


class MirageEditor(w.VBox):
    """Interactive mirage editor: click where a scene point's mirage image should appear and solve
    for the atmosphere that puts it there.

    Shows the render through `field` (a quarter-resolution preview first, then full resolution,
    rendered in the background) and, on demand, the straight view beside it. Mode *Points*: click
    a scene object (the source: Camera.pick, without atmosphere), then where its image should
    appear (the destination); drag either marker to move it (shift-click places a point even next
    to a marker); the Pairs tab lists the pairs with
    their weight and margin. Mode *Camera*: drag to orbit, shift- or right-drag to pan, wheel to
    dolly; the Camera tab has the numbers. *Solve* runs refracta.edit.solve in the background
    (progress, Cancel); the Result tab shows the misses, the changed parameters and each pair's
    light path before and after. Undo/Redo cover pairs, camera, solves and loaded files. The Files
    tab saves and loads the scene (TOML, with the solved atmosphere and the camera) and the pairs
    (JSON, the format of ``refracta edit --pairs``). An atmosphere with hot spots shows each spot's
    footprint on the ground, numbered; the Hot spots tab lists them with toggles that make their
    parameters (hot_spot<i>_x, ...) free in the next solve.

    Args:
        scene, camera, field: the refracta.Scene, the full-resolution refracta.Camera and the
            atmosphere to edit.
        free: the parameters a solve may change (None: refracta.edit.solve's default).
        stop_height: height [m] where the pairs' light paths end on the ground (None: none);
            ground= is its deprecated spelling (one release, with a DeprecationWarning).
        max_length: [m] rays end after this length in renders (None: the renderer's default).
        scale: display pixels per image pixel (None: the image is shown DISPLAY_WIDTH wide).
        background: a photograph to click on (see set_background), or None.
        **options: render_options, solve_options, scene_text, scene_folder, turbulence, preview_scale, display
            (see refracta.widgets.model.EditorModel).

    Example::

        road = refracta.examples.hot_road(320, 120)
        editor = MirageEditor(road.scene, road.camera, road.field, free=["surface_dt", "surface_depth"],
                              stop_height=0.0, max_length=road.max_length)
        editor                          # in a notebook cell: shows it
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
        scale: float | None = None,
        background=None,
        **options,
    ):
        self._background: np.ndarray | None = None  # display values (H, W, 3) of the photograph
        self._background_mode = "edges"
        self.model = EditorModel(
            scene, camera, field, free, stop_height=stop_height, max_length=max_length, autorender=False, **options
        )
        self._scale = float(scale) if scale is not None else None
        self._syncing = False
        self._listed: tuple | None = None  # (pairs, selected, result) the pair list shows
        self._view_lock = threading.RLock()
        self._build()
        super().__init__(children=[self._toolbar, self._message, self._images, self._tabs])
        self.add_class("refracta-editor")
        self.model.observe(self._changed)
        for what in ("camera", "field", "pairs", "result", "history", "busy", "mode", "message", "progress"):
            self._changed(what)
        if background is not None:
            self.set_background(background)
        self.model.render()

    @classmethod
    def from_file(cls, path, free: Sequence[str] | None = None, **kwargs) -> MirageEditor:
        """An editor for a scene file (refracta.load_scene): exports keep everything in the file."""
        from refracta.scene_file import load_scene, read_scene_text

        loaded = load_scene(path)
        if loaded.field is None:
            raise ValueError(f"{path}: has no [atmosphere] table to edit")
        return cls(
            loaded.scene,
            loaded.camera,
            loaded.field,
            free,
            scene_text=read_scene_text(path),
            scene_folder=Path(os.fspath(path)).absolute().parent,
            turbulence=loaded.turbulence,
            **kwargs,
        )

    # ---------------------------------------------------------------- the Python API
    @property
    def field(self) -> _core.IndexField:
        """The current atmosphere (after a solve: the solved one)."""
        return self.model.field

    @property
    def camera(self) -> _core.Camera:
        return self.model.camera

    @property
    def pairs(self) -> list:
        """The point pairs (refracta.edit.PointPair; pixel destinations of `camera`)."""
        return list(self.model.pairs)

    @property
    def result(self):
        """The last solve's refracta.edit.EditResult (None before the first)."""
        return self.model.result

    def add_pair(self, destination, source, weight: float | None = None, margin: float | None = None) -> int:
        """Add a pair (see EditorModel.add_pair); returns its index."""
        return self.model.add_pair(destination, source, weight, margin)

    def solve(self, wait: bool = False):
        """Start a solve; with wait=True block until it and the render after it have finished and
        return its EditResult (None when it failed, was cancelled or dropped; the message says why)."""
        before = self.model.result
        job = self.model.solve()
        if wait and job is not None:
            self.model.wait()
            # This solve's result, or None when it failed or was dropped (the one before was returned: a trial).
            return self.model.result if self.model.result is not before else None
        return None

    def wait(self, timeout: float | None = None) -> bool:
        """Block until the renders and the solve have finished; False if `timeout` [s] passed."""
        return self.model.wait(timeout)

    def cancel(self) -> None:
        self.model.cancel()

    def undo(self) -> bool:
        return self.model.undo()

    def redo(self) -> bool:
        return self.model.redo()

    def export_scene(self, path) -> Path:
        """Write the scene (TOML) with the editor's camera and atmosphere."""
        return self.model.export_scene(path)

    def export_pairs(self, path) -> Path:
        """Write the pairs (JSON, the format of ``refracta edit --pairs``)."""
        return self.model.export_pairs(path)

    def import_scene(self, path) -> None:
        self.model.import_scene(path)

    def import_pairs(self, path) -> None:
        self.model.import_pairs(path)

    def __reduce__(self):
        # A live widget with a worker thread: what it edits pickles instead (the pickler's own
        # error named a lambda inside it).
        raise TypeError(
            "MirageEditor cannot be pickled (a live widget with a worker thread): pickle what it edits "
            "(editor.field, editor.camera, editor.pairs) or save it with editor.export_scene(path)"
        )

    def close(self) -> None:
        """Stop the background work and close the widgets."""
        if hasattr(self, "model"):  # not when the constructor failed before making it
            self.model.close()
        for child in self.children:
            _close_tree(child)
        super().close()

    # ---------------------------------------------------------------- building the controls
    def _button(self, description: str, handler, tooltip: str = "", icon: str = "", style: str = "") -> w.Button:
        button = w.Button(
            description=description, tooltip=tooltip, icon=icon, button_style=style, layout=w.Layout(width="auto")
        )
        button.on_click(lambda _b: self._guard(handler))
        return button

    def _build(self) -> None:
        self._build_toolbar()
        self._build_tabs()

    def _build_toolbar(self) -> None:
        """The images, the buttons, the progress bars and the message line."""
        model = self.model
        self._canvas = ImageCanvas(on_pointer=lambda message: self._guard(self._pointer, message, clears_mistake=False))
        self._straight = ImageCanvas(interactive=False, cursor="default")
        self._straight_box = w.VBox(
            [w.HTML("<b>straight (no atmosphere)</b>"), self._straight], layout=w.Layout(display="none")
        )
        self._images = w.HBox(
            [w.VBox([w.HTML("<b>through the atmosphere</b>"), self._canvas]), self._straight_box],
            layout=w.Layout(flex_flow="row wrap"),
        )
        self._mode = w.ToggleButtons(
            options=[("Points", "points"), ("Camera", "camera")],
            value=model.mode,
            tooltips=[
                "click a source, then its destination; drag markers; shift-click: a point by a marker",
                "drag: orbit; shift/right drag: pan; wheel: dolly",
            ],
            style={"button_width": "70px"},
        )
        self._mode.observe(lambda change: self._guard(model.set_mode, change["new"]), names="value")
        self._straight_toggle = w.ToggleButton(
            description="Straight view", value=False, tooltip="render the scene without atmosphere beside the image"
        )
        self._straight_toggle.observe(lambda change: self._guard(model.set_show_straight, change["new"]), names="value")
        self._undo = self._button("Undo", model.undo, icon="undo")
        self._redo = self._button("Redo", model.redo, icon="repeat")
        self._solve = self._button(
            "Solve", model.solve, "solve for the atmosphere that meets the pairs", style="primary"
        )
        self._cancel = self._button("Cancel", model.cancel, "stop the solve and renders", style="warning")
        self._render_progress = w.FloatProgress(min=0.0, max=1.0, description="render", layout=w.Layout(width="210px"))
        self._solve_progress = w.FloatProgress(min=0.0, max=1.0, description="solve", layout=w.Layout(width="210px"))
        self._render_status = w.HTML()
        self._render_status.add_class("refracta-render-status")
        self._pair_count = w.HTML()
        self._pair_count.add_class("refracta-pair-count")
        self._toolbar = w.VBox(
            [
                w.HBox(
                    [self._mode, self._straight_toggle, self._undo, self._redo, self._solve, self._cancel],
                    layout=w.Layout(flex_flow="row wrap"),
                ),
                w.HBox(
                    [self._render_progress, self._solve_progress, self._render_status, self._pair_count],
                    layout=w.Layout(flex_flow="row wrap", align_items="center"),
                ),
            ]
        )
        self._message = w.HTML()
        self._message.add_class("refracta-message")

    def _build_tabs(self) -> None:
        """Pairs, Camera, Result, Files and Hot spots."""
        model = self.model
        # Pairs tab
        self._pair_rows = w.VBox()
        names = _free_choices(model.field)
        self._free = w.SelectMultiple(
            options=names,
            value=tuple(model.free or ()),
            rows=min(6, len(names)),
            description="free",
            tooltip="parameters a solve may change (none: the default)",
        )
        self._free.observe(
            lambda change: None if self._syncing else self._guard(model.set_free, change["new"]), names="value"
        )
        pairs_tab = w.VBox([self._pair_rows, self._free])

        # Camera tab
        def number(description):
            field = w.FloatText(
                description=description, layout=w.Layout(width="190px"), style={"description_width": "60px"}
            )
            field.observe(lambda _change: self._camera_typed(), names="value")
            return field

        self._position = [number(f"eye {axis}") for axis in "xyz"]
        self._look_at = [number(f"look {axis}") for axis in "xyz"]
        self._vfov = number("vfov [°]")
        camera_tab = w.VBox(
            [
                w.HBox(self._position),
                w.HBox(self._look_at),
                self._vfov,
                w.HTML("Camera mode: drag to orbit, shift- or right-drag to pan, wheel to dolly. Positions in metres."),
            ]
        )

        # Result tab
        self._result = w.HTML("No solve yet.")
        self._result.add_class("refracta-result")
        self._fan = w.Image(format="png", layout=w.Layout(max_width="100%"))
        result_tab = w.VBox([self._result, self._fan])

        # Hot spots tab: the spots of the atmosphere, each with toggles for its free parameters
        self._spot_rows = w.VBox()
        self._spot_toggles: dict[str, w.ToggleButton] = {}  # parameter name -> its ToggleButton in the spot list
        spots_tab = w.VBox(
            [
                self._spot_rows,
                w.HTML(
                    "Each spot's footprint is drawn on the ground in the image (where the camera sees the ground "
                    "without atmosphere): solid, the radius (gaussian: 1 sigma; compact: where it ends); dashed, "
                    "where a gaussian spot fades out. Toggle a parameter to let a solve change it (as in the "
                    "Pairs tab's free list)."
                ),
            ]
        )

        # Files tab
        self._scene_path = w.Text(value="edited_scene.toml", description="scene", layout=w.Layout(width="360px"))
        self._pairs_path = w.Text(value="pairs.json", description="pairs", layout=w.Layout(width="360px"))
        files_tab = w.VBox(
            [
                w.HBox(
                    [
                        self._scene_path,
                        self._button("Save", lambda: model.export_scene(self._scene_path.value)),
                        self._button("Load", lambda: model.import_scene(self._scene_path.value)),
                    ]
                ),
                w.HBox(
                    [
                        self._pairs_path,
                        self._button("Save", lambda: model.export_pairs(self._pairs_path.value)),
                        self._button("Load", lambda: model.import_pairs(self._pairs_path.value)),
                    ]
                ),
                w.HTML(
                    "Scene: TOML with the editor's camera and atmosphere (refracta.load_scene). Pairs: JSON "
                    "for <code>refracta edit scene.toml --pairs pairs.json -o solved.toml</code>. "
                    "Paths are on the kernel's machine."
                ),
            ]
        )
        self._tabs = w.Tab(children=[pairs_tab, camera_tab, result_tab, files_tab, spots_tab])
        for index, title in enumerate(("Pairs", "Camera", "Result", "Files", "Hot spots")):
            self._tabs.set_title(index, title)

    # ---------------------------------------------------------------- events from the browser
    def _guard(self, function, *args, clears_mistake: bool = True):
        """Run a handler; user mistakes become a message in the editor, never a traceback. With
        clears_mistake, an accepted edit that says nothing itself clears an earlier mistake's
        message (it stayed red); pointer events pass False (a click's release follows its press,
        whose message stays)."""
        was_error, said = self.model.message_kind == "error", self.model.messages_said
        try:
            result = function(*args)
            if clears_mistake and was_error and self.model.messages_said == said:
                self.model.say("")
            return result
        except USER_ERRORS as error:
            self.model.say(str(error), "error")
        except Exception as error:  # a bug: logged, and said in the editor
            log.exception("refracta.widgets: handler failed")
            self.model.say(f"Internal error ({type(error).__name__}): {error}", "error")
        return None

    def _pointer(self, message: dict) -> None:
        event = message.get("event")
        if event == "wheel":
            self.model.wheel(message.get("steps", 0.0))
        elif event == "down":
            self.model.pointer_down(
                message["u"],
                message["v"],
                int(message.get("button", 0)),
                bool(message.get("shift", False)),
                float(message.get("scale", 1.0)),
            )
        elif (
            event == "move" and "u" in message and "v" in message
        ):  # a move queued past its button's release carries none
            self.model.pointer_move(message["u"], message["v"])
        elif event == "up":
            self.model.pointer_up(message.get("u"), message.get("v"))

    def _camera_typed(self) -> None:
        if self._syncing:
            return
        camera = self.model.camera
        position = [f.value for f in self._position]
        look_at = [f.value for f in self._look_at]
        if (
            np.array_equal(position, camera.position)
            and np.array_equal(look_at, camera.look_at)
            and self._vfov.value == camera.vfov
        ):
            return
        self._guard(self.model.set_camera, position, look_at, self._vfov.value)
        if self.model.camera is camera:  # refused: show the kept camera again (its value blocked every later edit)
            self._show_camera()

    # ---------------------------------------------------------------- redrawing after model changes
    def _changed(self, what: str) -> None:
        handler = getattr(self, f"_show_{what}", None)
        if handler is not None:
            with self._view_lock:  # renders and solves report from worker threads
                handler()

    def _display_scale(self, camera: _core.Camera) -> float:
        scale = self._scale if self._scale is not None else min(MAX_SCALE, max(1.0, DISPLAY_WIDTH / camera.width))
        if self.model.show_straight:
            scale = max(min(1.0, scale), BESIDE * scale)
        return float(scale)

    # ---------------------------------------------------------------- a photograph as the background
    def set_background(self, photo=None, mode: str = "edges") -> None:
        """Show a photograph as the image to click on (matching a photograph, refracta.photo).

        photo: a refracta.photo.Photo, a path (refracta.photo.load) or an (H, W[, C]) array of display
        values in [0, 1]; None shows the render alone again. Its pixels are taken as the camera's
        (the same aspect within 1 %; resampled to the render's size, nearest pixel), so a click
        places a destination on the photograph's pixel. mode: how the render shows on it --
        'edges' (the render's edges drawn on the photograph, refracta.photo.overlay), 'blend'
        (half and half) or 'photo' (the photograph alone). Raises ValueError for another aspect or
        mode.
        """
        from refracta import photo as _photo

        if mode not in ("edges", "blend", "photo"):
            raise ValueError(f"mode must be 'edges', 'blend' or 'photo' (got {mode!r})")
        if photo is None:
            self._background = None
        else:
            if isinstance(photo, (str, os.PathLike)):
                photo = _photo.load(photo)
            if not isinstance(photo, _photo.Photo):
                photo = _photo.Photo(np.asarray(photo, dtype=np.float32), linear=False)
            shown = photo.display()
            camera = self.model.camera
            aspect, wanted = shown.shape[1] / shown.shape[0], camera.width / camera.height
            if abs(aspect / wanted - 1.0) > 0.01:
                raise ValueError(
                    f"the photograph is {shown.shape[1]}x{shown.shape[0]} pixels, not the camera's aspect "
                    f"({camera.width}x{camera.height}): crop it, or make the camera with Photo.camera"
                )
            self._background = shown
        self._background_mode = mode
        with self._view_lock:
            self._show_image()

    def _on_background(self, pixels: np.ndarray) -> np.ndarray:
        """The render's uint8 (H, W, 3) pixels on the background photograph (as they are without one)."""
        if self._background is None:
            return pixels
        from refracta import photo as _photo

        height, width = pixels.shape[:2]
        rows = ((np.arange(height) + 0.5) * self._background.shape[0] / height).astype(int)
        columns = ((np.arange(width) + 0.5) * self._background.shape[1] / width).astype(int)
        background = self._background[rows[:, None], columns[None, :]]
        if self._background_mode == "photo":
            shown = background
        else:
            render = pixels.astype(np.float32) / 255.0
            shown = _photo.overlay(background, render, mode=self._background_mode, linear=False).image
        return (np.clip(shown, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)

    def _show_image(self) -> None:
        image = self.model.images["curved"]
        if image is not None:
            self._canvas.show(self._on_background(image.pixels), image.level)
            height, width = image.pixels.shape[:2]
            self._render_status.value = f"image: {image.level} ({width}×{height})"

    def _show_straight(self) -> None:
        self._straight_box.layout.display = "flex" if self.model.show_straight else "none"
        self._show_camera()  # the image sizes: side by side or alone
        image = self.model.images["straight"]
        if image is not None:
            self._straight.show(image.pixels, image.level)

    def _show_camera(self) -> None:
        camera = self.model.camera
        scale = self._display_scale(camera)
        for canvas in (self._canvas, self._straight):
            with canvas.hold_sync():
                canvas.width, canvas.height, canvas.scale = camera.width, camera.height, scale
        self._show_spot_outlines()
        self._syncing = True
        try:
            for fields, values in ((self._position, camera.position), (self._look_at, camera.look_at)):
                for field, value in zip(fields, values):
                    field.value = float(value)
            self._vfov.value = float(camera.vfov)
        finally:
            self._syncing = False

    def _show_pairs(self) -> None:
        model = self.model
        markers = model.markers()
        self._canvas.markers = markers
        self._straight.markers = markers
        pairs = model.pairs
        self._pair_count.value = f"<b>{len(pairs)}</b> pair{'s' if len(pairs) != 1 else ''}"
        listed = (pairs, model.selected, model.result)
        if model.dragging or listed == self._listed:
            return  # the list is rebuilt once the drag ends
        self._listed = listed
        old = self._pair_rows.children
        self._pair_rows.children = [self._pair_row(i, pair) for i, pair in enumerate(pairs)] or [
            w.HTML("No pairs yet: in Points mode click a scene object, then where its mirage image should appear.")
        ]
        for row in old:
            _close_tree(row)

    def _pair_row(self, index: int, pair) -> w.HBox:
        model = self.model
        destination = ", ".join(f"{x:.1f}" for x in pair.destination)
        source = ", ".join(f"{x:.2f}" for x in pair.source)
        miss = ""
        result = model.result
        if result is not None and model.result_matches_pairs:
            from refracta.widgets.model import unmet_pairs

            unmet = index in unmet_pairs(result)
            verdict = ("not met", "#c62828") if unmet else ("met", "#1a7f37")
            miss = (
                f"miss {result.initial_distances[index]:.3g} → {result.distances[index]:.3g} m "
                f"<span style='color:{verdict[1]}'>{verdict[0]}</span>"
            )
        selected = "font-weight:bold;" if index == model.selected else ""
        label = w.HTML(f"<span style='{selected}'>#{index}</span> destination ({destination}) px ← source ({source}) m")
        weight = w.Text(
            value=f"{pair.weight:g}",
            description="weight",
            continuous_update=False,
            layout=w.Layout(width="150px"),
            style={"description_width": "50px"},
        )
        margin = w.Text(
            value=f"{pair.margin:g}",
            description="margin",
            continuous_update=False,
            tooltip="the pair is met once its miss is within this [pixels]",
            layout=w.Layout(width="150px"),
            style={"description_width": "50px"},
        )
        weight.observe(
            lambda change: self._edit_pair(model.set_weight, index, change["new"], weight, "weight"), names="value"
        )
        margin.observe(
            lambda change: self._edit_pair(model.set_margin, index, change["new"], margin, "margin"), names="value"
        )
        delete = self._button("", lambda: model.delete_pair(index), f"delete pair {index}", icon="trash")
        select = self._button("", lambda: model.select(index), f"highlight pair {index}", icon="crosshairs")
        return w.HBox([label, weight, margin, select, delete, w.HTML(miss)], layout=w.Layout(align_items="center"))

    def _edit_pair(self, setter, index: int, text: str, field: w.Text, name: str) -> None:
        """A weight or margin typed into the list: parsed and checked by the model; a bad value is
        named in the message and the field shows the pair's value again."""
        if index >= len(self.model.pairs):
            return
        current = getattr(self.model.pairs[index], name)
        value: float | str
        try:
            value = float(text)
        except ValueError:
            value = text  # the model's check names the field and the text
        if value == current:
            return
        before = self.model.pairs
        self._guard(setter, index, value)
        if self.model.pairs is before:  # refused: show the kept value again
            field.value = f"{current:g}"

    def _show_result(self) -> None:
        result = self.model.result
        if result is None:
            self._result.value = "No solve yet."
            return
        rows = "".join(
            f"<tr><td>{html.escape(name)}</td><td>{start:.6g}</td><td>{solved:.6g}</td>"
            f"<td>{html.escape(unit)}</td></tr>"
            for name, start, solved, unit in self.model.changed_parameters()
        )
        misses = "".join(
            f"<tr><td>#{i}</td><td>{a:.3g}</td><td>{b:.3g}</td></tr>"
            for i, (a, b) in enumerate(zip(result.initial_distances, result.distances))
        )
        verdict = "success" if result.success else "not every pair met"
        self._result.value = (
            f"<b>{html.escape(result.field.type_name)}: {verdict}</b> — {result.iterations} iterations, "
            f"{result.time:.3g} s<br><small>{html.escape(result.message)}</small>"
            f"<table {TABLE_STYLE}><tr><th>parameter</th><th>start</th><th>solved</th><th>unit</th></tr>{rows}</table>"
            f"<table {TABLE_STYLE}><tr><th>pair</th><th>miss before [m]</th><th>after [m]</th></tr>{misses}</table>"
        )

    def _show_fan(self) -> None:
        self._fan.value = self.model.fan_png or b""

    def _show_field(self) -> None:
        names = tuple(_free_choices(self.model.field))
        if tuple(self._free.options) != names:  # a loaded scene with another model
            self._syncing = True
            try:
                self._free.options = names
            finally:
                self._syncing = False
        self._show_spots()
        self._show_free()
        self._show_result()

    def _show_free(self) -> None:
        free = tuple(self.model.free or ())
        syncing, self._syncing = self._syncing, True
        try:
            if tuple(self._free.value) != free:
                self._free.value = free
            for name, toggle in self._spot_toggles.items():
                toggle.value = name in free
        finally:
            self._syncing = syncing

    def _show_spot_outlines(self) -> None:
        outlines = self.model.spot_outlines()
        self._canvas.spots = outlines
        self._straight.spots = outlines

    def _show_spots(self) -> None:
        """The spot list (values, units, free toggles) and the outlines on the images."""
        self._show_spot_outlines()
        field, free = self.model.field, set(self.model.free or ())
        info = {p["name"]: p for p in field.param_info}
        rows, self._spot_toggles = [], {}
        for index, spot in enumerate(self.model.hot_spots):
            prefix = f"hot_spot{index}_"
            names = [n for n in field.param_names if n.startswith(prefix)]
            values = ", ".join(f"{n[len(prefix) :]} {field.params[n]:.4g} {info[n]['unit']}" for n in names)
            colour = "#ff5722" if spot.dt > 0.0 else "#29b6f6"  # canvas.js's SPOT_COLOURS
            label = w.HTML(f"<b style='color:{colour}'>#{index}</b> {spot.footprint}: {html.escape(values)}")
            toggles = []
            for name in names:
                toggle = w.ToggleButton(
                    description=name[len(prefix) :],
                    value=name in free,
                    tooltip=f"let a solve change {name}",
                    layout=w.Layout(width="auto"),
                )
                toggle.observe(lambda change, name=name: self._toggle_free(name, change["new"]), names="value")
                self._spot_toggles[name] = toggle
                toggles.append(toggle)
            rows.append(w.VBox([label, w.HBox([w.HTML("free:"), *toggles], layout=w.Layout(align_items="center"))]))
        old = self._spot_rows.children
        self._spot_rows.children = rows or [
            w.HTML(
                f"This atmosphere ({html.escape(field.type_name)}) has no hot spots: give PhysicalAtmosphere or "
                "LogisticProfile <code>hot_spots=[refracta.HotSpot(x, z, radius, dt)]</code>."
            )
        ]
        for row in old:
            _close_tree(row)

    def _toggle_free(self, name: str, on: bool) -> None:
        """A spot parameter's free toggle: adds it to or removes it from the free parameters."""
        if self._syncing:
            return
        free = set(self.model.free or ()) - {name} | ({name} if on else set())
        names = [*self.model.field.param_names, *CAMERA_PARAMETERS]  # camera ones too (a trial lost them)
        self._guard(self.model.set_free, [n for n in names if n in free])

    def _show_message(self) -> None:
        colour = MESSAGE_COLOURS.get(self.model.message_kind, "#333")
        self._message.value = f"<span style='color:{colour}'>{html.escape(self.model.message)}</span>"

    def _show_progress(self) -> None:
        progress = dict(self.model.progress)
        render = progress.get("render") or progress.get("straight")
        self._render_progress.value = render[1] if render else (1.0 if self.model.images["curved"] else 0.0)
        self._render_progress.description = "render"
        solve = progress.get("solve")
        self._solve_progress.value = solve[1] if solve else (1.0 if self.model.result is not None else 0.0)

    def _show_busy(self) -> None:
        self._cancel.disabled = not self.model.busy
        self._show_progress()

    def _show_history(self) -> None:
        self._undo.disabled = not self.model.can_undo
        self._redo.disabled = not self.model.can_redo

    def _show_mode(self) -> None:
        self._canvas.cursor = "crosshair" if self.model.mode == "points" else "move"
        if self._mode.value != self.model.mode:
            self._mode.value = self.model.mode


def _close_tree(widget: w.Widget) -> None:
    """Close a widget and its children (their comms to the browser)."""
    for child in getattr(widget, "children", ()):
        _close_tree(child)
    widget.close()
