// One texel's moment shadow: stored moments read back (fp64 / fp32 / unorm16 after the
// optimised quantisation transform), biased toward the bias vector, then Hamburger or Hausdorff
// 4MSM, VSM, or the generic canonical bound (shared/MOMENTS.md 2-3). Used by the shadow maps and
// by refracta.moments.shadow_intensity alike.
#pragma once

#include "refracta/raster/moments.h"
#include "refracta/raster/quantization.h"

#include <string>

namespace refracta {

enum class MomentShadowMethod { kHamburger, kHausdorff, kVsm, kCanonical };
MomentShadowMethod parse_moment_shadow_method(const std::string& name);  // "hamburger", "hausdorff", "vsm", "canonical"

struct MomentShadowSettings {
  MomentShadowMethod method = MomentShadowMethod::kHamburger;
  bool signed_depth = false;   // depths in [-1, 1] (JCGT 2017) instead of [0, 1] (I3D 2015)
  double bias = 3e-6;          // alpha, the weight of the bias vector (3e-6 unit / 3e-7 signed for fp32)
  Moments4 bias_vector{0.5, 0.5, 0.5, 0.5};  // (0, 0.375, 0, 0.375) for signed depths
  MomentStorage storage = MomentStorage::kFp64;

  // The published defaults for a depth range: bias 3e-6 toward 0.5 (unit), 3e-7 toward
  // (0, 0.375, 0, 0.375) (signed); storage unorm16 needs ~10x more (3e-5 / 6e-5, MOMENTS.md 2.5).
  static MomentShadowSettings defaults(bool signed_depth, MomentStorage storage = MomentStorage::kFp32);
  void validate() const;  // throws std::invalid_argument naming the bad field
};

// Shadow intensity in [0, 1] (the mass of the filtered depth distribution in front of z_f) from
// b_1..b_4 as they were filtered (before storage).
double moment_shadow(const Moments4& b, double z_f, const MomentShadowSettings& settings);

}  // namespace refracta
