// The moment math over arrays of texels and pixels, with its checks: what refracta.moments and
// refracta.oit hand to C++ (the bindings bind these directly).
#pragma once

#include "refracta/raster/moment_shadow.h"
#include "refracta/raster/oit.h"

#include <Eigen/Core>

#include <string>
#include <tuple>
#include <vector>

namespace refracta {

using MomentRows = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;  // b_1 .. b_4 per row

// Power moments of depths in [0, 1] or [-1, 1] lie in [-1, 1]; beyond this (room for biased or
// hand-made moments) the fp32 / unorm16 storage transforms overflow to NaN.
constexpr double kMaxMoment = 1.5;

// The shadow intensity of each row of moments at the receiver depth z_f[i] (method by name, as
// parse_moment_shadow_method). Throws std::invalid_argument for moments that are not finite or
// beyond kMaxMoment, depths that are not finite, different lengths, or bad settings.
Eigen::VectorXd shadow_intensities(const MomentRows& moments, const Eigen::VectorXd& z_f, const std::string& method,
                                   const MomentShadowSettings& settings);

// The optimised quantisation transform (depth_range "unit" or "signed") of each row, or its inverse.
MomentRows quantize_moments(const MomentRows& moments, const std::string& depth_range, bool inverse);

// MBOIT's per-pixel fast path: b_0 .. b_m (m = 4, 6 or 8) factorised once, queried at every z_f:
// (lower bound, weight at the query, 1 where the fallback was taken else 0) per query.
std::tuple<Eigen::VectorXd, Eigen::VectorXd, Eigen::VectorXd> power_moment_bounds(const std::vector<double>& moments,
                                                                                  const Eigen::VectorXd& z_f);

// One pixel's fragments (depth [m], alpha, colour) composited over `background`; throws
// std::invalid_argument when the three lists differ in length or a fragment is bad.
Vec3d composite_pixel(const std::vector<double>& depths, const std::vector<double>& alphas,
                      const std::vector<Vec3d>& colors, const Vec3d& background, const OitSettings& settings);

}  // namespace refracta
