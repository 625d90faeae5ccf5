// The turbulent ray as a deviation from the calm one (turbulence_path.h).
#include "refracta/media/turbulence_path.h"

#include <cmath>

namespace refracta {

namespace {

constexpr int kTableNodes = 4096;  // per table (turbulence_path.h: interpolation error ~1e-7)

}  // namespace

DeviationStepper::DeviationStepper(const Turbulence& turbulence, const IndexField& calm, double lo, double hi,
                                   const IndexField* spotted)
    : turbulence_(turbulence), calm_(calm), spotted_(spotted), lo_(lo), per_metre_(0.0) {
  // A layer without an envelope (no top): the field itself at every height.
  if (std::isfinite(hi) && hi > lo) {
    per_metre_ = (kTableNodes - 1) / (hi - lo);
    n_.resize(kTableNodes);
    dn_.resize(kTableNodes);
    for (int k = 0; k < kTableNodes; ++k) calm.evaluate_height(lo + k / per_metre_, &n_[size_t(k)], &dn_[size_t(k)]);
  }
  if (std::isfinite(turbulence.depth)) {
    envelope_top_ = turbulence.region().top;
    envelope_per_metre_ = (kTableNodes - 1) / envelope_top_;
    envelope_.resize(kTableNodes);
    for (int k = 0; k < kTableNodes; ++k) {
      envelope_[size_t(k)] = std::exp(-(k / envelope_per_metre_) / turbulence.depth);
    }
  }
}

void DeviationStepper::calm_at(const Vec3d& p, double* n, Vec3d* grad) const {
  if (spotted_) {
    spotted_->evaluate(p, n, grad);
    return;
  }
  *grad = Vec3d::Zero();
  const double u = (p.y() - lo_) * per_metre_;
  if (n_.empty() || !(u >= 0.0 && u < kTableNodes - 1)) {
    calm_.evaluate_height(p.y(), n, &grad->y());
    return;
  }
  const size_t k = size_t(u);
  const double f = u - double(k);
  *n = n_[k] + f * (n_[k + 1] - n_[k]);
  grad->y() = dn_[k] + f * (dn_[k + 1] - dn_[k]);
}

CalmPoint DeviationStepper::calm_point(const Vec3d& x, const Vec3d& t) const {
  CalmPoint point;
  point.x = x;
  point.t = t;
  calm_at(x, &point.n, &point.grad);
  return point;
}

Vec3d DeviationStepper::gradient(const Vec3d& p) const {
  const Turbulence& w = turbulence_;
  const double u = p.y() * envelope_per_metre_;
  if (envelope_.empty() || !(u >= 0.0 && u < kTableNodes - 1)) {  // no envelope, below the ground or above the table
    double dn;
    Vec3d grad;
    w.evaluate(p, &dn, &grad);
    return grad;
  }
  const double c = w.cos_yaw, s = w.sin_yaw;
  double b;
  Vec3d g;
  w.grid->evaluate(w.lattice_point(p), &b, &g);
  const size_t k = size_t(u);
  const double e = envelope_[k] + (u - double(k)) * (envelope_[k + 1] - envelope_[k]);
  const double de_dh = -e / w.depth;
  return Vec3d(w.scale * (c * g.x() - s * g.z()) * e, w.scale * (de_dh * b + e * g.y()),
               w.scale * (s * g.x() + c * g.z()) * e);
}

void DeviationStepper::advance(const CalmPoint& a, const CalmPoint& mid, const CalmPoint& b, double step,
                               RayDeviation* deviation) const {
  RayDeviation& d = *deviation;
  const Vec3d half = d.dx + 0.5 * step * (d.tangent(a) - a.t);
  const Vec3d x = mid.x + half;
  double n0;
  Vec3d calm_grad;
  calm_at(x, &n0, &calm_grad);
  d.dv += step * (gradient(x) + (calm_grad - mid.grad));
  d.dx = half + 0.5 * step * (d.tangent(b) - b.t);
}

}  // namespace refracta
