// Ready-made skies of Scene.set_sky and Scene.set_physical_sky: the gradient sky a mirage scene
// needs behind it, and the physical sky with the sun it implies.
#pragma once

#include "refracta/core/image.h"
#include "refracta/core/math.h"
#include "refracta/shading/environment_light.h"
#include "refracta/shading/light.h"
#include "refracta/shading/physical_sky.h"

#include <functional>
#include <memory>
#include <string>

namespace refracta {

// Scene.set_sky's horizon when none is given: a clear day's pale blue (linear RGB radiance
// [W/(m^2 sr)]), bright enough that an unlit test scene is readable at exposure 1.
inline const Vec3d kDefaultSkyColour{0.7, 0.8, 0.95};

// The gradient sky as a small equirectangular map (256 rows x 4 columns: constant in azimuth):
// linear in sin(elevation) from `horizon` (and below) to `zenith`, rows from the zenith down.
Image gradient_sky_image(const Vec3d& horizon, const Vec3d& zenith);

// The sky light of Scene.set_sky, times scale (>= 0): a ConstantEnvironment (cosine-sampled) when
// zenith == horizon, else an EnvironmentLight of gradient_sky_image; null when it is black.
LightPtr gradient_sky(const Vec3d& horizon, const Vec3d& zenith, double scale);

// The sun disc of a physical sky.
struct SunDisc {
  double angular_diameter = 0.53;  // [deg] in (0, 180): the sun's mean apparent diameter
  double limb_darkening = 0.0;     // u in [0, 1]: I(mu) = 1 - u (1 - mu)
  void validate() const;           // throws std::invalid_argument listing every problem
};

// A physical sky and the sun it implies, both times scale (>= 0), either null when black: the sky
// light (scaled unless scale is 1), and a SunLight toward the sky's sun of the solar disc's
// radiance through the sky's extinction at its 10 nm nodes (Color::tabulated interpolates to
// 1 nm). Spectral radiance [W/(m^2 sr nm)] in spectral renders, its CIE-Y-weighted mean in RGB
// (Color::illuminant's convention: RGB (1, 1, 1) is D65 at 1 W/(m^2 sr nm) mean; multiply by
// integral ybar = 106.86 nm for W/(m^2 sr)). Everything is validated before `build` makes the
// sky's table (~0.5 s; the bindings build it interruptibly).
struct SkyAndSun {
  LightPtr sky, sun;
};
using SkyBuilder = std::function<std::shared_ptr<PhysicalSkyLight>(const PhysicalSkySettings&)>;
SkyAndSun physical_sky_with_sun(const PhysicalSkySettings& settings, const SunDisc& disc, double scale,
                                const SkyBuilder& build = {});

// An equirectangular environment map read from a file (any format OpenImageIO reads), remembering
// the file's absolute path (a pickled scene refers to it).
std::shared_ptr<EnvironmentLight> environment_from_file(const std::string& path, double scale = 1.0,
                                                        const Mat3d& rotation = Mat3d::Identity());

}  // namespace refracta
