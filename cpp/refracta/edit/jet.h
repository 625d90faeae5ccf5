// ceres::Jet as a refracta scalar: value_of() for Jets, so the scalar-templated fields and
// integrators run with automatic derivatives. Only the edit layer includes Ceres.
#pragma once

#include "refracta/core/math.h"

#include <ceres/jet.h>

namespace refracta {

template <int N>
struct ScalarValue<ceres::Jet<double, N>> {
  static double of(const ceres::Jet<double, N>& x) { return x.a; }
};

}  // namespace refracta
