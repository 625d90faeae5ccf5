// TemperatureProfile: a measured sounding (heights, temperatures) turned into a C1 temperature
// profile by monotone piecewise-cubic Hermite interpolation (Fritsch & Carlson 1980, with the
// Fritsch-Butland slopes of Moler's pchip), then n through the same air formula and hydrostatic
// pressure as PhysicalAtmosphere. Beyond the sounding the temperature levels off smoothly,
// T = T_end + s w tanh(dh / w) (s: end slope, w: end interval), so it stays C1 and bounded.
// Parameters: the temperatures t0..t{m-1} [K], the pressure at the lowest height, humidity and
// wavelength; the heights are fixed data (Config).
#pragma once

#include "refracta/core/error.h"
#include "refracta/media/air.h"
#include "refracta/media/hydrostatic_column.h"
#include "refracta/media/index_field.h"

#include <string>

namespace refracta {

// The sounding's fixed heights [m], strictly increasing (not parameters).
struct SoundingHeights {
  std::vector<double> heights;
};

// A measured sounding: temperatures [K] at strictly increasing heights [m], joined by a monotone C1
// cubic (pchip) and levelling off smoothly beyond the ends, as T_end + s w tanh(dh / w) (s: the end
// slope, w: the end interval): up to one more interval's worth of the end gradient (a coarse top
// interval of 10 K over 10 m goes on to ~10 K more; add a level where the air is known to turn);
// hydrostatic pressure from `pressure` [Pa] at the lowest height; n from the same air formula as
// PhysicalAtmosphere. The temperatures are the parameters t0, t1, ... (with pressure, humidity,
// wavelength).
template <class T>
class TemperatureProfileModel : public HydrostaticAirModel<TemperatureProfileModel<T>, T> {
 public:
  using Config = SoundingHeights;
  static constexpr const char* kTypeName = "TemperatureProfile";
  static constexpr double kBelow = 2000.0, kAbove = 20000.0;  // modelled margin [m]

  // A radiosonde's 1 s data to 30 km has ~6000 levels; each level is a parameter and adds 16
  // hydrostatic nodes (~7 us): 10^5 levels build in ~0.5 s, 10^7 would take minutes and gigabytes.
  static constexpr size_t kMaxLevels = 100'000;
  static void check_level_count(const Config& config) {
    if (config.heights.size() > kMaxLevels) {
      throw_invalid("TemperatureProfile: at most ", kMaxLevels, " levels (got ", config.heights.size(), ")");
    }
  }

  static std::vector<ParamSpec> param_specs(const Config& config) {
    check_level_count(config);  // before allocating a spec per level
    std::vector<ParamSpec> specs;
    for (size_t i = 0; i < config.heights.size(); ++i) {
      if (i % 4096 == 0) poll_cancel();  // millions of levels take seconds (TemperatureProfile's Ctrl-C)
      specs.push_back({"t" + std::to_string(i), kStandardGroundTemperature, 200.0, 340.0, "K",
                       "temperature at height " + std::to_string(config.heights[i]) + " m"});
    }
    specs.push_back({"pressure", kStandardPressure, 50000.0, 110000.0, "Pa",
                     "pressure at the lowest height"});
    specs.push_back({"humidity", 0.0, 0.0, 1.0, "1", "relative humidity"});
    specs.push_back({"wavelength", 550.0, 380.0, 780.0, "nm", "vacuum wavelength"});
    return specs;
  }
  static std::vector<std::string> gauge_params() { return {}; }

  static void validate(const Config& config, const std::vector<double>& v) {
    check_level_count(config);
    const auto& h = config.heights;
    if (h.size() < 2) {
      throw_invalid("TemperatureProfile: needs at least 2 heights (got ", h.size(), ")");
    }
    for (size_t i = 0; i < h.size(); ++i) {
      if (!std::isfinite(h[i])) throw_invalid("TemperatureProfile: heights[", i, "] is not finite");
      if (i > 0 && !(h[i] > h[i - 1])) {
        throw_invalid("TemperatureProfile: heights must be strictly increasing (heights[", i,
                      "] = ", h[i], " <= heights[", i - 1, "] = ", h[i - 1], ")");
      }
    }
    const size_t m = h.size();
    for (size_t i = 0; i < m; ++i) {
      if (!(v[i] >= kColdestAir && v[i] <= kHottestAir)) {
        throw_invalid("TemperatureProfile: temperatures[", i, "] (t", i, ") must be in [", kColdestAir, ", ",
                      kHottestAir, "] K, in kelvin (15 C is 288.15 K; got ", v[i], ")");
      }
    }
    check_ground_pressure(v[m], "TemperatureProfile");
    if (!(v[m + 1] >= 0.0 && v[m + 1] <= 1.0)) {
      throw_invalid("TemperatureProfile: humidity must be in [0, 1] (got ", v[m + 1], ")");
    }
    if (!(v[m + 2] >= 230.0 && v[m + 2] <= 2000.0)) {
      throw_invalid("TemperatureProfile: wavelength must be in [230, 2000] nm (got ", v[m + 2], ")");
    }
  }

  TemperatureProfileModel(const Config& config, const std::vector<T>& v)
      : h_(config.heights), t_(v.begin(), v.begin() + config.heights.size()) {
    const size_t m = h_.size();
    pressure_ = v[m];
    humidity_ = v[m + 1];
    wavelength_ = v[m + 2];
    dispersion_ = edlen_dispersion(wavelength_);
    compute_slopes();
    std::vector<NodeRun> runs = {{h_.front() - kBelow, h_.back() + kAbove, 100.0}};
    for (size_t i = 0; i + 1 < m; ++i) runs.push_back({h_[i], h_[i + 1], (h_[i + 1] - h_[i]) / 16});
    const double w0 = h_[1] - h_[0], w1 = h_[m - 1] - h_[m - 2];
    runs.push_back({h_.front() - 10 * w0, h_.front(), w0 / 8});
    runs.push_back({h_.back(), h_.back() + 10 * w1, w1 / 8});
    column_ = HydrostaticColumn<T>([this](const T& h, T* t, T* dt) { temperature(h, t, dt); },
                                   make_nodes(h_.front() - kBelow, h_.back() + kAbove, runs),
                                   h_.front(), pressure_, kTypeName);
  }

  void temperature(const T& h, T* t, T* dt_dh) const {
    using std::tanh;
    const double hv = value_of(h);
    const size_t m = h_.size();
    if (hv <= h_.front() || hv >= h_.back()) {
      const bool below = hv <= h_.front();
      const size_t e = below ? 0 : m - 1;
      const double w = below ? h_[1] - h_[0] : h_[m - 1] - h_[m - 2];
      const T th = tanh((h - h_[e]) / w);
      *t = t_[e] + slope_[e] * w * th;
      *dt_dh = slope_[e] * (T(1.0) - th * th);
      return;
    }
    const size_t i = std::upper_bound(h_.begin(), h_.end(), hv) - h_.begin();
    const double a = h_[i - 1], width = h_[i] - a;
    const T u = (h - a) / width, u2 = u * u, u3 = u2 * u;
    *t = (T(2.0) * u3 - T(3.0) * u2 + T(1.0)) * t_[i - 1] +
         (u3 - T(2.0) * u2 + u) * width * slope_[i - 1] + (T(-2.0) * u3 + T(3.0) * u2) * t_[i] +
         (u3 - u2) * width * slope_[i];
    *dt_dh = ((T(6.0) * u2 - T(6.0) * u) * (t_[i - 1] - t_[i])) / width +
             (T(3.0) * u2 - T(4.0) * u + T(1.0)) * slope_[i - 1] +
             (T(3.0) * u2 - T(2.0) * u) * slope_[i];
  }

  const HydrostaticColumn<T>& column() const { return column_; }
  const T& humidity() const { return humidity_; }
  const EdlenDispersion<T>& dispersion() const { return dispersion_; }

 private:
  static double sign(double x) { return (x > 0) - (x < 0); }

  // Moler's pchip slopes: weighted harmonic means inside, a shape-preserving 3-point formula at
  // the ends.
  void compute_slopes() {
    const size_t m = h_.size();
    std::vector<T> delta(m - 1);
    std::vector<double> w(m - 1);
    for (size_t i = 0; i + 1 < m; ++i) {
      w[i] = h_[i + 1] - h_[i];
      delta[i] = (t_[i + 1] - t_[i]) / w[i];
    }
    slope_.assign(m, T(0.0));
    if (m == 2) {
      slope_[0] = slope_[1] = delta[0];
      return;
    }
    for (size_t k = 1; k + 1 < m; ++k) {
      if (value_of(delta[k - 1]) * value_of(delta[k]) > 0.0) {
        const double w1 = 2 * w[k] + w[k - 1], w2 = w[k] + 2 * w[k - 1];
        slope_[k] = T(w1 + w2) / (T(w1) / delta[k - 1] + T(w2) / delta[k]);
      }
    }
    slope_[0] = end_slope(w[0], w[1], delta[0], delta[1]);
    slope_[m - 1] = end_slope(w[m - 2], w[m - 3], delta[m - 2], delta[m - 3]);
  }

  static T end_slope(double w0, double w1, const T& d0, const T& d1) {
    T d = (T(2 * w0 + w1) * d0 - T(w0) * d1) / T(w0 + w1);
    if (sign(value_of(d)) != sign(value_of(d0))) return T(0.0);
    if (sign(value_of(d0)) != sign(value_of(d1)) && std::abs(value_of(d)) > 3 * std::abs(value_of(d0))) {
      return T(3.0) * d0;
    }
    return d;
  }

  std::vector<double> h_;
  std::vector<T> t_, slope_;
  T pressure_, humidity_, wavelength_;
  EdlenDispersion<T> dispersion_;
  HydrostaticColumn<T> column_;
};

}  // namespace refracta
