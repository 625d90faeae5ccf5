// The physical sky seen from above the scene's ground. The sky's table is the sky of an observer
// at its altitude, the scene's y = 0, while the aerial perspective fills and dims every segment
// with the air at the segment's own heights: from a raised camera a black object far away then
// fades toward the in-scatter of the air at the camera's height, and the sky behind it stayed the
// ground's -- from 200 m in 5 km visibility the horizon is 31 % brighter than from the ground
// (from 1 850 m in clear air 48 %), and distant black boxes showed brighter than the sky beside
// them (a trial: contrast -0.2 at 5 and 10 km, where Koschmieder gives 0.02 and 0.0004). The sun
// likewise: it reaches 200 m through less haze (e^0.28 more light there, 5 km visibility, 30 deg).
//
// RaisedSky tabulates the sky also for an observer at about the camera's height (kHeightStep),
// and a path that leaves the air from height y sees the two blended linearly in y between 0 and
// the camera's height, clamped: the camera's own rays see its sky above the horizon (below it, with
// below_horizon 'ground', the ground's radiance without the air between), paths leaving the
// ground the ground's, between them a blend (over a 1.2 km aerosol scale height a few percent
// off mid-way from 1 850 m), above the camera the camera's. The sun's radiance is scaled alike by
// the ratio of its transmittances to the two heights. Light sampling keeps the ground sky's
// distribution (its density is the sampling's; only the radiance a sample carries moves).
#pragma once

#include "refracta/core/spectrum.h"
#include "refracta/render/render_scene.h"
#include "refracta/shading/physical_sky.h"

#include <array>
#include <memory>

namespace refracta {

class RaisedSky {
 public:
  // Below this camera height [m] the ground's sky serves: the horizon from 10 m differs from the
  // ground's by ~0.3 % in clear air, ~1.6 % in 5 km visibility (PhysicalSky(altitude=h)).
  static constexpr double kLeastHeight = 10.0;
  // The raised table's height is the camera's to this fraction (a 1 % grid in log height): a
  // camera moved by less (an editor's drag, a sweep's small steps) reuses the cached table.
  static constexpr double kHeightStep = 0.01;

  // The raised sky of a render whose camera is at scene height camera_y, or null where the
  // ground's serves: a scene without aerial perspective (its sky is the sky from y = 0 by
  // definition) or a camera within kLeastHeight of y = 0. A camera beyond the sky model's highest
  // altitude sees the sky from there. The table is PhysicalSky::shared's (built once per height,
  // 0.5-1.6 s, then cached).
  static std::shared_ptr<const RaisedSky> for_camera(const RenderScene& scene, double camera_y);

  // Whether `light` is a light this raises (the scene's sky or sun).
  bool raises(const Light& light) const { return &light == ground_ || &light == sun_; }
  // `light`'s radiance along dir as seen from scene height y, given `ground`, its radiance as seen
  // from y = 0 (its Le, or a light sample's L); any other light: `ground`.
  Spectrum seen_from(const Light& light, double y, const Vec3d& dir, const Spectrum& ground,
                     const SampledWavelengths& lambda) const;
  // The same from the light's own Le, evaluated only where the blend needs it (a camera ray that
  // leaves the air sees the raised sky alone).
  Spectrum Le(const Light& light, double y, const Vec3d& dir, const SampledWavelengths& lambda) const;

 private:
  double blend(double y) const;  // the raised table's weight at height y, in [0, 1]

  const Light* ground_ = nullptr;  // the scene's sky light (perhaps scaled)
  const Light* sun_ = nullptr;     // the scene's sun, or null
  std::shared_ptr<const PhysicalSky> ground_sky_;
  std::shared_ptr<const PhysicalSkyLight> raised_;
  Vec3d sun_ratio_rgb_ = Vec3d::Ones();  // the sun's RGB radiance at the raised height over the ground's
  double height_ = 0.0;  // the camera's height [m]: the blend's top (its table: height_ to kHeightStep)
  double scale_ = 1.0;
};

}  // namespace refracta
