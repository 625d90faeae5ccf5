// Tabulated height-only fields (tabulated_height_field.h).
#include "refracta/media/tabulated_height_field.h"

#include "refracta/core/error.h"
#include "refracta/media/dispersed_field.h"

#include <algorithm>
#include <cmath>
#include <exception>

namespace refracta {

namespace {

// Initial intervals of at most a metre (features thinner than the quarter-point checks can see
// are only resolved where refinement already goes), between 64 and 1e5 of them.
constexpr double kInitialSpacing = 1.0;  // [m]
constexpr int kMinInitialIntervals = 64, kMaxInitialIntervals = 100000;
constexpr int kMaxDepth = 40;          // below ~1e-8 of the range: a kink, accept it
constexpr size_t kMaxNodes = 1 << 20;  // 16 MB at most

bool evaluable(const IndexField& field, double h) {
  double n, dn;
  try {
    field.evaluate_height(h, &n, &dn);
  } catch (const std::exception&) {
    return false;
  }
  return n > 0.0 && std::isfinite(n) && std::isfinite(dn);
}

// The end of [from, to] nearest `to` that the field still evaluates, by bisection (from must be one).
double evaluable_end(const IndexField& field, double from, double to) {
  if (evaluable(field, to)) return to;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (from + to);
    (evaluable(field, mid) ? from : to) = mid;
  }
  return from;
}

}  // namespace

TabulatedHeightField::TabulatedHeightField(FieldPtr base, double lo, double hi, double tolerance)
    : base_(std::move(base)), tolerance_(tolerance) {
  if (!base_ || !base_->height_only()) throw_invalid("TabulatedHeightField: the base must be a height-only field");
  if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi)) {
    throw_invalid("TabulatedHeightField: need lo < hi, both finite (got ", lo, ", ", hi, ")");
  }
  if (!(tolerance > 0.0)) throw_invalid("TabulatedHeightField: tolerance must be > 0 (got ", tolerance, ")");
  // The part of [lo, hi] the base models (an atmosphere ends somewhere).
  double start = lo;
  if (!evaluable(*base_, start)) {
    start = evaluable(*base_, 0.0) ? evaluable_end(*base_, 0.0, lo) : hi;
  }
  lo_ = start;
  hi_ = lo_ < hi ? evaluable_end(*base_, lo_, hi) : lo_;
  if (!(hi_ > lo_)) return;  // nothing tabulated: every height is the base's
  Sample previous = base_at(lo_);
  h_.push_back(lo_);
  samples_.push_back(previous);
  const int intervals = int(std::clamp(std::ceil((hi_ - lo_) / kInitialSpacing), double(kMinInitialIntervals),
                                       double(kMaxInitialIntervals)));
  for (int i = 1; i <= intervals; ++i) {
    const double b = lo_ + (hi_ - lo_) * i / intervals;
    const Sample sb = base_at(b);
    refine(h_.back(), previous, b, sb, 0);
    previous = sb;
  }
  cubics_.resize(h_.size() - 1);
  for (size_t k = 0; k + 1 < h_.size(); ++k) {
    const double width = h_[k + 1] - h_[k];
    const Sample &a = samples_[k], &b = samples_[k + 1];
    const double da = width * a.dn, db = width * b.dn, jump = b.n - a.n;
    cubics_[k] = {a.n, da, 3.0 * jump - 2.0 * da - db, -2.0 * jump + da + db, 1.0 / width};
  }
  // Buckets of equal width, 16 per node: nodes crowd into thin layers (centimetres apart in a
  // hot layer, metres elsewhere), and a bucket should hold only a few of them.
  const size_t buckets = std::clamp<size_t>(16 * h_.size(), 1, size_t(1) << 22);  // at most 16 MB
  bucket_width_ = (hi_ - lo_) / double(buckets);
  bucket_.resize(buckets + 1);
  size_t i = 0;
  for (size_t k = 0; k <= buckets; ++k) {
    const double at = lo_ + k * bucket_width_;
    while (i + 2 < h_.size() && h_[i + 1] <= at) ++i;
    bucket_[k] = uint32_t(i);
  }
}

TabulatedHeightField::Sample TabulatedHeightField::base_at(double h) const {
  Sample s;
  base_->evaluate_height(h, &s.n, &s.dn);
  return s;
}

// Appends the nodes after a up to and including b.
void TabulatedHeightField::refine(double a, const Sample& sa, double b, const Sample& sb, int depth) {
  const double width = b - a;
  auto hermite = [&](double t) {
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * sa.n + (t3 - 2 * t2 + t) * width * sa.dn + (-2 * t3 + 3 * t2) * sb.n +
           (t3 - t2) * width * sb.dn;
  };
  bool close = depth >= kMaxDepth || h_.size() >= kMaxNodes;
  Sample mid{};
  if (!close) {
    mid = base_at(a + 0.5 * width);
    close = std::abs(hermite(0.5) - mid.n) <= tolerance_;
    for (double t : {0.25, 0.75}) {
      if (!close) break;
      close = std::abs(hermite(t) - base_at(a + t * width).n) <= tolerance_;
    }
  }
  if (close) {
    h_.push_back(b);
    samples_.push_back(sb);
    return;
  }
  refine(a, sa, a + 0.5 * width, mid, depth + 1);
  refine(a + 0.5 * width, mid, b, sb, depth + 1);
}

size_t TabulatedHeightField::interval_of(double h) const {
  const size_t k = std::min(bucket_.size() - 2, size_t((h - lo_) / bucket_width_));
  // upper_bound over the bucket's few nodes by a forward scan (16 buckets a node: mostly one or
  // two comparisons, predictable, where a binary search mispredicts): the same node.
  const size_t last = std::min<size_t>(bucket_[k + 1] + 2, h_.size());
  size_t it = bucket_[k];
  while (it < last && !(h < h_[it])) ++it;
  return std::min<size_t>(it, h_.size() - 1) - 1;
}

TabulatedHeightField::Sample TabulatedHeightField::interpolate(size_t i, double h) const {
  const Cubic& c = cubics_[i];
  const double t = (h - h_[i]) * c.inverse_width;
  return {c.c0 + t * (c.c1 + t * (c.c2 + t * c.c3)), (c.c1 + t * (2.0 * c.c2 + 3.0 * t * c.c3)) * c.inverse_width};
}

void TabulatedHeightField::evaluate_height(double h, double* n, double* dn_dh) const {
  if (!(h >= lo_ && h <= hi_) || h_.size() < 2) {
    base_->evaluate_height(h, n, dn_dh);
    return;
  }
  const Sample s = interpolate(interval_of(h), h);
  *n = s.n;
  *dn_dh = s.dn;
}

void TabulatedHeightField::evaluate(const Vec3d& p, double* n, Vec3d* grad) const {
  double dn;
  evaluate_height(p.y(), n, &dn);
  *grad = Vec3d(0.0, dn, 0.0);
}

std::shared_ptr<const IndexField> TabulatedHeightField::with_param_values(const std::vector<double>& values) const {
  return std::make_shared<TabulatedHeightField>(base_->with_param_values(values), lo_, hi_, tolerance_);
}

FieldPtr tabulate_heights(const FieldPtr& field, double lo, double hi) {
  if (!field || !field->height_only()) return field;
  if (const FieldPtr inner = field->decorated()) {  // tabulate the air inside CurvedEarth
    return field->with_base(tabulate_heights(inner, field->base_height(lo), field->base_height(hi)));
  }
  if (dynamic_cast<const TabulatedHeightField*>(field.get())) return field;
  // Tabulated air dispersed to another wavelength (a spectral render's eye tables, one per
  // dispersion scale: render/hero_casters.h) is a table lookup and a multiply-add already.
  if (const auto* dispersed = dynamic_cast<const DispersedField*>(field.get());
      dispersed && dynamic_cast<const TabulatedHeightField*>(dispersed->base().get())) {
    return field;
  }
  return std::make_shared<TabulatedHeightField>(field, lo, hi);
}

}  // namespace refracta
