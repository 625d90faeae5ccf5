"""Batch ray tracing: argument shaping and the result object around the C++ batch tracer."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Callable

import numpy as np

from refracta import _core
from refracta._checks import real_array


def without_refraction(field: _core.IndexField | None) -> _core.IndexField | None:
    """The reference a render through `field` compares with: the same Earth, air that bends nothing.

    None (straight rays over a flat Earth) for a flat-Earth field or None; for a CurvedEarth of
    radius R, a CurvedEarth of the same R over uniform air (n = 1), so the "without the atmosphere"
    image still hides what the Earth's bulge hides (a render with None would show a flat Earth)::

        refracta.render(scene, camera, refracta.without_refraction(ship.field), ...)
    """
    if field is None:
        return None
    if not isinstance(field, _core.IndexField):
        raise ValueError(f"without_refraction: field must be an IndexField or None (got {type(field).__name__})")
    if isinstance(field, _core.CurvedEarth):
        return _core.CurvedEarth(_core.LinearSquaredProfile(1.0, 0.0), field.radius)
    return None


@dataclass(frozen=True, eq=False)  # arrays: == would be ambiguous (two batches are equal by identity)
class RayBatch:
    """Ends of a batch of traced rays.

    Unpacks as ``end_points, end_directions, lengths = trace_rays(...)``.

    Attributes:
        end_points: (N, 3) float64, where each path ended [m].
        end_directions: (N, 3) float64, unit tangents there.
        lengths: (N,) float64, arc length of each path [m].
        stops: (N,) str array, why each path ended ('max_length' or 'stop_height').
        evaluations: (N,) int64, field evaluations per ray.
    """

    end_points: np.ndarray
    end_directions: np.ndarray
    lengths: np.ndarray
    stops: np.ndarray
    evaluations: np.ndarray

    def __iter__(self) -> Iterator[np.ndarray]:
        return iter((self.end_points, self.end_directions, self.lengths))

    def __len__(self) -> int:
        return 3

    def __getitem__(self, index):
        """As the 3-tuple it unpacks as: end_points, end_directions, lengths."""
        return (self.end_points, self.end_directions, self.lengths)[index]


def trace_rays(
    field: _core.IndexField,
    origins,
    directions,
    options: _core.TraceOptions | None = None,
    *,
    progress: bool | Callable[[int, int], None] = False,
    **fields,
) -> RayBatch:
    """Trace many curved rays in parallel (oneTBB, GIL released; Ctrl-C stops it).

    origins: (3,) or (N, 3); directions: (N, 3) or (3,) -- a single row is broadcast against
    the other. options: a :class:`refracta.TraceOptions` (None: its defaults), and any of its
    fields as keywords, as in :func:`refracta.trace_ray`. progress: True for a bar on stderr, or
    a callable ``progress(done, total)`` called about every 50 ms.
    """
    origins, directions = _rows(origins, "origins"), _rows(directions, "directions")
    if origins.ndim == 1 and directions.ndim == 2:
        origins = np.broadcast_to(origins, directions.shape)
    elif directions.ndim == 1 and origins.ndim == 2:
        directions = np.broadcast_to(directions, origins.shape)
    origins = np.atleast_2d(origins)
    directions = np.atleast_2d(directions)
    if origins.shape != directions.shape:
        raise ValueError(
            f"origins and directions must have matching shapes (N, 3); got {origins.shape} and {directions.shape}"
        )
    # Broadcast views as they are: C++ counts the rays against memory before copying them.
    return _batch(*_core._trace_batch(field, origins, directions, options, progress, **fields))


def _rows(value, name: str) -> np.ndarray:
    """`value` as float64 of shape (3,) or (N, 3), else ValueError naming it."""
    array = real_array(value, f"trace_rays: {name}")
    if array.ndim not in (1, 2) or array.shape[-1] != 3:
        raise ValueError(f"trace_rays: {name} must have shape (3,) or (N, 3) (got {array.shape})")
    return array


def _batch(points, directions, lengths, stops, evaluations) -> RayBatch:
    """A RayBatch of the C++ batch's arrays (stops as TraceStop numbers)."""
    names = np.array(_core._stop_names)
    return RayBatch(points, directions, lengths, names[stops.astype(np.int64)], evaluations.astype(np.int64))


class ElevationTable(_core._ElevationTable):
    """Paths by launch elevation from one eye height in a height-only field.

    Every ray launched with the same elevation from the same height follows the same path in its
    vertical plane, so the table traces a few hundred to a few thousand elevations exactly
    (trace 'stratified') and serves any number of rays, at any azimuth, by interpolation. It
    refines until the interpolation error is below ``tol`` [m] along the whole path, never
    interpolates between rays of different kind (one reaching the ground, one turning), and traces
    queries exactly where such an edge could not be resolved.

    ``ElevationTable(field, eye_height, min_elevation, max_elevation, options=None, progress=False,
    **fields)``: the eye is at (0, eye_height, 0); elevations and azimuths are in degrees, azimuth
    measured from +x toward +z (the C++ table's radians are converted once, in its binding).
    options: a :class:`refracta.ElevationTableOptions` (None: its defaults); any of its fields, or
    of its ``trace`` options (max_length, stop_height, step), may be given as keywords. Its
    properties (options, tol, eye_height, size, evaluations, exact_intervals, elevations [deg]) are
    the C++ table's. Pickles as its arguments (the table is rebuilt where it is unpickled).
    """

    def __init__(
        self,
        field: _core.IndexField,
        eye_height: float,
        min_elevation: float,
        max_elevation: float,
        options: _core.ElevationTableOptions | None = None,
        *,
        progress: bool | Callable[[int, int], None] = False,
        **fields,
    ):
        super().__init__(field, eye_height, min_elevation, max_elevation, options, progress, **fields)
        # What pickling rebuilds the table from (the build is deterministic: the copy is identical).
        self._arguments = (field, eye_height, min_elevation, max_elevation, self.options)
        self.field = field

    def ends(self, elevations, azimuths=0.0) -> RayBatch:
        """Ends of the rays launched at ``elevations`` [deg] (and ``azimuths`` [deg])."""
        flat = (np.asarray(values, dtype=np.float64).ravel() for values in (elevations, azimuths))
        return _batch(*self._ends(*flat))

    def __reduce__(self):
        """Pickled as its constructor's arguments; unpickling rebuilds the same table."""
        return (ElevationTable, self._arguments)

    def __repr__(self) -> str:
        return f"ElevationTable(size={self.size}, eye_height={self.eye_height}, tol={self.tol})"
