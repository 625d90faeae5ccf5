// The Water material: its validated parameters, tables and BSDFs (water_surface.h).
#include "refracta/shading/water_surface.h"

#include "refracta/shading/thin_film.h"
#include "refracta/shading/water.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

namespace refracta {

namespace {

// The index every 1 nm over [kLambdaMin, kLambdaMax]: linear interpolation between nodes errs by
// < 1e-8 (its second derivative is ~1e-7 per nm^2 in the visible).
constexpr double kTableStep = 1.0;  // [nm]
constexpr size_t kTableSize = size_t((kLambdaMax - kLambdaMin) / kTableStep) + 1;

// The transmittance quadrature: midpoints of an n x n grid over the proposal's unit square.
constexpr int kQuadrature = 64;

}  // namespace

RoughTransmittance::EtaTable::EtaTable(const Beckmann& distribution, double lo, double hi, int nodes)
    : lo(lo), hi(hi), nodes(nodes), t(size_t(kMu) * size_t(nodes), 0.0), hemispherical(size_t(nodes), 0.0) {
  // mu = 0 exactly is the proposal's degenerate direction: its grazing limit, from this mu.
  constexpr double kGrazingMu = 1e-7;
  for (int k = 0; k < nodes; ++k) {
    const double eta = lo + (hi - lo) * k / (nodes - 1);
    const WaterInterfaceBsdf interface(Spectrum::Constant(eta), eta, distribution);
    for (int j = 0; j < kMu; ++j) {
      const double mu = std::max(mu_node(j), kGrazingMu);
      const Vec3d wo(std::sqrt(std::max(0.0, 1.0 - mu * mu)), 0.0, mu);
      double sum = 0.0;
      for (int a = 0; a < kQuadrature; ++a) {
        for (int b = 0; b < kQuadrature; ++b) {
          const auto m = distribution.sample_wm(wo, Vec2d((a + 0.5) / kQuadrature, (b + 0.5) / kQuadrature));
          double etap;
          Vec3d wi;
          if (!m || !refract(wo, *m, eta, &etap, &wi) || !(wi.z() < 0.0)) continue;
          // The density of wi when every proposed normal refracts (no lobe choice).
          const double denominator = wi.dot(*m) + wo.dot(*m) / etap;
          const double pdf = distribution.sampling_pdf(wo, *m) * std::abs(wi.dot(*m)) / (denominator * denominator);
          if (pdf > 0.0) sum += interface.transmission(wo, wi, eta, TransportMode::kImportance) * std::abs(wi.z()) / pdf;
        }
      }
      t[size_t(k) * kMu + size_t(j)] = sum / (kQuadrature * kQuadrature);
    }
    double h = 0.0;  // 2 int T mu dmu, trapezoidal over the mu nodes
    for (int j = 1; j < kMu; ++j) {
      const double mu0 = mu_node(j - 1), mu1 = mu_node(j);
      h += (t[size_t(k) * kMu + size_t(j - 1)] * mu0 + t[size_t(k) * kMu + size_t(j)] * mu1) * (mu1 - mu0);
    }
    hemispherical[size_t(k)] = h;
  }
}

double RoughTransmittance::EtaTable::node(double eta, int* k) const {
  const double x = std::clamp((eta - lo) / (hi - lo) * (nodes - 1), 0.0, double(nodes - 1));
  *k = std::min(int(x), nodes - 2);
  return x - *k;
}

RoughTransmittance::RoughTransmittance(const Beckmann& distribution)
    : distribution_(distribution), near_(distribution, kNearLo, kNearHi, kNearNodes) {}

const RoughTransmittance::EtaTable& RoughTransmittance::table_for(double eta) const {
  if (near_.covers(eta)) return near_;
  std::call_once(wide_built_, [this] { wide_ = EtaTable(distribution_, kWideLo, kWideHi, kWideNodes); });
  return wide_;
}

std::shared_ptr<const RoughTransmittance> RoughTransmittance::for_alpha(double alpha) {
  static std::mutex mutex;
  static std::map<double, std::shared_ptr<const RoughTransmittance>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  auto& table = tables[alpha];
  if (!table) table = std::make_shared<RoughTransmittance>(Beckmann(alpha));
  return table;
}

double RoughTransmittance::operator()(double mu, double eta) const {
  const EtaTable& table = table_for(eta);
  int k;
  const double we = table.node(eta, &k);
  const double x = std::sqrt(std::clamp(std::abs(mu), 0.0, 1.0)) * (kMu - 1);
  const int j = std::min(int(x), kMu - 2);
  const double wm = x - j;
  auto at = [&](int kk) {
    const size_t row = size_t(kk) * kMu + size_t(j);
    return (1.0 - wm) * table.t[row] + wm * table.t[row + 1];
  };
  return (1.0 - we) * at(k) + we * at(k + 1);
}

double RoughTransmittance::hemispherical(double eta) const {
  const EtaTable& table = table_for(eta);
  int k;
  const double w = table.node(eta, &k);
  return (1.0 - w) * table.hemispherical[size_t(k)] + w * table.hemispherical[size_t(k) + 1];
}

Water::Water(const WaterParameters& parameters) : parameters_(parameters) {
  check_water_range("Water", "wind_speed", parameters.wind_speed, 0.0, kWaterMaxWindSpeed, "m/s");
  check_water_range("Water", "temperature_c", parameters.temperature_c, kWaterMinCelsius, kWaterMaxCelsius, "deg C");
  check_water_range("Water", "salinity", parameters.salinity, 0.0, kWaterMaxSalinity, "g/kg");
  mean_square_slope_ = cox_munk_mean_square_slope(parameters.wind_speed);
  const double resolved = parameters.resolved_slope_variance;
  if (!std::isfinite(resolved) || resolved < 0.0 || resolved > mean_square_slope_ - kMinUnresolvedSlopeVariance) {
    throw_invalid("Water: resolved_slope_variance must be in [0, ", mean_square_slope_ - kMinUnresolvedSlopeVariance,
                  "] (Cox-Munk's total ", mean_square_slope_, " at wind_speed ", parameters.wind_speed, " less ",
                  kMinUnresolvedSlopeVariance, " kept by the microfacets) (got ", resolved, ")");
  }
  alpha_ = std::sqrt(mean_square_slope_ - resolved);
  ior_table_.resize(kTableSize);
  std::vector<double> lambda(kTableSize), r(kTableSize);
  for (size_t i = 0; i < kTableSize; ++i) {
    lambda[i] = kLambdaMin + double(i) * kTableStep;
    ior_table_[i] = water_ior(lambda[i], parameters.temperature_c, parameters.salinity);
    r[i] = water_body_reflectance(lambda[i], parameters.salinity);
  }
  body_reflectance_ = Color::tabulated(lambda, r, Color::Kind::kReflectance);
  for (int c = 0; c < 3; ++c) ior_rgb_[c] = ior(kRgbWavelengths[c]);
  ior_sampling_rgb_ = ior(Ior::kRgbWavelength);
  transmittance_ = RoughTransmittance::for_alpha(alpha_);
}

double Water::interpolate(const std::vector<double>& table, double wavelength_nm) {
  const double x = std::clamp((wavelength_nm - kLambdaMin) / kTableStep, 0.0, double(table.size() - 1));
  const size_t i = std::min(size_t(x), table.size() - 2);
  const double t = x - double(i);
  return (1.0 - t) * table[i] + t * table[i + 1];
}

const Bsdf* Water::bsdf(const SurfaceInteraction&, const MaterialContext& context, ScratchBuffer& scratch) const {
  const SampledWavelengths& lambda = *context.lambda;
  Spectrum eta;
  double eta_sampling;
  if (lambda.spectral) {
    for (int i = 0; i < kSpectrumSamples; ++i) eta[i] = ior(lambda.lambda[i]) / context.eta_outside;
    eta_sampling = eta[0];
  } else {
    eta_sampling = ior_sampling_rgb_ / context.eta_outside;
    eta << ior_rgb_ / context.eta_outside, eta_sampling;  // channel 3 is unused
  }
  const Beckmann distribution(alpha_);
  if (!parameters_.body) return scratch.make<WaterInterfaceBsdf>(eta, eta_sampling, distribution);
  // The rough interface's internal diffuse reflectance: what of isotropic light from below does not cross.
  Spectrum fdr;
  for (int c = 0; c < kSpectrumSamples; ++c) fdr[c] = 1.0 - transmittance_->hemispherical(eta[c]) / (eta[c] * eta[c]);
  // A saturated blue spectrum's linear sRGB can fall just below 0 in red: clamped.
  const Spectrum r = body_reflectance_.sample(lambda).max(0.0);
  const Spectrum body_albedo = r * (1.0 - fdr) / (1.0 - r * fdr);
  return scratch.make<WaterBodyBsdf>(eta, eta_sampling, distribution, *transmittance_, r, fdr, channel_mean(body_albedo, lambda));
}

double Water::transmittance(double mu, double wavelength_nm) const {
  const double eta = ior(checked_wavelength(wavelength_nm, "Water.transmittance: wavelength_nm"));
  if (!(std::abs(mu) <= 1.0)) throw_invalid("Water.transmittance: mu must be in [-1, 1] (got ", mu, ")");
  return (*transmittance_)(mu, eta);
}

double Water::internal_reflectance(double wavelength_nm) const {
  const double eta = ior(checked_wavelength(wavelength_nm, "Water.internal_reflectance: wavelength_nm"));
  return 1.0 - transmittance_->hemispherical(eta) / (eta * eta);
}

std::optional<double> Water::interior_ior(const SampledWavelengths& lambda) const {
  if (parameters_.body) return std::nullopt;  // reflection-only: no path enters the body
  return lambda.spectral ? ior(lambda.hero()) : ior_sampling_rgb_;
}

std::string Water::describe() const {
  const WaterParameters& p = parameters_;
  return concat("Water(wind_speed=", exact(p.wind_speed), ", temperature_c=", exact(p.temperature_c),
                ", salinity=", exact(p.salinity), p.body ? "" : ", body=False",
                p.priority ? concat(", priority=", p.priority) : "",
                p.resolved_slope_variance > 0.0 ? concat(", resolved_slope_variance=", exact(p.resolved_slope_variance)) : "",
                ")");
}

}  // namespace refracta
