"""How wrong is a straight shadow connection to a lamp through a hot road's air?
(render/direct_lighting.h connects finite lights by straight segments and claims a sagitta
L^2 |grad n| / 8: 1.25 mm over 10 m through a 10 K / 10 cm road layer; shared/SHADING.md
section 6 asks for the error of that choice to be measured.)

The true connection is solved by two-point shooting: from a point A near the road, curved rays
are traced with refracta.trace_ray (rk45 to TRACE_TOL) at launch elevations e in the vertical
plane through the lamp B (a height-only field keeps the path in it), and e is found by the
secant method until the path crosses the lamp's vertical line at the lamp's height. Measured:
the angle between the straight and the solved launch directions, the largest distance between
the path and the segment AB, the path-length change (the 1/r^2 factor) and the irradiance
error. The irradiance of a point source through the field is E_perp = I dOmega_B / dA_perp:
launched from B at elevation e_B, azimuth phi, the tube lands on a vertical strip dh at
horizontal distance D, dA_perp = cos(e_A) |dh/de| de D dphi, dOmega_B = cos(e_B) de dphi, so
E_perp = I cos(e_B) / (cos(e_A) D |dh/de|) (I / r^2 without a field); dh/de by central
differences of shots from B.

Bounds: a ray's curvature is |grad_perp n| / n <= |grad n|, so a path of chord L through a field
with |grad n| <= g deviates from the chord by at most g L^2 / 8 and its end directions by at
most g L / 2 (the arc of constant curvature g is the extreme case). The tube factor is checked
against its first-order (paraxial) estimate: a perturbed ray's height obeys dh''/dx = n''(h) dh,
so dh/de = D + int_0^D (D - x) x n''(h(x)) dx and E_perp r^2 / I - 1 = -(1/D) int (D - x) x n'' dx.
"""

import numpy as np
import pytest

import refracta

ROAD = dict(surface_dt=10.0, surface_depth=0.1)  # the header's hot road: 10 K, 10 cm e-folding
TRACE_TOL = 1e-10  # rk45 position tolerance [m]: far below the 1e-6 m deviations measured
HIT_TOL = 1e-11  # the shot's miss at the lamp [m] when the secant stops
HEADER_SAGITTA = 1.25e-3  # direct_lighting.h: "a 10 m connection ... deviates 1.25 mm"
SAMPLES = 2001  # points along each solved path for the distance and the gradient maximum
# The bounds use the gradient's maximum over SAMPLES points of the path: sampling misses at most
# ~1e-6 of a smooth maximum; the traced path's own error is TRACE_TOL. 1e-3 relative covers both.
SAMPLED_MAX = 1e-3
D_ELEVATION = 1e-6  # [rad] central-difference step of dh/de (truncation ~1e-12 relative)
# The paraxial estimate of the tube factor drops terms of order (D^2 |n''| / 6)^2 relative to the
# factor itself (<= 0.1 here) and n''' D^3 variations of the path height: 20% of the factor.
PARAXIAL = 0.2
NO_FIELD = 1e-6  # the tube formula against I / r^2 without the road layer (lapse rate only)

# (height of A [m], height of the lamp [m], horizontal distance [m])
CASES = [
    (0.01, 0.01, 10.0),
    (0.05, 0.05, 10.0),
    (0.02, 0.3, 10.0),
    (0.1, 1.5, 10.0),
    (0.05, 0.05, 30.0),
    (0.1, 1.5, 30.0),
]


def shoot(field, origin, elevation, distance, toward=1.0):
    """The curved ray from origin (3,) at `elevation` [rad] toward +x (toward=1) or -x: (its
    crossing (point, s, direction) of the vertical plane `distance` [m] away, the RayPath)."""
    direction = np.array([toward * np.cos(elevation), np.sin(elevation), 0.0])
    path = refracta.trace_ray(
        field, origin, direction, tol=TRACE_TOL, max_length=1.01 * distance / np.cos(elevation) + 0.01
    )
    crossings = path.crossings([1.0, 0.0, 0.0], origin[0] + toward * distance)
    assert len(crossings) == 1, crossings
    return crossings[0], path


def solve_connection(field, a, b):
    """Launch elevation [rad] of the curved path from a to b (same z), by the secant method."""
    distance = b[0] - a[0]

    def miss(e):
        return shoot(field, a, e, distance)[0][0][1] - b[1]

    e0 = np.arctan2(b[1] - a[1], distance)
    x0, x1 = e0, e0 - 1e-4
    f0, f1 = miss(x0), miss(x1)
    for _ in range(40):
        x0, f0, x1 = x1, f1, x1 - f1 * (x1 - x0) / (f1 - f0)
        f1 = miss(x1)
        if abs(f1) < HIT_TOL:
            return x1
    raise AssertionError(f"shooting did not converge: miss {f1} m")


def tube_irradiance(field, a, b, arrival):
    """E_perp r^2 / I at a from an isotropic lamp at b whose solved path arrives at b along
    `arrival` (unit, a -> b): the ray tube from b, dh/de by central differences."""
    distance = b[0] - a[0]
    e_b = np.arctan2(-arrival[1], arrival[0])  # launch elevation at b back toward a
    up = shoot(field, b, e_b + D_ELEVATION, distance, toward=-1.0)[0][0][1]
    down = shoot(field, b, e_b - D_ELEVATION, distance, toward=-1.0)[0][0][1]
    dh_de = (up - down) / (2.0 * D_ELEVATION)
    (_, _, direction_at_a), _ = shoot(field, b, e_b, distance, toward=-1.0)
    e_a = np.arctan2(-direction_at_a[1], -direction_at_a[0])
    r2 = distance**2 + (b[1] - a[1]) ** 2
    return np.cos(e_b) / (np.cos(e_a) * distance * abs(dh_de)) * r2


def paraxial_tube(field, points, distance):
    """First-order tube factor -(1/D) int_0^D (D - x) x n''(h(x)) dx along path points (K, 3)."""
    step = 1e-4
    above, below = points + [0.0, step, 0.0], points - [0.0, step, 0.0]
    n2 = (field.grad_ior(above)[:, 1] - field.grad_ior(below)[:, 1]) / (2.0 * step)
    x = points[:, 0] - points[0, 0]
    return -np.trapezoid((distance - x) * x * n2, x) / distance


def test_tube_formula_without_a_road_is_inverse_square():
    field = refracta.PhysicalAtmosphere()
    a, b = np.array([0.0, 0.05, 0.0]), np.array([10.0, 0.3, 0.0])
    e = solve_connection(field, a, b)
    (_, _, arrival), _ = shoot(field, a, e, 10.0)
    assert tube_irradiance(field, a, b, arrival) == pytest.approx(1.0, abs=NO_FIELD)


@pytest.mark.parametrize("h_a,h_b,distance", CASES)
def test_straight_connection_error(h_a, h_b, distance):
    field = refracta.PhysicalAtmosphere(**ROAD)
    a, b = np.array([0.0, h_a, 0.0]), np.array([distance, h_b, 0.0])
    chord = np.linalg.norm(b - a)
    straight = np.arctan2(h_b - h_a, distance)
    e = solve_connection(field, a, b)
    (end, s_end, arrival), path = shoot(field, a, e, distance)
    assert np.linalg.norm(end - b) < 10 * HIT_TOL

    points = np.array([path.point_at(s)[0] for s in np.linspace(0.0, s_end, SAMPLES)])
    unit = (b - a) / chord
    offsets = points - a
    deviation = float(np.linalg.norm(offsets - np.outer(offsets @ unit, unit), axis=1).max())
    g = float(np.linalg.norm(field.grad_ior(points), axis=1).max())
    angle = abs(e - straight)
    length_change = (s_end - chord) / chord
    tube = tube_irradiance(field, a, b, arrival)
    expected_tube = 1.0 + paraxial_tube(field, points, distance)
    # a receiver facing up (the road, a floor) at a: cos factor from the arrival elevation
    cos_change = np.sin(e) / np.sin(straight) - 1.0 if h_b != h_a else float("nan")
    print(
        f'A {h_a} m, lamp {h_b} m, {distance} m: angle {angle:.3e} rad ({np.degrees(angle) * 3600:.1f}"; '
        f"bound {g * chord / 2:.3e}), deviation {deviation * 1e3:.4f} mm (bound {g * chord**2 / 8 * 1e3:.4f}), "
        f"min height {points[:, 1].min():.4f} m, 1/r^2 change {-2 * length_change:.1e}, "
        f"tube E r^2/I - 1 = {tube - 1:+.3e} (paraxial {expected_tube - 1:+.3e}), "
        f"cos (up-facing) change {cos_change:+.2e}"
    )
    assert deviation <= g * chord**2 / 8 * (1 + SAMPLED_MAX)
    assert angle <= g * chord / 2 * (1 + SAMPLED_MAX)
    if distance <= 10.0:
        assert deviation <= HEADER_SAGITTA  # the header's figure for a 10 m connection
    # the path is longer than its chord by at most L^3 g^2 / 24 (the constant-curvature arc)
    assert 0.0 <= length_change <= (g * chord) ** 2 / 24 * (1 + SAMPLED_MAX) + 1e-12
    assert tube - 1 == pytest.approx(expected_tube - 1, rel=PARAXIAL)
