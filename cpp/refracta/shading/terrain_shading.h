// A terrain's colour from where a point is, for elevation data without an orthophoto: vegetation
// low, bare rock above a tree line and on steep slopes, snow above a snow line where snow lies
// (not on cliffs); Lambertian (diffuse.h's BSDF) with that reflectance.
//   TerrainShading(snow_line = 3000 m, tree_line = 2000 m, rock_slope = 35 deg, earth_radius = inf,
//                  vegetation, rock, snow): heights are true heights above sea level; with
//   a finite earth_radius R > 0 the scene's y is CurvedEarth's flat height y' = R ln(1 + h / R) and is turned
//   back into h = R (exp(y' / R) - 1). The slope is the angle of the shading normal from +y: the
//   Earth-flattening transform is conformal, so the flat frame keeps slope angles.
// Albedos: conifer forest ~0.08 in the visible (Betts & Ball 1997, J. Geophys. Res. 102, 28901),
// bare granite/limestone rock 0.2-0.3, old snow ~0.8 (Warren 1982, Rev. Geophys. 20, 67).
#pragma once

#include "refracta/core/error.h"
#include "refracta/shading/color.h"
#include "refracta/shading/diffuse.h"

#include <algorithm>
#include <limits>
#include <cmath>

namespace refracta {

struct TerrainShadingParameters {
  double snow_line = 3000.0;  // [m] above sea level: the summer snow line of the Alps
  double tree_line = 2000.0;  // [m]: vegetation gives way to rock (Alpine tree line ~1800-2200 m)
  double rock_slope = 35.0;   // [deg]: steeper ground is bare rock (scree's angle of repose ~35 deg)
  // [m] of the scene's CurvedEarth; inf: a flat Earth, y is the height (as Camera.project and
  // AerialPerspective spell it; 0 too, as it did)
  double earth_radius = std::numeric_limits<double>::infinity();
  Vec3d vegetation{0.06, 0.09, 0.04};
  Vec3d rock{0.25, 0.23, 0.21};
  Vec3d snow{0.80, 0.80, 0.83};
};

// Terrain coloured by elevation, slope and snow line (shading/terrain_shading.h), the default of
// Scene.add_terrain: Lambertian, its reflectance ``vegetation`` below ``tree_line`` [m], ``rock``
// above it and wherever the ground is steeper than ``rock_slope`` [deg], ``snow`` above
// ``snow_line`` [m] on slopes under 55 deg (snow slides off steeper ones); the covers blend over
// 100 m of height and 5 deg of slope. Heights are true heights above sea level: with
// ``earth_radius`` R > 0 (the scene's CurvedEarth radius) the scene's y is the flat height y' = R
// ln(1 + h/R) and h = R (exp(y'/R) - 1); inf (or 0) means a flat Earth (h = y). The slope is the shading
// normal's angle from +y (the Earth-flattening map is conformal: it keeps angles). Colours are
// linear RGB albedos in [0, 1]: conifer forest ~0.08, rock 0.2-0.3, old snow ~0.8.
class TerrainShading final : public Material {
 public:
  // Snow slides off slopes steeper than this [deg] (avalanche starting zones are 30-55 deg).
  static constexpr double kSnowMaxSlope = 55.0;
  // Heights [m] and slopes [deg] over which one cover blends into the next (no hard contour lines).
  static constexpr double kHeightBlend = 100.0;
  static constexpr double kSlopeBlend = 5.0;

  explicit TerrainShading(const TerrainShadingParameters& p) : p_(p) {
    const auto in_unit = [](const Vec3d& c, const char* name) {
      if (!is_finite(c) || c.minCoeff() < 0.0 || c.maxCoeff() > 1.0) {
        throw_invalid("TerrainShading: ", name, " must be a colour in [0, 1] (got (", c.x(), ", ", c.y(), ", ", c.z(), "))");
      }
    };
    in_unit(p.vegetation, "vegetation"), in_unit(p.rock, "rock"), in_unit(p.snow, "snow");
    if (!std::isfinite(p.snow_line) || !std::isfinite(p.tree_line)) throw_invalid("TerrainShading: snow_line and tree_line must be finite");
    if (!(p.rock_slope > 0.0 && p.rock_slope < 90.0)) throw_invalid("TerrainShading: rock_slope must be in (0, 90) deg (got ", p.rock_slope, ")");
    if (!(p.earth_radius >= 0.0)) {
      throw_invalid("TerrainShading: earth_radius must be >= 0 [m] (inf, or 0, for a flat Earth; got ", p.earth_radius, ")");
    }
  }

  // The reflectance at a point of true height h [m] on ground sloping `slope` [deg].
  Vec3d reflectance(double h, double slope) const {
    const auto step = [](double x, double edge, double width) { return std::clamp((x - edge) / width + 0.5, 0.0, 1.0); };
    const double rocky = std::max(step(h, p_.tree_line, kHeightBlend), step(slope, p_.rock_slope, kSlopeBlend));
    const double snowy = step(h, p_.snow_line, kHeightBlend) * (1.0 - step(slope, kSnowMaxSlope, kSlopeBlend));
    const Vec3d ground = (1.0 - rocky) * p_.vegetation + rocky * p_.rock;
    return (1.0 - snowy) * ground + snowy * p_.snow;
  }

  const Bsdf* bsdf(const SurfaceInteraction& si, const MaterialContext& context, ScratchBuffer& scratch) const override {
    const double r = p_.earth_radius, y = si.p.y();
    const double h = r > 0.0 && std::isfinite(r) ? r * std::expm1(y / r) : y;
    const double slope = radians_to_degrees(std::acos(std::clamp(std::abs(si.ns.y()), 0.0, 1.0)));
    return scratch.make<DiffuseBsdf>(reflectance_spectrum(reflectance(h, slope), *context.lambda));
  }
  const TerrainShadingParameters& parameters() const { return p_; }
  std::string describe() const override {
    return concat("TerrainShading(snow_line=", p_.snow_line, ", tree_line=", p_.tree_line, ", rock_slope=", p_.rock_slope,
                  ", earth_radius=", p_.earth_radius, ")");
  }

 private:
  TerrainShadingParameters p_;
};

}  // namespace refracta
