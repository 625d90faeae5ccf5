// One texel's moment shadow: stored moments read back (fp64 / fp32 / unorm16 after the
// optimised quantisation transform), biased toward the bias vector, then Hamburger or Hausdorff
// 4MSM, VSM, or the generic canonical bound (shared/MOMENTS.md 2-3). Used by the shadow maps and
// by refracta.moments.shadow_intensity alike.
#pragma once

#include "refracta/core/error.h"
#include "refracta/raster/moments.h"
#include "refracta/raster/quantization.h"

#include <optional>
#include <string>

namespace refracta {

// How a shadow intensity is read from four moments. Python spells the 4MSMs as render_raster
// does: "msm_hamburger", "msm_hausdorff" (refracta.moments accepts the old "hamburger",
// "hausdorff" with a DeprecationWarning).
enum class MomentShadowMethod { kHamburger, kHausdorff, kVsm, kCanonical };
MomentShadowMethod parse_moment_shadow_method(const std::string& name);  // "msm_hamburger", "msm_hausdorff", "vsm", "canonical"
const char* moment_shadow_method_name(MomentShadowMethod method);

// How a moment shadow map keeps its four power moments and biases them (Peters & Klein 2015; Peters et al. 2017):
// depth_range 'unit' ([0, 1], Peters & Klein I3D 2015) or 'signed' ([-1, 1], Peters et al. JCGT
// 2017); storage 'fp64', 'fp32' or 'unorm16' (16 bits through the optimised quantisation
// transforms); bias (alpha) and bias_vector (b*): None means the published value for the depth
// range and storage (published_bias, published_bias_vector).
struct MomentShadowSettings {
  DepthRange depth_range = DepthRange::kUnit;  // [0, 1] (I3D 2015) or [-1, 1] (JCGT 2017)
  Storage storage = Storage::kFp32;            // how a GPU would keep them (the shadow maps' default)
  // alpha, the weight of bias_vector (Peters & Klein's alpha) in [0, 1); unset (None) gives
  // published_bias(depth_range, storage).
  std::optional<double> bias;
  // b*, the 4 moments biased toward; unset (None): published_bias_vector(depth_range, storage).
  std::optional<Moments4> bias_vector;

  // The published strengths: 3e-6 (unit) / 3e-7 (signed) for fp32 and fp64 (Peters & Klein 2015
  // sec. 5; Peters et al. 2017 sec. 3.2); unorm16 needs ~10x more: 3e-5 / 6e-5.
  static double published_bias(DepthRange range, Storage storage);
  // (0.5, 0.5, 0.5, 0.5) for unit depths; for signed ones (0, 0.375, 0, 0.375), and with 16-bit
  // storage (the sparse quantisation) (0, 0.628, 0, 0.628) (Peters et al. 2017).
  static Moments4 published_bias_vector(DepthRange range, Storage storage);
  double bias_or_published() const { return bias ? *bias : published_bias(depth_range, storage); }
  Moments4 bias_vector_or_published() const { return bias_vector ? *bias_vector : published_bias_vector(depth_range, storage); }

  void check(Problems& problems) const;  // adds every bad field
  void validate() const;                 // throws std::invalid_argument listing them all
};

// Shadow intensity in [0, 1] (the mass of the filtered depth distribution in front of z_f) from
// b_1..b_4 as they were filtered (before storage).
double moment_shadow(const Moments4& b, double z_f, MomentShadowMethod method, const MomentShadowSettings& settings);

}  // namespace refracta
