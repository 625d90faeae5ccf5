// Tabulated height-only fields (tabulated_height_field.h).
#include "refracta/media/tabulated_height_field.h"

#include "refracta/core/error.h"
#include "refracta/media/dispersed_field.h"

#include <algorithm>
#include <array>
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

// The cubic through values f0, f1 with slopes d0, d1 (per unit of the parameter) on [0, 1].
std::array<double, 4> hermite_cubic(double f0, double d0, double f1, double d1) {
  const double jump = f1 - f0;
  return {f0, d0, 3.0 * jump - 2.0 * d0 - d1, -2.0 * jump + d0 + d1};
}

double cubic_at(const std::array<double, 4>& c, double t) { return c[0] + t * (c[1] + t * (c[2] + t * c[3])); }

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
    const std::array<double, 4> c = hermite_cubic(a.n, width * a.dn, b.n, width * b.dn);
    cubics_[k] = {c[0], c[1], c[2], c[3], 1.0 / width};
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

// --- TabulatedCurvedEarth ------------------------------------------------------------------

namespace {

// Blocks of about kBlock [m] (between kMinInitialIntervals and kMaxInitialIntervals of them):
// a block is 2^d equal parts (d <= kMaxBlockDepth), each part's cubic checked against the air at
// its quarter points and at least every kCheckSpacing [m] along it -- as densely as a metre's
// quarter points, so no thinner feature hides than in 1 m intervals (over ranges longer than
// kMaxInitialIntervals metres, as densely as those intervals' quarter points: a sunset's
// 1 500 km) -- or, where the air has finer structure (a surface layer, an inversion, a knot),
// kFinePerBlock intervals, each 2^d parts checked at their quarter points (d <= kMaxPartDepth):
// the table as it was before blocks. The smooth air above a few tens of metres is then one part
// per 32 m, not 32 (a cubic over 32 m of the standard atmosphere is off by ~32^4 (n - 1) /
// (384 H^4) ~ 2e-16, H its 8 km scale height): 86 km of air in ~3 000 parts (200 KB) where 1 m
// intervals took 86 000 (5.5 MB), so a lookup finds its part in cache (the cold sea's shadow
// rays spent half their air lookups waiting for memory).
constexpr double kBlock = 32.0;
constexpr int kFinePerBlock = 32;
constexpr int kMaxBlockDepth = 5;
constexpr double kCheckSpacing = 0.25;
// Parts of a metre's interval: at most 2^kMaxPartDepth (1 m / 65536 = 15 um; a kink in n -- a
// temperature profile's knot -- is accepted there, its cubic off by ~jump(dn/dh) x 15 um / 16);
// at most kMaxParts in all (64 MB of coefficients), past which the rest are accepted as they are.
constexpr int kMaxPartDepth = 16;
constexpr size_t kMaxParts = size_t(1) << 20;

// A(y'), A', B(y'), B' of the flattened air (flattened_height's transform, split at n - 1).
struct FlatSample {
  double a, da, b, db;
};

FlatSample flat_sample(const IndexField& base, double radius, double y) {
  const double scale = std::exp(y / radius);  // r / R = dh/dy'
  double n, dn;
  base.evaluate_height(radius * (scale - 1.0), &n, &dn);
  const double excess = n - 1.0;
  return {scale, scale / radius, excess * scale, scale * (dn * scale + excess / radius)};
}

}  // namespace

struct TabulatedCurvedEarth::Table {
  // A part's cubics in its parameter v in [0, 1]: A = a0 + v (a1 + v (a2 + v a3)), B alike.
  struct alignas(64) Part {
    std::array<double, 4> a, b;
  };
  struct Interval {
    uint32_t first;            // its first part (fine: its first interval in `fine`)
    uint32_t count;            // 2^d parts (fine: kFinePerBlock intervals)
    double inverse_part;       // count / the interval's width [1/m]
    bool fine = false;         // a block of intervals (kBlock)
  };
  double lo = 0.0, hi = 0.0;      // [m], flat
  double tolerance = 0.0;         // in B (and so in n')
  double inverse_width = 0.0;     // blocks per metre
  std::vector<Interval> intervals;  // the blocks
  std::vector<Interval> fine;       // the intervals of fine blocks
  std::vector<Part> parts;
};

TabulatedCurvedEarth::TabulatedCurvedEarth(const CurvedEarth& air, double lo, double hi, double tolerance)
    : CurvedEarth(air.base(), air.radius()), decorated_(air.base()) {
  if (!(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi)) {
    throw_invalid("TabulatedCurvedEarth: need lo < hi, both finite (got ", lo, ", ", hi, ")");
  }
  if (!(tolerance > 0.0)) throw_invalid("TabulatedCurvedEarth: tolerance must be > 0 (got ", tolerance, ")");
  auto table = std::make_shared<Table>();
  table_ = table;
  table->tolerance = tolerance;
  // The part of [lo, hi] the air models (TabulatedHeightField's rule).
  double start = lo;
  if (!evaluable(air, start)) start = evaluable(air, 0.0) ? evaluable_end(air, 0.0, lo) : hi;
  table->lo = start;
  table->hi = start < hi ? evaluable_end(air, start, hi) : start;
  if (!(table->hi > table->lo)) return;  // nothing tabulated: every height is the air's own
  const IndexField& base = *air.base();
  const double radius = air.radius(), span = table->hi - table->lo;
  const size_t count = size_t(std::clamp(std::ceil(span / kBlock), double(kMinInitialIntervals),
                                         double(kMaxInitialIntervals)));
  table->inverse_width = double(count) / span;
  const double width = span / double(count);
  const double check_spacing = std::max(kCheckSpacing, 0.25 * span / double(kMaxInitialIntervals));
  table->intervals.reserve(count);
  std::vector<FlatSample> nodes;
  std::vector<Table::Part> parts;
  // [from, from + length) as 2^d parts, d the least up to max_depth whose cubics hold B to the
  // tolerance at least every check_spacing and at their quarter points; false where none does
  // (or the parts reach kMaxParts), the last depth's parts kept.
  auto cut = [&](double from, double length, int max_depth) {
    for (int depth = 0; depth <= max_depth; ++depth) {
      const size_t pieces = size_t(1) << depth;
      const double step = length / double(pieces);
      auto at = [&](double k) { return flat_sample(base, radius, from + step * k); };
      nodes.resize(pieces + 1);
      for (size_t k = 0; k <= pieces; ++k) nodes[k] = at(double(k));
      parts.resize(pieces);
      bool close = true;
      const int checks = std::max(4, int(std::ceil(step / check_spacing)));
      for (size_t k = 0; k < pieces; ++k) {
        const FlatSample &p = nodes[k], &q = nodes[k + 1];
        parts[k].a = hermite_cubic(p.a, step * p.da, q.a, step * q.da);
        parts[k].b = hermite_cubic(p.b, step * p.db, q.b, step * q.db);
        for (int i = 1; i < checks && close; ++i) {
          const double t = double(i) / checks;
          close = std::abs(cubic_at(parts[k].b, t) - at(double(k) + t).b) <= tolerance;
        }
      }
      if (close) return true;
      // Past the cap: a block's parts stay unchecked no longer than a metre's (the fine cut's).
      if (table->parts.size() + 2 * pieces > kMaxParts) return false;
    }
    return false;
  };
  auto add = [&](std::vector<Table::Interval>* to, double parts_per_metre) {
    to->push_back({uint32_t(table->parts.size()), uint32_t(parts.size()), parts_per_metre * double(parts.size())});
    table->parts.insert(table->parts.end(), parts.begin(), parts.end());
  };
  for (size_t j = 0; j < count; ++j) {
    const double from = table->lo + width * double(j);
    if (cut(from, width, kMaxBlockDepth)) {
      add(&table->intervals, table->inverse_width);
      continue;
    }
    table->intervals.push_back({uint32_t(table->fine.size()), uint32_t(kFinePerBlock),
                                table->inverse_width * kFinePerBlock, true});
    const double fine_width = width / kFinePerBlock;
    for (int i = 0; i < kFinePerBlock; ++i) {
      cut(from + fine_width * i, fine_width, kMaxPartDepth);  // at kMaxPartDepth: accepted as it is
      add(&table->fine, table->inverse_width * kFinePerBlock);
    }
  }
}

TabulatedCurvedEarth::TabulatedCurvedEarth(const TabulatedCurvedEarth& of, std::shared_ptr<const double> scale)
    : CurvedEarth(of.base(), of.radius()), table_(of.table_), scale_(std::move(scale)) {
  decorated_ = scale_ ? std::make_shared<DispersedField>(base(), scale_) : base();
}

size_t TabulatedCurvedEarth::parts() const { return table_->parts.size(); }

void TabulatedCurvedEarth::evaluate_height(double y, double* n, double* dn_dy) const {
  const Table& table = *table_;
  if (!(y >= table.lo && y <= table.hi) || table.intervals.empty()) {
    flattened_height(*decorated_, radius(), y, n, dn_dy);
    return;
  }
  const double t = (y - table.lo) * table.inverse_width;
  const size_t j = std::min(size_t(t), table.intervals.size() - 1);
  const Table::Interval* block = &table.intervals[j];
  double u = (t - double(j)) * double(block->count);
  if (block->fine) {  // its metre's interval
    const size_t i = std::min<size_t>(size_t(u), block->count - 1);
    u = (u - double(i)) * double(table.fine[block->first + i].count);
    block = &table.fine[block->first + i];
  }
  const Table::Interval& interval = *block;
  const size_t k = std::min<size_t>(size_t(u), interval.count - 1);
  const double v = u - double(k);
  const Table::Part& part = table.parts[interval.first + k];
  const std::array<double, 4>&a = part.a, &b = part.b;
  const double s = scale_ ? *scale_ : 1.0;
  const double value_a = cubic_at(a, v), value_b = cubic_at(b, v);
  const double slope_a = a[1] + v * (2.0 * a[2] + 3.0 * v * a[3]);
  const double slope_b = b[1] + v * (2.0 * b[2] + 3.0 * v * b[3]);
  *n = value_a + s * value_b;
  *dn_dy = (slope_a + s * slope_b) * interval.inverse_part;
}

void TabulatedCurvedEarth::evaluate(const Vec3d& p, double* n, Vec3d* grad) const {
  double dn;
  evaluate_height(p.y(), n, &dn);
  *grad = Vec3d(0.0, dn, 0.0);
}

std::shared_ptr<const IndexField> TabulatedCurvedEarth::with_param_values(const std::vector<double>& values) const {
  const auto air = std::static_pointer_cast<const CurvedEarth>(CurvedEarth::with_param_values(values));
  // The range as built (the evaluable part of the original's) and its tolerance.
  const TabulatedCurvedEarth fresh(*air, table_->lo, table_->hi, table_->tolerance);
  return std::shared_ptr<const IndexField>(new TabulatedCurvedEarth(fresh, scale_));
}

std::shared_ptr<const IndexField> TabulatedCurvedEarth::with_base(std::shared_ptr<const IndexField> base) const {
  if (base == this->base()) return std::shared_ptr<const IndexField>(new TabulatedCurvedEarth(*this, nullptr));
  if (const auto* dispersed = dynamic_cast<const DispersedField*>(base.get());
      dispersed && dispersed->base() == this->base()) {
    return std::shared_ptr<const IndexField>(new TabulatedCurvedEarth(*this, dispersed->scale_source()));
  }
  return CurvedEarth::with_base(std::move(base));
}

FieldPtr tabulate_heights(const FieldPtr& field, double lo, double hi) {
  if (!field || !field->height_only()) return field;
  if (dynamic_cast<const TabulatedCurvedEarth*>(field.get())) return field;
  if (const auto* curved = dynamic_cast<const CurvedEarth*>(field.get())) {
    // Up to the top of the air at least: escaping rays are integrated up to it (Caster::escape_direction;
    // the cold sea's 41 km of reach ends half way to the physical atmosphere's 86 km).
    const double top = curved->straight_above();
    return std::make_shared<TabulatedCurvedEarth>(*curved, lo, std::isfinite(top) ? std::max(hi, top) : hi);
  }
  if (const FieldPtr inner = field->decorated()) {  // tabulate the air inside another decorator
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
