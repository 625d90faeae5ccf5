// What the batch functions of the shading library share (spectrum_batch.h, material_batch.h,
// microfacet_batch.h): row-major matrices (a row per colour, direction or sample, as numpy lays
// them out), row-count broadcasting, and a function evaluated per row.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/math.h"

#include <vector>

namespace refracta {

using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using RowMatrixX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMatrixX4d = Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor>;

// Row counts a and b broadcast (one of them may be 1); std::invalid_argument naming `what` otherwise.
inline size_t broadcast(size_t a, size_t b, const char* what) {
  if (a == b || b == 1) return a;
  if (a == 1) return b;
  throw_invalid(what, ": row counts differ (", a, " and ", b, ")");
}

// f at each row of a: (N,).
template <class T, class F>
Eigen::VectorXd at_each(const std::vector<T>& a, const F& f) {
  Eigen::VectorXd out(a.size());
  for (size_t i = 0; i < a.size(); ++i) out[i] = f(a[i]);
  return out;
}

// f at each pair of rows of a and b, one of them possibly a single row (broadcast); `what` names
// them in the error.
template <class A, class B, class F>
Eigen::VectorXd at_each_pair(const std::vector<A>& a, const std::vector<B>& b, const char* what, const F& f) {
  Eigen::VectorXd out(broadcast(a.size(), b.size(), what));
  for (Eigen::Index i = 0; i < out.size(); ++i) out[i] = f(a[a.size() == 1 ? 0 : i], b[b.size() == 1 ? 0 : i]);
  return out;
}

}  // namespace refracta
