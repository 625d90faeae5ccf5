// The Water material: its validated parameters, tables and BSDFs (water_surface.h).
#include "refracta/shading/water_surface.h"

#include "refracta/shading/thin_film.h"
#include "refracta/shading/water.h"

#include <algorithm>
#include <cmath>

namespace refracta {

namespace {

// Tables every 1 nm over [kLambdaMin, kLambdaMax]: linear interpolation of the index between
// nodes errs by < 1e-8 (its second derivative is ~1e-7 per nm^2 in the visible).
constexpr double kTableStep = 1.0;  // [nm]
constexpr size_t kTableSize = size_t((kLambdaMax - kLambdaMin) / kTableStep) + 1;

}  // namespace

Water::Water(const WaterParameters& parameters) : parameters_(parameters) {
  alpha_ = std::sqrt(cox_munk_mean_square_slope(parameters.wind_speed));  // checks wind_speed
  // water_ior checks temperature_c and salinity (naming them) on the first node.
  ior_table_.resize(kTableSize);
  fdr_table_.resize(kTableSize);
  std::vector<double> lambda(kTableSize), r(kTableSize);
  for (size_t i = 0; i < kTableSize; ++i) {
    lambda[i] = kLambdaMin + double(i) * kTableStep;
    ior_table_[i] = water_ior(lambda[i], parameters.temperature_c, parameters.salinity);
    fdr_table_[i] = fresnel_diffuse_reflectance(1.0 / ior_table_[i]);
    r[i] = water_body_reflectance(lambda[i], parameters.salinity);
  }
  body_reflectance_ = Color::tabulated(lambda, r, Color::Kind::kReflectance);
  for (int c = 0; c < 3; ++c) {
    ior_rgb_[c] = ior(kRgbWavelengths[c]);
    fdr_rgb_[c] = interpolate(fdr_table_, kRgbWavelengths[c]);
  }
  ior_sampling_rgb_ = ior(Ior::kRgbWavelength);
}

double Water::interpolate(const std::vector<double>& table, double wavelength_nm) {
  const double x = std::clamp((wavelength_nm - kLambdaMin) / kTableStep, 0.0, double(table.size() - 1));
  const size_t i = std::min(size_t(x), table.size() - 2);
  const double t = x - double(i);
  return (1.0 - t) * table[i] + t * table[i + 1];
}

const Bsdf* Water::bsdf(const SurfaceInteraction&, const MaterialContext& context, ScratchBuffer& scratch) const {
  const SampledWavelengths& lambda = *context.lambda;
  Spectrum eta, fdr;
  double eta_sampling;
  if (lambda.spectral) {
    for (int i = 0; i < kSpectrumSamples; ++i) {
      eta[i] = ior(lambda.lambda[i]) / context.eta_outside;
      fdr[i] = interpolate(fdr_table_, lambda.lambda[i]);
    }
    eta_sampling = eta[0];
  } else {
    eta_sampling = ior_sampling_rgb_ / context.eta_outside;
    eta << ior_rgb_ / context.eta_outside, eta_sampling;  // channel 3 is unused
    fdr << fdr_rgb_, fdr_rgb_.y();
  }
  const Beckmann distribution(alpha_);
  if (!parameters_.body) return scratch.make<WaterInterfaceBsdf>(eta, eta_sampling, distribution);
  // The internal diffuse reflectance is the table's, for water under vacuum: the air's n - 1 ~ 3e-4
  // changes it by < 1e-4.
  // A saturated blue spectrum's linear sRGB can fall just below 0 in red: clamped.
  const Spectrum r = body_reflectance_.sample(lambda).max(0.0);
  const Spectrum body_albedo = r * (1.0 - fdr) / (1.0 - r * fdr);
  return scratch.make<WaterBodyBsdf>(eta, eta_sampling, distribution, r, fdr, channel_mean(body_albedo, lambda));
}

std::optional<double> Water::interior_ior(const SampledWavelengths& lambda) const {
  if (parameters_.body) return std::nullopt;  // reflection-only: no path enters the body
  return lambda.spectral ? ior(lambda.hero()) : ior_sampling_rgb_;
}

std::string Water::describe() const {
  const WaterParameters& p = parameters_;
  return concat("Water(wind_speed=", p.wind_speed, ", temperature_c=", p.temperature_c, ", salinity=", p.salinity,
                p.body ? "" : ", body=False", p.priority ? concat(", priority=", p.priority) : "", ")");
}

}  // namespace refracta
