// moment_shadow: storage, bias, method.
#include "refracta/raster/moment_shadow.h"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace refracta {

MomentShadowMethod parse_moment_shadow_method(const std::string& name) {
  if (name == "msm_hamburger") return MomentShadowMethod::kHamburger;
  if (name == "msm_hausdorff") return MomentShadowMethod::kHausdorff;
  if (name == "vsm") return MomentShadowMethod::kVsm;
  if (name == "canonical") return MomentShadowMethod::kCanonical;
  throw_invalid("method must be 'msm_hamburger', 'msm_hausdorff', 'vsm' or 'canonical' (got '", name, "')");
}

const char* moment_shadow_method_name(MomentShadowMethod method) {
  switch (method) {
    case MomentShadowMethod::kHamburger: return "msm_hamburger";
    case MomentShadowMethod::kHausdorff: return "msm_hausdorff";
    case MomentShadowMethod::kVsm: return "vsm";
    case MomentShadowMethod::kCanonical: return "canonical";
  }
  return "?";
}

double MomentShadowSettings::published_bias(DepthRange range, Storage storage) {
  const bool is_signed = range == DepthRange::kSigned;
  if (storage == Storage::kUnorm16) return is_signed ? 6e-5 : 3e-5;
  return is_signed ? 3e-7 : 3e-6;
}

Moments4 MomentShadowSettings::published_bias_vector(DepthRange range, Storage storage) {
  if (range != DepthRange::kSigned) return Moments4{0.5, 0.5, 0.5, 0.5};
  return storage == Storage::kUnorm16 ? Moments4{0.0, 0.628, 0.0, 0.628} : Moments4{0.0, 0.375, 0.0, 0.375};
}

// The published unit vector (0.5, ...) is a two-point distribution: its Hankel matrix is singular,
// and round-off may leave its least eigenvalue this far below 0.
constexpr double kMomentRoundOff = 1e-12;

void MomentShadowSettings::check(Problems& problems) const {
  if (bias) problems.check(*bias >= 0.0 && *bias < 1.0, "bias must be in [0, 1) (got ", *bias, ")");
  if (bias_vector) {
    // b* is biased toward as a moment vector (b_k = E[z^k]) of depths in the range: b_k of depths
    // in [0, 1] lie in [0, 1]; of depths in [-1, 1] odd ones in [-1, 1], even ones in [0, 1]. Far
    // beyond, the bias swamps the map's own moments (a trial's (1e300, 0, 0, 0) lit every receiver).
    const bool is_signed = depth_range == DepthRange::kSigned;
    bool within = true;
    for (int k = 0; k < 4; ++k) {
      const double v = (*bias_vector)[k], lowest = is_signed && k % 2 == 0 ? -1.0 : 0.0;  // k = 0 is b_1
      within = within && v >= lowest && v <= 1.0;
    }
    const Moments4& b = *bias_vector;
    problems.check(within, "bias_vector must hold moments of depths in the ", is_signed ? "signed" : "unit",
                   " range: b1..b4 each in ", is_signed ? "[-1, 1] (b2 and b4 in [0, 1])" : "[0, 1]", " (got (", b[0],
                   ", ", b[1], ", ", b[2], ", ", b[3], "))");
    // Moments of some distribution have a positive semi-definite Hankel matrix (Peters & Klein
    // 2015, sec. 3); (1, 0, 1, 0) is in the box but is none, and the biased moments then lost the
    // lower bound on PCF (a trial: 1.0 where PCF is 0.65).
    Eigen::Matrix3d hankel;
    hankel << 1.0, b[0], b[1], b[0], b[1], b[2], b[1], b[2], b[3];
    const double lowest =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(hankel, Eigen::EigenvaluesOnly).eigenvalues()(0);
    problems.check(!within || lowest >= -kMomentRoundOff, "bias_vector must be the moments of some distribution of "
                   "depths: the Hankel matrix ((1, b1, b2), (b1, b2, b3), (b2, b3, b4)) must be positive semi-definite "
                   "(got (", b[0], ", ", b[1], ", ", b[2], ", ", b[3], "): its least eigenvalue is ", lowest, ")");
  }
}

void MomentShadowSettings::validate() const {
  Problems problems("MomentShadowSettings");
  check(problems);
  problems.throw_if_any();
}

double moment_shadow(const Moments4& b, double z_f, MomentShadowMethod method, const MomentShadowSettings& settings) {
  const bool is_signed = settings.depth_range == DepthRange::kSigned;
  const Moments4 read = stored_moments(b, settings.storage, is_signed);
  const double alpha = settings.bias_or_published();
  const Moments4 target = settings.bias_vector_or_published();
  // (1 - alpha) b + alpha b* (bias_moments, without allocating: this runs once per lookup).
  std::array<double, 4> c;
  for (int j = 0; j < 4; ++j) c[j] = (1.0 - alpha) * read[j] + alpha * target[j];
  switch (method) {
    case MomentShadowMethod::kHamburger: return hamburger_4msm(c, z_f);
    case MomentShadowMethod::kHausdorff: return hausdorff_4msm(c, z_f, is_signed ? -1.0 : 0.0, 1.0);
    case MomentShadowMethod::kVsm: return vsm_shadow(c[0], c[1], z_f, 1e-12);
    case MomentShadowMethod::kCanonical: {
      const MomentBound bound = canonical_bound({1.0, c[0], c[1], c[2], c[3]}, z_f);
      return bound.fallback ? vsm_shadow(c[0], c[1], z_f, 1e-12) : bound.lower;
    }
  }
  return 0.0;
}

}  // namespace refracta
