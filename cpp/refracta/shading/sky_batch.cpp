// The physical sky over many directions and wavelengths at once (sky_batch.h).
#include "refracta/shading/sky_batch.h"

#include "refracta/core/error.h"

#include <cmath>

namespace refracta {

PhysicalSkySettings sky_settings(const Vec3d& sun_direction, std::optional<double> aerosol, double ozone_du, double ground_albedo,
                                 double altitude, double rayleigh_scale, const std::string& below_horizon,
                                 std::optional<double> visibility, bool multiple_scattering) {
  PhysicalSkySettings s;
  s.multiple_scattering = multiple_scattering;
  // Normalised, as Scene.set_physical_sky always did (one rule for both ways to make a sky).
  const double norm = sun_direction.norm();
  if (!(norm > 0.0 && std::isfinite(norm))) {
    throw_invalid("sun_direction must be non-zero and finite (got (", sun_direction.x(), ", ", sun_direction.y(), ", ",
                  sun_direction.z(), "))");
  }
  s.sun_direction = sun_direction / norm;
  if (aerosol && visibility) {  // an explicit aerosol = 1.0 (the default) is one too
    throw_invalid("give aerosol or visibility, not both (got aerosol ", *aerosol, " and visibility ", *visibility,
                  " km)");
  }
  if (aerosol) s.aerosol = *aerosol;
  s.ozone_du = ozone_du;
  s.ground_albedo = ground_albedo;
  s.altitude = altitude;
  s.rayleigh_scale = rayleigh_scale;
  s.below_horizon = below_horizon_from(below_horizon);
  if (visibility) set_visibility(&s, *visibility);
  return s;
}

PhysicalSkyState sky_state(const PhysicalSkySettings& s) {
  return {s.sun_direction, s.aerosol, s.ozone_du, s.ground_albedo, s.altitude, s.rayleigh_scale, int(s.below_horizon),
          s.multiple_scattering};
}

PhysicalSkySettings sky_settings_from_state(const PhysicalSkyState& state) {
  PhysicalSkySettings s;
  int below = 0;
  std::tie(s.sun_direction, s.aerosol, s.ozone_du, s.ground_albedo, s.altitude, s.rayleigh_scale, below, s.multiple_scattering) = state;
  if (below != int(BelowHorizon::kGround) && below != int(BelowHorizon::kHorizon)) {
    throw_invalid("PhysicalSky: bad pickle state (below_horizon ", below, ")");
  }
  s.below_horizon = BelowHorizon(below);
  return s;
}

RowMatrixXd sky_radiance(const PhysicalSky& sky, const std::vector<Vec3d>& dirs, const std::vector<double>& lambda_nm,
                         bool direct) {
  RowMatrixXd out(dirs.size(), lambda_nm.size());
  for (size_t i = 0; i < dirs.size(); ++i) {
    for (size_t j = 0; j < lambda_nm.size(); ++j) {
      out(i, j) = direct ? sky.radiance_direct(dirs[i], lambda_nm[j]) : sky.radiance(dirs[i], lambda_nm[j]);
    }
  }
  return out;
}

RowMatrixX3d sky_rgb_radiance(const PhysicalSky& sky, const std::vector<Vec3d>& dirs) {
  RowMatrixX3d out(dirs.size(), 3);
  for (size_t i = 0; i < dirs.size(); ++i) out.row(i) = sky.rgb_radiance(dirs[i]).transpose();
  return out;
}

std::tuple<RowMatrixX3d, Eigen::VectorXd, RowMatrixX3d> sample_sky(const PhysicalSkyLight& sky,
                                                                    const RowMatrixXd& u) {
  if (u.cols() != 2) throw_invalid("u must have shape (N, 2) (got ", u.cols(), " columns)");
  RowMatrixX3d dirs = RowMatrixX3d::Zero(u.rows(), 3), rgb = RowMatrixX3d::Zero(u.rows(), 3);
  Eigen::VectorXd pdf = Eigen::VectorXd::Zero(u.rows());
  for (Eigen::Index i = 0; i < u.rows(); ++i) {
    const auto s = sky.sample_li({}, Vec2d(u(i, 0), u(i, 1)), SampledWavelengths::rgb());
    if (!s) continue;
    dirs.row(i) = s->wi.transpose();
    pdf[i] = s->pdf;
    rgb.row(i) = s->L.head<3>().matrix().transpose();
  }
  return {dirs, pdf, rgb};
}

Eigen::VectorXd sky_pdf(const PhysicalSkyLight& sky, const std::vector<Vec3d>& dirs) {
  return at_each(dirs, [&](const Vec3d& d) { return sky.pdf_direction(d); });
}

std::pair<Vec3d, Vec3d> along_rgb(const AerialPerspective& air, const Vec3d& a, const Vec3d& b, double earth_radius) {
  const AirFrame frame{earth_radius};
  frame.validate();
  AirFrame::check_segment(a, b, "AerialPerspective.along_rgb");
  const auto segment = air.along(a, b, frame, SampledWavelengths::rgb());
  return {segment.transmittance.head<3>().matrix(), segment.inscatter.head<3>().matrix()};
}

}  // namespace refracta
