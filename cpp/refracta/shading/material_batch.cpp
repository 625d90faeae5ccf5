// A material's BSDF evaluated over many directions at once (material_batch.h).
#include "refracta/shading/material_batch.h"

#include "refracta/core/error.h"
#include "refracta/core/scratch.h"
#include "refracta/media/ior_range.h"
#include "refracta/scene/surface_interaction.h"

#include <algorithm>
#include <cmath>

namespace refracta {

namespace {

// Sample numbers in [0, 1) may be 1 - 2^-53; the samplers are written for u < 1 - 1e-16 (a
// float64 rounding of 1 - 1e-16 is the largest below 1 they are safe at).
constexpr double kBelowOne = 1.0 - 1e-16;

// Builds the BSDF at a neutral surface point (no textures: constant colours) for each row's wavelengths.
class Evaluator {
 public:
  Evaluator(const Material& material, const BsdfQuery& query, size_t n) : material_(material), query_(query) {
    if (!usable_ior(query.eta_outside)) {  // 1e200 passed, and its square overflowed to NaN results
      throw_invalid("eta_outside must be a refractive index in [", kMinIor, ", ", kMaxIor, "] (got ",
                    query.eta_outside, ")");
    }
    if (!query.wavelengths) return;
    const RowMatrixX4d& w = *query.wavelengths;
    if (w.rows() != 1 && size_t(w.rows()) != n) {
      throw_invalid("wavelengths must have shape (4,) or (N, 4) with N = ", n, " [nm]");
    }
    for (double l : w.reshaped()) checked_wavelength(l, "wavelengths");
  }
  bool spectral() const { return query_.wavelengths.has_value(); }
  int channels() const { return spectral() ? 4 : 3; }
  // Row i's wavelengths, into lambda_ (which the BSDF may terminate), and its BSDF (or null).
  const Bsdf* build(size_t i) {
    lambda_ = SampledWavelengths::rgb();
    if (spectral()) {
      const RowMatrixX4d& w = *query_.wavelengths;
      lambda_.spectral = true;
      lambda_.lambda = w.row(w.rows() == 1 ? 0 : Eigen::Index(i)).transpose().array();
      lambda_.pdf.setConstant(1.0 / (kLambdaMax - kLambdaMin));
    }
    scratch_.reset();
    MaterialContext context;
    context.lambda = &lambda_;
    context.eta_outside = query_.eta_outside;
    return material_.bsdf(si_, context, scratch_);
  }
  const SampledWavelengths& lambda() const { return lambda_; }

 private:
  const Material& material_;
  const BsdfQuery& query_;
  SampledWavelengths lambda_;
  SurfaceInteraction si_;
  ScratchBuffer scratch_;
};

// value(bsdf, wo, wi) for every (wo, wi) row; RGB rows share one BSDF, spectral rows build their own.
template <class Value>
void for_pairs(const Material& material, const std::vector<Vec3d>& wo, const std::vector<Vec3d>& wi,
               const BsdfQuery& query, const Value& value) {
  const size_t n = broadcast(wo.size(), wi.size(), "wo and wi");
  Evaluator evaluator(material, query, n);
  if (n == 0) return;  // no rows: nothing to build (row 0 of an empty (0, 4) was read: a segfault)
  const Bsdf* bsdf = evaluator.build(0);
  for (size_t i = 0; i < n; ++i) {
    if (evaluator.spectral() && i > 0) bsdf = evaluator.build(i);
    value(i, bsdf, wo[wo.size() == 1 ? 0 : i], wi[wi.size() == 1 ? 0 : i], evaluator.channels());
  }
}

}  // namespace

TransportMode transport_mode_from(const std::string& name) {
  if (name == "radiance") return TransportMode::kRadiance;
  if (name == "importance") return TransportMode::kImportance;
  throw_invalid("mode must be 'radiance' or 'importance' (got '", name, "')");
}

RowMatrixXd bsdf_f(const Material& material, const std::vector<Vec3d>& wo, const std::vector<Vec3d>& wi,
                   const BsdfQuery& query) {
  RowMatrixXd out(broadcast(wo.size(), wi.size(), "wo and wi"), query.wavelengths ? 4 : 3);
  for_pairs(material, wo, wi, query, [&](size_t i, const Bsdf* bsdf, const Vec3d& o, const Vec3d& w, int channels) {
    const Spectrum f = bsdf ? bsdf->f(o, w, query.mode) : Spectrum::Zero().eval();
    out.row(i) = f.head(channels).matrix().transpose();
  });
  return out;
}

Eigen::VectorXd bsdf_pdf(const Material& material, const std::vector<Vec3d>& wo, const std::vector<Vec3d>& wi,
                         const BsdfQuery& query) {
  Eigen::VectorXd out(broadcast(wo.size(), wi.size(), "wo and wi"));
  for_pairs(material, wo, wi, query, [&](size_t i, const Bsdf* bsdf, const Vec3d& o, const Vec3d& w, int) {
    out[Eigen::Index(i)] = bsdf ? bsdf->pdf(o, w, query.mode) : 0.0;
  });
  return out;
}

BsdfSamples bsdf_sample(const Material& material, const std::vector<Vec3d>& wo, const RowMatrixXd& u,
                        const BsdfQuery& query) {
  if (u.cols() != 3) throw_invalid("u must have shape (N, 3) (got ", u.cols(), " columns)");
  const size_t n = broadcast(wo.size(), size_t(u.rows()), "wo and u");
  Evaluator evaluator(material, query, n);
  const int channels = evaluator.channels();
  const BsdfSamples::Bools no = BsdfSamples::Bools::Zero(n);
  BsdfSamples out{RowMatrixX3d::Zero(n, 3), RowMatrixXd::Zero(n, channels), RowMatrixXd::Zero(n, channels),
                  Eigen::VectorXd::Zero(n), BsdfSamples::Flags::Zero(n), no, Eigen::VectorXd::Ones(n), no, no};
  for (size_t i = 0; i < n; ++i) {  // fresh wavelengths per sample: a dielectric may terminate them
    const Bsdf* bsdf = evaluator.build(i);
    const Vec3d ui = u.row(u.rows() == 1 ? 0 : Eigen::Index(i)).transpose();
    const Vec3d& o = wo[wo.size() == 1 ? 0 : i];
    std::optional<BsdfSample> s;
    if (bsdf && o.z() != 0.0) {
      s = bsdf->sample(o, std::min(ui[0], kBelowOne), Vec2d(std::min(ui[1], kBelowOne), std::min(ui[2], kBelowOne)),
                       query.mode);
    }
    out.terminated[i] = evaluator.lambda().secondary_terminated();
    if (!(s && s->pdf > 0.0 && s->weight.maxCoeff() > 0.0)) continue;
    out.valid[i] = true;
    out.wi.row(i) = s->wi.transpose();
    out.weight.row(i) = s->weight.head(channels).matrix().transpose();
    out.f.row(i) = s->f.head(channels).matrix().transpose();
    out.pdf[i] = s->pdf;
    out.eta[i] = s->eta;
    out.flags[i] = s->flags;
    out.is_delta[i] = s->is_specular();
  }
  return out;
}

std::optional<double> interior_ior_at(const Material& material, std::optional<double> wavelength_nm) {
  SampledWavelengths lambda = SampledWavelengths::rgb();
  if (wavelength_nm) {
    lambda = SampledWavelengths::sample_uniform(0.0);
    lambda.lambda[0] = checked_wavelength(*wavelength_nm, "interior_ior: wavelength");
  }
  return material.interior_ior(lambda);
}

}  // namespace refracta
