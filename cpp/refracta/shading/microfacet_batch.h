// Microfacet distributions (microfacet.h, beckmann.h) over many directions at once: what
// refracta.shading's Beckmann and TrowbridgeReitz expose (directions: unit vectors in the local
// frame, a row each).
#pragma once

#include "refracta/shading/batch.h"
#include "refracta/shading/microfacet.h"

namespace refracta {

// D(m), G1(w) and the height-correlated G(wo, wi) at each row (wo or wi may be one row).
template <class Distribution>
Eigen::VectorXd microfacet_D(const Distribution& d, const std::vector<Vec3d>& m) {
  return at_each(m, [&](const Vec3d& v) { return d.D(v); });
}
template <class Distribution>
Eigen::VectorXd microfacet_G1(const Distribution& d, const std::vector<Vec3d>& w) {
  return at_each(w, [&](const Vec3d& v) { return d.G1(v); });
}
template <class Distribution>
Eigen::VectorXd microfacet_G(const Distribution& d, const std::vector<Vec3d>& wo, const std::vector<Vec3d>& wi) {
  return at_each_pair(wo, wi, "wo and wi", [&](const Vec3d& o, const Vec3d& i) { return d.G(o, i); });
}

// The visible-normal density D_w(m) at each (w, m) row pair (either may be one row).
inline Eigen::VectorXd visible_normal_density(const TrowbridgeReitz& d, const std::vector<Vec3d>& w,
                                              const std::vector<Vec3d>& m) {
  return at_each_pair(w, m, "w and m", [&](const Vec3d& a, const Vec3d& b) { return d.D_visible(a, b); });
}

// A visible normal sampled for each w from each row (u1, u2) of u (either may be one row): (N, 3).
inline RowMatrixX3d sample_visible_normals(const TrowbridgeReitz& d, const std::vector<Vec3d>& w,
                                           const RowMatrixXd& u) {
  if (u.cols() != 2) throw_invalid("u must have shape (N, 2) (got ", u.cols(), " columns)");
  RowMatrixX3d out(broadcast(w.size(), size_t(u.rows()), "w and u"), 3);
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    const Eigen::Index row = u.rows() == 1 ? 0 : i;
    out.row(i) = d.sample_wm(w[w.size() == 1 ? 0 : size_t(i)], Vec2d(u(row, 0), u(row, 1))).transpose();
  }
  return out;
}

}  // namespace refracta
