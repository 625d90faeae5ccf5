// The turbulent ray as a deviation from the calm one (turbulence_path.h).
#include "refracta/media/turbulence_path.h"

namespace refracta {

CalmPoint calm_point(const IndexField& calm, const Vec3d& x, const Vec3d& t) {
  CalmPoint point;
  point.x = x;
  point.t = t;
  calm.evaluate_height(x.y(), &point.n, &point.dn_dh);
  return point;
}

void advance_deviation(const Turbulence& turbulence, const IndexField& calm, const CalmPoint& a, const CalmPoint& mid,
                         const CalmPoint& b, double step, RayDeviation* deviation) {
  RayDeviation& d = *deviation;
  const Vec3d half = d.dx + 0.5 * step * (d.tangent(a) - a.t);
  const Vec3d x = mid.x + half;
  double dn, n0, dn0;
  Vec3d grad;
  turbulence.evaluate(x, &dn, &grad);
  calm.evaluate_height(x.y(), &n0, &dn0);
  grad.y() += dn0 - mid.dn_dh;
  d.dv += step * grad;
  d.dx = half + 0.5 * step * (d.tangent(b) - b.t);
}

}  // namespace refracta
