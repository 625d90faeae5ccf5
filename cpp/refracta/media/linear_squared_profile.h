// LinearSquaredProfile: n^2 = n0^2 + alpha y, the textbook field whose rays are parabolas
// (ORACLES.md: y(x) = y0 + t0 x + alpha x^2 / (4 beta^2)). Undefined (n^2 <= 0) where
// n0^2 + alpha y <= 0; a ray reaching there raises NumericalError.
#pragma once

#include "refracta/core/error.h"
#include "refracta/media/index_field.h"

namespace refracta {

// n^2 = n0^2 + alpha y: rays are parabolas y = y0 + t0 x + alpha x^2 / (4 beta^2), beta = n(y0)
// cos(e0).
template <class T>
class LinearSquaredModel : public HeightOnlyModel<LinearSquaredModel<T>, T> {
 public:
  using Config = NoConfig;
  static constexpr const char* kTypeName = "LinearSquaredProfile";

  static std::vector<ParamSpec> param_specs(const Config&) {
    return {
        {"n0", 1.000277, 0.5, 3.0, "1", "index at y = 0"},
        {"alpha", 0.0, -1e-3, 1e-3, "1/m", "d(n^2)/dy"},
    };
  }
  static std::vector<std::string> gauge_params() { return {}; }
  static void validate(const Config&, const std::vector<double>& v) {
    if (!(v[0] > 0.0)) throw_invalid("LinearSquaredProfile: n0 must be > 0 (got ", v[0], ")");
  }

  LinearSquaredModel(const Config&, const std::vector<T>& v) : n0_(v[0]), alpha_(v[1]) {}

  void evaluate_height(const T& h, T* n, T* dn_dh) const {
    using std::sqrt;
    const T n_squared = n0_ * n0_ + alpha_ * h;
    *n = value_of(n_squared) > 0.0 ? T(sqrt(n_squared)) : T(std::numeric_limits<double>::quiet_NaN());
    *dn_dh = alpha_ / (T(2.0) * *n);
  }

 private:
  T n0_, alpha_;
};

}  // namespace refracta
