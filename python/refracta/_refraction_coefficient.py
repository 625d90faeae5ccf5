"""refracta.refraction_coefficient (issue 20): the surveyors' coefficient of refraction k of a traced
ray, and the drop and hidden height of a distant target with and without refraction.

Surveyors and the curvature calculators (Bislin, Metabunk) model terrestrial refraction as a ray of
constant curvature k / R over an Earth of radius R: a sight line leaving the eye horizontally is
(1 - k) d^2 / (2R) above the eye's height at distance d, as if the Earth's radius were R / (1 - k)
(Bomford, Geodesy, 4th ed., sec. 3.2; Hirt et al. 2010, J. Geophys. Res. 115, D21102). Here the ray
is traced through the actual air by refracta's integrator (refracta.trace_ray over CurvedEarth's
flat frame, exact in the ray's vertical plane) and k is the value that reproduces its height.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from refracta import _core, _options
from refracta._checks import number as _number

# The searches on the launch elevation stop when their bracket moves the ray's height at the
# target's distance by less than this [m]: a tenth of trace_ray's default tol (1e-6 m).
_HEIGHT_TOL = 1e-7
# The steepest launch the searches try [rad] (89.9 deg).
_STEEPEST = math.radians(89.9)


@dataclass(frozen=True)
class RefractionCoefficient:
    """The result of :func:`refracta.refraction_coefficient`. Lengths in metres, angles in degrees.

    Attributes:
        k: the coefficient of refraction: a ray leaving the eye horizontally is
            ``eye_height + (1 - k) distance**2 / (2 earth_radius)`` above the surface at ``distance``
            (about 0.17 in the U.S. Standard Atmosphere near sea level; 1 where the ray follows the
            Earth's curve; above 1 in ducts; without air the formula's own truncation,
            -(eye_height / R + 5 distance^2 / (12 R^2)), -1e-5 at 30 km).
        earth_radius: R [m] of the curved Earth the ray was traced over.
        eye_height: the eye's height above the surface [m].
        distance: the distance along the surface [m] at which everything is measured.
        drop_straight: how far the surface at ``distance`` lies below the eye's horizontal straight
            sight line, less the eye's height: ``(R + eye_height) (1 / cos(distance / R) - 1)``
            (about distance^2 / (2R)).
        drop_refracted: the same for the traced horizontal ray: its height at ``distance`` less the
            eye's height (``(1 - k) distance^2 / (2R)`` by the definition of k).
        hidden_height_straight: how much of a target at ``distance`` the Earth's bulge hides from the
            eye along straight lines (0 within the geometric horizon).
        hidden_height_refracted: the same through the air: the height at ``distance`` of the lowest
            traced ray that passes over the surface all the way (the ray grazing the horizon), 0
            when the surface at ``distance`` is in view (to the tracer's tolerance). In a mirage,
            where rays meeting the ground and rays clearing it alternate with the launch
            elevation, it is one such transition near the horizontal (the bisection's); use an
            ElevationTable for the whole fan.
        target_height: the target's height above the surface [m], or None when none was given.
        true_elevation: the target's elevation [deg] from the eye along a straight line, or None.
        apparent_elevation: the launch elevation [deg] of the traced ray that reaches the target
            (where it is seen), or None when no target was given or it is hidden
            (``target_height < hidden_height_refracted``). apparent minus true elevation is about
            k distance / (2R) [rad] for a ray of constant curvature. Where a mirage shows the
            target more than once, one of its images (the search's).
    """

    k: float
    earth_radius: float
    eye_height: float
    distance: float
    drop_straight: float
    drop_refracted: float
    hidden_height_straight: float
    hidden_height_refracted: float
    target_height: float | None
    true_elevation: float | None
    apparent_elevation: float | None


_SHORTEST = 1.0  # [m] the shortest distance k is measured over (refraction_coefficient)
# The highest drop of the straight horizontal sight line at `distance` [m]: the Karman line, above
# which there is no air to refract (1 121 km of distance over the Earth; the longest sight line
# photographed is 443 km). Beyond it k is no longer the air's, and the traces, which scan for
# turning heights metre by metre, ran 70 s at 3 000 km and failed after 18 s at 9 900 km (a trial).
_HIGHEST_DROP = 100e3


def _finite(value, name: str, low: float) -> float:
    number = _number(value, name)  # not True (1 m), not "30"
    if not (math.isfinite(number) and number >= low):
        raise ValueError(f"{name} must be finite and >= {low:g} [m] (got {number!r})")
    return number


def _curved_earth(field, earth_radius) -> _core.CurvedEarth:
    if not isinstance(field, _core.IndexField):
        raise ValueError(f"field must be an IndexField (got {type(field).__name__})")
    if not field.height_only:
        local = [what for what in ("hot_spots", "turbulence") if getattr(field, what, None)]
        why = f"this {field.type_name} carries {' and '.join(local)}" if local else f"a {field.type_name} does not"
        raise ValueError(f"field must depend on height only ({why})")
    if isinstance(field, _core.CurvedEarth):
        if earth_radius is not None and float(earth_radius) != field.radius:
            raise ValueError(
                f"earth_radius {earth_radius!r} differs from the CurvedEarth field's radius {field.radius!r}: give one"
            )
        return field
    if earth_radius is None:
        return _core.CurvedEarth(field)  # CurvedEarth's own default radius (C++)
    return _core.CurvedEarth(field, _number(earth_radius, "earth_radius"))  # CurvedEarth names its range


class _Tracer:
    """Rays from the eye along -z in CurvedEarth's flat frame, read where they cross x' = distance."""

    def __init__(self, curved: _core.CurvedEarth, eye_height: float, distance: float, fields: dict):
        for name in ("max_length", "stop_height"):
            if name in fields:
                raise ValueError(f"refraction_coefficient sets {name} itself: do not pass it")
        # Checked here so that a misspelt keyword is refused in this function's name, not trace_ray's.
        known = _options.fields(_core.TraceOptions)
        unknown = sorted(set(fields) - set(known))
        if unknown:
            options = ", ".join(n for n in known if n not in ("max_length", "stop_height"))
            raise ValueError(
                f"refraction_coefficient: unknown option {', '.join(map(repr, unknown))} (its keywords: "
                f"target_height, earth_radius, and trace options: {options})"
            )
        self.curved, self.distance, self.fields = curved, distance, fields
        self.eye = (0.0, float(curved.flat_height(eye_height)), 0.0)

    def height_at_distance(self, elevation: float, ground: bool) -> float | None:
        """True height [m] at ``distance`` of the ray launched at ``elevation`` [rad], or None when
        (with ``ground``) it meets the surface first."""
        # The flat frame's path to x' = distance is at most about distance / cos(elevation) long
        # (the ray's bending changes its slope by a few mrad over 100 km): half again as long is ample.
        reach = 1.5 * self.distance / max(math.cos(elevation), 1e-3) + 10.0
        stop = {"stop_height": 0.0} if ground else {}
        path = _core.trace_ray(
            self.curved,
            self.eye,
            (0.0, math.sin(elevation), -math.cos(elevation)),
            max_length=reach,
            **stop,
            **self.fields,
        )
        crossings = path.crossings((0.0, 0.0, -1.0), self.distance)
        if not crossings:
            if ground and path.stop == "stop_height":
                return None
            raise _core.NumericalError(
                f"refraction_coefficient: the ray at {math.degrees(elevation):g} deg did not reach "
                f"{self.distance:g} m within {reach:g} m of path (it turned back)"
            )
        return float(self.curved.true_height(crossings[0][0][1]))


def _hidden_height(tracer: _Tracer) -> tuple[float, float]:
    """(hidden height [m], the launch elevation [rad] of the limiting ray): bisection between a ray
    that meets the surface before ``distance`` and one above it that clears it, until the bracket
    moves the height at ``distance`` by under _HEIGHT_TOL (it moves it by at most d per radian)."""
    high, step = 0.0, 1e-3
    while tracer.height_at_distance(high, ground=True) is None:
        if high >= _STEEPEST:
            raise _core.NumericalError("refraction_coefficient: no ray from the eye clears the surface")
        high, step = min(high + step, _STEEPEST), 2.0 * step
    low, step = -1e-3, 1e-3
    while tracer.height_at_distance(low, ground=True) is not None:
        if low <= -_STEEPEST:  # even steep rays reach `distance` first: the surface there is in view
            return 0.0, low
        low, step = max(low - step, -_STEEPEST), 2.0 * step
    while (high - low) * tracer.distance > _HEIGHT_TOL:
        middle = 0.5 * (low + high)
        if tracer.height_at_distance(middle, ground=True) is None:
            low = middle
        else:
            high = middle
    height = tracer.height_at_distance(high, ground=True)
    assert height is not None  # `high` clears by the loop's invariant
    # Within the horizon the limiting ray meets the surface at `distance` itself: height 0, which
    # the bisection leaves a few nanometres up (a sea-level target then counted as hidden).
    return (height if height > _HEIGHT_TOL else 0.0), high


def _apparent_elevation(tracer: _Tracer, target: float, low: float, low_height: float, guess: float) -> float:
    """Launch elevation [rad] of a ray reaching ``target`` [m] at ``distance``: above the limiting ray
    ``low`` (whose height there is ``low_height`` <= target), from ``guess`` (the straight line's
    elevation) upward to a bracket, then regula falsi (Illinois) with bisection where a ray in the
    bracket meets the ground, until the height is within _HEIGHT_TOL of the target."""
    if low_height >= target:
        return low
    high, step = max(guess, low), 1e-3
    while True:
        reached = tracer.height_at_distance(high, ground=True)
        if reached is not None and reached >= target:
            break
        if reached is not None:
            low, low_height = high, reached
        if high >= _STEEPEST:
            raise _core.NumericalError(f"refraction_coefficient: no ray reaches the target at {target:g} m")
        high, step = min(high + step, _STEEPEST), 2.0 * step
    high_height, side = reached, 0
    while True:
        middle = low + (target - low_height) * (high - low) / (high_height - low_height)
        if not low < middle < high:
            middle = 0.5 * (low + high)
        reached = tracer.height_at_distance(middle, ground=True)
        if reached is None:  # a ray in the bracket meets the ground (a mirage's layer): bisect
            low, low_height, side = middle, -math.inf, 0
            continue
        if abs(reached - target) < _HEIGHT_TOL or (high - low) * tracer.distance < _HEIGHT_TOL:
            return middle
        # Illinois: halve the stale end's height so the bracket closes from both sides.
        if reached < target:
            low, low_height = middle, reached
            if side == -1:
                high_height = target + 0.5 * (high_height - target)
            side = -1
        else:
            high, high_height = middle, reached
            if side == 1:
                low_height = target + 0.5 * (low_height - target)
            side = 1


def straight_elevation(distance: float, eye_height: float, target_height: float, radius: float) -> float:
    """[deg] The elevation at the eye of the straight line to a target: the eye `eye_height` [m] and
    the target `target_height` [m] above a sphere of `radius` [m] (math.inf: flat), `distance` [m]
    apart along it (the central angle distance / radius). Where the target shows with no air."""
    if not math.isfinite(radius):
        return math.degrees(math.atan2(target_height - eye_height, distance))
    phi = distance / radius
    far = radius + target_height
    return math.degrees(math.atan2(far * math.cos(phi) - (radius + eye_height), far * math.sin(phi)))


def refraction_coefficient(
    field: _core.IndexField,
    eye_height,
    distance,
    *,
    target_height=None,
    earth_radius=None,
    **fields,
) -> RefractionCoefficient:
    """The coefficient of refraction k of ``field`` seen from ``eye_height`` [m] over ``distance`` [m]
    (along the surface), and the drop and hidden height of a target there with and without the air.

    k is the value for which the surveyors' formula reproduces the traced height of a ray leaving
    the eye horizontally: at ``distance`` it is ``eye_height + (1 - k) distance**2 / (2R)`` above the
    surface. For a uniform gradient near the ground k = -R (dn/dh) / n: 503 P / T^2 (0.0343 + dT/dh)
    with P [hPa], T [K], dT/dh [K/m] (about 0.17 in the standard atmosphere; 1 at
    dT/dh = +0.128 K/m at 15 C and 1013 hPa, +0.112 K/m at 0 C: the ray follows the Earth; the
    formula's rounding gives 0.129, where this air's k is 1.004 from the ground, 1.002 from 2 m).

    field: a CurvedEarth (R is its radius) or a height-only field of true heights (PhysicalAtmosphere,
    TemperatureProfile, ...), which is put over a curved Earth, ``CurvedEarth(field, earth_radius)``
    (None: CurvedEarth's default radius) -- a flat-Earth field has no drop or horizon of its own,
    so its air is measured over the curved Earth it stands for. eye_height >= 0 and distance > 0
    [m]: true heights above the surface and distance along it. target_height [m] (optional): a
    target's height above the surface at ``distance``: its true and apparent elevations are returned
    too. Further keywords go to refracta.trace_ray (``trace``, default 'stratified', ``tol``,
    ``step``, ...; max_length and stop_height are set here): every ray is refracta.trace_ray's.
    The horizontal ray is traced through the field's formula even below the surface (a ducted
    ray, k > 1, may reach it).

    Returns a :class:`RefractionCoefficient`. ValueError for a field that is not height-only, a
    negative or non-finite height, a distance below 1 m or beyond where the straight horizontal sight
    line passes 100 km over the surface (1 121 km over the Earth: above the air), or an
    earth_radius that contradicts a CurvedEarth's; refracta.NumericalError where no ray reaches
    the distance.
    """
    curved = _curved_earth(field, earth_radius)
    radius = float(curved.radius)
    h0 = _finite(eye_height, "eye_height", 0.0)
    d = _number(distance, "distance")  # NaN and infinities fail the range below, which names it
    # Below a metre the Earth's drop (d^2 / 2R < 1e-7 m) is lost in the heights' rounding: k came
    # out 0.185 at 1 mm and 1.0 at 1 um for a field whose k is 0.1695 from 1 m on.
    # The longest: where the straight sight line's drop R (1 / cos(d / R) - 1) reaches _HIGHEST_DROP.
    longest = radius * math.acos(radius / (radius + _HIGHEST_DROP))
    if not _SHORTEST <= d <= longest:
        raise ValueError(
            f"distance must be in [{_SHORTEST:g}, {longest:g}] m (got {d!r}): beyond, the horizontal sight line "
            f"passes over the surface more than {_HIGHEST_DROP / 1e3:g} km up, above the air"
        )
    target = None if target_height is None else _finite(target_height, "target_height", 0.0)
    # 'stratified' (exact paths from n cos e = const) by default: it finds a grazing ray's lowest
    # point exactly, where rk45's nodes can step over a dip of centimetres below the surface.
    tracer = _Tracer(curved, h0, d, {"trace": "stratified", **fields})

    level = tracer.height_at_distance(0.0, ground=False)
    assert level is not None  # without a ground the ray always has a height there
    drop_refracted = level - h0
    k = 1.0 - 2.0 * radius * drop_refracted / (d * d)

    phi = d / radius
    drop_straight = (radius + h0) * (1.0 / math.cos(phi) - 1.0)
    horizon = math.acos(radius / (radius + h0))  # the geometric horizon's angle at the centre
    hidden_straight = radius / math.cos(phi - horizon) - radius if phi > horizon else 0.0
    hidden_refracted, limit = _hidden_height(tracer)

    true_elevation = apparent_elevation = None
    if target is not None:
        true_elevation = straight_elevation(d, h0, target, radius)
        if target >= hidden_refracted:
            guess = math.radians(true_elevation)
            apparent_elevation = math.degrees(_apparent_elevation(tracer, target, limit, hidden_refracted, guess))
    return RefractionCoefficient(
        k=k,
        earth_radius=radius,
        eye_height=h0,
        distance=d,
        drop_straight=drop_straight,
        drop_refracted=drop_refracted,
        hidden_height_straight=hidden_straight,
        hidden_height_refracted=hidden_refracted,
        target_height=target,
        true_elevation=true_elevation,
        apparent_elevation=apparent_elevation,
    )
