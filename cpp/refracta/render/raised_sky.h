// The physical sky seen from above the scene's ground. The sky's table is the sky of an observer
// at its altitude, the scene's y = 0, while the aerial perspective fills and dims every segment
// with the air at the segment's own heights: from a raised camera a black object far away then
// fades toward the in-scatter of the air at the camera's height, and the sky behind it stayed the
// ground's -- from 200 m in 5 km visibility the horizon is 31 % brighter than from the ground
// (from 1 850 m in clear air 48 %), and distant black boxes showed brighter than the sky beside
// them (a trial: contrast -0.2 at 5 and 10 km, where Koschmieder gives 0.02 and 0.0004).
//
// RaisedSky tabulates the sky also for an observer at the camera's height, and a path that leaves
// the air from height y sees the two blended linearly in y between 0 and the camera's height
// (clamped): exact for the camera's own rays (what shows behind every object) and for paths
// leaving from the ground, between them a blend of the two. Light sampling keeps the ground
// sky's distribution (its density is the sampling's; only the radiance a sample carries moves).
#pragma once

#include "refracta/core/spectrum.h"
#include "refracta/render/render_scene.h"
#include "refracta/shading/physical_sky.h"

#include <memory>

namespace refracta {

class RaisedSky {
 public:
  // Below this camera height [m] the ground's sky serves: the horizon from 10 m differs from the
  // ground's by ~0.3 % in clear air, ~1.6 % in 5 km visibility (PhysicalSky(altitude=h)).
  static constexpr double kLeastHeight = 10.0;

  // The raised sky of a render whose camera is at scene height camera_y, or null where the
  // ground's serves: a scene without aerial perspective (its sky is the sky from y = 0 by
  // definition), a camera within kLeastHeight of y = 0 or beyond the sky model's altitudes. The
  // table is PhysicalSky::shared's (built once per height, ~0.5 s, then cached).
  static std::shared_ptr<const RaisedSky> for_camera(const RenderScene& scene, double camera_y);

  // Whether `light` is the sky this raises.
  bool raises(const Light& light) const { return &light == ground_; }
  // `light`'s radiance along dir as seen from scene height y (any other light: its Le).
  Spectrum Le(const Light& light, double y, const Vec3d& dir, const SampledWavelengths& lambda) const;

 private:
  const Light* ground_ = nullptr;  // the scene's sky light (perhaps scaled)
  std::shared_ptr<const PhysicalSkyLight> raised_;
  double height_ = 0.0, scale_ = 1.0;
};

}  // namespace refracta
