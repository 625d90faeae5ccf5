// A ray through turbulent air followed as its deviation from the calm ray (issue 21): the air is
// a height-only calm part n0(h) plus a turbulence layer delta_n(x) (turbulence.h); the calm ray
// x0(s), v0(s) (v = n t) is known (the eye's ElevationTable), and the turbulent ray is
//   x(s) = x0(s) + dx(s),  v(s) = v0(s) + dv(s),
// the ray equations dx/ds = v/|v|, dv/ds = grad n (Born & Wolf ch. 3.2) becoming
//   d(dx)/ds = t(v0 + dv) - t0,
//   d(dv)/ds = grad delta_n(x0 + dx) + [n0'(y0 + dy) - n0'(y0)] y^,
// where t(v) = v / |v|. Nothing is linearised: the turbulence is evaluated where the ray is, not
// on the calm path, and the calm air's pull on the deviation is its gradient's difference. What
// makes it cheap is the step: the calm path's strong bending (a mirage's) is in x0, so the
// deviation needs steps only as fine as the turbulence's cells, with one evaluation each, where
// the full ray under rk45's error control through the same air takes many more (bench_realism).
// To first order (a weak perturbation) dv(s) is the transverse gradient integrated along the calm
// path -- the geometric-optics angle of arrival whose variance Tatarskii gives ("Wave Propagation
// in a Turbulent Medium", 1961, ch. 6; Andrews & Phillips 2005 ch. 6) -- and dx its lever arm's
// integral.
#pragma once

#include "refracta/core/math.h"
#include "refracta/media/index_field.h"
#include "refracta/media/turbulence.h"

#include <vector>

namespace refracta {

// The calm ray at one arc length: position, unit tangent, n0 and its gradient there (a height-only
// calm air's: (0, dn0/dh, 0)).
struct CalmPoint {
  Vec3d x = Vec3d::Zero();
  Vec3d t = Vec3d::UnitX();
  double n = 1.0;
  Vec3d grad = Vec3d::Zero();
};

// The turbulent ray's offset from the calm ray.
struct RayDeviation {
  Vec3d dx = Vec3d::Zero();  // x - x0 [m]
  Vec3d dv = Vec3d::Zero();  // v - v0 (v = n t)

  // The turbulent ray's unit tangent where the calm ray is at `at`.
  Vec3d tangent(const CalmPoint& at) const { return (at.n * at.t + dv).normalized(); }
};

// What one step of the deviation evaluates, tabulated once per render: the calm air's n0 and
// dn0/dh over the layer's heights, and the turbulence's envelope. Both are smooth on the layer's
// depth (centimetres), so linear interpolation at kTableStep / depth is exact to ~(1/4096)^2 / 8,
// 1e-7 of the values: far below the deviation's own terms (the calm pull n0'' dy and the
// turbulence's gradient). Outside the tabulated heights: the field and the envelope's formula.
//
// Calm air that is not height-only (hot spots over layered air: `spotted`, whose height-only part
// is `calm`) is evaluated where the ray is, not tabulated: its pull on the deviation is then
// grad n0(x0 + dx) - grad n0(x0), sideways too.
class DeviationStepper {
 public:
  // `calm` height-only; heights [lo, hi] tabulated. `spotted` (if given): the calm air itself,
  // `calm` its height-only part.
  DeviationStepper(const Turbulence& turbulence, const IndexField& calm, double lo, double hi,
                   const IndexField* spotted = nullptr);

  // The calm point of the calm field at x along unit t.
  CalmPoint calm_point(const Vec3d& x, const Vec3d& t) const;
  // n0 and its gradient at p.
  void calm_at(const Vec3d& p, double* n, Vec3d* grad) const;
  // The turbulence's delta_n gradient at p (Turbulence::evaluate's, the envelope tabulated).
  Vec3d gradient(const Vec3d& p) const;

  // One step of `step` [m] of arc length (position Verlet: drift half, kick, drift half; one
  // evaluation of the turbulence and one of the calm air's height profile), from calm point a over
  // mid to b (b's n: mid's).
  void advance(const CalmPoint& a, const CalmPoint& mid, const CalmPoint& b, double step,
               RayDeviation* deviation) const;

 private:
  const Turbulence& turbulence_;
  const IndexField& calm_;
  const IndexField* spotted_;
  double lo_, per_metre_;           // calm table: heights lo + k / per_metre_
  std::vector<double> n_, dn_;      // n0, dn0/dh there
  double envelope_per_metre_ = 0.0; // envelope table over [0, envelope_top_]
  double envelope_top_ = 0.0;
  std::vector<double> envelope_;
};

}  // namespace refracta
