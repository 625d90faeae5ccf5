// The moment math over arrays (moment_arrays.h).
#include "refracta/raster/moment_arrays.h"

#include "refracta/core/error.h"
#include "refracta/raster/power_moment_bound.h"

#include <cmath>

namespace refracta {

namespace {

Moments4 row(const MomentRows& moments, Eigen::Index i) {
  return {moments(i, 0), moments(i, 1), moments(i, 2), moments(i, 3)};
}

void check_finite(const Eigen::Ref<const Eigen::ArrayXd>& values, const char* what) {
  if (!values.allFinite()) throw_invalid(what, " must be finite");
}

}  // namespace

Eigen::VectorXd shadow_intensities(const MomentRows& moments, const Eigen::VectorXd& z_f, const std::string& method,
                                   const MomentShadowSettings& settings) {
  const MomentShadowMethod parsed = parse_moment_shadow_method(method);
  settings.validate();
  if (!moments.allFinite()) throw_invalid("moments must be finite");
  check_finite(z_f.array(), "z_f");
  if (z_f.size() != moments.rows()) throw_invalid("moments and z_f must have the same length");
  for (Eigen::Index i = 0; i < moments.size(); ++i) {
    if (!(std::abs(moments.data()[i]) <= kMaxMoment)) {
      throw_invalid("moments must lie in [-", kMaxMoment, ", ", kMaxMoment,
                    "] (power moments of depths in [-1, 1]; got ", moments.data()[i], ")");
    }
  }
  Eigen::VectorXd out(z_f.size());
  for (Eigen::Index i = 0; i < z_f.size(); ++i) out[i] = moment_shadow(row(moments, i), z_f[i], parsed, settings);
  return out;
}

MomentRows quantize_moments(const MomentRows& moments, const std::string& depth_range, bool inverse) {
  const bool is_signed = parse_depth_range(depth_range) == DepthRange::kSigned;
  if (!moments.allFinite()) throw_invalid("moments must be finite");
  MomentRows out(moments.rows(), 4);
  for (Eigen::Index i = 0; i < moments.rows(); ++i) {
    const Moments4 r = inverse ? inverse_quantization_transform(row(moments, i), is_signed)
                               : quantization_transform(row(moments, i), is_signed);
    for (int k = 0; k < 4; ++k) out(i, k) = r[size_t(k)];
  }
  return out;
}

std::tuple<Eigen::VectorXd, Eigen::VectorXd, Eigen::VectorXd> power_moment_bounds(const std::vector<double>& moments,
                                                                                  const Eigen::VectorXd& z_f) {
  const int m = int(moments.size()) - 1;
  if (m != 4 && m != 6 && m != 8) {
    throw_invalid("moments must hold b_0 .. b_m with m = 4, 6 or 8 (got ", moments.size(), " values)");
  }
  check_finite(z_f.array(), "z_f");
  const PowerMomentBound bound(moments.data(), m);
  Eigen::VectorXd lower(z_f.size()), at_query(z_f.size()), fallback(z_f.size());
  for (Eigen::Index i = 0; i < z_f.size(); ++i) {
    const MomentBound r = bound.at(z_f[i]);
    lower[i] = r.lower;
    at_query[i] = r.at_query;
    fallback[i] = r.fallback ? 1.0 : 0.0;
  }
  return {lower, at_query, fallback};
}

Vec3d composite_pixel(const std::vector<double>& depths, const std::vector<double>& alphas,
                      const std::vector<Vec3d>& colors, const Vec3d& background, const OitSettings& settings) {
  if (alphas.size() != depths.size() || colors.size() != depths.size()) {
    throw_invalid("depths, alphas and colors must describe the same fragments (", depths.size(), ", ", alphas.size(),
                  ", ", colors.size(), ")");
  }
  std::vector<Fragment> fragments;
  for (size_t i = 0; i < depths.size(); ++i) fragments.push_back({depths[i], alphas[i], colors[i]});
  validate_fragments(fragments);
  settings.validate();
  return composite(fragments, background, settings);
}

}  // namespace refracta
