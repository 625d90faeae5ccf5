// A hydrostatic column's pressure and temperature near the ground, tabulated on a uniform grid of
// heights for the fields that evaluate them at every step of a 3-D trace (hot spots, turbulence):
// there the column's own evaluation -- its temperature profile's exponentials, a search of the
// pressure integral's nodes and an exponential of it -- was a fifth of a hot-spot render (perf, the
// compact spot at 1280 x 720). Cubic Hermite with the exact slopes at the nodes: with the spacing a
// 128th of the finest scale tabulated (the surface layer's e-folding depth d), the value's error is
// (d/128)^4/384 |T''''| ~ 1e-11 dT for the layer dT e^(-h/d): a few ulp of n for dT up to 60 K; the
// slope's ~4e-9 of the layer's own (3e-13 1/m in dn/dh at 10 K: rays bend the same to far below any
// tracing tolerance). P and T are read as the interpolants and their slopes as the interpolants'
// derivatives, so that each stays consistent with its slope within the table.
#pragma once

#include <cmath>
#include <vector>

namespace refracta {

class ColumnTable {
 public:
  ColumnTable() = default;

  // state(h, &p, &dp_dh, &t, &dt_dh) gives the exact column at h; the table spans [lo, hi] [m] with
  // nodes `spacing` apart, one of them at h = 0 (where a surface layer's T'' jumps).
  template <class State>
  ColumnTable(double lo, double hi, double spacing, const State& state) {
    const long below = long(std::ceil(-lo / spacing)), above = long(std::ceil(hi / spacing));
    lo_ = -double(below) * spacing;
    spacing_ = spacing;
    per_metre_ = 1.0 / spacing;
    nodes_.resize(size_t(below + above + 1));
    for (size_t k = 0; k < nodes_.size(); ++k) {
      Node& node = nodes_[k];
      state(lo_ + double(k) * spacing, &node.p, &node.dp_dh, &node.t, &node.dt_dh);
    }
  }

  bool covers(double h) const {
    const double u = (h - lo_) * per_metre_;
    return u >= 0.0 && u < double(nodes_.size()) - 1.0;
  }

  // P [Pa], dP/dh [Pa/m], T [K] and dT/dh [K/m] at h (covers(h)).
  void at(double h, double* p, double* dp_dh, double* t, double* dt_dh) const {
    const double u = (h - lo_) * per_metre_;
    const size_t k = size_t(u);
    const double f = u - double(k), f2 = f * f, f3 = f2 * f;
    const Node& a = nodes_[k];
    const Node& b = nodes_[k + 1];
    const double h00 = 2.0 * f3 - 3.0 * f2 + 1.0, h10 = f3 - 2.0 * f2 + f, h01 = 3.0 * f2 - 2.0 * f3, h11 = f3 - f2;
    *p = h00 * a.p + h10 * spacing_ * a.dp_dh + h01 * b.p + h11 * spacing_ * b.dp_dh;
    *t = h00 * a.t + h10 * spacing_ * a.dt_dh + h01 * b.t + h11 * spacing_ * b.dt_dh;
    // The derivatives of the Hermite basis in u, over the spacing.
    const double d00 = 6.0 * f2 - 6.0 * f, d10 = 3.0 * f2 - 4.0 * f + 1.0, d11 = 3.0 * f2 - 2.0 * f;
    *dp_dh = d00 * (a.p - b.p) * per_metre_ + d10 * a.dp_dh + d11 * b.dp_dh;
    *dt_dh = d00 * (a.t - b.t) * per_metre_ + d10 * a.dt_dh + d11 * b.dt_dh;
  }

 private:
  struct Node {
    double p, dp_dh, t, dt_dh;
  };
  std::vector<Node> nodes_;
  double lo_ = 0.0, spacing_ = 1.0, per_metre_ = 1.0;
};

}  // namespace refracta
