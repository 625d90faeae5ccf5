// Spectral colour over many colours and wavelengths at once (spectrum_batch.h).
#include "refracta/shading/spectrum_batch.h"

#include "refracta/core/error.h"

#include <algorithm>
#include <chrono>
#include <random>

namespace refracta {

Color::Kind color_kind_from(const std::string& name) {
  if (name == "reflectance") return Color::Kind::kReflectance;
  if (name == "unbounded") return Color::Kind::kUnbounded;
  if (name == "illuminant") return Color::Kind::kIlluminant;
  throw_invalid("kind must be 'reflectance', 'unbounded' or 'illuminant' (got '", name, "')");
}

namespace spectral {

namespace {

// The table's coefficients of a reflectance, which must lie in [0, 1] (the table clamps).
Coefficients table_coefficients(const Vec3d& rgb, const char* range_message) {
  for (int d = 0; d < 3; ++d) {
    if (!(rgb[d] >= 0.0 && rgb[d] <= 1.0)) throw_invalid(range_message, " (got ", rgb[d], ")");
  }
  return rgb_to_spectrum_table().coefficients(rgb);
}

Color color_of(const Vec3d& rgb, Color::Kind kind) {
  if (kind == Color::Kind::kReflectance) return Color::reflectance(rgb);
  return kind == Color::Kind::kUnbounded ? Color::unbounded(rgb) : Color::illuminant(rgb);
}

}  // namespace

Upsampling upsampling_from(const std::string& name) {
  if (name == "fit") return Upsampling::kFit;
  if (name == "table") return Upsampling::kTable;
  throw_invalid("method must be 'fit' or 'table' (got '", name, "')");
}

RowMatrixXd rgb_to_spectrum(const std::vector<Vec3d>& rgb, const std::vector<double>& lambda_nm, Color::Kind kind,
                            Upsampling method) {
  if (method == Upsampling::kTable && kind != Color::Kind::kReflectance) {
    throw_invalid("method='table' serves reflectances only");
  }
  RowMatrixXd out(rgb.size(), lambda_nm.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    if (method == Upsampling::kTable) {
      const Coefficients c = table_coefficients(rgb[i], "rgb must be in [0, 1] for a reflectance");
      for (size_t j = 0; j < lambda_nm.size(); ++j) {
        const double l = lambda_nm[j];
        out(i, j) = l >= kLambdaMin && l <= kLambdaMax ? sigmoid_polynomial(c, l) : 0.0;
      }
    } else {
      const Color color = color_of(rgb[i], kind);
      for (size_t j = 0; j < lambda_nm.size(); ++j) out(i, j) = color.evaluate(lambda_nm[j]);
    }
  }
  return out;
}

RowMatrixX4d reflectance_coefficients(const std::vector<Vec3d>& rgb, Upsampling method) {
  RowMatrixX4d out(rgb.size(), 4);
  for (size_t i = 0; i < rgb.size(); ++i) {
    FitResult fit;
    if (method == Upsampling::kTable) {
      fit.c = table_coefficients(rgb[i], "rgb must be in [0, 1]");
    } else {
      fit = fit_reflectance_robust(rgb[i]);
    }
    out.row(i) << fit.c[0], fit.c[1], fit.c[2], fit.residual;
  }
  return out;
}

Eigen::VectorXd blackbody(double temperature, const std::vector<double>& lambda_nm, std::optional<double> luminance) {
  if (!luminance) return at_each(lambda_nm, [&](double l) { return planck(l, temperature); });
  const Color c = Color::blackbody(temperature, *luminance);
  return at_each(lambda_nm, [&](double l) { return c.evaluate(l); });
}

RowMatrixX3d cie_xyz(const std::vector<double>& lambda_nm) {
  RowMatrixX3d out(lambda_nm.size(), 3);
  for (size_t i = 0; i < lambda_nm.size(); ++i) out.row(i) = cie_xyz(lambda_nm[i]).transpose();
  return out;
}

Eigen::VectorXd d65(const std::vector<double>& lambda_nm, bool normalised) {
  return at_each(lambda_nm, [&](double l) { return normalised ? d65_normalised(l) : d65(l); });
}

RowMatrixX3d xyz_to_linear_srgb(const std::vector<Vec3d>& xyz) {
  RowMatrixX3d out(xyz.size(), 3);
  for (size_t i = 0; i < xyz.size(); ++i) out.row(i) = xyz_to_linear_srgb(xyz[i]).transpose();
  return out;
}

std::pair<RowMatrixX4d, RowMatrixX4d> sample_wavelengths(const std::vector<double>& u, bool terminate_secondary) {
  RowMatrixX4d lambda(u.size(), 4), pdf(u.size(), 4);
  for (size_t i = 0; i < u.size(); ++i) {
    if (!(u[i] >= 0.0 && u[i] < 1.0)) throw_invalid("u must be in [0, 1) (got ", u[i], ")");
    SampledWavelengths w = SampledWavelengths::sample_uniform(u[i]);
    if (terminate_secondary) w.terminate_secondary();
    lambda.row(i) = w.lambda.matrix().transpose();
    pdf.row(i) = w.pdf.matrix().transpose();
  }
  return {lambda, pdf};
}

RowMatrixX3d to_linear_srgb(const RowMatrixX4d& radiance, const RowMatrixX4d& lambda_nm, const RowMatrixX4d& pdf) {
  if (lambda_nm.rows() != radiance.rows() || pdf.rows() != radiance.rows()) {
    throw_invalid("radiance, wavelengths and pdf must have the same shape (N, 4)");
  }
  if (!((pdf.array() >= 0.0).all() && pdf.allFinite())) {
    throw_invalid("pdf must be finite and >= 0 [1/nm] (0: a terminated wavelength)");
  }
  RowMatrixX3d out(radiance.rows(), 3);
  for (Eigen::Index i = 0; i < radiance.rows(); ++i) {
    SampledWavelengths w;
    w.spectral = true;
    w.lambda = lambda_nm.row(i).transpose().array();
    w.pdf = pdf.row(i).transpose().array();
    out.row(i) = refracta::to_linear_srgb(Spectrum(radiance.row(i).transpose().array()), w).transpose();
  }
  return out;
}

TableMeasurement measure_table(int resolution, int quadrature_step_nm, int polish_steps, int samples, unsigned seed) {
  const RgbToSpectrumTable table(resolution, quadrature_step_nm, polish_steps);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Vec3d> colours(std::max(samples, 0));
  for (Vec3d& c : colours) c = Vec3d(uniform(rng), uniform(rng), uniform(rng));
  // Lookups timed apart from the round trip; the sum keeps the compiler from dropping them.
  const auto start = std::chrono::steady_clock::now();
  double sink = 0.0;
  for (const Vec3d& c : colours) sink += table.coefficients(c)[2];
  const double lookup = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  TableMeasurement out;
  double sum = 0.0;
  std::vector<double> s(kTableSamples);
  for (const Vec3d& rgb : colours) {
    const Coefficients c = table.coefficients(rgb);
    for (int i = 0; i < kTableSamples; ++i) s[i] = sigmoid_polynomial(c, kTableMin + i);
    const double e = (xyz_to_linear_srgb(xyz_of_reflectance(s)) - rgb).cwiseAbs().maxCoeff();
    out.max_error = std::max(out.max_error, e);
    sum += e;
  }
  out.build_seconds = table.build_seconds();
  out.mean_error = sum / std::max(samples, 1);
  out.worst_fit_residual = table.worst_fit_residual();
  out.lookup_seconds = lookup / std::max(samples, 1) + 0.0 * sink;
  return out;
}

}  // namespace spectral

}  // namespace refracta
