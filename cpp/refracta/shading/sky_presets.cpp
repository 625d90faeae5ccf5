// Ready-made skies (sky_presets.h).
#include "refracta/shading/sky_presets.h"

#include "refracta/core/error.h"
#include "refracta/core/spectrum.h"
#include "refracta/shading/constant_environment.h"
#include "refracta/shading/environment_light.h"
#include "refracta/shading/scaled_light.h"
#include "refracta/shading/sun_light.h"
#include "refracta/shading/tonemap.h"  // read_linear_image

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

namespace refracta {

Image gradient_sky_image(const Vec3d& horizon, const Vec3d& zenith) {
  // Rows at EnvironmentLight's nodes (row y at theta = pi y / (rows - 1), the poles on the first
  // and last), 257 so that the horizon is a node: the blend is exact there and at every node, and
  // its linear interpolation between them within (pi / 256)^2 / 8 = 2e-5 of its range. (Rows at
  // texel centres sat half a row off the lookup's nodes: the sky was 0.4 % low and its horizon
  // blurred over a row.) Azimuth needs no resolution.
  constexpr int kRows = 257, kColumns = 4;
  Image image(kColumns, kRows, 3);
  for (int y = 0; y < kRows; ++y) {
    const double theta = kPi * y / (kRows - 1);  // from the zenith
    const double t = std::clamp(std::cos(theta), 0.0, 1.0);
    const Vec3d c = (1.0 - t) * horizon + t * zenith;
    for (int x = 0; x < kColumns; ++x) {
      for (int k = 0; k < 3; ++k) image.at(x, y)[k] = float(c[k]);
    }
  }
  return image;
}

LightPtr gradient_sky(const Vec3d& horizon, const Vec3d& zenith, double scale) {
  if (!(scale >= 0.0) || !std::isfinite(scale)) throw_invalid("scale must be >= 0 (got ", scale, ")");
  Problems problems("set_sky");
  auto check = [&](const char* name, const Vec3d& radiance) {
    problems.check(radiance.allFinite() && radiance.minCoeff() >= 0.0, name,
                   " must be finite and >= 0 per channel (got (", radiance.x(), ", ", radiance.y(), ", ", radiance.z(),
                   "))");
  };
  check("horizon", horizon);
  if (zenith != horizon) check("zenith", zenith);
  problems.throw_if_any();
  if (!(scale * std::max(horizon.maxCoeff(), zenith.maxCoeff()) <= kMaxRadiance)) {
    throw_invalid("set_sky: the sky's radiance times scale must be at most ", kMaxRadiance, " (got scale ", scale,
                  "): images are float32");
  }
  if (!(horizon.maxCoeff() > 0.0 || zenith.maxCoeff() > 0.0)) return nullptr;  // black: no sky
  if (zenith == horizon) {  // a constant sky, sampled by cosine
    return std::make_shared<ConstantEnvironment>(Color::illuminant(horizon * scale));
  }
  return std::make_shared<EnvironmentLight>(gradient_sky_image(horizon, zenith), scale);
}

void SunDisc::validate() const {
  Problems problems("set_physical_sky");
  problems.check(angular_diameter >= SunLight::kMinAngularDiameter && angular_diameter < 180.0,
                 "sun_angular_diameter must be in [", SunLight::kMinAngularDiameter, ", 180) deg (got ",
                 angular_diameter, ")");
  problems.check(limb_darkening >= 0.0 && limb_darkening <= 1.0, "limb_darkening must be in [0, 1] (got ",
                 limb_darkening, ")");
  problems.throw_if_any();
}

SkyAndSun physical_sky_with_sun(const PhysicalSkySettings& settings, const SunDisc& disc, double scale,
                                const SkyBuilder& build) {
  settings.validate();
  disc.validate();
  if (!(scale >= 0.0 && scale <= kMaxRadiance)) {
    throw_invalid("scale must be in [0, ", kMaxRadiance, "] (got ", scale, "): images are float32");
  }
  const std::shared_ptr<PhysicalSkyLight> sky = build ? build(settings) : std::make_shared<PhysicalSkyLight>(settings);
  std::vector<double> lambda, radiance;
  for (int i = 0; i < PhysicalSky::kWavelengths; ++i) {
    lambda.push_back(PhysicalSky::wavelength(i));
    radiance.push_back(scale * sky->sky().sun_radiance(lambda.back(), disc.angular_diameter));
  }
  const Color sun_colour = Color::tabulated(lambda, radiance, Color::Kind::kIlluminant);
  SkyAndSun out;
  if (scale > 0.0) out.sky = scale == 1.0 ? LightPtr(sky) : std::make_shared<ScaledInfiniteLight>(sky, scale);
  if (!sun_colour.is_black() && sun_colour.rgb().maxCoeff() > 0.0) {
    out.sun = std::make_shared<SunLight>(settings.sun_direction, sun_colour, disc.angular_diameter, disc.limb_darkening);
  }
  return out;
}

std::shared_ptr<EnvironmentLight> environment_from_file(const std::string& path, double scale, const Mat3d& rotation) {
  // An 8- or 16-bit map holds sRGB-encoded colour, as a texture does (textures.cpp): decoded to
  // radiance, alpha aside (a PNG's 128 was radiance 0.502, a texture's 0.216: a trial).
  Image image = read_linear_image(path);
  auto light = std::make_shared<EnvironmentLight>(std::move(image), scale, rotation);
  light->set_source(std::filesystem::absolute(path).string());
  return light;
}

}  // namespace refracta
