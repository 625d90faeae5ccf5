// Transmittance and single-scattered sunlight along a segment of air (aerial_perspective.h).
#include "refracta/shading/aerial_perspective.h"

#include "refracta/core/error.h"
#include "refracta/core/parallel.h"
#include "refracta/core/spectrum.h"
#include "refracta/shading/color.h"
#include "refracta/shading/spectral.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace refracta {

using namespace air_optics;

namespace {

// The sun table: heights h = kTop u^2 on kHeights rows (fine near the ground); sun elevations on
// kElevations columns t in [0, 1], t = 1/2 at the horizon, e = (pi/2) (2t - 1)^2 above it and
// -kLowest (2t - 1)^2 below it (fine near the horizon, where the sun's light changes fastest).
constexpr int kHeights = 65, kElevations = 1025;  // the relative optical depth's error: (de / 2e)^2, 0.02 % at 2 deg
constexpr double kShadowed = 1e30;  // [m] a column where the planet hides the sun (e^-tau = 0)
constexpr double kLowest = 12.0 * kPi / 180.0;  // below the horizon dip at 80 km (9 deg): dark beyond

double elevation_to_t(double e) {
  return e >= 0.0 ? 0.5 + 0.5 * std::sqrt(std::min(e, 0.5 * kPi) / (0.5 * kPi))
                  : 0.5 - 0.5 * std::sqrt(std::min(-e, kLowest) / kLowest);
}

double t_to_elevation(double t) {
  const double s = 2.0 * t - 1.0;
  return s >= 0.0 ? 0.5 * kPi * s * s : -kLowest * s * s;
}

// The sun's column from height h where it stands e above the horizon (sun_column_direction: just
// below the planet's limb the grazing one; nullopt further below).
std::optional<Column> sun_column(double h, double e, int steps) {
  const Vec3d p(0.0, kEarthRadius + std::max(h, 0.0), 0.0);
  const auto d = sun_column_direction(p, Vec3d(std::cos(e), std::sin(e), 0.0));
  if (!d) return std::nullopt;
  return column_to_top(p, *d, steps);
}

}  // namespace

AerialPerspective::AerialPerspective(std::shared_ptr<const PhysicalSky> sky, double scale)
    : sky_(std::move(sky)), scale_(scale) {
  if (!sky_) throw_invalid("AerialPerspective: no sky");
  if (!(scale >= 0.0 && scale <= kMaxRadiance)) {
    throw_invalid("AerialPerspective: scale must be in [0, ", kMaxRadiance, "] (got ", scale, "): images are float32");
  }
  const PhysicalSkySettings& s = sky_->settings();
  air_ = {s.rayleigh_scale, s.aerosol, s.ozone_du};
  altitude_ = s.altitude;
  sun_ = s.sun_direction;
  std::array<double, kNodes> lambda{};
  for (int w = 0; w < kNodes; ++w) lambda[w] = node_wavelength(w);
  nodes_ = bands_at(lambda.data(), kNodes);
  nodes_.at_nodes = true;
  std::array<double, kNodes> d65{};
  for (int w = 0; w < kNodes; ++w) {
    std::array<double, kNodes> unit{};
    unit[w] = 1.0;
    rgb_weight_[w] = rgb_of_nodes(unit.data());
    d65[w] = spectral::d65_normalised(lambda[w]);
    d65_weight_[w] = d65[w] * rgb_weight_[w];
  }
  rgb_of_d65_ = rgb_of_nodes(d65.data());
  // The sun's columns over (height, elevation), one row of elevations per task (~0.1 s in all).
  sun_columns_.assign(size_t(kHeights) * kElevations, Column{});
  WorkControl control;
  parallel_for_each(kHeights, 1, control, [&](int64_t i) {
    const double u = double(i) / (kHeights - 1), h = kTop * u * u;
    for (int j = 0; j < kElevations; ++j) {
      const auto column = sun_column(h, t_to_elevation(double(j) / (kElevations - 1)), kSunColumnSteps);
      sun_columns_[size_t(i) * kElevations + j] = column ? *column : Column{kShadowed, kShadowed, kShadowed};
    }
  });
}

AerialPerspective::Bands AerialPerspective::bands_at(const double* lambda_nm, int count) const {
  Bands b;
  b.count = count;
  for (int i = 0; i < count; ++i) {
    const double l = lambda_nm[i];
    b.rayleigh[i] = air_.rayleigh_scale * beta_rayleigh(l);
    b.ozone[i] = lerp_nodes(kOzoneCrossSection, l) * air_.ozone_peak_density();
    b.irradiance[i] = PhysicalSky::solar_irradiance(l);
    b.lambda[i] = l;
  }
  return b;
}

void AerialPerspective::psi_of(const Located& x, const Bands& bands, double* psi) const {
  const MultipleScattering& ms = sky_->multiple_scattering();
  const double mu_s = std::clamp(x.up.dot(sun_), -1.0, 1.0);
  if (bands.at_nodes) return ms.at_nodes(x.height, mu_s, psi);
  for (int i = 0; i < bands.count; ++i) psi[i] = ms.at(x.height, mu_s, bands.lambda[i]);
}

AerialPerspective::Located AerialPerspective::locate(const Vec3d& p, const AirFrame& frame) const {
  // The air is modelled down to kDeepestAir; a point deeper (none a render reaches) takes that
  // depth's air: the densities' exponentials of a depth of 1000 km overflowed into NaN light.
  constexpr double kDeepestAir = -1e4;  // [m]
  if (std::isfinite(frame.earth_radius)) {
    const double rho = std::hypot(p.x(), p.z());
    const double phi = rho / frame.earth_radius;
    const Vec3d up = rho > 0.0 ? Vec3d(std::sin(phi) * p.x() / rho, std::cos(phi), std::sin(phi) * p.z() / rho)
                               : Vec3d(0.0, 1.0, 0.0);
    return {std::max(altitude_ + p.y(), kDeepestAir), up};
  }
  const Vec3d q(p.x(), kEarthRadius + altitude_ + p.y(), p.z());
  const double r = q.norm();
  return {std::max(r - kEarthRadius, kDeepestAir), q / r};
}

AerialPerspective::TableCell AerialPerspective::cell(double height, double elevation) const {
  const double h = std::clamp(height, 0.0, kTop);
  const double u = std::sqrt(h / kTop) * (kHeights - 1);
  const double t = elevation_to_t(elevation) * (kElevations - 1);
  TableCell c;
  c.h0 = std::min(int(u), kHeights - 2);
  c.e0 = std::min(int(t), kElevations - 2);
  // Linear in height between the rows (the columns' exponentials are near linear over a row;
  // linear in u would bend them like sqrt(h) near the ground).
  const double u0 = double(c.h0) / (kHeights - 1), u1 = double(c.h0 + 1) / (kHeights - 1);
  const double row0 = kTop * u0 * u0, row1 = kTop * u1 * u1;
  c.th = std::clamp((h - row0) / (row1 - row0), 0.0, 1.0);
  c.te = t - c.e0;
  return c;
}

Column AerialPerspective::sun_column_at(const TableCell& c) const {
  auto at = [&](int i, int j) { return sun_columns_[size_t(i) * kElevations + j]; };
  const double w00 = (1.0 - c.th) * (1.0 - c.te), w01 = (1.0 - c.th) * c.te, w10 = c.th * (1.0 - c.te), w11 = c.th * c.te;
  const Column a = at(c.h0, c.e0), b = at(c.h0, c.e0 + 1), d = at(c.h0 + 1, c.e0), e = at(c.h0 + 1, c.e0 + 1);
  return {w00 * a.r + w01 * b.r + w10 * d.r + w11 * e.r, w00 * a.m + w01 * b.m + w10 * d.m + w11 * e.m,
          w00 * a.o + w01 * b.o + w10 * d.o + w11 * e.o};
}

double AerialPerspective::sun_at(const Column& column, const Bands& bands, int band) const {
  return std::exp(-(bands.rayleigh[band] * column.r + air_.aerosol * kMieExtinction * column.m + bands.ozone[band] * column.o));
}

double AerialPerspective::sun_transmittance(double height, double elevation, double lambda_nm) const {
  checked_wavelength(lambda_nm, "AerialPerspective.sun_transmittance: wavelength");
  if (!std::isfinite(height)) throw_invalid("AerialPerspective.sun_transmittance: height must be finite (got ", height, ")");
  if (!(std::abs(elevation) <= 0.5 * kPi + 1e-12)) {
    throw_invalid("AerialPerspective.sun_transmittance: elevation must be in [-90, 90] deg (got ", radians_to_degrees(elevation),
                  ")");
  }
  const Bands b = bands_at(&lambda_nm, 1);
  return sun_at(sun_column_at(cell(height, elevation)), b, 0);
}

bool AerialPerspective::clip_to_air(Vec3d* a, Vec3d* b, const AirFrame& frame) const {
  const Vec3d chord = *b - *a;
  double lo = 0.0, hi = 1.0;
  if (std::isfinite(frame.earth_radius)) {  // height altitude + y, linear along the chord
    const double h0 = altitude_ + a->y(), dh = chord.y();
    if (dh == 0.0) return h0 <= kTop;
    const double t_top = (kTop - h0) / dh;
    if (dh > 0.0) {
      hi = std::min(hi, t_top);
    } else {
      lo = std::max(lo, t_top);
    }
  } else {  // |q(t)| <= kTopRadius on the sky's sphere, q(t) = q0 + t chord: a quadratic in t
    const Vec3d q0(a->x(), kEarthRadius + altitude_ + a->y(), a->z());
    const double r0 = q0.norm();
    const double A = chord.squaredNorm(), B = q0.dot(chord), C = (r0 - kTopRadius) * (r0 + kTopRadius);
    const double discriminant = B * B - A * C;
    if (!(discriminant > 0.0)) return C < 0.0;  // tangent or passing above (C < 0: a point, inside)
    const double q = -(B + std::copysign(std::sqrt(discriminant), B));  // the stable pair of roots
    const double t1 = q / A, t2 = q != 0.0 ? C / q : -t1;
    lo = std::max(lo, std::min(t1, t2));
    hi = std::min(hi, std::max(t1, t2));
  }
  if (!(lo < hi)) return false;
  if (hi < 1.0) *b = *a + hi * chord;  // ends inside the air stay bit for bit
  if (lo > 0.0) *a = *a + lo * chord;
  return true;
}

void AerialPerspective::integrate(const Vec3d& a_in, const Vec3d& b_in, const AirFrame& frame, const Bands& bands,
                                  bool inscatter, double* T, double* S) const {
  const int n = bands.count;
  std::fill(T, T + n, 1.0);
  std::fill(S, S + n, 0.0);
  Vec3d a = a_in, b = b_in;
  if (!clip_to_air(&a, &b, frame)) return;
  const Vec3d chord = b - a;
  const double length = chord.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return;
  const Vec3d dir = chord / length;
  const Located start = locate(a, frame), end = locate(b, frame);
  // A chord of the flat frame dips below the straight line between its ends' heights by up to
  // rho^2 / 8R over the sky's sphere.
  const double horizontal = std::hypot(chord.x(), chord.z());
  const double sag = std::isfinite(frame.earth_radius) ? 0.0 : horizontal * horizontal / (8.0 * kEarthRadius);
  const double span = std::abs(end.height - start.height) + sag;
  const int pieces = std::clamp(int(std::ceil(std::max(span / kPieceHeight, length / kPieceLength))), 1, kMaxPieces);
  const double mu = dir.dot(sun_), rayleigh_phase_mu = rayleigh_phase(mu), mie_phase_mu = mie_phase(mu);
  const double mie_extinction = air_.aerosol * kMieExtinction, mie_scattering = air_.aerosol * kMieScattering;
  const double piece = length / pieces;
  // The sunlight at a piece's ends (sun_cell: its table coordinates), linear in between.
  auto sun_cell_at = [&](const Located& x) {
    return sun_column_at(cell(x.height, std::asin(std::clamp(x.up.dot(sun_), -1.0, 1.0))));
  };
  Column sun0{}, sun1{};
  // The higher orders of scattering (the sky's Psi_ms, multiple_scattering.h) at a piece's ends,
  // linear in between.
  const bool multiple = inscatter && sky_->multiple_scattering().enabled();
  std::array<double, kNodes> psi0{}, psi1{};
  // The sun's optical depth and transmittance at the piece's ends per band (the end's are the next
  // piece's start's).
  std::array<double, kNodes> d_start{}, d_end{}, j_start{}, j_end{};
  auto sun_depth = [&](const Column& column, int w) {
    return bands.rayleigh[w] * column.r + mie_extinction * column.m + bands.ozone[w] * column.o;
  };
  if (inscatter) {
    sun0 = sun_cell_at(start);
    for (int w = 0; w < n; ++w) d_start[w] = sun_depth(sun0, w), j_start[w] = std::exp(-d_start[w]);
  }
  if (multiple) psi_of(start, bands, psi0.data());
  double h0 = start.height;
  for (int k = 0; k < pieces; ++k) {
    const Located next = k + 1 == pieces ? end : locate(a + chord * (double(k + 1) / pieces), frame);
    const Column c = column_along(h0, next.height, piece);
    if (inscatter) sun1 = sun_cell_at(next);
    if (multiple) psi_of(next, bands, psi1.data());
    for (int w = 0; w < n; ++w) {
      const double tau = bands.rayleigh[w] * c.r + mie_extinction * c.m + bands.ozone[w] * c.o;
      const double attenuation = std::exp(-tau);
      if (inscatter) {
        // The sun's transmittance along the piece (t in [0, 1]) taken as exponential between its
        // ends, J(t) = J0 e^(kappa t), kappa = ln(J1 / J0) (the sun's optical depth is near linear
        // along a piece), attenuated within the piece: integral of e^(-tau t) J(t) dt =
        // J0 (1 - e^-x) / x, x = tau - kappa. Linear between the ends where the planet hides the sun at one.
        d_end[w] = sun_depth(sun1, w);
        const double j0 = j_start[w], j1 = j_end[w] = std::exp(-d_end[w]);
        const double scattering = bands.rayleigh[w] * c.r * rayleigh_phase_mu + mie_scattering * c.m * mie_phase_mu;
        // The attenuation within the piece against a quantity linear along it: f1 for its start
        // value, f2 for its change.
        // (f2 = (1 - e^-tau (1 + tau)) / tau^2 = (f1 - e^-tau) / tau: one division.)
        const double inverse = tau < 1e-4 ? 0.0 : 1.0 / tau;
        const double f1 = tau < 1e-4 ? 1.0 - 0.5 * tau : (1.0 - attenuation) * inverse;
        const double f2 = tau < 1e-3 ? 0.5 - tau / 3.0 + tau * tau / 8.0 : (f1 - attenuation) * inverse;
        double sunlight;
        if (j0 > 1e-30 && j1 > 1e-30) {
          const double x = tau + d_end[w] - d_start[w];  // tau - ln(j1 / j0)
          sunlight = j0 * (std::abs(x) < 1e-6 ? 1.0 - 0.5 * x : -std::expm1(-x) / x);
        } else {
          sunlight = j0 * f1 + (j1 - j0) * f2;
        }
        double light = scattering * sunlight;
        if (multiple) {
          const double total_scattering = bands.rayleigh[w] * c.r + mie_scattering * c.m;
          light += total_scattering * (psi0[w] * f1 + (psi1[w] - psi0[w]) * f2);
        }
        S[w] += T[w] * light * bands.irradiance[w];
      }
      T[w] *= attenuation;
    }
    h0 = next.height;
    sun0 = sun1;
    j_start = j_end;
    d_start = d_end;
    psi0 = psi1;
  }
  for (int w = 0; w < n; ++w) S[w] *= scale_;
}

AerialPerspective::Bands AerialPerspective::bands_of(const SampledWavelengths& lambda) const {
  std::array<double, kSpectrumSamples> l{};
  for (int i = 0; i < kSpectrumSamples; ++i) l[i] = lambda.lambda[i];
  return bands_at(l.data(), kSpectrumSamples);
}

// The D65-weighted projection: a grey transmittance stays grey, and white light through the air
// keeps the colour the spectral render gives it.
Spectrum AerialPerspective::rgb_transmittance(const double* T) const {
  Vec3d rgb = Vec3d::Zero();
  for (int w = 0; w < kNodes; ++w) rgb += T[w] * d65_weight_[w];
  rgb = rgb.cwiseQuotient(rgb_of_d65_).cwiseMax(0.0).cwiseMin(1.0);
  return Spectrum(rgb.x(), rgb.y(), rgb.z(), 1.0);
}

AerialPerspective::Segment AerialPerspective::along(const Vec3d& a, const Vec3d& b, const AirFrame& frame,
                                                    const SampledWavelengths& lambda) const {
  Segment out;
  if (lambda.spectral) {
    std::array<double, kSpectrumSamples> T{}, S{};
    integrate(a, b, frame, bands_of(lambda), true, T.data(), S.data());
    for (int i = 0; i < kSpectrumSamples; ++i) out.transmittance[i] = T[i], out.inscatter[i] = S[i];
    return out;
  }
  std::array<double, kNodes> T{}, S{};
  integrate(a, b, frame, nodes_, true, T.data(), S.data());
  Vec3d rgb_s = Vec3d::Zero();
  for (int w = 0; w < kNodes; ++w) rgb_s += S[w] * rgb_weight_[w];
  // Into the sRGB gamut as the sky's Le (PhysicalSkyLight::Le): negative channels clipped, Y kept.
  rgb_s = clip_keeping_luminance(rgb_s);
  out.transmittance = rgb_transmittance(T.data());
  out.inscatter = Spectrum(rgb_s.x(), rgb_s.y(), rgb_s.z(), 0.0);
  return out;
}

Spectrum AerialPerspective::transmittance(const Vec3d& a, const Vec3d& b, const AirFrame& frame,
                                          const SampledWavelengths& lambda) const {
  if (lambda.spectral) {
    std::array<double, kSpectrumSamples> T{}, S{};
    integrate(a, b, frame, bands_of(lambda), false, T.data(), S.data());
    return Spectrum(T[0], T[1], T[2], T[3]);
  }
  std::array<double, kNodes> T{}, S{};
  integrate(a, b, frame, nodes_, false, T.data(), S.data());
  return rgb_transmittance(T.data());
}

void AirFrame::validate() const {
  if (!(earth_radius > 0.0)) throw_invalid("earth_radius must be > 0 [m] (infinity: a flat scene) (got ", earth_radius, ")");
}

void AirFrame::check_segment(const Vec3d& a, const Vec3d& b, const char* what) {
  // The names are built only for a message: this runs on every segment a caller asks about.
  if (!within_reach(a)) check_within_reach(a, concat(what, ": a").c_str());
  if (!within_reach(b)) check_within_reach(b, concat(what, ": b").c_str());
}

std::pair<double, double> AerialPerspective::along_at(const Vec3d& a, const Vec3d& b, const AirFrame& frame,
                                                      double lambda_nm) const {
  frame.validate();
  AirFrame::check_segment(a, b, "AerialPerspective.along");
  checked_wavelength(lambda_nm, "AerialPerspective.along: wavelength");
  double T = 1.0, S = 0.0;
  integrate(a, b, frame, bands_at(&lambda_nm, 1), true, &T, &S);
  return {T, S};
}

double AerialPerspective::inscatter_reference(const Vec3d& a_in, const Vec3d& b_in, const AirFrame& frame,
                                              double lambda_nm, int steps) const {
  frame.validate();
  AirFrame::check_segment(a_in, b_in, "AerialPerspective.inscatter_reference");
  checked_wavelength(lambda_nm, "AerialPerspective.inscatter_reference: wavelength");
  // At most a million (4 s): each step traces its sun column, and the loop cannot be interrupted.
  if (steps < 1 || steps > 1'000'000) {
    throw_invalid("AerialPerspective.inscatter_reference: steps must be in [1, 1000000] (got ", steps, ")");
  }
  const Bands band = bands_at(&lambda_nm, 1);
  const double sigma_ozone = lerp_nodes(kOzoneCrossSection, lambda_nm);
  Vec3d a = a_in, b = b_in;
  if (!clip_to_air(&a, &b, frame)) return 0.0;
  const Vec3d chord = b - a;
  const double length = chord.norm(), ds = length / steps;
  if (!(length > 0.0)) return 0.0;
  const double mu = chord.normalized().dot(sun_);
  double tau = 0.0, sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const Located x = locate(a + chord * ((i + 0.5) / steps), frame);
    const Column rho = densities(x.height);
    const double extinction = band.rayleigh[0] * rho.r + air_.aerosol * kMieExtinction * rho.m + band.ozone[0] * rho.o;
    const double tau_x = tau + 0.5 * extinction * ds;
    tau += extinction * ds;
    const double mu_s = std::clamp(x.up.dot(sun_), -1.0, 1.0);
    const double psi = sky_->multiple_scattering().at(x.height, mu_s, lambda_nm);
    sum += (band.rayleigh[0] * rho.r + air_.aerosol * kMieScattering * rho.m) * psi * std::exp(-tau_x) * ds;
    const auto sun = sun_column(x.height, std::asin(mu_s), 4 * kSunColumnSteps);
    if (!sun) continue;
    const double sun_t = std::exp(-air_.optical_depth(*sun, lambda_nm, sigma_ozone));
    sum += (band.rayleigh[0] * rho.r * rayleigh_phase(mu) + air_.aerosol * kMieScattering * rho.m * mie_phase(mu)) *
           std::exp(-tau_x) * sun_t * ds;
  }
  return sum * band.irradiance[0] * scale_;
}

}  // namespace refracta
