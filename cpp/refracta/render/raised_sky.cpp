// The physical sky seen from a raised camera (raised_sky.h).
#include "refracta/render/raised_sky.h"

#include "refracta/shading/color.h"
#include "refracta/shading/sun_light.h"

#include <algorithm>
#include <cmath>

namespace refracta {

std::shared_ptr<const RaisedSky> RaisedSky::for_camera(const RenderScene& scene, double camera_y) {
  const Light* source = scene.aerial_source();
  if (!source || !(camera_y >= kLeastHeight)) return nullptr;
  double scale = 1.0;
  const PhysicalSkyLight* sky = physical_sky_of(*source, &scale);
  if (!sky) return nullptr;
  const double step = std::log1p(kHeightStep);
  PhysicalSkySettings settings = sky->settings();
  const double table = std::min(std::exp(std::round(std::log(camera_y) / step) * step),
                                kPhysicalSkyHighestAltitude - settings.altitude);
  if (!(table >= kLeastHeight)) return nullptr;  // the ground's own altitude is already the model's top
  settings.altitude += table;
  auto raised = std::make_shared<RaisedSky>();
  raised->ground_ = source;
  raised->sun_ = scene.sun();
  raised->ground_sky_ = PhysicalSky::shared(sky->settings());
  raised->raised_ = std::make_shared<const PhysicalSkyLight>(settings);
  // Ratios of the two suns as RGB renders take them (clip_keeping_luminance): the raised sun keeps
  // its own luminance where either spectrum leaves the gamut.
  const Vec3d below = clip_keeping_luminance(raised->ground_sky_->sun_radiance_rgb());
  const Vec3d above = clip_keeping_luminance(raised->raised_->sky().sun_radiance_rgb());
  for (int c = 0; c < 3; ++c) raised->sun_ratio_rgb_[c] = below[c] > 0.0 ? above[c] / below[c] : 1.0;
  raised->height_ = camera_y;
  raised->scale_ = scale;
  return raised;
}

double RaisedSky::blend(double y) const { return std::clamp(y / height_, 0.0, 1.0); }

Spectrum RaisedSky::seen_from(const Light& light, double y, const Vec3d& dir, const Spectrum& ground,
                              const SampledWavelengths& lambda) const {
  const double t = blend(y);
  if (t == 0.0 || !raises(light)) return ground;
  if (&light == sun_) {  // the ground's sun times the ratio of the transmittances to the two heights
    Spectrum ratio = Spectrum::Ones();
    for (int i = 0; i < kSpectrumSamples; ++i) {
      if (!lambda.spectral) {
        if (i < 3) ratio[i] = sun_ratio_rgb_[i];
      } else if (const double below = ground_sky_->sun_transmittance(lambda.lambda[i]); below > 0.0) {
        ratio[i] = raised_->sky().sun_transmittance(lambda.lambda[i]) / below;
      }
    }
    return (ground * (1.0 - t + t * ratio)).eval();
  }
  const Spectrum above = scale_ * raised_->Le(dir, lambda);
  return t == 1.0 ? above : ((1.0 - t) * ground + t * above).eval();
}

Spectrum RaisedSky::Le(const Light& light, double y, const Vec3d& dir, const SampledWavelengths& lambda) const {
  if (&light == ground_ && blend(y) == 1.0) return scale_ * raised_->Le(dir, lambda);
  return seen_from(light, y, dir, light.Le(dir, lambda), lambda);
}

}  // namespace refracta
