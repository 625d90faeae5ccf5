// Moment quantisation transforms (values from MOMENTS.md 2.5; column-vector orientation).
#include "refracta/raster/quantization.h"

#include <Eigen/Dense>

#include "refracta/core/error.h"

#include <algorithm>
#include <cmath>

namespace refracta {

Storage parse_storage(const std::string& name) {
  if (name == "fp64") return Storage::kFp64;
  if (name == "fp32") return Storage::kFp32;
  if (name == "unorm16") return Storage::kUnorm16;
  throw_invalid("storage must be 'fp64', 'fp32' or 'unorm16' (got '", name, "')");
}

const char* storage_name(Storage storage) {
  switch (storage) {
    case Storage::kFp64: return "fp64";
    case Storage::kFp32: return "fp32";
    case Storage::kUnorm16: return "unorm16";
  }
  return "?";
}

DepthRange parse_depth_range(const std::string& name) {
  if (name == "unit") return DepthRange::kUnit;
  if (name == "signed") return DepthRange::kSigned;
  throw_invalid("depth_range must be 'unit' or 'signed' (got '", name, "')");
}

const char* depth_range_name(DepthRange range) { return range == DepthRange::kSigned ? "signed" : "unit"; }

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

Moments4 stored_moments(const Moments4& b, Storage storage, bool signed_depth) {
  Moments4 out = b;
  if (storage == Storage::kFp32) {
    for (double& v : out) v = double(float(v));
  } else if (storage == Storage::kUnorm16) {
    Moments4 q = quantization_transform(b, signed_depth);
    for (double& v : q) v = std::round(std::clamp(v, 0.0, 1.0) * 65535.0) / 65535.0;
    out = inverse_quantization_transform(q, signed_depth);
  }
  return out;
}

namespace {

// q = A v + offset for the odd (b1, b3, ..) and even (b2, b4, ..) halves; A and offsets from the
// MBOIT supplementary code (6 moments: its matrices act on row vectors, 8: on column vectors,
// as the [0, 1] property of every valid moment vector confirms; tests/raster check it).
struct MboitTransform {
  Eigen::MatrixXd odd, even;
  Eigen::VectorXd odd_offset, even_offset;
};

const MboitTransform& mboit_transform(int m) {
  static const MboitTransform six = [] {
    MboitTransform t;
    Eigen::Matrix3d odd, even;
    odd << 2.5, -1.87499864450, 1.26583039016, -10.0, 4.20757543111, -1.47644882902, 8.0, -1.83257678661,
        0.71061660238;
    even << 4.0, 9.0, -0.57759806484, -4.0, -24.0, 4.61936647543, 0.0, 16.0, -3.07953906655;
    t.odd = odd.transpose();
    t.even = even.transpose();
    t.odd_offset = Eigen::Vector3d(0.5, 0.5, 0.5);
    t.even_offset = Eigen::Vector3d(0.0, 0.0, 0.018888946);
    return t;
  }();
  static const MboitTransform eight = [] {
    MboitTransform t;
    Eigen::Matrix4d odd, even;
    odd << 3.48044635732474, -27.5760737514826, 55.1267384344761, -31.5311110403183, 1.26797185782836,
        -0.928755808743913, -2.07520453231032, 1.23598848322588, -2.1671560004294, 6.17950199592966,
        -0.276515571579297, -4.23583042392097, 0.974332879165755, -0.443426830933027, -0.360491648368785,
        0.310149466050223;
    even << 0.280504133158527, -0.757633844606942, 0.392179589334688, -0.887531871812237, -2.01362265883247,
        0.221551373038988, -1.06107954265125, 2.83887201588367, -7.31010494985321, 13.9855979699139,
        -0.114305766176437, -7.4361899359832, -15.8954215629556, 79.6186327084103, -127.457278992502,
        63.7349456687829;
    t.odd = odd;
    t.even = even;
    t.odd_offset = Eigen::Vector4d::Constant(0.5);
    t.even_offset = Eigen::Vector4d(0.972481993925964, 1.0, 0.999179192513328, 0.991778293073131);
    return t;
  }();
  if (m == 6) return six;
  if (m == 8) return eight;
  throw_invalid("16-bit MBOIT storage: 6 or 8 moments here (got ", m, ")");
}

Eigen::VectorXd round_trip(const Eigen::MatrixXd& a, const Eigen::VectorXd& offset, const Eigen::VectorXd& v) {
  Eigen::VectorXd q = a * v + offset;
  for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = std::round(std::clamp(q[i], 0.0, 1.0) * 65535.0) / 65535.0;
  return a.partialPivLu().solve(q - offset);
}

}  // namespace

std::vector<double> stored_mboit_unorm16(const std::vector<double>& b) {
  const int m = int(b.size());
  const MboitTransform& t = mboit_transform(m);
  Eigen::VectorXd odd(m / 2), even(m / 2);
  for (int i = 0; i < m / 2; ++i) odd[i] = b[2 * i], even[i] = b[2 * i + 1];
  const Eigen::VectorXd o = round_trip(t.odd, t.odd_offset, odd), e = round_trip(t.even, t.even_offset, even);
  std::vector<double> out(m);
  for (int i = 0; i < m / 2; ++i) out[2 * i] = o[i], out[2 * i + 1] = e[i];
  return out;
}

}  // namespace refracta
