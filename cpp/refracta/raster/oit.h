// Order-independent transparency for one pixel's fragments (view depth, alpha, colour):
// the exact front-to-back composite (= depth peeling with enough layers), depth peeling with k
// layers, weighted blended OIT (McGuire & Bavoil, JCGT 2013) and moment-based OIT with power
// moments (Muenstermann et al., I3D 2018; MOMENTS.md 4).
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/math.h"
#include "refracta/raster/quantization.h"

#include <optional>
#include <string>
#include <vector>

namespace refracta {

struct Fragment {
  double depth;  // view depth [m], > 0
  double alpha;  // in [0, 1]
  Vec3d colour;  // linear RGB, not premultiplied
};

// MBOIT's moments: powers of the warped depth, or trigonometric (Fourier) ones on a circle.
enum class MomentBasis { kPower, kTrigonometric };
MomentBasis parse_moment_basis(const std::string& name);  // "power", "trigonometric"
const char* moment_basis_name(MomentBasis basis);

// WBOIT's depth weight: McGuire & Bavoil (JCGT 2013) equation 7 or 9.
enum class WboitWeight { kEq7, kEq9 };
WboitWeight parse_wboit_weight(const std::string& name);  // "eq7", "eq9"
const char* wboit_weight_name(WboitWeight weight);

// Moment-based order-independent transparency (Muenstermann et al., I3D 2018): basis
// 'power' (moments 4, 6 or 8) or 'trigonometric' (2, 3 or 4); overestimation beta; bias None: the
// published value for the basis, moment count and storage; storage 'fp32', 'unorm16' (the 16-bit
// ROV variant, re-quantised after every fragment) or 'fp64' (the method itself); log-depth warp
// over [z_near, z_far] [m] (both 0: the fragments' own range, in render_raster the frame's).
struct MboitSettings {
  MomentBasis basis = MomentBasis::kPower;
  int moments = 4;              // 4, 6 or 8 power moments; 2, 3 or 4 trigonometric
  double beta = 0.25;           // overestimation in [0, 1]: the share of the fragment's own layer in front
  // alpha, the weight of the bias vector in [0, 1); unset (None) gives the published value for
  // the basis, the moment count and the storage (published_bias).
  std::optional<double> bias;
  double z_near = 0.0;  // near end of the log-depth warp [m]
  double z_far = 0.0;   // far end of the log-depth warp [m]; both 0: the fragments' own range
  // fp32: the moments summed and normalised in single precision (additive blending into a float
  // render target); unorm16, the 16-bit ROV variant (MOMENTS.md 4.5): b0 in fp32 and the
  // normalised moments re-quantised to 16 bits after every fragment, in list order (4 power
  // moments through Theta*_4, 6 and 8 through the MBOIT matrices (stored_mboit_unorm16),
  // trigonometric ones as c/2 + 1/2); fp64: in double, no GPU's storage but the method's own
  // behaviour (order independence, exactness for n/2 + 1 fragments), with fp32's bias.
  Storage storage = Storage::kFp32;

  // fp32: 5e-7 / 5e-6 / 5e-5 for 4 / 6 / 8 power moments; unorm16: 6e-5 (the Unity HDRP port),
  // 5e-5, 5e-4; trigonometric: 4e-4 for 2 moments, 2e-4 for 3 and 4.
  static double published_bias(MomentBasis basis, int moments, Storage storage);
  double bias_or_published() const { return bias ? *bias : published_bias(basis, moments, storage); }
  void check(Problems& problems) const;  // adds every bad field
  void validate() const;                 // throws std::invalid_argument listing them all
};

Vec3d composite_exact(std::vector<Fragment> fragments, const Vec3d& background);
Vec3d composite_peeled(std::vector<Fragment> fragments, const Vec3d& background, int layers);
Vec3d composite_wboit(const std::vector<Fragment>& fragments, const Vec3d& background, WboitWeight weight);
Vec3d composite_mboit(const std::vector<Fragment>& fragments, const Vec3d& background, const MboitSettings& options);

void validate_fragments(const std::vector<Fragment>& fragments);  // throws std::invalid_argument

enum class OitMethod { kExact, kPeel, kWboit, kMboit };
OitMethod parse_oit_method(const std::string& name);  // "exact", "peel", "wboit", "mboit"
const char* oit_method_name(OitMethod method);

// How surfaces with alpha < 1 are composited: method 'exact' (sorted: depth peeling with enough
// layers), 'peel' (the `layers` nearest), 'wboit' (McGuire & Bavoil, JCGT 2013, depth weight 'eq7'
// or 'eq9') or 'mboit' (moment-based, settings in `mboit`).
struct OitSettings {
  OitMethod method = OitMethod::kMboit;
  int layers = 4;               // peel: layers kept
  WboitWeight weight = WboitWeight::kEq7;  // wboit
  MboitSettings mboit;  // MboitSettings (method 'mboit')

  void check(Problems& problems) const;  // adds every bad field (of the method's settings)
  void validate() const;                 // throws std::invalid_argument listing them all
  // Bytes per pixel a GPU would keep: sorted lists 20 per fragment (depth, alpha, RGB fp32);
  // peeling 12 per layer (RGBA16F + depth fp32); WBOIT 10 (RGBA16F + R16F); MBOIT b0 in fp32 and
  // the moments in fp32 or 16 bits, plus the RGBA16F accumulation. ValueError unless
  // fragments_per_pixel is finite and >= 0.
  double bytes_per_pixel(double fragments_per_pixel) const;
};

Vec3d composite(const std::vector<Fragment>& fragments, const Vec3d& background, const OitSettings& settings);

}  // namespace refracta
