"""Spectral colour: RGB <-> spectra, black bodies, the CIE 1931 observer, and the physical sky.

PhysicalSky(sun_direction, aerosol=None (1: a clear sky), ozone_du=300, ground_albedo=0, altitude=0,
rayleigh_scale=1, below_horizon='ground' (the Lambertian ground) or 'horizon' (the horizon's
radiance at the same azimuth, sampled over the whole sphere)): radiance(dirs (N, 3) unit,
wavelengths (M,)) -> (N, M) [W/(m^2 sr nm)]
(direct=True integrates without the table), rgb_radiance(dirs) -> (N, 3) linear sRGB in the
same per-nm normalisation as the renderer (Y = integral(L y)/integral(y)), sun_transmittance,
sun_radiance(wavelengths, angular_diameter_deg=0.53), sun_radiance_rgb, solar_irradiance,
rayleigh_optical_depth(wavelength), optical_depth, sample_li(u (N, 2)) -> (dirs, pdf, rgb),
pdf_li(dirs) (per steradian), power() [W-like luminance, pi R^2 integral of Y], preprocess;
visibility [km] instead of aerosol sets the aerosol from Koschmieder's law (3.912 / V at 550 nm).

AerialPerspective(sky, scale=1): the same air along a segment from a viewer at a to a point b:
along(a, b, wavelength) -> (transmittance, in-scatter [W/(m^2 sr nm)]), along_rgb(a, b) -> the
RGB pair renders apply, inscatter_reference (brute-force quadrature), sun_transmittance(height,
elevation_deg, wavelength). Scene.set_physical_sky(aerial_perspective=True) applies it to every
segment the renderers cast.

Thin vectorised wrappers of refracta's C++ colour code (cpp/refracta/shading/color.h,
spectral.h, physical_sky.h), the same functions spectral rendering uses. Conventions:

- Wavelengths in nanometres; the tables cover [360, 830] nm and spectra are 0 outside.
- Linear sRGB (IEC 61966-2-1 primaries, D65 white), not gamma-encoded.
- Reflectances upsample by Jakob & Hanika 2019 ("A Low-Dimensional Function Space for Efficient
  Spectral Upsampling", CGF 38(2)): s(lambda) = 1/2 + x/(2 sqrt(1 + x^2)), x a quadratic in the
  wavelength, fitted so that the spectrum's colour under D65 is the RGB (CIELAB difference).
- A radiance spectrum's XYZ is integral(L cmf) / integral(y): a spectrum of 1 has Y = 1. A
  reflectance's XYZ is taken under D65, normalised so that white has Y = 1.
- Emission RGB is RGB x D65 scaled to Y = 1 (d65(normalised=True)): (1, 1, 1) is sRGB white.

Example::

    from refracta import spectrum
    lam = np.arange(360.0, 831.0)
    s = spectrum.rgb_to_spectrum([0.8, 0.3, 0.1], lam)       # (471,) reflectance in [0, 1]
    spectrum.spectrum_to_rgb(lam, s, kind="reflectance")     # ~ (0.8, 0.3, 0.1): seen under D65
"""

from __future__ import annotations

import numpy as np

from refracta import _core
from refracta._checks import flag, number, real_array

PhysicalSky = _core.PhysicalSky  # documented in C++ (physical_sky.h): see help(PhysicalSky)
AerialPerspective = _core.AerialPerspective  # documented in C++ (aerial_perspective.h)

__all__ = [
    "AerialPerspective",
    "LAMBDA_MAX",
    "PhysicalSky",
    "LAMBDA_MIN",
    "blackbody",
    "cie_xyz",
    "cie_y_integral",
    "d65",
    "rgb_to_spectrum",
    "spectrum_to_rgb",
    "to_linear_srgb",
    "sample_wavelengths",
    "xyz_to_linear_srgb",
]

LAMBDA_MIN = 360.0  # [nm] the range spectral rendering samples and the CIE tables cover
LAMBDA_MAX = 830.0  # [nm]


def _wavelengths(wavelengths) -> tuple[np.ndarray, bool]:
    try:  # strings ('500'), booleans and complex numbers refused, as numpy would read them
        lam = real_array(wavelengths, "wavelengths")
    except ValueError:
        raise ValueError(f"wavelengths must be a number or numbers [nm] (got {wavelengths!r})") from None
    if lam.ndim > 1:
        raise ValueError(f"wavelengths must be a number or a 1-D array (got shape {lam.shape})")
    return np.atleast_1d(lam), lam.ndim == 0


def _rgb(rgb, what: str = "rgb") -> tuple[np.ndarray, bool]:
    try:
        colours = real_array(rgb, what)
    except ValueError:
        raise ValueError(f"{what} must be numbers, shape (3,) or (N, 3) (got {rgb!r})") from None
    if colours.shape[-1:] != (3,) or colours.ndim > 2:
        raise ValueError(f"{what} must have shape (3,) or (N, 3) (got {colours.shape})")
    return np.atleast_2d(colours), colours.ndim == 1


def rgb_to_spectrum(rgb, wavelengths, kind: str = "reflectance", method: str = "fit") -> np.ndarray:
    """The spectrum of linear sRGB colour(s) at the given wavelengths [nm].

    rgb: (3,) or (N, 3). wavelengths: scalar or (M,). Returns (M,) or (N, M) (a scalar
    wavelength drops that axis). kind: 'reflectance' (rgb in [0, 1]; values in [0, 1]),
    'unbounded' (rgb >= 0: scale 2 max(rgb) times the fit of rgb/scale, pbrt-v4's
    RGBUnboundedSpectrum) or 'illuminant' (unbounded x D65 normalised to Y = 1, in the units of
    the RGB radiance per nm of 1/integral(y)). method: 'fit' (a Gauss-Newton fit per colour, as
    Color::reflectance) or 'table' (reflectances only: the coefficient table textures use at
    render time). Raises ValueError for colours out of range or non-finite input. The inverse is
    spectrum_to_rgb with the same kind: its default is 'illuminant' (a tabulated spectrum is
    usually a light), this one's 'reflectance' (a colour is usually a surface's), so a round trip
    names kind= (with the defaults (0.8, 0.3, 0.1) comes back (0.92, 0.29, 0.09)).
    """
    colours, single = _rgb(rgb)
    lam, scalar = _wavelengths(wavelengths)
    out = _core._spectrum_rgb_to_spectrum(colours, lam, kind, method)
    if not np.all(np.isfinite(out)):  # the input is finite (C++ checks it): [1e308, 1, 1] gave NaN
        raise ValueError(
            f"rgb_to_spectrum: rgb up to {np.abs(colours).max():g} overflows float64 in the {kind} spectrum "
            "(an unbounded or illuminant spectrum is 2 max(rgb) times the fit of rgb / (2 max(rgb)))"
        )
    if scalar:
        out = out[:, 0]
    return out[0] if single else out


def spectrum_to_rgb(wavelengths, values, kind: str = "illuminant") -> np.ndarray:
    """Linear sRGB (3,) of a tabulated spectrum: values (M,) at increasing wavelengths (M,) [nm].

    The spectrum is linearly interpolated to 1 nm over [360, 830] (0 outside the samples) and
    integrated against the CIE 1931 2-degree functions. kind='illuminant': a radiance,
    XYZ = integral(L cmf)/integral(y); 'reflectance' (values in [0, 1]) or 'unbounded' (>= 0):
    under D65, XYZ = integral(s cmf D65)/integral(y D65). XYZ -> sRGB by the IEC 61966-2-1 matrix.
    The inverse of rgb_to_spectrum with the same kind (whose default is 'reflectance': give kind=).
    """
    lam, _ = _wavelengths(wavelengths)
    v = real_array(values, "values")
    if v.shape != lam.shape:
        raise ValueError(f"values must have the shape of wavelengths {lam.shape} (got {v.shape})")
    rgb = _core._spectrum_tabulated_to_rgb(lam, v, kind)
    if np.all(np.isfinite(v)) and not np.all(np.isfinite(rgb)):  # 1e307 W/(m^2 sr nm) summed past float64
        raise ValueError(f"values up to {np.abs(v).max():g} overflow float64 when integrated over wavelength")
    return rgb


def blackbody(temperature: float, wavelengths, luminance: float | None = None) -> np.ndarray:
    """Planck's law at temperature [K]: spectral radiance [W/(m^2 sr nm)] at wavelengths [nm].

    With `luminance`, the spectrum is scaled so that its Y (integral(L y)/integral(y), over
    [360, 830] nm) equals it, as Color::blackbody; values outside [360, 830] nm are then 0.
    Returns a float or (M,) array like `wavelengths`.
    """
    lam, scalar = _wavelengths(wavelengths)
    temperature = number(temperature, "blackbody: temperature")
    luminance = None if luminance is None else number(luminance, "blackbody: luminance")
    out = _core._spectrum_blackbody(temperature, lam, luminance)
    return out[0] if scalar else out


def cie_xyz(wavelengths) -> np.ndarray:
    """The CIE 1931 2-degree colour-matching functions (x, y, z) at wavelengths [nm]: (3,) or (M, 3).

    From the 1 nm tables (colour-science's CIE data), linearly interpolated, 0 outside [360, 830].
    """
    lam, scalar = _wavelengths(wavelengths)
    out = _core._spectrum_cie_xyz(lam)
    return out[0] if scalar else out


def d65(wavelengths, normalised: bool = False) -> np.ndarray:
    """The CIE D65 spectral power distribution at wavelengths [nm].

    normalised=False: relative, 100 at 560 nm (the CIE table). normalised=True: scaled to Y = 1
    (D65 integral(y) / integral(y D65)), the spectrum of emission RGB (1, 1, 1).
    """
    lam, scalar = _wavelengths(wavelengths)
    out = _core._spectrum_d65(lam, flag(normalised, "d65: normalised"))
    return out[0] if scalar else out


def cie_y_integral() -> float:
    """integral y(lambda) d lambda over the 1 nm table [nm] (trapezoidal rule, ~106.86)."""
    return _core._spectrum_cie_y_integral()


def xyz_to_linear_srgb(xyz) -> np.ndarray:
    """CIE XYZ (3,) or (N, 3) to linear sRGB with the IEC 61966-2-1 matrix."""
    values, single = _rgb(xyz, "xyz")
    out = _core._spectrum_xyz_to_linear_srgb(values)
    if not np.all(np.isfinite(out)):  # the input is finite (C++ checks it): 1e308 gave inf
        raise ValueError(
            f"xyz_to_linear_srgb: xyz up to {np.abs(values).max():g} overflows float64 through the sRGB matrix "
            "(its entries reach 3.2)"
        )
    return out[0] if single else out


def sample_wavelengths(u, terminate_secondary: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Hero-wavelength samples (Wilkie et al. 2014) for u (N,) uniform in [0, 1).

    Returns (wavelengths, pdf), each (N, 4): the hero 360 + 470 u nm and three more rotated by a
    quarter of the range each (wrapping around), pdf 1/470 per nm. terminate_secondary keeps the
    hero only (pdf of the others 0, the hero's divided by 4), as a dispersive interface does.
    """
    uu = np.atleast_1d(real_array(u, "sample_wavelengths: u"))  # not '0.5', True or 0.5 + 1j
    if uu.ndim != 1:
        raise ValueError(f"sample_wavelengths: u must be a number or a 1-D array (got shape {uu.shape})")
    return _core._spectrum_sample_wavelengths(uu, flag(terminate_secondary, "sample_wavelengths: terminate_secondary"))


def to_linear_srgb(radiance, wavelengths, pdf) -> np.ndarray:
    """The renderer's spectral -> linear sRGB estimate, per row of (N, 4) arrays.

    XYZ = (1/4) sum_i L_i cmf(lambda_i) / pdf_i / integral(y), wavelengths of pdf 0 (terminated)
    skipped, then the IEC 61966-2-1 matrix. Returns (N, 3).
    """
    names = ("radiance", "wavelengths", "pdf")
    arrays = [np.atleast_2d(real_array(a, f"to_linear_srgb: {n}")) for a, n in zip((radiance, wavelengths, pdf), names)]
    rgb = _core._spectrum_to_linear_srgb(*arrays)
    if not np.all(np.isfinite(rgb)):  # the inputs are finite (C++ checks them): radiance / pdf overflowed
        radiance_, pdf_ = arrays[0], arrays[2]
        smallest = pdf_[pdf_ > 0.0].min() if np.any(pdf_ > 0.0) else 0.0
        raise ValueError(
            f"to_linear_srgb: radiance / pdf overflows float64 (radiance up to {np.abs(radiance_).max():g}, "
            f"pdf down to {smallest:g} per nm; a hero-wavelength pdf is 1/470)"
        )
    return rgb


def _measure_table(
    resolution: int, quadrature_step_nm: int = 5, polish_steps: int = 2, samples: int = 20000, seed: int = 7
) -> dict:
    """Build an RGB -> coefficient table and measure it (the numbers behind color.cpp's choice).

    Returns build_seconds, max_error and mean_error of the round trip RGB -> spectrum -> RGB over
    `samples` uniform random colours, lookup_seconds per lookup and the worst fit residual
    (CIELAB Delta E) over the table's nodes.
    """
    return _core._spectrum_measure_table(
        int(resolution), int(quadrature_step_nm), int(polish_steps), int(samples), int(seed)
    )
