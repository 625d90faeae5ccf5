// LogisticProfile: the original mirage editor's 8-parameter height profile (Choi 2017, the
// refractive-index-editor's TestModel), in scene units. A background, an inversion layer and a hot
// spot, each a logistic step:
//   n(h) = 1 + 0.003 k_s (f(n_bg, 10 a_bg, 0, h) + f(n_inv, -0.1 a_inv, h_ciso, h)
//                         + f(n_hot, 0.3 a_hot, 0, h)) / (|n_bg| + |n_inv| + |n_hot|),
//   f(L, w, x0, x) = L / (1 + e^((x0 - x)/w)).
// Gauge freedom: scaling (n_bg, n_inv, n_hot) together changes nothing (the normaliser divides it
// out), so an optimiser must hold one amplitude fixed: gauge_params() names n_bg.
//
// Areal hot spots (the follow-up's "the hot spot does not consider its spatial location"): the hot
// term's deficit near the ground, n_hot - f(n_hot, w, 0, h) = n_hot sigma(-h/w) (w = 0.3 a_hot), is
// scaled by S(x, z) = sum_i dt_i F_i(r_i) (hot_spot.h; dt_i the spot's strength, 1 = the whole
// term), so the hot layer is there only over the spots and n_hot's constant far value elsewhere:
//   hot term = n_hot (1 - S(x, z) sigma(-h/w)).
// Without spots the term is the profile's own, n_hot (1 - sigma(-h/w)) = f(n_hot, w, 0, h).
#pragma once

#include "refracta/core/error.h"
#include "refracta/media/hot_spot.h"
#include "refracta/media/index_field.h"
#include "refracta/media/logistic.h"
#include "refracta/media/turbulence.h"

#include <array>

namespace refracta {

// The fixed data of a LogisticProfile besides its parameters: its hot spots as made, whether the
// hot layer is off (the height-only part of a profile with spots: the hot term at its far value),
// and its turbulence (delta n added, in scene units).
struct LogisticConfig {
  std::vector<HotSpot> hot_spots;
  bool hot_layer_off = false;
  std::shared_ptr<const Turbulence> turbulence;
};

// The original mirage editor's height profile (Choi 2017), in scene units::
//
//     n(h) = 1 + 0.003 k_s (f(n_bg, 10 a_bg, 0, h) + f(n_inv, -0.1 a_inv, h_ciso, h)
//            + f(n_hot, 0.3 a_hot, 0, h)) / (|n_bg| + |n_inv| + |n_hot|)
//     f(L, w, x0, x) = L / (1 + e^((x0 - x) / w))
//
// Scaling n_bg, n_inv, n_hot together changes nothing (gauge freedom): editing fixes n_bg by
// default. hot_spots=[refracta.HotSpot(x, z, radius, strength), ...] localise the hot term: its
// deficit near the ground, n_hot * sigma(-h / (0.3 a_hot)), is scaled by sum_i dt_i F_i(r_i), so
// the hot layer lies only over the spots (parameters hot_spot<i>_x, _z, _radius, _dt).
template <class T>
class LogisticModel : public HeightOnlyModel<LogisticModel<T>, T> {
 public:
  using Config = LogisticConfig;
  static constexpr const char* kTypeName = "LogisticProfile";
  enum Index { kNBg, kNInv, kNHot, kHCiso, kABg, kAInv, kAHot, kKs, kCount };

  static std::vector<ParamSpec> param_specs(const Config& config) {
    std::vector<ParamSpec> specs = base_param_specs();
    const ParamSpec dt{"dt", 1.0, 0.0, 10.0, "1", "strength of the hot-spot term at the centre (1: the whole term)"};
    for (ParamSpec& spec : hot_spot_param_specs(config.hot_spots, false, dt)) specs.push_back(spec);
    return specs;
  }
  static constexpr bool kSpotsHaveDepth = false;  // whether a spot's depth is a parameter
  // The spots' search boxes are centred on their current values (hot_spot_param_specs).
  static Config config_at(Config config, const std::vector<double>& values) {
    config.hot_spots = hot_spots_from(config.hot_spots, values, kCount, kSpotsHaveDepth);
    return config;
  }
  static Config height_only_config(const Config& config) { return {{}, !config.hot_spots.empty(), nullptr}; }

  static std::vector<ParamSpec> base_param_specs() {
    return {
        {"n_bg", 3.0, -10.0, 10.0, "1", "background amplitude"},
        {"n_inv", 0.1, -10.0, 10.0, "1", "inversion-layer amplitude"},
        {"n_hot", 0.1, -10.0, 10.0, "1", "hot-spot amplitude"},
        {"h_ciso", 1.0, -10.0, 100.0, "scene units", "height of the inversion layer"},
        {"a_bg", 1.0, 1e-2, 100.0, "1", "background width (logistic width 10 a_bg)"},
        {"a_inv", 1.0, 1e-2, 100.0, "1", "inversion width (logistic width 0.1 a_inv)"},
        {"a_hot", 1.0, 1e-2, 100.0, "1", "hot-spot width (logistic width 0.3 a_hot)"},
        {"k_s", 10.0, -300.0, 300.0, "1", "overall strength: n - 1 reaches 0.003 k_s"},
    };
  }
  static std::vector<std::string> gauge_params() { return {"n_bg"}; }

  static void validate(const Config& config, const std::vector<double>& k) {
    validate_hot_spots(kTypeName, k, kCount, config.hot_spots.size(), false);
    // Widths from a micrometre: no air layer is thinner, and below that the gradient outruns
    // double precision (a_hot = 1e-300 gave 8e296 /m, and rk45 stepped through the layer).
    constexpr double kLeastWidth = 1e-6;
    const char* widths[] = {"a_bg", "a_inv", "a_hot"};
    for (int i = 0; i < 3; ++i) {
      if (!(k[kABg + i] >= kLeastWidth) || !std::isfinite(k[kABg + i])) {
        throw_invalid("LogisticProfile: ", widths[i], " must be >= ", kLeastWidth, " m and finite (got ", k[kABg + i], ")");
      }
    }
    if (std::abs(k[kNBg]) + std::abs(k[kNInv]) + std::abs(k[kNHot]) == 0.0) {
      throw_invalid("LogisticProfile: n_bg, n_inv and n_hot are all 0; at least one amplitude "
                    "must be non-zero");
    }
    // The normalised sum lies in [-1, 1], so n >= 1 - 0.003 |k_s| everywhere.
    if (!(0.003 * std::abs(k[kKs]) < 1.0)) {
      throw_invalid("LogisticProfile: |k_s| must be < 333.3 so that n stays > 0 (got ", k[kKs], ")");
    }
  }

  LogisticModel(const Config& config, const std::vector<T>& k)
      : spots_(config.hot_spots), hot_layer_off_(config.hot_layer_off), turbulence_(config.turbulence) {
    for (int i = 0; i < kCount; ++i) k_[i] = k[i];
    const int per = hot_spot_param_count(false);
    for (size_t i = 0; i < spots_.size(); ++i) {
      spot_values_.emplace_back(k.begin() + kCount + per * i, k.begin() + kCount + per * (i + 1));
    }
  }

  bool height_only() const { return spots_.empty() && !turbulence_; }

  void evaluate_height(const T& h, T* n, T* dn_dh) const {
    T sum, slope;
    background(h, &sum, &slope);
    if (hot_layer_off_) {
      sum += k_[kNHot];
    } else {
      add_step(k_[kNHot], hot_width(), T(0.0), h, &sum, &slope);
    }
    *n = T(1.0) + scale() * sum;
    *dn_dh = scale() * slope;
  }

  void evaluate(const Vec3<T>& p, T* n, Vec3<T>* grad) const {
    if (spots_.empty()) {
      HeightOnlyModel<LogisticModel<T>, T>::evaluate(p, n, grad);
    } else {
      evaluate_with_spots(p, n, grad);
    }
    if (turbulence_) {
      T dn;
      Vec3<T> dgrad;
      turbulence_->evaluate(p, &dn, &dgrad);
      *n += dn;
      *grad += dgrad;
    }
  }

  // Over each spot's reach, up to where sigma(-h/w) is negligible; the turbulence's slab.
  std::vector<LocalRegion> local_regions() const {
    std::vector<LocalRegion> regions;
    const double top = -std::log(kNegligibleFeature) * value_of(hot_width());
    for (size_t i = 0; i < spots_.size(); ++i) {
      HotSpot spot = spots_[i];
      spot.radius = value_of(spot_values_[i][2]);
      regions.push_back({value_of(spot_values_[i][0]), value_of(spot_values_[i][1]), spot.reach(), top, spot.radius});
    }
    if (turbulence_) regions.push_back(turbulence_->region());
    return regions;
  }

 private:
  void evaluate_with_spots(const Vec3<T>& p, T* n, Vec3<T>* grad) const {
    T sum, slope;
    background(p.y(), &sum, &slope);
    // S(x, z) and its gradient.
    T s(0.0), ds_dx(0.0), ds_dz(0.0);
    for (size_t i = 0; i < spots_.size(); ++i) {
      const std::vector<T>& v = spot_values_[i];
      T f, df_dx, df_dz;
      hot_spot_footprint(spots_[i].footprint, T(p.x() - v[0]), T(p.z() - v[1]), T(1.0) / v[2], &f, &df_dx, &df_dz);
      s += v[3] * f, ds_dx += v[3] * df_dx, ds_dz += v[3] * df_dz;
    }
    // n_hot (1 - S sigma(-h/w)): d/dh = n_hot S sigma'(-h/w) / w.
    const T w = hot_width(), z = -p.y() / w;
    const T sigma = logistic(z);
    sum += k_[kNHot] * (T(1.0) - s * sigma);
    slope += k_[kNHot] * s * logistic_slope(z) / w;
    *n = T(1.0) + scale() * sum;
    *grad = Vec3<T>(-scale() * k_[kNHot] * sigma * ds_dx, scale() * slope, -scale() * k_[kNHot] * sigma * ds_dz);
  }

  T scale() const {
    using std::abs;
    return T(0.003) * k_[kKs] / (abs(k_[kNBg]) + abs(k_[kNInv]) + abs(k_[kNHot]));
  }
  T hot_width() const { return T(0.3) * k_[kAHot]; }
  // The background and inversion steps and their slope.
  void background(const T& h, T* sum, T* slope) const {
    *sum = *slope = T(0.0);
    add_step(k_[kNBg], T(10.0) * k_[kABg], T(0.0), h, sum, slope);
    add_step(k_[kNInv], T(-0.1) * k_[kAInv], k_[kHCiso], h, sum, slope);
  }

  // f(L, w, x0, x) = L sigma((x - x0)/w) and its derivative in x.
  static void add_step(const T& amplitude, const T& width, const T& x0, const T& x, T* f,
                       T* df_dx) {
    const T z = (x - x0) / width;
    *f += amplitude * logistic(z);
    *df_dx += amplitude * logistic_slope(z) / width;
  }

  std::array<T, kCount> k_;
  std::vector<HotSpot> spots_;               // footprints (their numbers are in spot_values_)
  std::vector<std::vector<T>> spot_values_;  // x, z, radius, dt per spot
  bool hot_layer_off_ = false;
  std::shared_ptr<const Turbulence> turbulence_;
};

}  // namespace refracta
