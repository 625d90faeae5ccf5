// Shadow maps of a directional light (the sun, orthographic) or a spot light (perspective) from
// refracta's rasterizer: the light-view depth
// map, and what each method reads from it (shared/MOMENTS.md):
//   hard       one depth compare (the classic shadow map);
//   pcf        the fraction of a k x k texel window in front of the receiver (cost grows as k^2);
//   vsm, hamburger, hausdorff
//              four power moments (z, z^2, z^3, z^4) per texel, box-filtered over k x k texels by
//              separable running sums (cost independent of k), stored as fp64 / fp32 / unorm16
//              (the optimised quantisation transforms), read with bilinear filtering, then VSM,
//              Hamburger 4MSM or Hausdorff 4MSM.
// Depths are normalised to [0, 1] (or [-1, 1] for signed) over the depth range the map holds.
#pragma once

#include "refracta/core/memory.h"
#include "refracta/core/parallel.h"
#include "refracta/raster/moment_shadow.h"
#include "refracta/raster/rasterizer.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace refracta {

enum class ShadowMethod { kHard, kPcf, kVsm, kHamburger, kHausdorff };
ShadowMethod parse_shadow_method(const std::string& name);  // "hard", "pcf", "vsm", "msm_hamburger", "msm_hausdorff"
const char* shadow_method_name(ShadowMethod method);

// The shadow maps of render_raster (an orthographic map for the sun, a perspective one per spot
// light): method 'hard' (one depth compare), 'pcf' (kernel x kernel compares), 'vsm',
// 'msm_hamburger', 'msm_hausdorff' (four moments box-filtered kernel x kernel, read through
// `moments`).
struct ShadowMapOptions {
  ShadowMethod method = ShadowMethod::kHamburger;
  int resolution = 1024;     // texels per side, in [2, 8192]
  int kernel = 1;            // k x k filter (odd) of PCF and of the moment map
  MomentShadowSettings moments;  // MomentShadowSettings of the moment methods (vsm, msm_*): depth range, storage, bias
  double depth_bias = 2e-4;  // hard / pcf: compare against z - depth_bias (normalised depth)
  double normal_offset = 1.5;  // receivers are moved this many texels along their normal
  // VSM light-bleeding reduction (Lauritzen) in [0, 1): intensities below this amount of light become 0.
  double bleeding_reduction = 0.0;

  void check(Problems& problems) const;  // adds every bad field
  // A map's bytes per texel while it is built: the depth, and the moment methods' float moments.
  double bytes_per_texel() const;
  void validate() const;                 // throws std::invalid_argument listing them all
};

class ShadowMap {
 public:
  // The sun shining along -toward_light onto the square of half-size `half_size` [m] around
  // `centre` (seen from the light).
  ShadowMap(const Scene& scene, const Vec3d& toward_light, const Vec3d& centre, double half_size,
            const ShadowMapOptions& options, WorkControl& control);
  // Any light view: a spot light's perspective view from its position (RasterView::perspective).
  ShadowMap(const Scene& scene, const RasterView& light_view, const ShadowMapOptions& options, WorkControl& control);

  // Shadow intensity in [0, 1] at a surface point with unit normal n (0: lit, 1: in shadow).
  double shadow(const Vec3d& point, const Vec3d& normal) const;
  // Bytes per texel of what the method reads (depth: fp32; moments: 4 x fp64 / fp32 / unorm16).
  int bytes_per_texel() const;
  double build_seconds() const { return build_seconds_; }
  const ShadowMapOptions& options() const { return options_; }

 private:
  void build(const Scene& scene, WorkControl& control);
  double normalised(double depth) const;
  double depth_at(int x, int y) const;  // normalised; the far end where nothing is drawn

  ShadowMapOptions options_;
  RasterView view_;
  VisibilityBuffer buffer_;
  double near_ = 0.0, far_ = 1.0;
  // The filtered moment map as stored, per texel: fp64, fp32, or unorm16 (the quantised q of the
  // optimised transform; lookups filter q bilinearly and transform back once, which equals
  // filtering the decoded moments because the transform is affine).
  UninitializedVector<Moments4> moments_;
  UninitializedVector<std::array<float, 4>> moments_fp32_;
  UninitializedVector<std::array<uint16_t, 4>> moments_unorm16_;
  double build_seconds_ = 0.0;
};

}  // namespace refracta
