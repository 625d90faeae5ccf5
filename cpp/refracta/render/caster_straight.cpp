// Straight continuation above the bending air (caster.h: Caster::straight_rest, IorFloors::Gradients).
//
// A ray's direction t turns along its path at the rate dt/ds = grad_perp ln n (the ray equation
// d(n t)/ds = grad n, less its part along t), so between arc lengths 0 and l
//   |t(l) - t(0)|  <=  integral_0^l |grad_perp ln n| ds  <=  K l,
// with K a bound of |grad ln n| = |dn/dh| / n (height-only air) over the heights the path visits.
// The path leaves the straight line x(0) + l t(0) by at most
//   |x(l) - x(0) - l t(0)|  <=  integral_0^l |t(u) - t(0)| du  <=  K l^2 / 2.
// Where that stays within the path's tolerance over the rest of its length L -- a quarter of the
// pixel's footprint, sagitta_pixels * spread * (s0 + s + l) at arc length s + l of the cast (shadow
// rays: the camera's pixel, set_secondary_spread; s0: their cone's width where they start, over
// spread: Caster::cast's origin_width), at least options.sagitta -- the rest of the
// path is that line: K L^2 / 2 <= tol(L) suffices for every l <= L (K l^2 / 2 - tol(l) is convex
// and <= 0 at both ends). The heights visited are the line's, widened by the tolerance itself: a
// path that has not yet strayed by tol stays within those heights, where K holds, so it never
// strays by tol (the bound is its own support). A shadow ray toward a 35-degree sun from a
// hillside 1 km up meets no more than the standard atmosphere's |dn/dh| / n ~ 2.7e-8 / m: over
// 1.4 km to the hill tops it strays 3 cm, against a quarter pixel's 0.38 m (a 1.1 mrad pixel).
//
// The end's direction: where |e| of the line exceeds the turn K L, the path keeps the sign of its
// elevation and Bouguer's invariant n(h) cos e = n(h0) cos e0 gives it exactly at the line's end
// height, off the path's by at most K L^2 / 2: an elevation error of K (K L^2 / 2) / tan e_least
// (d e / dh = cos e (dn/dh) / (n sin e)); otherwise the line's own direction, off by K L. Either
// must be within sagitta_pixels * spread [rad] (escape_direction's quarter pixel), since the end
// may be the sky.
#include "refracta/render/caster.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

namespace refracta {

namespace {

// How far an interval's bound is widened beyond the largest slope sampled at its ends or across
// it: samples are at most 0.1 % of the height apart (1 mm near the ground), where a smooth
// profile's dn/dh changes by a fraction of a percent; 25 % covers that many times over.
constexpr double kGradientMargin = 1.25;

}  // namespace

std::shared_ptr<const IorFloors::Gradients> gradient_bound(const HeightSamples& samples) {
  auto out = std::make_shared<IorFloors::Gradients>();
  out->heights = samples.heights;
  std::vector<double> n_at, slope;  // n and |dn/dh| / n at each height (inf: not evaluable)
  const double inf = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < samples.heights.size(); ++i) {
    const double n = samples.n[i], dn = samples.dn[i];
    const bool usable = n > 0.0 && std::isfinite(n) && std::isfinite(dn);  // outside the modelled air: no bound there
    n_at.push_back(usable ? n : inf);
    slope.push_back(usable ? std::abs(dn) / n : inf);
  }
  if (out->heights.empty()) return nullptr;
  const size_t intervals = out->heights.size() - 1;
  if (intervals == 0) return nullptr;
  std::vector<double> level(intervals);
  for (size_t i = 0; i < intervals; ++i) {
    const double gap = out->heights[i + 1] - out->heights[i];
    const double secant = std::abs(n_at[i + 1] - n_at[i]) / (gap * std::min(n_at[i], n_at[i + 1]));
    const double most = std::max({slope[i], slope[i + 1], std::isfinite(secant) ? secant : inf});
    level[i] = kGradientMargin * most;
  }
  // A sparse table: the largest bound over any run of 2^k intervals, for ranges in two lookups.
  out->most.push_back(std::move(level));
  for (size_t width = 2; width <= intervals; width *= 2) {
    const std::vector<double>& below = out->most.back();
    std::vector<double> next(intervals - width + 1);
    for (size_t i = 0; i < next.size(); ++i) next[i] = std::max(below[i], below[i + width / 2]);
    out->most.push_back(std::move(next));
  }
  out->sum_up();
  return out;
}

void IorFloors::Gradients::sum_up() {
  climbed.assign(heights.size(), 0.0);
  for (size_t i = 0; i + 1 < heights.size(); ++i) climbed[i + 1] = climbed[i] + most[0][i] * (heights[i + 1] - heights[i]);
}

bool IorFloors::Gradients::climbed_around(double h, double* below, double* above) const {
  if (!(h >= heights.front()) || !(h <= heights.back())) return false;
  const size_t at = size_t(std::lower_bound(heights.begin(), heights.end(), h) - heights.begin());
  *above = climbed[at];
  *below = heights[at] == h ? climbed[at] : climbed[at - 1];
  return true;
}

double IorFloors::Gradients::steepest(double lo, double hi) const {
  if (!(lo >= heights.front()) || !(hi <= heights.back()) || !(lo <= hi)) return std::numeric_limits<double>::infinity();
  const size_t last = heights.size() - 2;  // the last interval
  // The intervals that meet [lo, hi]: from the one holding lo to the one holding hi.
  const auto upper = std::upper_bound(heights.begin(), heights.end(), lo);
  const size_t first = std::min(size_t(std::max<std::ptrdiff_t>(upper - heights.begin() - 1, 0)), last);
  const auto lower = std::lower_bound(heights.begin(), heights.end(), hi);
  const size_t end = std::clamp(size_t(std::max<std::ptrdiff_t>(lower - heights.begin() - 1, 0)), first, last);
  const size_t count = end - first + 1;
  size_t k = 0;
  while ((size_t(2) << k) <= count) ++k;
  return std::max(most[k][first], most[k][end + 1 - (size_t(1) << k)]);
}

bool Caster::straight_rest(const Vec3d& x, const Vec3d& v, double s, double remaining, double bottom, double spread,
                           PathEnd* end, double s0) const {
  if (!layered_ || !floors_ || !floors_->gradients || !(remaining > 0.0)) return false;
  const Vec3d t = v.normalized();
  // The rest of the path, or down to the stop height, where a traced path ends.
  double length = remaining;
  if (t.y() < 0.0) length = std::min(length, (x.y() - bottom) / -t.y());
  if (!(length > 0.0)) return false;
  const double per_metre = options_.sagitta_pixels * spread;  // [m per m of path], and [rad]
  const double tolerance = std::max(options_.sagitta, per_metre * (s0 + s + length));
  const double h_end = x.y() + length * t.y();
  // The slope where the path is bounds the bend from below: where even it strays too far, no
  // look-up over the heights can make the line do (over a curved Earth the flat frame's
  // n' = n e^(y/R) bends paths by about 1/R: 1.3e-7 / m above the cold sea's inversion, where a
  // shadow ray with 40 km to go would stray 100 m against its 1.5 m).
  double n0, dn0;
  layered_->evaluate_height(x.y(), &n0, &dn0);
  if (!(0.5 * std::abs(dn0) / n0 * length * length <= tolerance)) return false;
  const double bend =
      floors_->gradients->steepest(std::min(x.y(), h_end) - tolerance, std::max(x.y(), h_end) + tolerance);
  const double stray = 0.5 * bend * length * length;
  if (!(stray <= tolerance)) return false;
  const double turn = bend * length;
  const double elevation = std::asin(std::clamp(t.y(), -1.0, 1.0));
  const bool keeps_sign = std::abs(elevation) > turn;
  const double direction_error = keeps_sign ? bend * stray / std::tan(std::abs(elevation) - turn) : turn;
  if (!(direction_error <= per_metre)) return false;
  if (legs_ && first_entry(regions_, x, t, length)) return false;  // a region bends it: cast in legs
  // Bouguer's invariant: the direction at height h, the sign of the elevation kept.
  const double cos_e0 = std::sqrt(t.x() * t.x() + t.z() * t.z());
  const Vec3d across = cos_e0 > 0.0 ? Vec3d(t.x() / cos_e0, 0.0, t.z() / cos_e0) : Vec3d(1.0, 0.0, 0.0);
  auto direction_at = [&](double h) -> Vec3d {
    if (!keeps_sign) return t;
    double n, dn;
    layered_->evaluate_height(h, &n, &dn);
    const double cos_e = std::min(n0 * cos_e0 / n, 1.0);
    const double sin_e = std::copysign(std::sqrt((1.0 - cos_e) * (1.0 + cos_e)), t.y());
    return (cos_e * across + Vec3d(0.0, sin_e, 0.0)).normalized();
  };
  // Tested against the scene up to where the line, and the path within `tolerance` of it, has
  // risen above every object.
  double reach = length;
  if (t.y() > 0.0) reach = std::min(length, std::max(0.0, (ceiling_ + tolerance - x.y()) / t.y()));
  const int chords = reach > 0.0 ? int(std::ceil(reach / options_.chord)) : 0;
  for (int i = 0; i < chords; ++i) {
    const double a = reach * i / chords, b = reach * (i + 1) / chords;
    const Vec3d p = x + a * t;
    if (chord_blocked(p, t, b - a, Handoff{p, t, s + a}, end, /*regions=*/false)) {
      end->direction = direction_at(end->hit->point.y());
      end->length = s + a + std::min(end->hit->t, b - a);
      return true;
    }
  }
  end->end_point = x + length * t;
  end->direction = direction_at(h_end);
  end->length = s + length;
  return true;
}

}  // namespace refracta
