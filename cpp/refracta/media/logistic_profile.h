// LogisticProfile: the original mirage editor's 8-parameter height profile (Choi 2017, the
// refractive-index-editor's TestModel), in scene units. A background, an inversion layer and a hot
// spot, each a logistic step:
//   n(h) = 1 + 0.003 k_s (f(n_bg, 10 a_bg, 0, h) + f(n_inv, -0.1 a_inv, h_ciso, h)
//                         + f(n_hot, 0.3 a_hot, 0, h)) / (|n_bg| + |n_inv| + |n_hot|),
//   f(L, w, x0, x) = L / (1 + e^((x0 - x)/w)).
// Gauge freedom: scaling (n_bg, n_inv, n_hot) together changes nothing (the normaliser divides it
// out), so an optimiser must hold one amplitude fixed: gauge_params() names n_bg.
#pragma once

#include "refracta/core/error.h"
#include "refracta/media/index_field.h"
#include "refracta/media/logistic.h"

#include <array>

namespace refracta {

template <class T>
class LogisticModel : public HeightOnlyModel<LogisticModel<T>, T> {
 public:
  using Config = NoConfig;
  static constexpr const char* kTypeName = "LogisticProfile";
  enum Index { kNBg, kNInv, kNHot, kHCiso, kABg, kAInv, kAHot, kKs, kCount };

  static std::vector<ParamSpec> param_specs(const Config&) {
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

  static void validate(const Config&, const std::vector<double>& k) {
    const char* widths[] = {"a_bg", "a_inv", "a_hot"};
    for (int i = 0; i < 3; ++i) {
      if (!(k[kABg + i] > 0.0)) {
        throw_invalid("LogisticProfile: ", widths[i], " must be > 0 (got ", k[kABg + i], ")");
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

  LogisticModel(const Config&, const std::vector<T>& k) {
    for (int i = 0; i < kCount; ++i) k_[i] = k[i];
  }

  void evaluate_height(const T& h, T* n, T* dn_dh) const {
    using std::abs;
    const T scale = T(0.003) * k_[kKs] / (abs(k_[kNBg]) + abs(k_[kNInv]) + abs(k_[kNHot]));
    T sum(0.0), slope(0.0);
    add_step(k_[kNBg], T(10.0) * k_[kABg], T(0.0), h, &sum, &slope);
    add_step(k_[kNInv], T(-0.1) * k_[kAInv], k_[kHCiso], h, &sum, &slope);
    add_step(k_[kNHot], T(0.3) * k_[kAHot], T(0.0), h, &sum, &slope);
    *n = T(1.0) + scale * sum;
    *dn_dh = scale * slope;
  }

 private:
  // f(L, w, x0, x) = L sigma((x - x0)/w) and its derivative in x.
  static void add_step(const T& amplitude, const T& width, const T& x0, const T& x, T* f,
                       T* df_dx) {
    const T z = (x - x0) / width;
    *f += amplitude * logistic(z);
    *df_dx += amplitude * logistic_slope(z) / width;
  }

  std::array<T, kCount> k_;
};

}  // namespace refracta
