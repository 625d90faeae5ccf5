// The quintic smooth step (C2, exactly 0 below and 1 above its interval) and its derivative.
#pragma once

#include "refracta/core/math.h"

namespace refracta {

// s(u) = 6u^5 - 15u^4 + 10u^3 on [0, 1], clamped outside.
template <class T>
void smoothstep5(const T& u, T* s, T* ds_du) {
  const double uv = value_of(u);
  if (uv <= 0.0) {
    *s = T(0.0);
    *ds_du = T(0.0);
  } else if (uv >= 1.0) {
    *s = T(1.0);
    *ds_du = T(0.0);
  } else {
    const T u2 = u * u;
    *s = u2 * u * (T(10.0) + u * (T(-15.0) + T(6.0) * u));
    *ds_du = T(30.0) * u2 * (u - T(1.0)) * (u - T(1.0));
  }
}

}  // namespace refracta
