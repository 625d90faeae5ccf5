"""Index-field models: formulas, analytic gradients, parameters and errors."""

import numpy as np
import pytest

import refracta

# Central differences with step 1e-5 of the field's scale: truncation ~ (h/scale)^2 ~ 1e-10
# relative, round-off ~ 1e-16 / 1e-5 ~ 1e-11 of n; gradients must agree to 1e-6 relative.
GRADIENT_RTOL = 1e-6


def central_gradient(field, points, step):
    grad = np.zeros_like(points)
    for axis in range(3):
        offset = np.zeros(3)
        offset[axis] = step
        grad[:, axis] = (field.ior(points + offset) - field.ior(points - offset)) / (2 * step)
    return grad


def logistic_reference(h, n_bg, n_inv, n_hot, h_ciso, a_bg, a_inv, a_hot, k_s):
    f = lambda L, w, x0, x: L / (1 + np.exp((x0 - x) / w))  # noqa: E731
    total = f(n_bg, 10 * a_bg, 0, h) + f(n_inv, -0.1 * a_inv, h_ciso, h) + f(n_hot, 0.3 * a_hot, 0, h)
    return 1 + 0.003 * k_s * total / (abs(n_bg) + abs(n_inv) + abs(n_hot))


FIELDS = {
    "logistic": (refracta.LogisticProfile(), 1e-5),
    "logistic_custom": (
        refracta.LogisticProfile(n_bg=2, n_inv=-0.5, n_hot=0.7, h_ciso=3, a_bg=0.5, a_inv=2, a_hot=0.3, k_s=-20),
        1e-5,
    ),
    "linear_squared": (refracta.LinearSquaredProfile(n0=1.0003, alpha=2e-5), 1e-3),
    "hot_road": (refracta.PhysicalAtmosphere(surface_dt=12.0, surface_depth=0.08), 1e-5),
    "inversion": (
        refracta.PhysicalAtmosphere(
            inversion_dt=5, inversion_base=10, inversion_thickness=20, humidity=0.6, wavelength=470.0
        ),
        1e-2,
    ),
    "sounding": (
        refracta.TemperatureProfile(
            [0.0, 0.05, 0.2, 1.0, 5.0, 30.0], [305.0, 297.0, 292.0, 290.0, 289.5, 291.0], humidity=0.3
        ),
        1e-6,
    ),
}


@pytest.mark.parametrize("name", sorted(FIELDS))
def test_analytic_gradient_matches_central_differences(name):
    field, step = FIELDS[name]
    heights = np.array([0.01, 0.07, 0.15, 0.4, 1.2, 2.9, 7.0, 18.0, 26.0, 45.0])
    points = np.stack([np.linspace(-3, 3, heights.size), heights, np.linspace(2, -1, heights.size)], axis=1)
    analytic = field.grad_ior(points)
    numeric = central_gradient(field, points, step)
    scale = np.abs(analytic[:, 1]).max()
    # GRADIENT_RTOL (derived above); 1e-15 absolute where the gradient is 0.
    np.testing.assert_allclose(analytic, numeric, rtol=0, atol=GRADIENT_RTOL * scale + 1e-15)
    assert np.all(analytic[:, [0, 2]] == 0.0)
    assert field.height_only


def test_logistic_profile_matches_the_editor_formula():
    params = dict(n_bg=3, n_inv=0.1, n_hot=0.1, h_ciso=1, a_bg=1, a_inv=1, a_hot=1, k_s=10)
    field = refracta.LogisticProfile(**params)
    h = np.linspace(-5, 20, 51)
    points = np.stack([np.zeros_like(h), h, np.zeros_like(h)], axis=1)
    # The same logistic formula in numpy and C++: double rounding.
    np.testing.assert_allclose(field.ior(points), logistic_reference(h, **params), rtol=1e-15, atol=1e-15)


def test_logistic_profile_does_not_overflow_far_from_its_steps():
    field = refracta.LogisticProfile()
    far = np.array([[0, 1e6, 0], [0, -1e6, 0], [0, 1e300, 0]])
    n = field.ior(far)
    assert np.all(np.isfinite(n)) and np.all(np.isfinite(field.grad_ior(far)))
    # Far above every step all three logistic terms are saturated at their amplitude except the
    # inversion term (negative width): n -> 1 + 0.003 k_s (n_bg + n_hot) / sum |n|.
    assert n[0] == pytest.approx(1 + 0.003 * 10 * (3 + 0.1) / 3.2, rel=1e-12)


def test_logistic_common_amplitude_scale_is_a_gauge_freedom():
    field = refracta.LogisticProfile()
    scaled = field.with_params(n_bg=3 * 7.5, n_inv=0.1 * 7.5, n_hot=0.1 * 7.5)
    points = np.stack([np.zeros(9), np.linspace(-2, 6, 9), np.zeros(9)], axis=1)
    # The gauge scaling is exact up to double rounding.
    np.testing.assert_allclose(scaled.ior(points), field.ior(points), rtol=1e-15)
    assert field.gauge_params == ["n_bg"]


def test_linear_squared_profile_formula():
    field = refracta.LinearSquaredProfile(1.0002, 3e-5)
    y = np.array([-2.0, 0.0, 7.0])
    # The same closed form in numpy and C++: double rounding.
    np.testing.assert_allclose(field.ior(np.stack([0 * y, y, 0 * y], 1)), np.sqrt(1.0002**2 + 3e-5 * y), rtol=1e-15)


def test_temperature_profile_reproduces_a_physical_atmosphere():
    physical = refracta.PhysicalAtmosphere(
        surface_dt=6.0, surface_depth=0.3, inversion_dt=3, inversion_base=40, inversion_thickness=30
    )
    heights = np.concatenate([np.linspace(0.0, 3.0, 400), np.linspace(3.05, 150.0, 600)])
    sounding = refracta.TemperatureProfile(heights, physical.temperature(heights))
    probe = np.array([0.013, 0.21, 0.77, 2.2, 12.0, 45.0, 55.0, 120.0])
    points = np.stack([0 * probe, probe, 0 * probe], 1)
    # pchip on a 7.5 mm / 25 cm grid: temperatures to ~1e-4 K -> n to ~1e-10.
    np.testing.assert_allclose(sounding.temperature(probe), physical.temperature(probe), atol=2e-3)
    # 30x the ~1e-10 the pchip temperature error gives n (comment above).
    np.testing.assert_allclose(sounding.ior(points), physical.ior(points), atol=3e-9)


def test_temperature_profile_is_monotone_between_samples():
    sounding = refracta.TemperatureProfile([0, 1, 2, 3], [300, 290, 290, 295])
    h = np.linspace(0, 3, 301)
    t = sounding.temperature(h)
    assert np.all(np.diff(t[:101]) <= 1e-12) and np.all(np.abs(t[100:201] - 290) < 1e-12)
    assert np.all(np.diff(t[200:]) >= -1e-12)


def test_custom_field_reproduces_a_builtin_model():
    builtin = refracta.LinearSquaredProfile(1.0003, 4e-5)
    custom = refracta.CustomField(
        lambda p: np.sqrt(1.0003**2 + 4e-5 * p[:, 1]),
        lambda p: np.stack([0 * p[:, 0], 4e-5 / (2 * np.sqrt(1.0003**2 + 4e-5 * p[:, 1])), 0 * p[:, 0]], 1),
        height_only=True,
    )
    points = np.array([[0, 1.5, 0], [3, 20, -1]], dtype=float)
    # The same closed form in numpy and C++: double rounding.
    np.testing.assert_allclose(custom.ior(points), builtin.ior(points), rtol=1e-15)
    for method in ("rk45", "stratified"):
        a = refracta.trace_ray(builtin, [0, 1.5, 0], [1, -0.002, 0.3], trace=method, max_length=300)
        b = refracta.trace_ray(custom, [0, 1.5, 0], [1, -0.002, 0.3], trace=method, max_length=300)
        # Identical n and gradient, so the same steps: only rounding in the callback's arithmetic.
        np.testing.assert_allclose(b.points, a.points, rtol=0, atol=1e-12)


def test_parameters_bounds_and_with_params():
    field = refracta.PhysicalAtmosphere(surface_dt=4.0)
    assert field.params["surface_dt"] == 4.0 and field.params["t_ground"] == 288.15
    assert field.param_names[0] == "t_ground" and len(field.param_names) == 10
    low, high = field.bounds["surface_depth"]
    assert 0 < low < 0.1 < high  # the bounds enclose the default depth 0.1 m (any positive lower bound)
    hotter = field.with_params(surface_dt=9.0)
    assert isinstance(hotter, refracta.PhysicalAtmosphere)
    assert hotter.params["surface_dt"] == 9.0 and field.params["surface_dt"] == 4.0
    assert "surface_dt=9" in repr(hotter)
    sounding = refracta.TemperatureProfile([0, 10], [290, 289])
    assert sounding.param_names == ["t0", "t1", "pressure", "humidity", "wavelength"]
    assert sounding.with_params(t1=280.0).temperature(10.0) == pytest.approx(280.0)
    info = refracta.LogisticProfile().param_info
    assert info[0]["name"] == "n_bg" and info[0]["default"] == 3.0


@pytest.mark.parametrize(
    "make, message",
    [
        (lambda: refracta.LogisticProfile(a_bg=-1), "a_bg must be >= 1e-06 m"),
        (lambda: refracta.LogisticProfile(a_hot=1e-300), "a_hot must be >= 1e-06 m"),
        (lambda: refracta.LogisticProfile(n_bg=0, n_inv=0, n_hot=0), "amplitude"),
        (lambda: refracta.LogisticProfile(k_s=400), "k_s"),
        (lambda: refracta.LogisticProfile(bogus=1), "unknown parameter 'bogus'"),
        (lambda: refracta.LogisticProfile(3.0, "a"), "positional parameter 2 must be a number"),
        (lambda: refracta.LogisticProfile(k_s="a"), "k_s must be a number"),
        (lambda: refracta.LogisticProfile(3.0, n_bg=1.0), "'n_bg' given twice"),
        (lambda: refracta.LogisticProfile(*[1.0] * 9), "at most 8 positional parameters"),
        (lambda: refracta.LogisticProfile().with_params(n_bgg=1), "unknown parameter 'n_bgg'"),
        (lambda: refracta.LinearSquaredProfile(n0=-1), "n0 must be > 0"),
        (lambda: refracta.PhysicalAtmosphere(surface_depth=0), "surface_depth"),
        (lambda: refracta.PhysicalAtmosphere(t_ground=float("nan")), "t_ground must be finite"),
        (lambda: refracta.PhysicalAtmosphere(surface_dt=-300), "temperature"),
        (lambda: refracta.PhysicalAtmosphere(humidity=2), "humidity"),
        (lambda: refracta.TemperatureProfile([0, 0], [290, 289]), "strictly increasing"),
        (lambda: refracta.TemperatureProfile([0, 1, 2], [290, 289]), "same length"),
        (lambda: refracta.TemperatureProfile([0, 1], [290, -1]), r"temperatures\[1\]"),
        (lambda: refracta.TemperatureProfile([0], [290]), "at least 2"),
        (lambda: refracta.CustomField(1.0, lambda p: p), "callable"),
    ],
)
def test_bad_parameters_raise_value_errors_naming_them(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_bad_points_raise_value_errors():
    field = refracta.PhysicalAtmosphere()
    with pytest.raises(ValueError, match="finite"):
        field.ior([0.0, float("nan"), 0.0])
    with pytest.raises(ValueError, match=r"shape \(N, 3\)"):
        field.ior(np.zeros((4, 2)))
    with pytest.raises(refracta.NumericalError, match="below the modelled range"):
        field.ior([0.0, -5000.0, 0.0])


def test_undefined_index_raises_numerical_error():
    field = refracta.LinearSquaredProfile(n0=1.0, alpha=-0.01)  # n^2 <= 0 above y = 100
    with pytest.raises(refracta.NumericalError, match="n must be finite and > 0"):
        field.ior([0.0, 150.0, 0.0])


def test_custom_field_with_wrong_output_shape_is_reported():
    field = refracta.CustomField(lambda p: np.ones((len(p), 2)), lambda p: np.zeros_like(p))
    with pytest.raises(ValueError, match="ior returned"):
        refracta.trace_ray(field, [0, 1, 0], [1, 0, 0], max_length=10)
    assert not field.height_only
    with pytest.raises(ValueError, match="height only"):
        refracta.trace_ray(field, [0, 1, 0], [1, 0, 0], trace="stratified", max_length=10)
