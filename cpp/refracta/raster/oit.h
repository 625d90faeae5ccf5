// Order-independent transparency for one pixel's fragments (view depth, alpha, colour):
// the exact front-to-back composite (= depth peeling with enough layers), depth peeling with k
// layers, weighted blended OIT (McGuire & Bavoil, JCGT 2013) and moment-based OIT with power
// moments (Muenstermann et al., I3D 2018; MOMENTS.md 4).
#pragma once

#include "refracta/core/math.h"

#include <string>
#include <vector>

namespace refracta {

struct Fragment {
  double depth;  // view depth [m], > 0
  double alpha;  // in [0, 1]
  Vec3d colour;  // linear RGB, not premultiplied
};

struct MbOitOptions {
  bool trigonometric = false;   // power moments (4, 6, 8) or trigonometric ones (2, 3, 4 complex)
  int moments = 4;              // 4, 6 or 8 power moments; 2, 3 or 4 trigonometric
  double beta = 0.25;           // overestimation: the share of the fragment's own layer in front
  double bias = -1.0;           // < 0: the published fp32 value for the moment count
  double z_near = 0.0, z_far = 0.0;  // log-warp range; z_far <= z_near: the fragments' own range
  // fp32 (emulated in double), or the 16-bit ROV variant (MOMENTS.md 4.5): b0 in fp32 and the
  // normalised moments re-quantised to 16 bits after every fragment, in list order (4 power
  // moments through Theta*_4, 6 and 8 through the MBOIT matrices (stored_mboit_unorm16),
  // trigonometric ones as c/2 + 1/2).
  bool unorm16 = false;
};

Vec3d composite_exact(std::vector<Fragment> fragments, const Vec3d& background);
Vec3d composite_peeled(std::vector<Fragment> fragments, const Vec3d& background, int layers);
// weight: "eq7" or "eq9" of McGuire & Bavoil.
Vec3d composite_wboit(const std::vector<Fragment>& fragments, const Vec3d& background, const std::string& weight);
Vec3d composite_mboit(const std::vector<Fragment>& fragments, const Vec3d& background, const MbOitOptions& options);

void validate_fragments(const std::vector<Fragment>& fragments);  // throws std::invalid_argument

enum class OitMethod { kExact, kPeel, kWboit, kMboit };
OitMethod parse_oit_method(const std::string& name);  // "exact", "peel", "wboit", "mboit"

// One OIT configuration: the method and its settings.
struct OitSettings {
  OitMethod method = OitMethod::kMboit;
  int layers = 4;               // peel
  std::string weight = "eq7";   // wboit
  MbOitOptions mboit;

  void validate() const;        // throws std::invalid_argument naming the bad field
  // Bytes per pixel a GPU would keep: sorted lists 20 per fragment (depth, alpha, RGB fp32);
  // peeling 12 per layer (RGBA16F + depth fp32); WBOIT 10 (RGBA16F + R16F); MBOIT b0 in fp32 and
  // the moments in fp32 or 16 bits, plus the RGBA16F accumulation.
  double bytes_per_pixel(double fragments_per_pixel) const;
};

Vec3d composite(const std::vector<Fragment>& fragments, const Vec3d& background, const OitSettings& settings);

}  // namespace refracta
