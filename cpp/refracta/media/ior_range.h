// The refractive indices the ray integrators accept. Every medium has n of order 1 (air 1.0003,
// water 1.33, diamond 2.42; metamaterials reach a few tens); outside [kMinIor, kMaxIor] the ray
// equations' n^3 and n^2 - beta^2 over- or underflow in double long before n itself does
// (n = 1e-300 gave NaN points, n = 1e300 an endless stratified trace), so such n is an error.
#pragma once

#include <cmath>

namespace refracta {

constexpr double kMinIor = 1e-50, kMaxIor = 1e50;

// n finite and within [kMinIor, kMaxIor].
inline bool usable_ior(double n) { return std::isfinite(n) && n >= kMinIor && n <= kMaxIor; }

}  // namespace refracta
