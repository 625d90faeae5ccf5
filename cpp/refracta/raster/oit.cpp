// Per-pixel transparency compositing.
#include "refracta/raster/oit.h"

#include "refracta/core/error.h"
#include "refracta/raster/moments.h"
#include "refracta/raster/power_moment_bound.h"
#include "refracta/raster/quantization.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>

namespace refracta {

void validate_fragments(const std::vector<Fragment>& fragments) {
  for (size_t i = 0; i < fragments.size(); ++i) {
    const Fragment& f = fragments[i];
    if (!(f.depth > 0.0) || !std::isfinite(f.depth)) throw_invalid("depths[", i, "] must be > 0 and finite (got ", f.depth, ")");
    if (!(f.alpha >= 0.0 && f.alpha <= 1.0)) throw_invalid("alphas[", i, "] must be in [0, 1] (got ", f.alpha, ")");
    if (!is_finite(f.colour)) throw_invalid("colors[", i, "] must be finite");
  }
}

namespace {

// Stable sort by depth: equal depths keep their submission order (deterministic tie-break).
void sort_front_to_back(std::vector<Fragment>& fragments) {
  std::stable_sort(fragments.begin(), fragments.end(),
                   [](const Fragment& a, const Fragment& b) { return a.depth < b.depth; });
}

}  // namespace

Vec3d composite_peeled(std::vector<Fragment> fragments, const Vec3d& background, int layers) {
  if (layers < 1) throw_invalid("layers must be >= 1 (got ", layers, ")");
  sort_front_to_back(fragments);
  Vec3d colour = Vec3d::Zero();
  double transmittance = 1.0;
  for (size_t i = 0; i < fragments.size() && int(i) < layers; ++i) {
    colour += transmittance * fragments[i].alpha * fragments[i].colour;
    transmittance *= 1.0 - fragments[i].alpha;
  }
  return colour + transmittance * background;
}

Vec3d composite_exact(std::vector<Fragment> fragments, const Vec3d& background) {
  const int count = int(fragments.size());
  return composite_peeled(std::move(fragments), background, std::max(count, 1));
}

Vec3d composite_wboit(const std::vector<Fragment>& fragments, const Vec3d& background, WboitWeight weight) {
  Vec3d accum = Vec3d::Zero();
  double accum_alpha = 0.0, revealage = 1.0;
  for (const Fragment& f : fragments) {
    const double z = std::abs(f.depth);
    const double raw = weight == WboitWeight::kEq7 ? 10.0 / (1e-5 + std::pow(z / 5.0, 2) + std::pow(z / 200.0, 6))
                                       : 0.03 / (1e-5 + std::pow(z / 200.0, 4));
    const double w = f.alpha * std::clamp(raw, 1e-2, 3e3);
    accum += f.colour * f.alpha * w;
    accum_alpha += f.alpha * w;
    revealage *= 1.0 - f.alpha;
  }
  const Vec3d average = accum / std::clamp(accum_alpha, 1e-4, 5e4);
  return average * (1.0 - revealage) + background * revealage;
}

Vec3d composite_mboit(const std::vector<Fragment>& fragments, const Vec3d& background, const MboitSettings& options) {
  // Published fp32 bias vectors and strengths (MOMENTS.md 4.4).
  static const std::vector<double> kBias4 = {0, 0.375, 0, 0.375};
  static const std::vector<double> kBias6 = {0, 0.48, 0, 0.451, 0, 0.45};
  static const std::vector<double> kBias8 = {0, 0.75, 0, 0.676667, 0, 0.63, 0, 0.600303};
  options.validate();
  const int m = options.moments;
  const bool trigonometric = options.basis == MomentBasis::kTrigonometric;
  const bool unorm16 = options.storage == Storage::kUnorm16;
  // A value as the storage keeps it: fp32 rounds every sum and quotient to single precision.
  const bool fp32 = options.storage == Storage::kFp32;
  auto kept = [fp32](double v) { return fp32 ? double(float(v)) : v; };
  // 16-bit bias vectors (MOMENTS.md 4.4); strengths: 6e-5 for 4 moments (the Unity HDRP port),
  // and for 6 / 8 moments 10x the fp32 values (no published 16-bit figure; measured to keep the
  // error of tests/raster at fp32's).
  static const std::vector<double> kBias4Unorm16 = {0, 0.628, 0, 0.628};
  static const std::vector<double> kBias6Unorm16 = {0, 0.5566, 0, 0.489, 0, 0.47869382};
  static const std::vector<double> kBias8Unorm16 = {0, 0.424749, 0, 0.224078, 0, 0.153692, 0, 0.129004};
  const std::vector<double>& target =
      unorm16 ? (m == 6 ? kBias6Unorm16 : (m == 8 ? kBias8Unorm16 : kBias4Unorm16))
              : (m == 6 ? kBias6 : (m == 8 ? kBias8 : kBias4));
  const double alpha_bias = options.bias_or_published();
  if (fragments.empty()) return background;
  // Log depth warp to [-1, 1] over the given or the fragments' range (MOMENTS.md 4.2).
  double z_near = options.z_near, z_far = options.z_far;
  if (!(z_far > z_near && z_near > 0.0)) {
    z_near = z_far = fragments[0].depth;
    for (const Fragment& f : fragments) z_near = std::min(z_near, f.depth), z_far = std::max(z_far, f.depth);
    if (z_far <= z_near) z_far = z_near * (1.0 + 1e-6);
  }
  const double log_near = std::log(z_near), log_range = std::log(z_far) - log_near;
  auto warp = [&](double z) {
    return std::clamp((std::log(std::clamp(z, z_near, z_far)) - log_near) / log_range, 0.0, 1.0) * 2.0 - 1.0;
  };
  if (trigonometric) {
    // Depths fill [0, 2 pi - theta] of the circle (MOMENTS.md 4.2); bias scales toward uniform.
    const double kWrap = kPi / 10.0;
    auto angle = [&](double z) { return (warp(z) + 1.0) * (kPi - kWrap / 2.0); };
    std::vector<std::complex<double>> c(m + 1, 0.0);  // normalised (c_j / c_0) after each fragment
    double total = 0.0;
    for (const Fragment& f : fragments) {
      const double a = -std::log(1.0 - std::min(f.alpha, 0.999));
      if (!(a > 0.0)) continue;  // nothing to add (and total + a would be 0 for a first such fragment)
      for (int j = 1; j <= m; ++j) {
        c[j] = (c[j] * total + a * std::polar(1.0, j * angle(f.depth))) / (total + a);
        if (unorm16) {  // stored as c/2 + 1/2 in 16 bits, per component
          auto q = [](double v) { return (std::round(std::clamp(0.5 * v + 0.5, 0.0, 1.0) * 65535.0) / 65535.0 - 0.5) * 2.0; };
          c[j] = {q(c[j].real()), q(c[j].imag())};
        } else {
          c[j] = {kept(c[j].real()), kept(c[j].imag())};
        }
      }
      total = kept(total + a);
    }
    const double total_transmittance = std::exp(-total);
    if (total < 0.00100050033) return background * total_transmittance;
    const double trig_bias = alpha_bias;
    for (int j = 1; j <= m; ++j) c[j] *= (1.0 - trig_bias);
    c[0] = 1.0;
    Vec3d accum = Vec3d::Zero();
    double accum_alpha = 0.0;
    for (const Fragment& f : fragments) {
      const double alpha = std::min(f.alpha, 0.999);
      const MomentBound bound = trigonometric_bound(c, angle(f.depth));
      const double absorbance = std::clamp(bound.lower + options.beta * bound.at_query, 0.0, 1.0);
      const double t = std::clamp(std::exp(-total * absorbance), 0.0, 1.0);
      accum += alpha * t * f.colour;
      accum_alpha += alpha * t;
    }
    if (!(accum_alpha > 0.0)) return background * total_transmittance;
    return total_transmittance * background + (1.0 - total_transmittance) * accum / accum_alpha;
  }
  // Pass 1: absorbance a = -ln(1 - alpha), alpha clamped so a stays finite (vkQuake: 0.999);
  // b_j = sum a z^j / sum a. The 16-bit ROV variant stores the moments normalised by b0 and
  // re-quantises them after every fragment, in list order; fp32 sums in single precision (additive
  // blending into a float render target) and normalises once (a trial: the sums were kept in double,
  // up to 3.4e-3 from a float emulation).
  // The warped depths are kept for pass 2 (one log per fragment, not two).
  thread_local std::vector<double> warped;
  warped.resize(fragments.size());
  std::array<double, PowerMomentBound::kMaxMoments + 1> b{};
  double total = 0.0;
  for (size_t i = 0; i < fragments.size(); ++i) {
    const double a = -std::log(1.0 - std::min(fragments[i].alpha, 0.999));
    const double z = warped[i] = warp(fragments[i].depth);
    if (!unorm16) {
      double power = z;
      for (int j = 1; j <= m; ++j, power *= z) b[j] = kept(b[j] + kept(a * power));
      total = kept(total + kept(a));
      continue;
    }
    if (!(a > 0.0)) continue;  // nothing to add (and total + a would be 0 for a first such fragment)
    double power = z;
    for (int j = 1; j <= m; ++j, power *= z) b[j] = (b[j] * total + a * power) / (total + a);
    total += a;
    if (m == 4) {
      const Moments4 stored = stored_moments({b[1], b[2], b[3], b[4]}, Storage::kUnorm16, true);
      for (int j = 1; j <= 4; ++j) b[j] = stored[j - 1];
    } else {
      const std::vector<double> stored = stored_mboit_unorm16(std::vector<double>(b.begin() + 1, b.begin() + m + 1));
      std::copy(stored.begin(), stored.end(), b.begin() + 1);
    }
  }
  const double total_transmittance = std::exp(-total);
  if (total < 0.00100050033) return background * total_transmittance + Vec3d::Zero();  // < 0.1 % covered
  if (!unorm16) {
    for (int j = 1; j <= m; ++j) b[j] = kept(b[j] / total);
  }
  // Bias (1 - alpha) b + alpha b*, and the Hankel matrix factorised once for all the pixel's
  // fragments (PowerMomentBound; closed-form roots for 4 moments).
  b[0] = 1.0;
  auto biased = [&](double bias) {
    std::array<double, PowerMomentBound::kMaxMoments + 1> out = b;
    for (int j = 1; j <= m; ++j) out[j] = (1.0 - bias) * b[j] + bias * target[size_t(j - 1)];
    return out;
  };
  // Each fragment's bound (pass 2 reads them).
  thread_local std::vector<MomentBound> bounds;
  bounds.resize(fragments.size());
  auto bound_all = [&](double bias) {
    const std::array<double, PowerMomentBound::kMaxMoments + 1> moments = biased(bias);
    const PowerMomentBound bound_of(moments.data(), m);
    bool falls_back = false;
    for (size_t i = 0; i < fragments.size(); ++i) falls_back |= (bounds[i] = bound_of.at(warped[i])).fallback;
    return falls_back;
  };
  // 16 bits: the moments re-quantised after every fragment can leave the moment space by their
  // rounding, in an order-dependent way; the Hankel matrix is then indefinite and every fragment
  // got the fallback's transmittance (8 moments: up to half the pixel's colour between orders of
  // three fragments, a trial). Such a pixel is biased kRebias times more, as often as needed up to
  // a bias of 0.5 (a single fragment's fallback is exact: MOMENTS.md 4.6).
  constexpr double kRebias = 10.0;
  const bool rounded = unorm16 && fragments.size() > 1;
  for (double bias = alpha_bias; bound_all(bias) && rounded && bias * kRebias < 0.5;) bias *= kRebias;
  // Pass 2: each fragment weighted by its estimated transmittance.
  Vec3d accum = Vec3d::Zero();
  double accum_alpha = 0.0;
  for (size_t i = 0; i < fragments.size(); ++i) {
    const Fragment& f = fragments[i];
    const double alpha = std::min(f.alpha, 0.999);
    const MomentBound& bound = bounds[i];
    const double absorbance = bound.lower + options.beta * bound.at_query;
    const double t = std::clamp(std::exp(-total * absorbance), 0.0, 1.0);
    accum += alpha * t * f.colour;
    accum_alpha += alpha * t;
  }
  // Resolve: the total coverage is exact; the colour is the transmittance-weighted average.
  if (!(accum_alpha > 0.0)) return background * total_transmittance;
  return total_transmittance * background + (1.0 - total_transmittance) * accum / accum_alpha;
}

OitMethod parse_oit_method(const std::string& name) {
  if (name == "exact") return OitMethod::kExact;
  if (name == "peel") return OitMethod::kPeel;
  if (name == "wboit") return OitMethod::kWboit;
  if (name == "mboit") return OitMethod::kMboit;
  throw_invalid("method must be 'exact', 'peel', 'wboit' or 'mboit' (got '", name, "')");
}

const char* oit_method_name(OitMethod method) {
  switch (method) {
    case OitMethod::kExact: return "exact";
    case OitMethod::kPeel: return "peel";
    case OitMethod::kWboit: return "wboit";
    case OitMethod::kMboit: return "mboit";
  }
  return "?";
}

MomentBasis parse_moment_basis(const std::string& name) {
  if (name == "power") return MomentBasis::kPower;
  if (name == "trigonometric") return MomentBasis::kTrigonometric;
  throw_invalid("basis must be 'power' or 'trigonometric' (got '", name, "')");
}

const char* moment_basis_name(MomentBasis basis) { return basis == MomentBasis::kTrigonometric ? "trigonometric" : "power"; }

WboitWeight parse_wboit_weight(const std::string& name) {
  if (name == "eq7") return WboitWeight::kEq7;
  if (name == "eq9") return WboitWeight::kEq9;
  throw_invalid("weight must be 'eq7' or 'eq9' (got '", name, "')");
}

const char* wboit_weight_name(WboitWeight weight) { return weight == WboitWeight::kEq9 ? "eq9" : "eq7"; }

double MboitSettings::published_bias(MomentBasis basis, int moments, Storage storage) {
  if (basis == MomentBasis::kTrigonometric) return moments == 2 ? 4e-4 : 2e-4;
  if (storage == Storage::kUnorm16) return moments == 4 ? 6e-5 : (moments == 6 ? 5e-5 : 5e-4);
  return moments == 4 ? 5e-7 : (moments == 6 ? 5e-6 : 5e-5);
}

void MboitSettings::check(Problems& problems) const {
  const int m = moments;
  if (basis == MomentBasis::kTrigonometric) {
    problems.check(m >= 2 && m <= 4, "trigonometric moments must be 2, 3 or 4 (got ", m, ")");
  } else {
    problems.check(m == 4 || m == 6 || m == 8, "power moments must be 4, 6 or 8 (got ", m, ")");
  }
  problems.check(beta >= 0.0 && beta <= 1.0, "beta must be in [0, 1] (got ", beta, ")");
  if (bias) problems.check(*bias >= 0.0 && *bias < 1.0, "bias must be in [0, 1) (got ", *bias, ")");
  problems.check(std::isfinite(z_near) && std::isfinite(z_far), "z_near and z_far must be finite");
  if (z_far > z_near) {
    problems.check(z_near > 0.0, "z_near must be > 0 with z_far > z_near (got z_near ", z_near, ", z_far ", z_far, ")");
  } else if (z_near != 0.0 || z_far != 0.0) {  // (10, 1) was taken silently as the fragments' own range
    problems.check(false, "z_far must exceed z_near (got z_near ", z_near, ", z_far ", z_far,
                   "); both 0, the default, take the fragments' own range");
  }
}

void MboitSettings::validate() const {
  Problems problems("MboitSettings");
  check(problems);
  problems.throw_if_any();
}

void OitSettings::check(Problems& problems) const {
  if (method == OitMethod::kPeel) problems.check(layers >= 1, "layers must be >= 1 (got ", layers, ")");
  if (method == OitMethod::kMboit) problems.check_nested("mboit", mboit);
}

void OitSettings::validate() const {
  Problems problems("OitSettings");
  check(problems);
  problems.throw_if_any();
}

double OitSettings::bytes_per_pixel(double fragments_per_pixel) const {
  if (!(fragments_per_pixel >= 0.0 && std::isfinite(fragments_per_pixel))) {
    throw_invalid("bytes_per_pixel: fragments_per_pixel must be finite and >= 0 (got ", fragments_per_pixel, ")");
  }
  switch (method) {
    case OitMethod::kExact: return 20.0 * fragments_per_pixel;
    case OitMethod::kPeel: return 12.0 * layers;
    case OitMethod::kWboit: return 10.0;
    case OitMethod::kMboit:
      return 4.0 + (mboit.storage == Storage::kUnorm16 ? 2.0 : 4.0) *
                       (mboit.basis == MomentBasis::kTrigonometric ? 2 * mboit.moments : mboit.moments) +
             8.0;
  }
  return 0.0;
}

Vec3d composite(const std::vector<Fragment>& fragments, const Vec3d& background, const OitSettings& settings) {
  switch (settings.method) {
    case OitMethod::kExact: return composite_exact(fragments, background);
    case OitMethod::kPeel: return composite_peeled(fragments, background, settings.layers);
    case OitMethod::kWboit: return composite_wboit(fragments, background, settings.weight);
    case OitMethod::kMboit: return composite_mboit(fragments, background, settings.mboit);
  }
  return background;
}

}  // namespace refracta
