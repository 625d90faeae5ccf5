// Moment quantisation transforms (values from MOMENTS.md 2.5; column-vector orientation).
#include "refracta/raster/quantization.h"

#include "refracta/core/error.h"

#include <algorithm>
#include <cmath>

namespace refracta {

MomentStorage parse_moment_storage(const std::string& name) {
  if (name == "fp64") return MomentStorage::kFp64;
  if (name == "fp32") return MomentStorage::kFp32;
  if (name == "unorm16") return MomentStorage::kUnorm16;
  throw_invalid("storage must be 'fp64', 'fp32' or 'unorm16' (got '", name, "')");
}

namespace {

constexpr double kDense[4][4] = {{-2.07224649, 32.23703778, -68.571074599, 39.3703274134},
                                 {13.7948857237, -59.4683975703, 82.0359750338, -35.364903257},
                                 {0.105877704, -1.9077466311, 9.3496555107, -6.6543490743},
                                 {9.7924062118, -33.7652110555, 47.9456096605, -23.9728048165}};
constexpr double kDenseInverse[4][4] = {{0.2227744146, 0.0771972861, 0.7926986636, 0.0319417555},
                                        {0.1549679261, 0.1394629426, 0.7963415838, -0.1722823173},
                                        {0.1451988946, 0.2120202157, 0.7258694464, -0.2758014811},
                                        {0.163127443, 0.2591432266, 0.6539092497, -0.3376131734}};
constexpr double kDenseOffset = 0.035955884801;

}  // namespace

Moments4 quantization_transform(const Moments4& b, bool signed_depth) {
  if (signed_depth) {
    const double s3 = std::sqrt(3.0);
    return {1.5 * b[0] - 2.0 * b[2] + 0.5, 4.0 * b[1] - 4.0 * b[3], s3 / 2.0 * b[0] - 2.0 * s3 / 9.0 * b[2] + 0.5,
            0.5 * b[1] + 0.5 * b[3]};
  }
  Moments4 q{};
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) q[i] += kDense[i][j] * b[j];
  }
  q[0] += kDenseOffset;
  return q;
}

Moments4 inverse_quantization_transform(const Moments4& q, bool signed_depth) {
  if (signed_depth) {
    const double s3 = std::sqrt(3.0);
    const double q1 = q[0] - 0.5, q3 = q[2] - 0.5;
    return {-q1 / 3.0 + s3 * q3, q[1] / 8.0 + q[3], -0.75 * q1 + 0.75 * s3 * q3, -q[1] / 8.0 + q[3]};
  }
  Moments4 shifted = q, b{};
  shifted[0] -= kDenseOffset;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) b[i] += kDenseInverse[i][j] * shifted[j];
  }
  return b;
}

Moments4 stored_moments(const Moments4& b, MomentStorage storage, bool signed_depth) {
  Moments4 out = b;
  if (storage == MomentStorage::kFp32) {
    for (double& v : out) v = double(float(v));
  } else if (storage == MomentStorage::kUnorm16) {
    Moments4 q = quantization_transform(b, signed_depth);
    for (double& v : q) v = std::round(std::clamp(v, 0.0, 1.0) * 65535.0) / 65535.0;
    out = inverse_quantization_transform(q, signed_depth);
  }
  return out;
}

}  // namespace refracta
