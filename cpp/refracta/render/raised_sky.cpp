// The physical sky seen from a raised camera (raised_sky.h).
#include "refracta/render/raised_sky.h"

#include "refracta/shading/scaled_light.h"

#include <algorithm>

namespace refracta {

std::shared_ptr<const RaisedSky> RaisedSky::for_camera(const RenderScene& scene, double camera_y) {
  const Light* source = scene.aerial_source();
  if (!source || !(camera_y >= kLeastHeight)) return nullptr;
  double scale = 1.0;
  const Light* inner = source;
  if (const auto* scaled = dynamic_cast<const ScaledInfiniteLight*>(inner)) scale = scaled->scale(), inner = scaled->light().get();
  const auto* sky = dynamic_cast<const PhysicalSkyLight*>(inner);
  if (!sky) return nullptr;
  PhysicalSkySettings settings = sky->settings();
  settings.altitude += camera_y;
  if (!(settings.altitude <= kPhysicalSkyHighestAltitude)) return nullptr;
  auto raised = std::make_shared<RaisedSky>();
  raised->ground_ = source;
  raised->raised_ = std::make_shared<const PhysicalSkyLight>(settings);
  raised->height_ = camera_y;
  raised->scale_ = scale;
  return raised;
}

Spectrum RaisedSky::Le(const Light& light, double y, const Vec3d& dir, const SampledWavelengths& lambda) const {
  if (&light != ground_) return light.Le(dir, lambda);
  const double t = std::clamp(y / height_, 0.0, 1.0);
  if (t == 0.0) return light.Le(dir, lambda);
  const Spectrum above = scale_ * raised_->Le(dir, lambda);
  return t == 1.0 ? above : ((1.0 - t) * light.Le(dir, lambda) + t * above).eval();
}

}  // namespace refracta
