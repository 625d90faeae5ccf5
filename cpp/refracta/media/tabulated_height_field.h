// A height-only field sampled once and interpolated: cubic Hermite in h through the base
// field's n and dn/dh at nodes placed by bisection until the interpolant agrees with the base
// to `tolerance` in n at the quarter points of every interval. A render evaluates n(h) tens of
// millions of times; a physical atmosphere's exponentials, powers and pressure table cost
// several times a lookup and a cubic. dn/dh is the cubic's derivative, so n and dn/dh stay
// consistent (integrating the table's dn/dh gives the table's n exactly).
#pragma once

#include "refracta/media/curved_earth.h"
#include "refracta/media/index_field.h"

#include <memory>
#include <vector>

namespace refracta {

class TabulatedHeightField final : public IndexField {
 public:
  // base height-only; the table spans the part of [lo, hi] [m] where the base can be evaluated,
  // heights outside it are the base's own. Throws std::invalid_argument for an empty range or
  // tolerance <= 0.
  TabulatedHeightField(FieldPtr base, double lo, double hi, double tolerance = 1e-12);

  std::string type_name() const override { return base_->type_name(); }
  void evaluate(const Vec3d& p, double* n, Vec3d* grad) const override;
  bool height_only() const override { return true; }
  void evaluate_height(double h, double* n, double* dn_dh) const override;
  const std::vector<ParamSpec>& param_specs() const override { return base_->param_specs(); }
  std::vector<double> param_values() const override { return base_->param_values(); }
  // The base with other values, tabulated over the same range.
  std::shared_ptr<const IndexField> with_param_values(const std::vector<double>& values) const override;
  std::vector<std::string> gauge_params() const override { return base_->gauge_params(); }
  // The base's: a table of its constant values above that height is the same constant (issue 13).
  double uniform_above() const override { return base_->uniform_above(); }

  const FieldPtr& base() const { return base_; }
  size_t nodes() const { return h_.size(); }

 private:
  struct Sample {
    double n, dn;
  };
  Sample base_at(double h) const;
  Sample interpolate(size_t i, double h) const;
  void refine(double a, const Sample& sa, double b, const Sample& sb, int depth);
  size_t interval_of(double h) const;

  FieldPtr base_;
  double lo_, hi_, tolerance_;
  std::vector<double> h_;
  std::vector<Sample> samples_;
  // Per interval: n = c0 + t (c1 + t (c2 + t c3)), t = (h - h_i) / width.
  struct Cubic {
    double c0, c1, c2, c3, inverse_width;
  };
  std::vector<Cubic> cubics_;
  // bucket_[k]: the interval holding lo_ + k * bucket_width_ (narrows the binary search).
  std::vector<uint32_t> bucket_;
  double bucket_width_ = 1.0;
};

// A CurvedEarth tabulated in the flat frame's height y' (issue 21 goal 5): its transformed index
// n'(y') = n(h) e^(y'/R) as two cubic Hermite tables on the same nodes,
//   A(y') = e^(y'/R)  and  B(y') = (n(h) - 1) e^(y'/R),   h = R (e^(y'/R) - 1),
// so that the air dispersed by any scale s (DispersedField: n_s - 1 = s (n - 1)) is
//   n'_s = A + s B,  dn'_s/dy' = A' + s B'
// and every dispersion scale of a spectral render shares one table. The nodes: [lo, hi] cut into
// blocks of about 32 m (64 to 1e5 of them), each 2^d equal parts (d <= 5) whose cubics hold B to
// `tolerance` at their quarter points and at least every 0.25 m, or, where the air has finer
// structure, 32 intervals of about a metre, each 2^d parts (d the least, at most kMaxPartDepth,
// for which the cubic of B is within `tolerance` at the quarter points of every part). A lookup
// is then two multiplies and two loads (three in a fine block: the block, its interval, then
// the part: one 64-byte cache line of coefficients), where the base tabulated in true heights
// inside CurvedEarth cost a bucket scan, a cubic and an exp per evaluation (53 % of the cold
// sea's CPU); the smooth air in 32 m parts keeps the table in cache (tabulated_height_field.cpp).
// Outside the table (or where the air cannot be evaluated) the exact CurvedEarth answers.
class TabulatedCurvedEarth final : public CurvedEarth {
 public:
  // air's base height-only; [lo, hi] [m] flat-frame heights. Throws std::invalid_argument for an
  // empty range or tolerance <= 0.
  TabulatedCurvedEarth(const CurvedEarth& air, double lo, double hi, double tolerance = 1e-12);

  void evaluate(const Vec3d& p, double* n, Vec3d* grad) const override;
  void evaluate_height(double y, double* n, double* dn_dy) const override;
  // The same air with other values, tabulated over the same range (at the same dispersion scale).
  std::shared_ptr<const IndexField> with_param_values(const std::vector<double>& values) const override;
  // The air inside: the base, or (dispersed) DispersedField(base, scale).
  std::shared_ptr<const IndexField> decorated() const override { return decorated_; }
  // Over the base dispersed by a DispersedField (dispersed_field, tunable_dispersed_field): this
  // table at that field's scale, sharing its nodes; over the base itself: this table at scale 1;
  // over any other base: a plain CurvedEarth.
  std::shared_ptr<const IndexField> with_base(std::shared_ptr<const IndexField> base) const override;

  size_t parts() const;  // cubic pieces of the table

 private:
  struct Table;  // tabulated_height_field.cpp
  TabulatedCurvedEarth(const TabulatedCurvedEarth& of, std::shared_ptr<const double> scale);

  std::shared_ptr<const Table> table_;
  std::shared_ptr<const double> scale_;  // the dispersion scale, read at every evaluation; null: 1
  FieldPtr decorated_;
};

// Height-only fields tabulated over [lo, hi] [m] (renders, ElevationTables): a CurvedEarth as a
// TabulatedCurvedEarth (in flat heights; dispersion still scales the real n - 1), a decorator's
// base in its own heights; others unchanged.
FieldPtr tabulate_heights(const FieldPtr& field, double lo, double hi);

}  // namespace refracta
