// PhysicalAtmosphere: n of real air. Temperature = U.S. Standard Atmosphere 1976 to 86 km
// (ground temperature and lapse rate adjustable; air.h) + an inversion layer (temperature rising by
// inversion_dt across [inversion_base, inversion_base + inversion_thickness], quintic smooth step)
// + a surface layer surface_dt e^(-h/surface_depth) for h >= 0 (hot road, warm or cold water;
// continued smoothly below h = 0, where the ground is) + areal hot spots (hot_spot.h): patches of
// ground whose excess dt e^(-h/depth) F(r) depends on the distance r from their centre. Pressure is
// hydrostatic for the column without the spots and horizontally uniform (a spot's own hydrostatic
// correction is ~1e-7 of P over a metre-deep layer: ~1e-10 in n); n from the modified Edlen
// formula (air.h) at the local temperature, optional humidity. Defaults: the standard atmosphere,
// n - 1 = 2.7784e-4 at the ground at 550 nm. Above 86 km the air is uniform at its top state.
#pragma once

#include "refracta/core/error.h"
#include "refracta/media/air.h"
#include "refracta/media/column_table.h"
#include "refracta/media/hot_spot.h"
#include "refracta/media/hydrostatic_column.h"
#include "refracta/media/index_field.h"
#include "refracta/media/smoothstep.h"
#include "refracta/media/turbulence.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>
#include <vector>

namespace refracta {

// The fixed data of a PhysicalAtmosphere besides its parameters: its hot spots as made (their
// footprints; positions and sizes are parameters) and its turbulence (data, not parameters).
struct PhysicalAtmosphereConfig {
  std::vector<HotSpot> hot_spots;
  std::shared_ptr<const Turbulence> turbulence;
};

// Real air: U.S. Standard Atmosphere 1976 temperature (its seven layers to 86 km, geometric
// heights, gravity falling with height) + a smooth inversion layer + a surface layer surface_dt *
// exp(-h / surface_depth) (h >= 0) + areal hot spots (hot_spots=[refracta.HotSpot, ...]),
// hydrostatic pressure, and the index of air from Edlen's formula revised by Birch & Downs
// (1993/94) at `wavelength`, optional relative humidity. The humidity is relative to the local
// temperature, so warmer air holds more vapour: a heated surface layer too, as if the road gave
// off water (at 50 %, 30 C air over a road 15 K warmer, the layer's index step is 7.9 % larger
// than with the air's vapour pressure carried down into it: a trial); a vapour pressure not below
// the air's is refused. The hydrostatic pressure takes dry air's gas constant (1.6 % in dP/dh in
// saturated air at 30 C, ~0.003 in k). Defaults give n - 1 = 2.7784e-4 at the
// ground (15 C, 101325 Pa, 550 nm). Modelled for heights in [-1000, 86000] m (uniform above). With
// hot spots the field is no longer height-only: its parameters gain hot_spot<i>_x, _z, _radius,
// _dt, _depth (a spot made with depth None takes surface_depth's value then, and keeps it when
// with_params or a solve changes surface_depth), and height_only_part is the same air without them.
template <class T>
class PhysicalAtmosphereModel : public HydrostaticAirModel<PhysicalAtmosphereModel<T>, T> {
 public:
  using Config = PhysicalAtmosphereConfig;
  static constexpr const char* kTypeName = "PhysicalAtmosphere";
  enum Index {
    kGroundTemperature, kLapseRate, kGroundPressure, kInversionDt, kInversionBase,
    kInversionThickness, kSurfaceDt, kSurfaceDepth, kHumidity, kWavelength, kCount
  };
  static constexpr double kLowest = -1000.0, kHighest = 86000.0;  // modelled heights [m]

  static std::vector<ParamSpec> param_specs(const Config& config) {
    std::vector<ParamSpec> specs = base_param_specs();
    const ParamSpec dt{"dt", 0.0, -30.0, 60.0, "K", "excess temperature at the centre on the ground"};
    for (ParamSpec& spec : hot_spot_param_specs(config.hot_spots, true, dt)) specs.push_back(spec);
    return specs;
  }
  static constexpr bool kSpotsHaveDepth = true;  // whether a spot's depth is a parameter
  // The spots' search boxes are centred on their current values (hot_spot_param_specs).
  static Config config_at(Config config, const std::vector<double>& values) {
    config.hot_spots = hot_spots_from(config.hot_spots, values, kCount, kSpotsHaveDepth);
    return config;
  }
  static Config height_only_config(const Config&) { return {}; }

  static std::vector<ParamSpec> base_param_specs() {
    return {
        {"t_ground", kStandardGroundTemperature, 220.0, 330.0, "K",
         "air temperature at h = 0 without the surface layer (the 1976 layers above shift with it)"},
        {"lapse_rate", kStandardLapseRate, -0.02, 0.02, "K/m", "tropospheric dT/dh is -lapse_rate"},
        {"pressure", kStandardPressure, 50000.0, 110000.0, "Pa", "pressure at h = 0"},
        {"inversion_dt", 0.0, -30.0, 30.0, "K", "temperature rise across the inversion layer"},
        {"inversion_base", 100.0, -100.0, 5000.0, "m", "bottom of the inversion layer"},
        {"inversion_thickness", 10.0, 0.1, 2000.0, "m", "thickness of the inversion layer"},
        {"surface_dt", 0.0, -30.0, 60.0, "K", "surface-layer excess temperature at h = 0"},
        {"surface_depth", 0.1, 0.005, 10.0, "m", "e-folding depth of the surface layer"},
        {"humidity", 0.0, 0.0, 1.0, "1", "relative humidity"},
        {"wavelength", 550.0, 380.0, 780.0, "nm", "vacuum wavelength"},
    };
  }
  static std::vector<std::string> gauge_params() { return {}; }

  static void validate(const Config& config, const std::vector<double>& v) {
    validate_base(v);  // first: a spot without its own depth took surface_depth's
    validate_hot_spots(kTypeName, v, kCount, config.hot_spots.size(), true);
    // A spot's dt is a temperature excess here, bounded alone as a plausible patch of ground; the
    // air the spots heat or cool together is checked against the column's (check_heated_air).
    constexpr double kColdestSpotDt = -150.0, kHottestSpotDt = 500.0;  // [K]
    for (size_t i = 0; i < config.hot_spots.size(); ++i) {
      const double dt = v[kCount + hot_spot_param_count(true) * i + kSpotDt];
      if (!(dt >= kColdestSpotDt && dt <= kHottestSpotDt)) {
        throw_invalid(kTypeName, ": hot_spot", i, "_dt must be in [", kColdestSpotDt, ", ", kHottestSpotDt, "] K (got ",
                      dt, ")");
      }
    }
    if (v[kHumidity] > 0.0 && std::isfinite(v[kGroundTemperature] + v[kSurfaceDt])) {
      // Relative humidity follows the local temperature (air.h), so the warmest air near the
      // ground holds the most vapour: more than the air's own pressure is water boiling, not air
      // (a trial's t_ground 400 K at humidity 1: 258 kPa of vapour in 101 kPa of air).
      // Where spots overlap their excesses add: the most that meet on one spot's disc.
      const int per = hot_spot_param_count(true);
      std::vector<std::array<double, 3>> discs;
      for (size_t i = 0; i < config.hot_spots.size(); ++i) {
        const double* spot = &v[kCount + per * i];
        discs.push_back({spot[kSpotX], spot[kSpotZ], reach_of(config.hot_spots[i], spot[kSpotRadius])});
      }
      double spot_heat = 0.0;
      for (const std::vector<size_t>& group : overlapping(discs)) {
        double heat = 0.0;
        for (size_t j : group) heat += std::max(v[kCount + per * j + kSpotDt], 0.0);
        spot_heat = std::max(spot_heat, heat);
      }
      const double hottest = v[kGroundTemperature] + std::max(v[kSurfaceDt], 0.0) + spot_heat;
      double e_s, de_dt;
      saturation_vapour_pressure(hottest, &e_s, &de_dt);
      if (!(v[kHumidity] * e_s < v[kGroundPressure])) {
        throw_invalid(kTypeName, ": humidity ", v[kHumidity], " at the ground's warmest ", hottest,
                      " K (surface_dt and hot spots included) is ", v[kHumidity] * e_s,
                      " Pa of water vapour, not less than the air's pressure ", v[kGroundPressure],
                      " Pa (the water would boil): lower humidity or the temperatures");
      }
    }
    // Positive temperature everywhere is checked while the pressure column is built.
  }

  static void validate_base(const std::vector<double>& v) {
    if (!(v[kGroundTemperature] >= kColdestAir && v[kGroundTemperature] <= kHottestAir)) {
      throw_invalid("PhysicalAtmosphere: t_ground must be in [", kColdestAir, ", ", kHottestAir,
                    "] K, in kelvin (15 C is 288.15 K; got ", v[kGroundTemperature], ")");
    }
    check_ground_pressure(v[kGroundPressure], "PhysicalAtmosphere");
    if (!(v[kInversionThickness] > 0.0)) {
      throw_invalid("PhysicalAtmosphere: inversion_thickness must be > 0 m (got ",
                    v[kInversionThickness], ")");
    }
    if (!(v[kSurfaceDepth] >= kShallowestLayer && v[kSurfaceDepth] <= kDeepestLayer)) {
      throw_invalid("PhysicalAtmosphere: surface_depth must be in [", kShallowestLayer, ", ", kDeepestLayer,
                    "] m (got ", v[kSurfaceDepth], ")");
    }
    if (!(v[kHumidity] >= 0.0 && v[kHumidity] <= 1.0)) {
      throw_invalid("PhysicalAtmosphere: humidity must be in [0, 1] (got ", v[kHumidity], ")");
    }
    if (!(v[kWavelength] >= 230.0 && v[kWavelength] <= 2000.0)) {
      throw_invalid("PhysicalAtmosphere: wavelength must be in [230, 2000] nm (got ",
                    v[kWavelength], ")");
    }
  }

  PhysicalAtmosphereModel(const Config& config, const std::vector<T>& v)
      : p_(v.begin(), v.begin() + kCount),
        spots_(config.hot_spots),
        turbulence_(config.turbulence),
        dispersion_(edlen_dispersion(p_[kWavelength])) {
    const int per = hot_spot_param_count(true);
    for (size_t i = 0; i < spots_.size(); ++i) {
      spot_values_.emplace_back(v.begin() + kCount + per * i, v.begin() + kCount + per * (i + 1));
      inv_radius_.push_back(T(1.0) / spot_values_[i][kSpotRadius]);
    }
    const double depth = value_of(p_[kSurfaceDepth]);
    const double base = value_of(p_[kInversionBase]), thick = value_of(p_[kInversionThickness]);
    // Node spacing for the column's 1e-12 accuracy (cubic Hermite with exact slopes, 4-point
    // Gauss-Legendre per interval): where T is linear (the standard layers) 1/T is smooth on the
    // scale T/T' > 30 km, so 100 m near the ground and 500 m above 2 km suffice; the layers' kinks
    // are nodes; the surface layer and the inversion vary on their own scales.
    std::vector<double> kinks;
    for (const StandardLayer& layer : kStandardLayers) kinks.push_back(geometric_height(layer.base));
    kinks.push_back(geometric_height(kStandardTop));
    std::vector<double> nodes = make_nodes(
        kLowest, kHighest,
        {{kLowest, 2000.0, 100.0}, {2000.0, kHighest, 500.0}, {-12.0 * depth, 12.0 * depth, depth / 10.0},
         {12.0 * depth, 40.0 * depth, depth / 2.0},
         {base, base + thick, thick / 40.0}},
        kinks);
    if (!spots_.empty()) check_heated_air(nodes);
    column_ = HydrostaticColumn<T>([this](const T& h, T* t, T* dt) { temperature(h, t, dt); },
                                   std::move(nodes), 0.0, p_[kGroundPressure], kTypeName);
    if constexpr (std::is_same_v<T, double>) tabulate_near_ground();
  }

  bool height_only() const { return spots_.empty() && !turbulence_; }

  // n and grad n at p: the column's air, heated by the spots, stirred by the turbulence.
  void evaluate(const Vec3<T>& p, T* n, Vec3<T>* grad) const {
    if (height_only()) {
      HydrostaticAirModel<PhysicalAtmosphereModel<T>, T>::evaluate(p, n, grad);
      return;
    }
    T excess(0.0);
    Vec3<T> grad_excess(T(0.0), T(0.0), T(0.0));
    bool heated = false;
    if (value_of(p.y()) <= column_.highest()) {
      for (size_t i = 0; i < spots_.size(); ++i) heated = add_spot(i, p, &excess, &grad_excess) || heated;
    }
    T p_air, dp_dh, t, dt_dh;
    // The column near the ground from its table where the spots or the turbulence change the air;
    // elsewhere its own state, so that the air outside a compact spot is exactly the height-only air
    // (at the seams -- a compact spot's rim, the table's ends -- n steps by an ulp or so and dn/dh by
    // ~1e-13 1/m: far below what a trace's error control resolves).
    bool tabulated = false;
    if constexpr (std::is_same_v<T, double>) {
      tabulated = (heated || turbulence_) && near_ground_.covers(p.y());
      if (tabulated) near_ground_.at(p.y(), &p_air, &dp_dh, &t, &dt_dh);
    }
    if (!tabulated) this->column_state(p.y(), &p_air, &dp_dh, &t, &dt_dh);
    Vec3<T> grad_t(T(0.0), dt_dh, T(0.0));
    if (heated) {
      t += excess;
      grad_t += grad_excess;
    }
    T dn_dp, dn_dt;
    air_index_at(p_air, t, p_[kHumidity], dispersion_, n, &dn_dp, &dn_dt);
    *grad = dn_dt * grad_t;
    grad->y() += dn_dp * dp_dh;
    if (turbulence_) {
      T dn;
      Vec3<T> dgrad;
      turbulence_->evaluate(p, &dn, &dgrad);
      *n += dn;
      *grad += dgrad;
    }
  }

  // Where the spots heat the air: a cylinder of each spot's reach, up to where e^(-h/depth) is
  // negligible.
  std::vector<LocalRegion> local_regions() const {
    std::vector<LocalRegion> regions;
    for (size_t i = 0; i < spots_.size(); ++i) {
      HotSpot s = spots_[i];
      s.radius = value_of(spot_values_[i][kSpotRadius]);
      regions.push_back({value_of(spot_values_[i][kSpotX]), value_of(spot_values_[i][kSpotZ]), s.reach(),
                         -std::log(kNegligibleFeature) * value_of(spot_values_[i][kSpotDepth]), s.radius});
    }
    if (turbulence_) regions.push_back(turbulence_->region());
    return regions;
  }

  // T(h) [K] and dT/dh [K/m] of the column (without the spots).
  void temperature(const T& h, T* t, T* dt_dh) const {
    using std::exp;
    standard_temperature(h, p_[kGroundTemperature], p_[kLapseRate], t, dt_dh);
    T step, dstep;
    smoothstep5((h - p_[kInversionBase]) / p_[kInversionThickness], &step, &dstep);
    *t += p_[kInversionDt] * step;
    *dt_dh += p_[kInversionDt] * dstep / p_[kInversionThickness];
    // Below the ground the layer continues as dT (2 - e^(h/d)): T and dT/dh stay continuous at
    // h = 0, so grad n has no jump there (a jump would cost rk4 an O(step) error and break the
    // derivatives editing takes through a ray crossing it), and T stays bounded as h -> -inf.
    if (value_of(h) > 0.0) {
      const T surface = p_[kSurfaceDt] * exp(-h / p_[kSurfaceDepth]);
      *t += surface;
      *dt_dh -= surface / p_[kSurfaceDepth];
    } else {
      const T rise = p_[kSurfaceDt] * exp(h / p_[kSurfaceDepth]);
      *t += T(2.0) * p_[kSurfaceDt] - rise;
      *dt_dh -= rise / p_[kSurfaceDepth];
    }
  }

  const HydrostaticColumn<T>& column() const { return column_; }
  const T& humidity() const { return p_[kHumidity]; }
  const EdlenDispersion<T>& dispersion() const { return dispersion_; }

 private:
  enum SpotIndex { kSpotX, kSpotZ, kSpotRadius, kSpotDt, kSpotDepth };

  // A spot's reach [m] at `radius`: beyond it the spot heats nothing (HotSpot::reach).
  static double reach_of(HotSpot spot, double radius) {
    spot.radius = radius;
    return spot.reach();
  }
  // For each spot (x, z, reach), the spots whose discs meet its own, itself included: a point is
  // heated only by spots whose discs hold it, and those all meet the disc of any one of them.
  static std::vector<std::vector<size_t>> overlapping(const std::vector<std::array<double, 3>>& discs) {
    std::vector<std::vector<size_t>> groups(discs.size());
    for (size_t i = 0; i < discs.size(); ++i) {
      for (size_t j = 0; j < discs.size(); ++j) {
        const double apart = std::hypot(discs[i][0] - discs[j][0], discs[i][1] - discs[j][1]);
        if (apart < discs[i][2] + discs[j][2] || i == j) groups[i].push_back(j);
      }
    }
    return groups;
  }

  // Where spots overlap their excesses add: at each height the air over a spot's disc is bounded by
  // the column's temperature plus the sum of the cooling excesses dt e(h) of the spots that meet it
  // (and of the heating ones'), e(h) up to 2 below the ground (surface_decay: the model's
  // continuation, as the column's own surface layer's, so a -150 K spot needs air above ~300 K at
  // -1000 m). That air must stay in (0, kHottestAir] K, as the column's own (a trial's -150 K spot
  // over 140 K air read n = 0.992 with no error).
  void check_heated_air(const std::vector<double>& heights) const {
    std::vector<std::array<double, 3>> discs;
    for (size_t i = 0; i < spots_.size(); ++i) {
      const std::vector<T>& v = spot_values_[i];
      discs.push_back({value_of(v[kSpotX]), value_of(v[kSpotZ]), reach_of(spots_[i], value_of(v[kSpotRadius]))});
    }
    const std::vector<std::vector<size_t>> groups = overlapping(discs);
    std::vector<double> excess(spots_.size());
    for (const double h : heights) {
      T t, slope;
      temperature(T(h), &t, &slope);
      for (size_t i = 0; i < spots_.size(); ++i) {
        T e, de_dh;
        surface_decay(T(h), spot_values_[i][kSpotDepth], &e, &de_dh);
        excess[i] = value_of(spot_values_[i][kSpotDt] * e);
      }
      for (const std::vector<size_t>& group : groups) {
        double cooling = 0.0, heating = 0.0;
        for (size_t j : group) (excess[j] < 0.0 ? cooling : heating) += excess[j];
        for (const double air : {value_of(t) + cooling, value_of(t) + heating}) {
          if (!(air > 0.0 && air <= kHottestAir)) {
            throw_invalid(kTypeName, ": the hot spots make the air ", air, " K at h = ", h, " m (the column's ",
                          value_of(t), " K and the spots' dt e^(-h/depth) added where they overlap, twice dt below ",
                          "the ground); it must stay in (0, ", kHottestAir, "] K: give the spots smaller dt");
          }
        }
      }
    }
  }

  // Spot i's excess dt e(h) F(r) added to t, and its gradient to grad_t; false where it adds nothing.
  bool add_spot(size_t i, const Vec3<T>& p, T* t, Vec3<T>* grad_t) const {
    const std::vector<T>& v = spot_values_[i];
    T f, df_dx, df_dz, e, de_dh;
    hot_spot_footprint(spots_[i].footprint, T(p.x() - v[kSpotX]), T(p.z() - v[kSpotZ]), inv_radius_[i], &f, &df_dx,
                       &df_dz);
    if (value_of(f) == 0.0 && value_of(df_dx) == 0.0 && value_of(df_dz) == 0.0) return false;
    surface_decay(p.y(), v[kSpotDepth], &e, &de_dh);
    *t += v[kSpotDt] * e * f;
    *grad_t += v[kSpotDt] * Vec3<T>(e * df_dx, de_dh * f, e * df_dz);
    return true;
  }

  // The column's state near the ground (column_table.h), from a surface-layer depth below h = 0 to a
  // tenth above the highest region (the spots' tops, the turbulent slab's), where rays inside them
  // evaluate the field; the spacing a 128th of the finest scale tabulated: the surface layer's
  // depth, or a low inversion's thickness / 4.4 (its quintic step's 4th derivative reaches 360 dT /
  // thickness^4, the layer's dT / depth^4: 360^(1/4) = 4.4). Not built beyond 65536 nodes (2 MB;
  // a deeper table -- spots metres deep over a centimetre layer -- takes milliseconds to build per
  // field, and editing builds one per parameter vector): the column's own state then.
  void tabulate_near_ground() {
    double top = 0.0;
    for (const LocalRegion& region : local_regions()) top = std::max(top, region.top);
    const double depth = p_[kSurfaceDepth];
    const double lo = -depth, hi = std::min(1.1 * top, kHighest);
    if (!(hi > 0.0)) return;
    double scale = depth;
    if (p_[kInversionBase] < hi) scale = std::min(scale, p_[kInversionThickness] / 4.4);
    const double spacing = scale / 128.0;
    constexpr double kMostNodes = 65536.0;
    if ((hi - lo) / spacing > kMostNodes) return;
    near_ground_ = ColumnTable(lo, hi, spacing, [this](double h, double* p, double* dp, double* t, double* dt) {
      this->column_state(h, p, dp, t, dt);
    });
  }

  std::vector<T> p_;
  std::vector<HotSpot> spots_;             // footprints (their numbers are in spot_values_)
  std::vector<std::vector<T>> spot_values_;  // x, z, radius, dt, depth per spot
  std::vector<T> inv_radius_;                // 1 / radius per spot
  std::shared_ptr<const Turbulence> turbulence_;
  EdlenDispersion<T> dispersion_;
  HydrostaticColumn<T> column_;
  ColumnTable near_ground_;  // double only (editing's Jets evaluate the column itself)
};

}  // namespace refracta
