// Shared, non-template parts of IndexField.
#include "refracta/media/index_field.h"
#include "refracta/media/dispersed_field.h"
#include "refracta/media/ior_range.h"

#include "refracta/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace refracta {

// By value, as the virtual's signature (the overrides keep the pointer); this default only refuses.
double IndexField::reference_wavelength() const {
  if (const auto inner = decorated()) return inner->reference_wavelength();
  const std::vector<ParamSpec>& specs = param_specs();
  for (size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].name == "wavelength") return param_values().at(i);
  }
  return kDefaultFieldWavelength;
}

std::shared_ptr<const IndexField> IndexField::with_base(
    std::shared_ptr<const IndexField> /*base*/) const {  // NOLINT(performance-unnecessary-value-param)
  throw std::logic_error(type_name() + " decorates no field: with_base is for decorators (decorated() != null)");
}

std::shared_ptr<const IndexField> IndexField::with_turbulence(
    std::shared_ptr<const Turbulence> /*turbulence*/) const {  // NOLINT(performance-unnecessary-value-param)
  throw_invalid("the field must be a PhysicalAtmosphere or LogisticProfile to carry turbulence (got ", type_name(), ")");
}

void IndexField::evaluate_height(double, double*, double*) const {
  throw std::logic_error(type_name() + " is not a height-only field");
}

void IndexField::evaluate_checked(const Vec3d& p, double* n, Vec3d* grad) const {
  evaluate(p, n, grad);
  if (!usable_ior(*n) || !is_finite(*grad)) {
    throw_numerical(type_name(), ": refractive index n = ", *n, ", grad n = (", grad->x(), ", ",
                    grad->y(), ", ", grad->z(), ") at (", p.x(), ", ", p.y(), ", ", p.z(),
                    ") m; n must be finite and > 0 (in [", kMinIor, ", ", kMaxIor, "])");
  }
}

std::vector<double> IndexField::ior_at(const std::vector<Vec3d>& points) const {
  std::vector<double> n(points.size());
  Vec3d grad;
  for (size_t i = 0; i < points.size(); ++i) evaluate_checked(points[i], &n[i], &grad);
  return n;
}

std::vector<Vec3d> IndexField::grad_ior_at(const std::vector<Vec3d>& points) const {
  std::vector<Vec3d> grad(points.size());
  double n;
  for (size_t i = 0; i < points.size(); ++i) evaluate_checked(points[i], &n, &grad[i]);
  return grad;
}

void check_returned_iors(const std::string& who, const std::vector<double>& n, const std::vector<Vec3d>& points) {
  for (size_t i = 0; i < n.size(); ++i) {
    if (!usable_ior(n[i])) {
      const Vec3d& p = points[i];
      throw_numerical(who, " returned n = ", n[i], " at (", p.x(), ", ", p.y(), ", ", p.z(),
                      ") m; n must be finite and > 0 (in [", kMinIor, ", ", kMaxIor, "])");
    }
  }
}

void check_returned_grads(const std::string& who, const std::vector<Vec3d>& grads, const std::vector<Vec3d>& points) {
  for (size_t i = 0; i < grads.size(); ++i) {
    if (!is_finite(grads[i])) {
      const Vec3d &g = grads[i], &p = points[i];
      throw_numerical(who, " returned (", g.x(), ", ", g.y(), ", ", g.z(), ") at (", p.x(), ", ", p.y(), ", ", p.z(),
                      ") m; it must be finite");
    }
  }
}

double lowest_ior_sampled(const IndexField& field, double lo, double hi, double margin) {
  double lowest = std::numeric_limits<double>::infinity(), n, dn;
  // Finest near the ground (h = 0, or the end of the range nearer it), where layers are thin.
  const double ground = std::clamp(0.0, lo, hi);
  for (double h = lo; h <= hi; h += std::max(1e-3, 1e-3 * std::abs(h - ground))) {
    // Heights outside the modelled range are skipped (a ray reaching them fails there anyway);
    // the modelled part beyond them still counts.
    try {
      field.evaluate_height(h, &n, &dn);
    } catch (const std::exception&) {
      continue;
    }
    if (n > 0.0 && std::isfinite(n)) lowest = std::min(lowest, n);
  }
  // Nothing evaluable (or an empty range): no bound at all, so no ray is taken for one that cannot turn.
  return std::isfinite(lowest) ? lowest - margin : 0.0;
}

size_t IndexField::param_index(const std::string& name) const {
  const auto& specs = param_specs();
  std::string names;
  for (size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].name == name) return i;
    names += (i ? ", " : "") + specs[i].name;
  }
  throw_invalid(type_name(), ": unknown parameter '", name, "' (parameters: ", names, ")");
}

}  // namespace refracta
