// Logistic (sigmoid) helpers that cannot overflow for any argument, for double and Jets.
#pragma once

#include "refracta/core/math.h"

#include <cmath>

namespace refracta {

// sigma(z) = 1 / (1 + e^-z), evaluated on the side where the exponential is <= 1.
template <class T>
T logistic(const T& z) {
  using std::exp;
  if (value_of(z) >= 0.0) return T(1.0) / (T(1.0) + exp(-z));
  const T e = exp(z);
  return e / (T(1.0) + e);
}

// sigma'(z) = sigma(z)(1 - sigma(z)) = e^-|z| / (1 + e^-|z|)^2, without cancellation.
template <class T>
T logistic_slope(const T& z) {
  using std::exp;
  const T e = value_of(z) >= 0.0 ? exp(-z) : exp(z);
  const T one_plus = T(1.0) + e;
  return e / (one_plus * one_plus);
}

}  // namespace refracta
