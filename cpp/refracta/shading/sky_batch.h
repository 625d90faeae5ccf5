// The physical sky over many directions and wavelengths at once (what refracta.spectrum's
// PhysicalSky and AerialPerspective expose), and the sky's settings as a flat tuple (pickling).
#pragma once

#include "refracta/shading/aerial_perspective.h"
#include "refracta/shading/physical_sky.h"
#include "refracta/shading/spectrum_batch.h"

#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace refracta {

// The settings of PhysicalSky's constructor: sun_direction normalised (non-zero), visibility [km],
// when given, sets the aerosol by Koschmieder's law (set_visibility); below_horizon is 'ground'
// or 'horizon'.
PhysicalSkySettings sky_settings(const Vec3d& sun_direction, std::optional<double> aerosol, double ozone_du, double ground_albedo,
                                 double altitude, double rayleigh_scale, const std::string& below_horizon,
                                 std::optional<double> visibility,
                                 bool multiple_scattering = PhysicalSkySettings{}.multiple_scattering);

// (sun_direction, aerosol, ozone_du, ground_albedo, altitude, rayleigh_scale, below_horizon as int,
// multiple_scattering).
using PhysicalSkyState = std::tuple<Vec3d, double, double, double, double, double, int, bool>;
PhysicalSkyState sky_state(const PhysicalSkySettings& settings);
PhysicalSkySettings sky_settings_from_state(const PhysicalSkyState& state);  // throws for a bad below_horizon

// The sky's radiance [W/(m^2 sr nm)] in each unit direction (dirs (N, 3) or (3,)) at each
// wavelength [nm] in [360, 830]: an array (directions, wavelengths). direct: integrated along each
// direction without the sky's table (slower; the table's reference).
RowMatrixXd sky_radiance(const PhysicalSky& sky, const std::vector<Vec3d>& dirs, const std::vector<double>& lambda_nm,
                         bool direct);
// The sky's radiance in each unit direction (dirs (N, 3) or (3,)) as RGB renders see it, (N, 3):
// linear sRGB of the spectrum's XYZ / integral ybar, i.e. a luminance-weighted spectral radiance
// [W/(m^2 sr nm)] (times 106.86 nm: W/(m^2 sr)).
RowMatrixX3d sky_rgb_radiance(const PhysicalSky& sky, const std::vector<Vec3d>& dirs);
// Light sampling at each row (u1, u2) of u (N, 2) in [0, 1): (directions (N, 3), pdf [1/sr] (N,),
// RGB radiance (N, 3)), 0 where nothing was sampled.
std::tuple<RowMatrixX3d, Eigen::VectorXd, RowMatrixX3d> sample_sky(const PhysicalSkyLight& sky,
                                                                    const RowMatrixXd& u);
// The light-sampling density [1/sr] of sample_li in each unit direction (dirs (N, 3) or (3,)).
Eigen::VectorXd sky_pdf(const PhysicalSkyLight& sky, const std::vector<Vec3d>& dirs);

// (transmittance, in-scatter) of the air from a to b as RGB renders apply them (linear sRGB).
std::pair<Vec3d, Vec3d> along_rgb(const AerialPerspective& air, const Vec3d& a, const Vec3d& b, double earth_radius);

}  // namespace refracta
