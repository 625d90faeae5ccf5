// Spectral colour over many colours and wavelengths at once: the batch forms of spectral.h and
// color.h that the Python module refracta.spectrum exposes (a row per colour, a column per
// wavelength [nm]), with their names parsed once into enums and their inputs checked here.
#pragma once

#include "refracta/shading/batch.h"
#include "refracta/shading/color.h"
#include "refracta/shading/spectral.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace refracta {

// 'reflectance', 'unbounded' or 'illuminant'; std::invalid_argument naming `kind` otherwise.
Color::Kind color_kind_from(const std::string& name);

namespace spectral {

// How a reflectance RGB becomes coefficients: a Gauss-Newton fit per colour (Color::reflectance)
// or the coefficient table textures use at render time (reflectances only, rgb in [0, 1]).
enum class Upsampling { kFit, kTable };
Upsampling upsampling_from(const std::string& name);  // 'fit' or 'table'

// The spectrum of each colour at each wavelength: (colours, wavelengths).
RowMatrixXd rgb_to_spectrum(const std::vector<Vec3d>& rgb, const std::vector<double>& lambda_nm, Color::Kind kind,
                            Upsampling method);
// Each reflectance's coefficients and the fit's CIELAB residual (0 from the table): (colours, 4).
RowMatrixX4d reflectance_coefficients(const std::vector<Vec3d>& rgb, Upsampling method);
// Planck's law at each wavelength; with a luminance, Color::blackbody's spectrum of that Y.
Eigen::VectorXd blackbody(double temperature, const std::vector<double>& lambda_nm, std::optional<double> luminance);
RowMatrixX3d cie_xyz(const std::vector<double>& lambda_nm);  // (wavelengths, 3)
Eigen::VectorXd d65(const std::vector<double>& lambda_nm, bool normalised);
RowMatrixX3d xyz_to_linear_srgb(const std::vector<Vec3d>& xyz);
// SampledWavelengths::sample_uniform at each u in [0, 1) (terminated: the hero only): (lambda, pdf).
std::pair<RowMatrixX4d, RowMatrixX4d> sample_wavelengths(const std::vector<double>& u, bool terminate_secondary);
// to_linear_srgb (color.h) of each row of four radiance samples at its wavelengths and pdfs.
RowMatrixX3d to_linear_srgb(const RowMatrixX4d& radiance, const RowMatrixX4d& lambda_nm, const RowMatrixX4d& pdf);

// A coefficient table built with these settings, measured over `samples` random colours (seeded):
// the numbers behind kTableResolution and kTableQuadratureStep (color.cpp).
struct TableMeasurement {
  double build_seconds = 0.0;
  double max_error = 0.0;   // of the round trip RGB -> spectrum -> RGB
  double mean_error = 0.0;
  double worst_fit_residual = 0.0;  // CIELAB Delta E over the table's nodes
  double lookup_seconds = 0.0;  // per lookup
};
TableMeasurement measure_table(int resolution, int quadrature_step_nm, int polish_steps, int samples, unsigned seed);

}  // namespace spectral

}  // namespace refracta
