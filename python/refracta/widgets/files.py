"""The mirage editor's files: the pairs as JSON in the format of `refracta edit --pairs`
(refracta.edit.load_pairs reads it back) and the scene as TOML (refracta.load_scene reads it back)
with the solved atmosphere and the editor's camera (refracta.scene_file.with_atmosphere and
with_camera).

Pairs file::

    {"pairs": [{"destination": [u, v], "source": [x, y, z], "weight": 1.0, "margin": 0.0}, ...],
     "free": ["surface_dt"], "stop_height": 0.0}   # solve() options, as `refracta edit` passes them

Destinations are pixels of the scene file's camera, so the scene is written with the editor's
camera: together the two files reproduce the edit with ``refracta edit scene.toml --pairs
pairs.json -o solved.toml``.
"""

from __future__ import annotations

import json
import warnings
from collections.abc import Sequence

import numpy as np

from refracta import _checks, _core
from refracta.scene_file import with_atmosphere, with_camera

__all__ = ["pairs_json", "scene_toml"]


def pairs_json(pairs: Sequence, options: dict | None = None) -> str:
    """The pairs (refracta.edit.PointPair) and solve options as the JSON text load_pairs reads.

    options: solve() keywords to store beside the pairs (free, stop_height, backend, bounds, ...);
    entries that are None are left out (solve's defaults apply), and a warning names any that JSON
    cannot hold (objects, callables), which `refracta edit` then solves without."""
    entries = []
    for pair in pairs:
        entries.append(
            {
                "destination": [float(x) for x in pair.destination],
                "source": [float(x) for x in pair.source],
                "weight": float(pair.weight),
                "margin": float(pair.margin),
            }
        )
    data: dict[str, object] = {"pairs": entries}
    dropped = []
    for name, value in (options or {}).items():
        plain = _json_value(value)
        if plain is not None:
            data[name] = plain
        elif value is not None:
            dropped.append(name)
    if dropped:
        warnings.warn(
            f"the pairs file cannot hold the solve option(s) {', '.join(dropped)} (only numbers, strings, "
            "lists and dicts of them): `refracta edit` with it solves without them",
            stacklevel=4,
        )
    return json.dumps(data, indent=2) + "\n"


def _json_value(value):
    """`value` as JSON holds it (tuples and arrays as lists, numpy numbers and bools as Python's),
    or None where it cannot."""
    if isinstance(value, (bool, str)) or value is None:
        return value
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.ndarray):
        value = value.tolist()
    if _checks.is_number(value):
        return value.item() if isinstance(value, np.generic) else value
    if isinstance(value, (list, tuple)):
        listed = [_json_value(v) for v in value]
        return None if any(i is None and v is not None for i, v in zip(listed, value)) else listed
    if isinstance(value, dict) and all(isinstance(k, str) for k in value):
        named = {k: _json_value(v) for k, v in value.items()}
        return None if any(named[k] is None and value[k] is not None for k in value) else named
    return None


def scene_toml(text: str | None, camera: _core.Camera, field: _core.IndexField, turbulence=None) -> str:
    """The scene file `text` with `camera` and `field` written into it (turbulence: the
    refracta.Turbulence whose layer `field` carries, see refracta.scene_file.atmosphere_table).
    Without a file (the editor was given Scene objects) only the camera and the atmosphere are
    written, under a comment saying so: load_scene reads it, but it has no objects to render."""
    if text is None:
        text = (
            "# Written by refracta.widgets.MirageEditor from a Scene object: the camera and the\n"
            "# solved atmosphere only (no objects). Start the editor from a scene file\n"
            "# (MirageEditor.from_file) to keep the whole scene.\n"
        )
    return with_atmosphere(with_camera(text, camera), field, turbulence)
