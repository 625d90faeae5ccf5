// Areal hot spots: a hot (dt > 0) or cold patch of ground centred at (x, z) whose temperature
// excess dt e^(-h/depth) F(r) falls off sideways with a footprint F of the distance r from the
// centre:
//   gaussian  F = exp(-r^2 / (2 radius^2))                     (smooth, never exactly zero)
//   compact   F = (1 - r/R)^4 (4 r/R + 1) for r < R, else 0     (Wendland's C2 function, R = radius;
//             Wendland 1995, "Piecewise polynomial, positive definite and compactly supported radial
//             functions of minimal degree", Adv. Comput. Math. 4)
// The models add them as parameters named hot_spot<i>_x, _z, _radius, _dt (and _depth for
// PhysicalAtmosphere), so editing moves and resizes them with exact derivatives. Templated on the
// scalar like the models.
#pragma once

#include "refracta/core/error.h"
#include "refracta/media/index_field.h"
#include "refracta/media/local_region.h"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

// A surface layer's excess (a hot spot's, PhysicalAtmosphere's surface layer) decays as
// e^(-h / depth), depth from a tenth of a millimetre (180 wavelengths of green light, thinner than
// any measured over hot ground; a trial's 1 nm layer sent the eye table's rays below the ground) to
// the troposphere's 10 km.
constexpr double kShallowestLayer = 1e-4, kDeepestLayer = 1e4;  // [m]

enum class Footprint { kGaussian, kCompact };
Footprint parse_footprint(const std::string& name);  // "gaussian", "compact"
const char* footprint_name(Footprint footprint);

// An areal hot (dt > 0) or cold (dt < 0) patch of ground centred at (x, z) [m]: the air above it is
// warmer by dt * exp(-h / depth) * F(r), r the horizontal distance from the centre, with footprint
// 'gaussian' F = exp(-r^2 / (2 radius^2)) or 'compact' F = (1 - r/R)^4 (4 r/R + 1) for r < R =
// radius (Wendland's C2 function: exactly zero outside). Give it to
// PhysicalAtmosphere(hot_spots=[...]) (dt [K]; depth [m], None: the atmosphere's surface_depth as
// the field is made) or LogisticProfile(hot_spots=[...]) (dt: strength of the profile's hot-spot
// term there, 1 = the whole term; depth must be None: the term's width is a_hot). The fields expose
// each spot's numbers as parameters hot_spot<i>_x, _z, _radius, _dt (, _depth), so refracta.edit.solve
// can move, resize and heat them; a spot's depth is then its own parameter, which with_params or a
// solve of surface_depth leaves where it is (change hot_spot<i>_depth with it to move both).
struct HotSpot {
  double x = 0.0, z = 0.0;  // centre on the ground [m]
  double radius = 1.0;      // [m]: the gaussian's standard deviation, or the compact support's radius
  double dt = 0.0;          // temperature excess at the centre on the ground [K] (LogisticProfile:
                            // the strength of its hot-spot term there, 1 = the whole term)
  double depth = 0.1;       // e-folding depth of the excess [m] (not used by LogisticProfile)
  Footprint footprint = Footprint::kGaussian;

  // Beyond this distance from the centre F < kNegligibleFeature (exactly 0 for compact) [m].
  double reach() const {
    return footprint == Footprint::kCompact ? radius : radius * std::sqrt(-2.0 * std::log(kNegligibleFeature));
  }
  // Equal numbers and footprint (a NaN depth equals a NaN depth: both "none").
  bool operator==(const HotSpot& other) const;
};

// A spot from its numbers, checked: x, z, radius, dt finite, radius > 0, depth > 0 and finite or
// none (nullopt: NaN), footprint "gaussian" or "compact"; std::invalid_argument naming the field.
HotSpot make_hot_spot(double x, double z, double radius, double dt, std::optional<double> depth,
                      const std::string& footprint);
// "HotSpot(x=..., z=..., radius=..., dt=..., depth=... or None, footprint='...')".
std::string hot_spot_repr(const HotSpot& spot);

// The parameter specs of the spots, appended after a model's own: names hot_spot<i>_<field>, the
// search box around the position and size each spot was made with.
std::vector<ParamSpec> hot_spot_param_specs(const std::vector<HotSpot>& spots, bool with_depth,
                                            const ParamSpec& dt_spec);
// Parameters per spot: x, z, radius, dt (, depth).
inline int hot_spot_param_count(bool with_depth) { return with_depth ? 5 : 4; }
// Checks the spots' parameters values[first ...] (radius > 0, depth > 0); model names the field.
void validate_hot_spots(const char* model, const std::vector<double>& values, size_t first, size_t count,
                        bool with_depth);
// The spots (their kinds from `made`) read back from parameter values.
std::vector<HotSpot> hot_spots_from(const std::vector<HotSpot>& made, const std::vector<double>& values, size_t first,
                                    bool with_depth);

// F at horizontal offset (dx, dz) from the centre and its gradient (dF/dx, dF/dz); inv_radius is
// 1 / radius (PhysicalAtmosphere keeps it per spot: a division after the square root was a tenth
// of a hot-spot render).
template <class T>
void hot_spot_footprint(Footprint kind, const T& dx, const T& dz, const T& inv_radius, T* f, T* df_dx, T* df_dz) {
  using std::exp;
  using std::sqrt;
  const T r2 = dx * dx + dz * dz;
  const T inv_r2 = inv_radius * inv_radius;
  if (kind == Footprint::kGaussian) {
    *f = exp(T(-0.5) * r2 * inv_r2);
    *df_dx = -*f * dx * inv_r2;
    *df_dz = -*f * dz * inv_r2;
    return;
  }
  if (!(value_of(r2) * value_of(inv_r2) < 1.0)) {
    *f = *df_dx = *df_dz = T(0.0);
    return;
  }
  // q = r/R; dF/dr = -20 q (1 - q)^3 / R, so grad F = -20 (1 - q)^3 (dx, dz) / R^2: no division
  // by r (smooth at the centre, where sqrt would give Jets infinite slopes).
  const T q = value_of(r2) > 0.0 ? sqrt(r2) * inv_radius : T(0.0);
  const T one_minus = T(1.0) - q;
  const T cube = one_minus * one_minus * one_minus;
  *f = cube * one_minus * (T(4.0) * q + T(1.0));
  const T slope = T(-20.0) * cube * inv_r2;
  *df_dx = slope * dx;
  *df_dz = slope * dz;
}

// The vertical profile of a spot's excess, e^(-h/depth) above the ground, continued below it as
// 2 - e^(h/depth) (C1 at h = 0 and bounded, like PhysicalAtmosphere's surface layer), and its slope.
template <class T>
void surface_decay(const T& h, const T& depth, T* e, T* de_dh) {
  using std::exp;
  if (value_of(h) > 0.0) {
    *e = exp(-h / depth);
    *de_dh = -*e / depth;
  } else {
    const T rise = exp(h / depth);
    *e = T(2.0) - rise;
    *de_dh = -rise / depth;
  }
}

}  // namespace refracta
