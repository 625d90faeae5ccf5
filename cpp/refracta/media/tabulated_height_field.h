// A height-only field sampled once and interpolated: cubic Hermite in h through the base
// field's n and dn/dh at nodes placed by bisection until the interpolant agrees with the base
// to `tolerance` in n at the quarter points of every interval. A render evaluates n(h) tens of
// millions of times; a physical atmosphere's exponentials, powers and pressure table cost
// several times a lookup and a cubic. dn/dh is the cubic's derivative, so n and dn/dh stay
// consistent (integrating the table's dn/dh gives the table's n exactly).
#pragma once

#include "refracta/media/index_field.h"

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

// Height-only fields tabulated over [lo, hi] [m] (renders, ElevationTables; CurvedEarth's
// base in true heights, so that dispersion still scales the real n - 1); others unchanged.
FieldPtr tabulate_heights(const FieldPtr& field, double lo, double hi);

}  // namespace refracta
