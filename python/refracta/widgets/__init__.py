"""refracta.widgets: the interactive mirage editor in Jupyter.

``MirageEditor(scene, camera, field, free=None)`` shows the render through the atmosphere
(a quarter-resolution preview, then full resolution, rendered in the background) with the
atmosphere's hot spots outlined on the ground, lets you click point pairs on it (a scene point,
then where its mirage image should appear), move the camera, solve for the atmosphere in the
background (progress, cancel, undo/redo) and save the solved scene (TOML) and the pairs (JSON,
as ``refracta edit`` reads them). See
``notebooks/04_interactive_editor.ipynb``.

Modules: ``model`` (EditorModel: state, gestures, undo/redo, background renders and solves; no
user interface, testable without a browser), ``jobs`` (the background runner: a newer request
cancels the older one), ``camera_moves`` (orbit, pan, dolly), ``files`` (the pairs and scene
files), ``canvas`` and ``view`` (the ipywidgets / anywidget front end: ``pip install
refracta[widgets]``), ``readouts`` (``show_readouts(image, aovs)``: hovering over a render shows
its per-pixel readouts, render(aovs=[...])).
"""

from refracta.widgets.model import EditorModel

__all__ = ["EditorModel", "MirageEditor", "ReadoutViewer", "readout_text", "show_readouts"]


def __getattr__(name):
    # The view needs ipywidgets and anywidget; the model does not (PEP 562: loaded on first use).
    if name == "MirageEditor":
        from refracta.widgets.view import MirageEditor

        return MirageEditor
    if name in ("ReadoutViewer", "show_readouts"):
        from refracta.widgets import readouts

        return getattr(readouts, name)
    if name == "readout_text":
        from refracta._readout_text import readout_text

        return readout_text
    raise AttributeError(f"module 'refracta.widgets' has no attribute {name!r}")
