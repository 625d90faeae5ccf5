// The physical sky (single scattering plus Hillaire's multiple-scattering term) and its light (physical_sky.h).
#include "refracta/shading/physical_sky.h"

#include "refracta/core/error.h"
#include "refracta/core/parallel.h"
#include "refracta/shading/air_optics.h"
#include "refracta/shading/color.h"
#include "refracta/shading/spectral.h"

#include <algorithm>
#include <chrono>
#include <deque>
#include <limits>
#include <mutex>
#include <cmath>
#include <string>

namespace refracta {

namespace {

using namespace air_optics;

constexpr double kSolarConstant = 1361.0;         // [W/m^2] Kopp & Lean 2011
constexpr double kSunTemperature = 5778.0;        // [K]
constexpr double kStefanBoltzmann = 5.670374419e-8;
constexpr int kViewSteps = 64;  // midpoint samples along a view ray
constexpr int kSunSteps = kSunColumnSteps;  // along a sun ray (optical depth)

double lerp_10nm(const double* values, double lambda_nm) { return lerp_nodes(values, lambda_nm); }

Vec3d rgb_of_10nm(const double* values) { return rgb_of_nodes(values); }

double luminance(const Vec3d& rgb) {
  return spectral::linear_srgb_to_xyz(rgb).y();
}

// The whole sphere's sampling coordinates (kHorizon, physical_sky.h): (x, t), t = (1 + s) / 2 with
// s = sign(e) sqrt(|e| / (pi/2)); d omega = 4 pi^2 |s| cos e dx dt.
Vec2d direction_to_xt(const Vec3d& d) {
  const Vec2d xy = PhysicalSky::direction_to_xy(d);
  const double e = std::atan2(d.y(), std::hypot(d.x(), d.z()));  // well conditioned at the poles too
  const double s = std::copysign(std::sqrt(std::abs(e) / (0.5 * kPi)), e);
  return Vec2d(xy.x(), std::clamp(0.5 * (1.0 + s), 0.0, 1.0));
}

Vec3d xt_to_direction(const Vec2d& xt) {
  const double s = 2.0 * xt.y() - 1.0, phi = 2.0 * kPi * xt.x(), e = 0.5 * kPi * s * std::abs(s);
  return Vec3d(std::cos(e) * std::cos(phi), std::sin(e), std::cos(e) * std::sin(phi));
}

double xt_jacobian(const Vec2d& xt) {
  const double s = 2.0 * xt.y() - 1.0;
  return 4.0 * kPi * kPi * std::abs(s) * std::cos(0.5 * kPi * s * s);
}

double xy_jacobian(const Vec2d& xy) { return 2.0 * kPi * kPi * xy.y() * std::cos(0.5 * kPi * xy.y() * xy.y()); }

const char* name_of(BelowHorizon b) { return b == BelowHorizon::kHorizon ? "horizon" : "ground"; }

}  // namespace

void PhysicalSkySettings::validate() const {
  std::vector<std::string> problems;
  if (!sun_direction.allFinite() || std::abs(sun_direction.norm() - 1.0) > 1e-6) {
    problems.push_back(concat("sun_direction must be a unit vector (got norm ", sun_direction.norm(), ")"));
  }
  if (!(aerosol >= 0.0) || !std::isfinite(aerosol)) problems.push_back(concat("aerosol must be >= 0 (got ", aerosol, ")"));
  // The Earth's column is 100-600 DU; beyond this bound the Chappuis band alone (optical depth ~1.3
  // at 600 nm per 10 000 DU) blackens the sky: not an atmosphere.
  if (!(ozone_du >= 0.0 && ozone_du <= kMostOzone)) {
    problems.push_back(concat("ozone_du must be in [0, ", kMostOzone, "] Dobson units (got ", ozone_du,
                              "; the Earth's column is 100-600)"));
  }
  if (!(ground_albedo >= 0.0 && ground_albedo <= 1.0)) problems.push_back(concat("ground_albedo must be in [0, 1] (got ", ground_albedo, ")"));
  if (!(altitude >= 0.0 && altitude <= kPhysicalSkyHighestAltitude)) {
    problems.push_back(concat("altitude must be in [0, ", kPhysicalSkyHighestAltitude, "] m (got ", altitude, ")"));
  }
  if (!(rayleigh_scale >= 0.0) || !std::isfinite(rayleigh_scale)) problems.push_back(concat("rayleigh_scale must be >= 0 (got ", rayleigh_scale, ")"));
  if (below_horizon != BelowHorizon::kGround && below_horizon != BelowHorizon::kHorizon) {
    problems.push_back(concat("below_horizon must be ground or horizon (got ", int(below_horizon), ")"));
  } else if (below_horizon == BelowHorizon::kHorizon && ground_albedo != 0.0 && !std::isnan(ground_albedo)) {
    problems.push_back(concat("ground_albedo must be 0 with below_horizon horizon (got ", ground_albedo,
                              "; the ground is seen only with below_horizon ground)"));
  }
  // Of otherwise valid settings (visibility= 0.001 comes back a rounding below, hence the margin).
  if (problems.empty() && visibility_of(*this) < kLeastVisibility * (1.0 - 1e-9)) {
    problems.push_back(concat("aerosol ", aerosol, " makes the meteorological visibility ", 1e3 * visibility_of(*this),
                              " m, below ", 1e3 * kLeastVisibility, " m: not an air the sky can be seen through"));
  }
  if (problems.empty()) return;
  std::string message = "PhysicalSky: ";
  for (size_t i = 0; i < problems.size(); ++i) message += (i ? "; " : "") + problems[i];
  throw_invalid(message);
}

BelowHorizon below_horizon_from(const std::string& name) {
  if (name == "ground") return BelowHorizon::kGround;
  if (name == "horizon") return BelowHorizon::kHorizon;
  throw_invalid("below_horizon must be 'ground' or 'horizon' (got '", name, "')");
}

namespace {

constexpr double kKoschmieder = 3.912;  // -ln(0.02): the 2 % contrast threshold

// The extinction [1/m] of the air's molecules (Rayleigh and ozone) at 550 nm at the observer.
double molecular_extinction(const PhysicalSkySettings& settings) {
  const Column rho = densities(settings.altitude);
  return settings.rayleigh_scale * beta_rayleigh(550.0) * rho.r +
         lerp_nodes(kOzoneCrossSection, 550.0) * settings.ozone_du * kDobsonUnit / kOzoneHalfWidth * rho.o;
}

}  // namespace

double visibility_of(const PhysicalSkySettings& settings) {
  const double total = molecular_extinction(settings) + kMieExtinction * settings.aerosol * densities(settings.altitude).m;
  return total > 0.0 ? kKoschmieder / total / 1e3 : std::numeric_limits<double>::infinity();
}

std::optional<std::string> fog_caveat(const PhysicalSkySettings& settings) {
  settings.validate();  // refused settings are not warned of first
  const double visibility_km = visibility_of(settings);
  if (!(visibility_km < kLeastResolvedVisibility)) return std::nullopt;
  if (!settings.multiple_scattering) {
    return concat("visibility ", visibility_km, " km is fog (below ", kLeastResolvedVisibility,
                  " km), whose light is mostly scattered many times: single scattering alone "
                  "(multiple_scattering=False) renders a sunlit fog far too dark");
  }
  return concat("visibility ", visibility_km, " km is fog the sky's multiple-scattering table does not resolve (below ",
                kLeastResolvedVisibility, " km): its brightness does not follow the visibility smoothly and a sunlit "
                "fog comes out far too dark");
}

double aerosol_for_visibility(double visibility_km, const PhysicalSkySettings& settings) {
  if (!(visibility_km >= kLeastVisibility) || !std::isfinite(visibility_km)) {
    throw_invalid("visibility must be >= ", kLeastVisibility, " km (1 m) and finite (got ", visibility_km, ")");
  }
  const double molecules = molecular_extinction(settings);
  const double total = kKoschmieder / (visibility_km * 1e3);
  if (!(total > molecules)) {
    throw_invalid("visibility ", visibility_km, " km is beyond what the air's molecules alone allow here (",
                  kKoschmieder / molecules / 1e3, " km)");
  }
  return (total - molecules) / (kMieExtinction * densities(settings.altitude).m);
}

void set_visibility(PhysicalSkySettings* settings, double visibility_km) {
  if (settings->aerosol != PhysicalSkySettings{}.aerosol) {
    throw_invalid("give aerosol or visibility, not both (got aerosol ", settings->aerosol, " and visibility ",
                  visibility_km, " km)");
  }
  settings->aerosol = aerosol_for_visibility(visibility_km, *settings);
}

// --- Directions ----------------------------------------------------------------------------------
Vec2d PhysicalSky::direction_to_xy(const Vec3d& d) {
  double phi = std::atan2(d.z(), d.x());
  if (phi < 0.0) phi += 2.0 * kPi;
  const double e = std::asin(std::clamp(d.y(), -1.0, 1.0));
  return Vec2d(std::min(phi / (2.0 * kPi), 1.0), std::sqrt(std::max(e, 0.0) / (0.5 * kPi)));
}

Vec3d PhysicalSky::xy_to_direction(const Vec2d& xy) {
  const double phi = 2.0 * kPi * xy.x(), e = 0.5 * kPi * xy.y() * xy.y();
  return Vec3d(std::cos(e) * std::cos(phi), std::sin(e), std::cos(e) * std::sin(phi));
}

// --- The sky -------------------------------------------------------------------------------------
std::shared_ptr<const PhysicalSky> PhysicalSky::shared(const PhysicalSkySettings& settings) {
  // A few skies are enough for sweeps over other parameters; each table is ~1.6 MB.
  constexpr size_t kCached = 4;
  static std::mutex mutex;
  static std::deque<std::shared_ptr<const PhysicalSky>> cache;  // most recently used first
  auto same = [&](const PhysicalSkySettings& s) {
    return s.sun_direction == settings.sun_direction && s.aerosol == settings.aerosol && s.ozone_du == settings.ozone_du &&
           s.ground_albedo == settings.ground_albedo && s.altitude == settings.altitude &&
           s.rayleigh_scale == settings.rayleigh_scale && s.below_horizon == settings.below_horizon &&
           s.multiple_scattering == settings.multiple_scattering;
  };
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (auto it = cache.begin(); it != cache.end(); ++it) {
      if (same((*it)->settings())) {
        std::shared_ptr<const PhysicalSky> sky = *it;
        cache.erase(it);
        cache.push_front(sky);
        return sky;
      }
    }
  }
  auto sky = std::make_shared<const PhysicalSky>(settings);  // built outside the lock (~0.5 s)
  std::lock_guard<std::mutex> lock(mutex);
  cache.push_front(sky);
  if (cache.size() > kCached) cache.pop_back();
  return sky;
}

PhysicalSky::PhysicalSky(const PhysicalSkySettings& settings) : settings_(settings) {
  settings_.validate();
  sun_ = settings_.sun_direction;
  const auto start = std::chrono::steady_clock::now();
  // Sun transmittance at the observer and the ground below the horizon.
  const Vec3d p0(0.0, kEarthRadius + settings_.altitude, 0.0);
  const std::optional<Vec3d> sun_way = sun_column_direction(p0, sun_);
  const bool shadowed = !sun_way;
  const Column c0 = shadowed ? Column{} : column_to_top(p0, *sun_way, 4 * kSunSteps);
  const double ozone_density = settings_.ozone_du * kDobsonUnit / kOzoneHalfWidth;  // [1/m^3] at the peak
  for (int w = 0; w < kWavelengths; ++w) {
    const double l = wavelength(w);
    const double tau = settings_.rayleigh_scale * beta_rayleigh(l) * c0.r + settings_.aerosol * kMieExtinction * c0.m +
                       kOzoneCrossSection[w] * ozone_density * c0.o;
    sun_transmittance_[w] = shadowed ? 0.0 : std::exp(-tau);
    ground_[w] = settings_.ground_albedo / kPi * solar_irradiance(l) * sun_transmittance_[w] * std::max(0.0, sun_.y());
  }
  ground_rgb_ = rgb_of_10nm(ground_.data());
  if (settings_.multiple_scattering) {
    multiple_scattering_ = MultipleScattering({settings_.rayleigh_scale, settings_.aerosol, settings_.ozone_du},
                                              settings_.ground_albedo);
  }
  // The table, one direction per task.
  table_.assign(size_t(kElevations) * kAzimuths * kWavelengths, 0.0f);
  rgb_.assign(size_t(kElevations) * kAzimuths, Vec3d::Zero());
  // Under the caller's cancel flags (core/parallel.h): Ctrl-C stops the ~0.5 s build at the next cell.
  WorkControl control;
  constexpr int64_t kCellsPerTask = 16;
  std::array<double, kWavelengths> lambda, rayleigh, ozone;
  for (int w = 0; w < kWavelengths; ++w) {
    lambda[w] = wavelength(w);
    rayleigh[w] = settings_.rayleigh_scale * beta_rayleigh(lambda[w]);
    ozone[w] = kOzoneCrossSection[w] * ozone_density;
  }
  const double mie_scattering = settings_.aerosol * kMieScattering, mie_extinction = settings_.aerosol * kMieExtinction;
  // The sky along dir, per table wavelength [W/(m^2 sr nm)].
  auto sky_along = [&](const Vec3d& dir, std::array<double, kWavelengths>& values) {
    std::array<double, kWavelengths> view{}, psi{};
    view.fill(1.0);
    // Shared path geometry for all wavelengths.
    const double length = exit_distance(p0, dir, kTopRadius);
    const double mu = dir.dot(sun_);
    const double pr = rayleigh_phase(mu), pm = mie_phase(mu);
    for (int i = 0; i < kViewSteps; ++i) {
      const double s = (i + 0.5) / kViewSteps, t = length * s * s, dt = length * 2.0 * s / kViewSteps;
      const Vec3d x = p0 + t * dir;
      const double r = x.norm();
      const Column rho = densities(r - kEarthRadius);
      const bool lit = !hits_earth(x, sun_);
      const Column sun = lit ? column_to_top(x, sun_, kSunSteps) : Column{};
      multiple_scattering_.at_nodes(r - kEarthRadius, x.dot(sun_) / r, psi.data());
      for (int w = 0; w < kWavelengths; ++w) {
        const double extinction = rayleigh[w] * rho.r + mie_extinction * rho.m + ozone[w] * rho.o;
        const double step = std::exp(-extinction * dt);
        // The view's transmittance integrated over the step, the air constant within it (exact
        // in uniform air however thick: fog).
        const double through = extinction * dt > 1e-6 ? view[w] * (1.0 - step) / extinction : view[w] * dt;
        double source = (rayleigh[w] * rho.r + mie_scattering * rho.m) * psi[w];  // the higher orders
        if (lit) {
          const double tau_sun = rayleigh[w] * sun.r + mie_extinction * sun.m + ozone[w] * sun.o;
          source += (rayleigh[w] * rho.r * pr + mie_scattering * rho.m * pm) * std::exp(-tau_sun);
        }
        values[w] += source * through;
        view[w] *= step;
      }
    }
    for (int w = 0; w < kWavelengths; ++w) values[w] *= solar_irradiance(lambda[w]);
  };
  // Each cell, then (the last task) the zenith, which every azimuth shares.
  const int64_t cells = int64_t(kElevations) * kAzimuths;
  parallel_for_each(cells + 1, kCellsPerTask, control, [&](int64_t index) {
    std::array<double, kWavelengths> values{};
    if (index == cells) {
      sky_along(Vec3d::UnitY(), values);
      zenith_ = values;
      zenith_rgb_ = rgb_of_10nm(values.data());
      return;
    }
    const int cell = int(index);
    const int row = cell / kAzimuths, column = cell % kAzimuths;
    sky_along(xy_to_direction(Vec2d((column + 0.5) / kAzimuths, (row + 0.5) / kElevations)), values);
    for (int w = 0; w < kWavelengths; ++w) table_[size_t(cell) * kWavelengths + w] = float(values[w]);
    rgb_[cell] = rgb_of_10nm(values.data());
  });
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double PhysicalSky::radiance_direct(const Vec3d& dir, double lambda_nm) const {
  if (!(std::abs(dir.norm() - 1.0) < 1e-6)) throw_invalid("dir must be a unit vector (got norm ", dir.norm(), ")");
  if (!(lambda_nm >= 360.0 && lambda_nm <= 830.0)) return 0.0;
  if (dir.y() < 0.0) {
    if (settings_.below_horizon == BelowHorizon::kGround) return ground_radiance(lambda_nm);
    const Vec3d level(dir.x(), 0.0, dir.z());  // the horizon at the same azimuth
    return radiance_direct(level.norm() > 0.0 ? Vec3d(level.normalized()) : Vec3d::UnitX(), lambda_nm);
  }
  const Vec3d p0(0.0, kEarthRadius + settings_.altitude, 0.0);
  const double ozone_density = settings_.ozone_du * kDobsonUnit / kOzoneHalfWidth;
  const double sigma_o = lerp_10nm(kOzoneCrossSection, lambda_nm);
  const double br = settings_.rayleigh_scale * beta_rayleigh(lambda_nm);
  const double length = exit_distance(p0, dir, kTopRadius), mu = dir.dot(sun_);
  // A finer quadrature than the table's (4x the steps on both rays): the table's reference.
  const int view_steps = 4 * kViewSteps, sun_steps = 4 * kSunSteps;
  const double mie_scattering = settings_.aerosol * kMieScattering;
  double sum = 0.0, view = 1.0;
  for (int i = 0; i < view_steps; ++i) {
    const double s = (i + 0.5) / view_steps, t = length * s * s, dt = length * 2.0 * s / view_steps;
    const Vec3d x = p0 + t * dir;
    const double r = x.norm();
    const Column rho = densities(r - kEarthRadius);
    const double ext = br * rho.r + settings_.aerosol * kMieExtinction * rho.m + sigma_o * ozone_density * rho.o;
    const double step = std::exp(-ext * dt);
    const double through = ext * dt > 1e-6 ? view * (1.0 - step) / ext : view * dt;
    view *= step;
    double source = (br * rho.r + mie_scattering * rho.m) * multiple_scattering_.at(r - kEarthRadius, x.dot(sun_) / r, lambda_nm);
    if (!hits_earth(x, sun_)) {
      const Column sun = column_to_top(x, sun_, sun_steps);
      const double tau_sun = br * sun.r + settings_.aerosol * kMieExtinction * sun.m + sigma_o * ozone_density * sun.o;
      source += (br * rho.r * rayleigh_phase(mu) + mie_scattering * rho.m * mie_phase(mu)) * std::exp(-tau_sun);
    }
    sum += source * through;
  }
  return sum * solar_irradiance(lambda_nm);
}

PhysicalSky::TablePoint PhysicalSky::table_point(const Vec3d& dir) {
  const Vec2d xy = direction_to_xy(dir);  // below the horizon: y = 0, the lowest row (kHorizon)
  const double fx = xy.x() * kAzimuths - 0.5, row = xy.y() * kElevations - 0.5;
  const double fy = std::clamp(row, 0.0, kElevations - 1.0);
  const int x0 = int(std::floor(fx)), y0 = std::min(int(fy), kElevations - 2);
  // Above the top row's centres (e > 88.6 deg) toward the zenith's one value: the top row alone
  // gave the zenith the radiance 88.6 deg up at each azimuth, 3.4 % apart on either side of it.
  const double zenith = std::clamp((row - (kElevations - 1)) * 2.0, 0.0, 1.0);
  return {y0, (x0 + kAzimuths) % kAzimuths, (x0 + 1) % kAzimuths, fx - x0, fy - y0, zenith};
}

double PhysicalSky::radiance(const Vec3d& dir, double lambda_nm) const {
  if (!(lambda_nm >= 360.0 && lambda_nm <= 830.0)) return 0.0;
  if (dir.y() < 0.0 && settings_.below_horizon == BelowHorizon::kGround) return ground_radiance(lambda_nm);
  const TablePoint p = table_point(dir);
  const double fw = (lambda_nm - 360.0) / 10.0;
  const int w0 = std::min(int(fw), kWavelengths - 2);
  const double tw = fw - w0;
  double out = 0.0;
  for (int k = 0; k < 2; ++k) {
    const int w = w0 + k;
    const double v = (1.0 - p.ty) * ((1.0 - p.tx) * table_at(p.y0, p.xa, w) + p.tx * table_at(p.y0, p.xb, w)) +
                     p.ty * ((1.0 - p.tx) * table_at(p.y0 + 1, p.xa, w) + p.tx * table_at(p.y0 + 1, p.xb, w));
    out += (k ? tw : 1.0 - tw) * ((1.0 - p.zenith) * v + p.zenith * zenith_[size_t(w)]);
  }
  return out;
}

Vec3d PhysicalSky::rgb_radiance(const Vec3d& dir) const {
  if (dir.y() < 0.0 && settings_.below_horizon == BelowHorizon::kGround) return ground_rgb_;
  const TablePoint p = table_point(dir);
  auto at = [&](int r, int c) { return rgb_[size_t(r) * kAzimuths + c]; };
  const Vec3d v = (1.0 - p.ty) * ((1.0 - p.tx) * at(p.y0, p.xa) + p.tx * at(p.y0, p.xb)) +
                  p.ty * ((1.0 - p.tx) * at(p.y0 + 1, p.xa) + p.tx * at(p.y0 + 1, p.xb));
  return (1.0 - p.zenith) * v + p.zenith * zenith_rgb_;
}

double PhysicalSky::ground_radiance(double lambda_nm) const { return lerp_10nm(ground_.data(), lambda_nm); }

double PhysicalSky::sun_transmittance(double lambda_nm) const { return lerp_10nm(sun_transmittance_.data(), lambda_nm); }

double PhysicalSky::solar_irradiance(double lambda_nm) {
  return kPi * spectral::planck(lambda_nm, kSunTemperature) * kSolarConstant /
         (kStefanBoltzmann * std::pow(kSunTemperature, 4.0));
}

double PhysicalSky::sun_radiance(double lambda_nm, double angular_diameter_deg) const {
  if (!(angular_diameter_deg > 0.0 && angular_diameter_deg < 180.0)) {
    throw_invalid("angular_diameter_deg must be in (0, 180) (got ", angular_diameter_deg, ")");
  }
  const double half = 0.5 * degrees_to_radians(angular_diameter_deg);
  return sun_irradiance(lambda_nm) / (2.0 * kPi * (1.0 - std::cos(half)));
}

Vec3d PhysicalSky::sun_radiance_rgb(double angular_diameter_deg) const {
  std::array<double, kWavelengths> values;
  for (int w = 0; w < kWavelengths; ++w) values[w] = sun_radiance(wavelength(w), angular_diameter_deg);
  return rgb_of_10nm(values.data());
}

// The sky's tables (ozone cross-sections, the sun's spectrum) cover the rendered range only.
static void check_sky_wavelength(const char* what, double lambda_nm) {
  if (!(lambda_nm >= kLambdaMin && lambda_nm <= kLambdaMax)) {
    throw_invalid("PhysicalSky.", what, ": wavelength must be in [", kLambdaMin, ", ", kLambdaMax, "] nm (got ",
                  lambda_nm, ")");
  }
}

double PhysicalSky::rayleigh_optical_depth(double lambda_nm) const {
  check_sky_wavelength("rayleigh_optical_depth", lambda_nm);
  const Vec3d p0(0.0, kEarthRadius + settings_.altitude, 0.0);
  return settings_.rayleigh_scale * beta_rayleigh(lambda_nm) * column_to_top(p0, Vec3d::UnitY(), 4096).r;
}

double PhysicalSky::optical_depth(double lambda_nm) const {
  check_sky_wavelength("optical_depth", lambda_nm);
  const Vec3d p0(0.0, kEarthRadius + settings_.altitude, 0.0);
  const Column c = column_to_top(p0, Vec3d::UnitY(), 4096);
  return settings_.rayleigh_scale * beta_rayleigh(lambda_nm) * c.r + settings_.aerosol * kMieExtinction * c.m +
         lerp_10nm(kOzoneCrossSection, lambda_nm) * settings_.ozone_du * kDobsonUnit / kOzoneHalfWidth * c.o;
}

// --- The light -----------------------------------------------------------------------------------
PhysicalSkyLight::PhysicalSkyLight(const PhysicalSkySettings& settings) : sky_(PhysicalSky::shared(settings)) {
  constexpr int nx = PhysicalSky::kAzimuths, ny = PhysicalSky::kElevations;
  const int rows = whole_sphere() ? 2 * ny : ny;
  std::vector<double> weights(size_t(nx) * rows);
  const double cell = 1.0 / (double(nx) * rows);
  for (int row = 0; row < rows; ++row) {
    for (int column = 0; column < nx; ++column) {
      const Vec2d p((column + 0.5) / nx, (row + 0.5) / rows);
      const Vec3d dir = whole_sphere() ? xt_to_direction(p) : PhysicalSky::xy_to_direction(p);
      const double solid_angle = (whole_sphere() ? xt_jacobian(p) : xy_jacobian(p)) * cell;
      const double y = std::max(0.0, luminance(sky_->rgb_radiance(dir)));  // Y of Le at the cell centre
      weights[size_t(row) * nx + column] = y * solid_angle;
      radiance_integral_ += y * solid_angle;
    }
  }
  if (!whole_sphere()) radiance_integral_ += 2.0 * kPi * std::max(0.0, luminance(sky_->rgb_radiance(Vec3d(0.0, -1.0, 0.0))));
  distribution_ = PiecewiseConstant2D(weights, nx, rows);
}

double PhysicalSkyLight::pdf_direction(const Vec3d& wi) const {
  if (!whole_sphere() && !(wi.y() > 0.0)) return 0.0;
  const Vec2d p = whole_sphere() ? direction_to_xt(wi) : PhysicalSky::direction_to_xy(wi);
  const double jacobian = whole_sphere() ? xt_jacobian(p) : xy_jacobian(p);
  if (!(jacobian > 0.0)) return 0.0;
  return distribution_.pdf(p) / jacobian;
}

std::optional<LightLiSample> PhysicalSkyLight::sample_li(const LightSampleContext& /*ctx*/, const Vec2d& u,
                                                         const SampledWavelengths& lambda) const {
  double pdf_p = 0.0;
  const Vec2d p = distribution_.sample(u, &pdf_p);
  const double jacobian = whole_sphere() ? xt_jacobian(p) : xy_jacobian(p);
  if (!(pdf_p > 0.0) || !(jacobian > 0.0)) return std::nullopt;
  LightLiSample s;
  s.wi = (whole_sphere() ? xt_to_direction(p) : PhysicalSky::xy_to_direction(p)).normalized();
  s.pdf = pdf_p / jacobian;
  if (!std::isfinite(s.pdf)) return std::nullopt;
  s.L = Le(s.wi, lambda);
  return s;
}

double PhysicalSkyLight::pdf_li(const LightSampleContext& /*ctx*/, const Vec3d& wi, const Vec3d& /*p_light*/,
                                const Vec3d& /*n_light*/) const {
  return pdf_direction(wi);
}

Spectrum PhysicalSkyLight::Le(const Vec3d& dir, const SampledWavelengths& lambda) const {
  if (!lambda.spectral) {
    // Into the sRGB gamut as Color::sample takes light: a low sun's reddened sky has negative blue.
    const Vec3d c = clip_keeping_luminance(sky_->rgb_radiance(dir));
    return Spectrum(c.x(), c.y(), c.z(), 0.0);
  }
  Spectrum s;
  for (int i = 0; i < kSpectrumSamples; ++i) s[i] = sky_->radiance(dir, lambda.lambda[i]);
  return s;
}

double PhysicalSkyLight::power() const {
  const double r = scene_radius_;  // one load: another render's preprocess may write it
  return kPi * r * r * radiance_integral_;
}

void PhysicalSkyLight::preprocess(const Vec3d& /*centre*/, double radius) {
  if (!(radius > 0.0) || !std::isfinite(radius)) throw_invalid("PhysicalSkyLight: scene radius must be > 0 (got ", radius, ")");
  scene_radius_ = radius;
}

std::string PhysicalSkyLight::describe() const {
  const PhysicalSkySettings& s = sky_->settings();
  // Named as Python knows it (refracta.spectrum.PhysicalSky), with its constructor's parameter names.
  return concat("PhysicalSky(sun_direction=(", s.sun_direction.x(), ", ", s.sun_direction.y(), ", ",
                s.sun_direction.z(), "), aerosol=", s.aerosol, ", ozone_du=", s.ozone_du,
                ", ground_albedo=", s.ground_albedo, ", altitude=", s.altitude, ", rayleigh_scale=", s.rayleigh_scale,
                ", below_horizon='", name_of(s.below_horizon), "', multiple_scattering=",
                s.multiple_scattering ? "True" : "False", ")");
}

}  // namespace refracta
