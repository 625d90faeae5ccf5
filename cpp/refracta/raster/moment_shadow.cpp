// moment_shadow: storage, bias, method.
#include "refracta/raster/moment_shadow.h"

#include "refracta/core/error.h"

#include <cmath>

namespace refracta {

MomentShadowMethod parse_moment_shadow_method(const std::string& name) {
  if (name == "hamburger") return MomentShadowMethod::kHamburger;
  if (name == "hausdorff") return MomentShadowMethod::kHausdorff;
  if (name == "vsm") return MomentShadowMethod::kVsm;
  if (name == "canonical") return MomentShadowMethod::kCanonical;
  throw_invalid("method must be 'hamburger', 'hausdorff', 'vsm' or 'canonical' (got '", name, "')");
}

MomentShadowSettings MomentShadowSettings::defaults(bool signed_depth, MomentStorage storage) {
  MomentShadowSettings s;
  s.signed_depth = signed_depth;
  s.storage = storage;
  if (storage == MomentStorage::kUnorm16) {
    s.bias = signed_depth ? 6e-5 : 3e-5;
  } else {
    s.bias = signed_depth ? 3e-7 : 3e-6;
  }
  s.bias_vector = signed_depth ? Moments4{0.0, 0.375, 0.0, 0.375} : Moments4{0.5, 0.5, 0.5, 0.5};
  return s;
}

void MomentShadowSettings::validate() const {
  if (!(bias >= 0.0 && bias < 1.0)) throw_invalid("bias must be in [0, 1) (got ", bias, ")");
  for (double v : bias_vector) {
    if (!std::isfinite(v)) throw_invalid("bias_vector must be finite");
  }
}

double moment_shadow(const Moments4& b, double z_f, const MomentShadowSettings& settings) {
  const Moments4 read = stored_moments(b, settings.storage, settings.signed_depth);
  // (1 - alpha) b + alpha b* (bias_moments, without allocating: this runs once per lookup).
  std::array<double, 4> c;
  for (int j = 0; j < 4; ++j) c[j] = (1.0 - settings.bias) * read[j] + settings.bias * settings.bias_vector[j];
  switch (settings.method) {
    case MomentShadowMethod::kHamburger: return hamburger_4msm(c, z_f);
    case MomentShadowMethod::kHausdorff: return hausdorff_4msm(c, z_f, settings.signed_depth ? -1.0 : 0.0, 1.0);
    case MomentShadowMethod::kVsm: return vsm_shadow(c[0], c[1], z_f, 1e-12);
    case MomentShadowMethod::kCanonical: {
      const MomentBound bound = canonical_bound({1.0, c[0], c[1], c[2], c[3]}, z_f);
      return bound.fallback ? vsm_shadow(c[0], c[1], z_f, 1e-12) : bound.lower;
    }
  }
  return 0.0;
}

}  // namespace refracta
