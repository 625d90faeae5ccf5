// PhysicalAtmosphere: n(h) of real air. Temperature = U.S. Standard Atmosphere 1976 (ground
// temperature and lapse rate adjustable) + an inversion layer (temperature rising by
// inversion_dt across [inversion_base, inversion_base + inversion_thickness], quintic smooth step)
// + a surface layer surface_dt e^(-h/surface_depth) for h >= 0 (hot road, warm or cold water;
// continued smoothly below h = 0, where the ground is). Pressure is hydrostatic for that temperature
// profile (hydrostatic_column.h); n from the modified Edlén formula (air.h), optional humidity.
// Defaults: the standard atmosphere, n - 1 = 2.7784e-4 at the ground at 550 nm.
#pragma once

#include "refracta/core/error.h"
#include "refracta/media/air.h"
#include "refracta/media/hydrostatic_column.h"
#include "refracta/media/index_field.h"
#include "refracta/media/smoothstep.h"

namespace refracta {

template <class T>
class PhysicalAtmosphereModel : public HydrostaticAirModel<PhysicalAtmosphereModel<T>, T> {
 public:
  using Config = NoConfig;
  static constexpr const char* kTypeName = "PhysicalAtmosphere";
  enum Index {
    kGroundTemperature, kLapseRate, kGroundPressure, kInversionDt, kInversionBase,
    kInversionThickness, kSurfaceDt, kSurfaceDepth, kHumidity, kWavelength, kCount
  };
  static constexpr double kLowest = -1000.0, kHighest = 32000.0;  // modelled heights [m]

  static std::vector<ParamSpec> param_specs(const Config&) {
    return {
        {"t_ground", kStandardGroundTemperature, 220.0, 330.0, "K",
         "air temperature at h = 0 without the surface layer"},
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

  static void validate(const Config&, const std::vector<double>& v) {
    if (!(v[kGroundPressure] > 0.0)) {
      throw_invalid("PhysicalAtmosphere: pressure must be > 0 Pa (got ", v[kGroundPressure], ")");
    }
    if (!(v[kInversionThickness] > 0.0)) {
      throw_invalid("PhysicalAtmosphere: inversion_thickness must be > 0 m (got ",
                    v[kInversionThickness], ")");
    }
    if (!(v[kSurfaceDepth] > 0.0)) {
      throw_invalid("PhysicalAtmosphere: surface_depth must be > 0 m (got ", v[kSurfaceDepth], ")");
    }
    if (!(v[kHumidity] >= 0.0 && v[kHumidity] <= 1.0)) {
      throw_invalid("PhysicalAtmosphere: humidity must be in [0, 1] (got ", v[kHumidity], ")");
    }
    if (!(v[kWavelength] >= 230.0 && v[kWavelength] <= 2000.0)) {
      throw_invalid("PhysicalAtmosphere: wavelength must be in [230, 2000] nm (got ",
                    v[kWavelength], ")");
    }
    // Positive temperature everywhere is checked while the pressure column is built.
  }

  PhysicalAtmosphereModel(const Config&, const std::vector<T>& v)
      : p_(v.begin(), v.end()) {
    const double depth = value_of(p_[kSurfaceDepth]);
    const double base = value_of(p_[kInversionBase]), thick = value_of(p_[kInversionThickness]);
    std::vector<double> nodes = make_nodes(
        kLowest, kHighest,
        {{kLowest, 2000.0, 10.0}, {2000.0, kHighest, 100.0}, {0.0, 12.0 * depth, depth / 40.0},
         {base, base + thick, thick / 80.0}});
    column_ = HydrostaticColumn<T>([this](const T& h, T* t, T* dt) { temperature(h, t, dt); },
                                   std::move(nodes), 0.0, p_[kGroundPressure], kTypeName);
  }

  // T(h) [K] and dT/dh [K/m].
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
  const T& wavelength() const { return p_[kWavelength]; }

 private:
  std::vector<T> p_;
  HydrostaticColumn<T> column_;
};

}  // namespace refracta
