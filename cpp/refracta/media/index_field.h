// The refractive-index field interface: n(x) and its gradient, named parameters, and the
// height-only flag. Models are written once as templates on the scalar (double for rendering,
// ceres::Jet for editing) and wrapped for double by ModelField (model_field.h).
#pragma once

#include "refracta/core/math.h"
#include "refracta/media/local_region.h"

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace refracta {

struct Turbulence;  // media/turbulence.h

// One named model parameter. [lower, upper] is the box an optimiser searches by default;
// construction checks physical validity only (model's validate), not this box.
struct ParamSpec {
  std::string name;
  double default_value;
  double lower;
  double upper;
  std::string unit;
  std::string doc;
};

// A refractive-index field n(x). Points are (N, 3) or (3,) float arrays in metres, y up.
//
// ior(points) -> n, shape (N,) (float for one point); grad_ior(points) -> grad n [1/m], (N, 3).
// params: dict of parameter values; param_names; bounds: dict name -> (lower, upper), the box an
// optimiser searches; ``with_params(**values)`` -> a new field; height_only: n depends on y alone;
// gauge_params: parameters an optimiser holds fixed by default (a joint scaling leaves rays
// unchanged). Raises refracta.NumericalError where n <= 0 or is not finite.
class IndexField {
 public:
  virtual ~IndexField() = default;

  virtual std::string type_name() const = 0;

  // n at p [m] and grad n [1/m]. Does not check the result; see evaluate_checked.
  virtual void evaluate(const Vec3d& p, double* n, Vec3d* grad) const = 0;

  // True when n depends on the height y alone; then evaluate_height is available.
  virtual bool height_only() const = 0;
  // n(h) and dn/dh [1/m]. Throws std::logic_error for fields that are not height-only.
  virtual void evaluate_height(double h, double* n, double* dn_dh) const;

  virtual const std::vector<ParamSpec>& param_specs() const = 0;
  virtual std::vector<double> param_values() const = 0;
  // A new field of the same model with other parameter values (validated).
  virtual std::shared_ptr<const IndexField> with_param_values(
      const std::vector<double>& values) const = 0;
  // Parameters an optimiser holds fixed by default because a joint change of them with others
  // leaves every ray path unchanged (a gauge freedom of the model).
  virtual std::vector<std::string> gauge_params() const { return {}; }
  // Height-only fields: n is constant (grad n = 0) at every height above this one [m] (+inf: no
  // such height). A ray above it goes straight: the stratified tracer ends the path in one step.
  virtual double uniform_above() const { return std::numeric_limits<double>::infinity(); }
  // Fields that depend on height alone except in a few bounded regions (areal hot spots, a
  // turbulent layer): the height-only field that holds outside local_regions(); null otherwise.
  virtual std::shared_ptr<const IndexField> height_only_part() const { return nullptr; }
  virtual std::vector<LocalRegion> local_regions() const { return {}; }
  // The world-frame direction of a ray at p [m] moving along unit d in this field's coordinates:
  // d itself, except for a spherical Earth in flat coordinates (CurvedEarth), where the frame at
  // p is turned by the central angle from the origin's.
  virtual Vec3d sky_direction(const Vec3d& /*p*/, const Vec3d& d) const { return d; }
  // The rotation taking the frame at p (this field's coordinates) to the world's: sky_direction of
  // each axis.
  virtual Eigen::Matrix3d sky_frame(const Vec3d& p) const {
    Eigen::Matrix3d rotation;
    for (int axis = 0; axis < 3; ++axis) rotation.col(axis) = sky_direction(p, Vec3d::Unit(axis));
    return rotation;
  }
  // The radius [m] of a spherical Earth these coordinates flatten (inf: flat).
  virtual double earth_radius() const { return std::numeric_limits<double>::infinity(); }
  // Height-only fields: above this height [m] a ray goes straight in the world frame (its
  // sky_direction stops changing): uniform_above(), or for a CurvedEarth its base's top in flat
  // coordinates (+inf: no such height).
  virtual double straight_above() const { return uniform_above(); }

  // Decorators -- fields that transform another (CurvedEarth) -- are taken apart and rebuilt only
  // through these three, so a function that must reach the air itself (dispersion, tabulation,
  // the autodiff dispatch) needs no type switch. decorated(): the field wrapped, null for others.
  virtual std::shared_ptr<const IndexField> decorated() const { return nullptr; }
  // The wavelength [nm] the field's n stands for (field_reference_wavelength): the decorated
  // field's, else its `wavelength` parameter, else kDefaultFieldWavelength (550).
  virtual double reference_wavelength() const;
  // The same decoration around another base; throws std::logic_error for fields that decorate none.
  virtual std::shared_ptr<const IndexField> with_base(std::shared_ptr<const IndexField> base) const;
  // Height y [m] of this field in decorated()'s coordinates (y itself for others).
  virtual double base_height(double y) const { return y; }

  // The same air with `turbulence` in place of its own (null: calm air). Throws
  // std::invalid_argument for fields that cannot carry turbulence (model_field.h: those whose
  // Config has one).
  virtual std::shared_ptr<const IndexField> with_turbulence(std::shared_ptr<const Turbulence> turbulence) const;
  // The turbulence this air carries (null: calm, or a field that cannot carry one).
  virtual std::shared_ptr<const Turbulence> turbulence() const { return nullptr; }

  // evaluate, throwing NumericalError when n <= 0 or anything is not finite.
  void evaluate_checked(const Vec3d& p, double* n, Vec3d* grad) const;
  // n and grad n [1/m] at each point [m], checked as evaluate_checked. A field whose evaluation has a
  // fixed cost per call (CustomField: a call into Python) evaluates all points at once.
  virtual std::vector<double> ior_at(const std::vector<Vec3d>& points) const;
  virtual std::vector<Vec3d> grad_ior_at(const std::vector<Vec3d>& points) const;
  // Index of a parameter by name; throws std::invalid_argument listing the valid names.
  size_t param_index(const std::string& name) const;
};

using FieldPtr = std::shared_ptr<const IndexField>;

// Checks values a field's code outside the library returned at points [m] (CustomField's Python
// callables): NumericalError naming `who` ("CustomField: ior") and the first point where n is not
// usable (ior_range.h) or a gradient is not finite.
void check_returned_iors(const std::string& who, const std::vector<double>& n, const std::vector<Vec3d>& points);
void check_returned_grads(const std::string& who, const std::vector<Vec3d>& grads, const std::vector<Vec3d>& points);

// The least n of a height-only field over heights [lo, hi] [m], sampled every millimetre near
// the ground (h = 0) with the spacing growing 0.1 % of the distance from it (about 2300 samples
// per decade of height beyond 1 m), less `margin`: a bound unless a dip deeper than `margin` hides between samples (the
// default, 1e-5, is a spike of ~10 K narrower than the spacing). Heights where the field throws
// (outside its modelled range) are skipped; 0 (no bound) if no height can be evaluated.
double lowest_ior_sampled(const IndexField& field, double lo, double hi, double margin = 1e-5);

// The Config of a model with no fixed data besides its parameters. A model's Config is a type
// outside the model template, so Model<double> and Model<Jet> share it.
struct NoConfig {};

// Temperature and pressure of a physical air column (fields built from air properties).
class AirColumn {
 public:
  virtual ~AirColumn() = default;
  virtual double temperature(double h) const = 0;  // [K]
  virtual double pressure(double h) const = 0;     // [Pa]
};

// Mixin giving a height-only model its 3D evaluate from evaluate_height. A model whose height
// dependence can be broken by local features (hot spots, turbulence) hides height_only() and
// evaluate() with its own.
template <class Derived, class T>
struct HeightOnlyModel {
  bool height_only() const { return true; }
  void evaluate(const Vec3<T>& p, T* n, Vec3<T>* grad) const {
    T dn_dh;
    static_cast<const Derived*>(this)->evaluate_height(p.y(), n, &dn_dh);
    *grad = Vec3<T>(T(0.0), dn_dh, T(0.0));
  }
};

}  // namespace refracta
