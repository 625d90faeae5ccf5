// Dispersion of the air (shared/ORACLES.md, "The air"): for dry air the wavelength enters the
// index only through the factor K(lambda) of n - 1 = K(lambda) P / T (Edlen; Birch & Downs 1993,
// air.h), so a whole field at another wavelength is the field at its reference wavelength with
// n - 1 scaled:
//   n_lambda - 1 = s (n_ref - 1),  s = K(lambda) / K(lambda_ref),  grad n_lambda = s grad n_ref.
// K is air_index's n - 1 at 101 325 Pa, 288.15 K, no water vapour (the ratio does not depend on
// the conditions: the pressure and temperature terms multiply the dispersion term). (n - 1) rises
// 1.5 % from 650 to 450 nm. Humid air disperses slightly differently (its water term has its own
// wavelength law; 1e-4 of n - 1 at 100 % humidity, 20 C): the scaling ignores that.
//
// The reference wavelength of a field is its own `wavelength` parameter where it has one
// (PhysicalAtmosphere, TemperatureProfile, CurvedEarth over either), else 550 nm (LogisticProfile,
// LinearSquaredProfile, CustomField: their n is taken as the index at 550 nm). CurvedEarth is
// dispersed through its base (n' = n(h) e^(y'/R): the Earth-flattening factor is geometry, not
// air), so dispersed_field rebuilds it over the dispersed base.
#pragma once

#include "refracta/media/index_field.h"

#include <limits>

namespace refracta {

// The reference wavelength of fields without a `wavelength` parameter [nm].
constexpr double kDefaultFieldWavelength = 550.0;

// K(lambda) / K(reference) of dry air; wavelengths [nm] in [230, 2000] (else std::invalid_argument).
double air_dispersion_scale(double wavelength_nm, double reference_nm);

// The wavelength [nm] the field's n stands for: IndexField::reference_wavelength.
double field_reference_wavelength(const IndexField& field);

// n' = 1 + scale (n - 1) of a base field, grad n' = scale grad n; height-only as its base. Its
// parameters are the base's (with_param_values keeps the scale).

// A field at another wavelength: n' = 1 + scale (n - 1), grad n' = scale grad n, height-only as its
// base; for dry air scale = K(lambda)/K(lambda_ref) (air_dispersion_scale). Its parameters are the
// base's. Spectral renders through a field build these per sample (each hero wavelength); build one
// with dispersed_field(field, wavelength).
//
// Built by dispersed_field, it knows its wavelength: its `wavelength` parameter (where its base
// has one: PhysicalAtmosphere, TemperatureProfile) is that wavelength, not the base's, so that
// field_reference_wavelength, a second dispersed_field (which scales from it) and the repr see the
// air it is (a trial: a field dispersed to 450 nm said 550, and dispersing it again scaled from
// 550); with_param_values then reads a new wavelength as a new scale over the base. Over a base
// without one (550 nm by convention) the parameters stay the base's.
class DispersedField final : public IndexField {
 public:
  // base non-null; scale > 0 and finite. wavelength_nm: the wavelength the scale takes the base to
  // (NaN: not known, the parameters are the base's).
  DispersedField(FieldPtr base, double scale, double wavelength_nm = std::numeric_limits<double>::quiet_NaN());
  // The scale read from `scale` at every evaluation, so that its owner can retune the field (and
  // its height_only_part, which shares it) to another wavelength without rebuilding anything: a
  // spectral render's pooled air, set to the hero wavelength of the sample that holds it
  // (render/hero_casters.h). The owner sets it > 0 and finite, and never while the field is in use.
  DispersedField(FieldPtr base, std::shared_ptr<const double> scale,
                 double wavelength_nm = std::numeric_limits<double>::quiet_NaN());

  std::string type_name() const override { return "DispersedField"; }
  void evaluate(const Vec3d& p, double* n, Vec3d* grad) const override;
  bool height_only() const override { return base_->height_only(); }
  double uniform_above() const override { return base_->uniform_above(); }
  void evaluate_height(double h, double* n, double* dn_dh) const override;
  const std::vector<ParamSpec>& param_specs() const override { return base_->param_specs(); }
  std::vector<double> param_values() const override;
  // The wavelength it was dispersed to (its base's parameters may have none: a LogisticProfile
  // dispersed to 450 nm said 550, and dispersing it again scaled from there, 1 % off: a trial).
  double reference_wavelength() const override {
    return std::isfinite(wavelength_) ? wavelength_ : base_->reference_wavelength();
  }
  std::shared_ptr<const IndexField> with_param_values(const std::vector<double>& values) const override;
  std::vector<std::string> gauge_params() const override { return base_->gauge_params(); }
  // The base's height-only part, dispersed alike; its regions.
  FieldPtr height_only_part() const override;
  std::vector<LocalRegion> local_regions() const override { return base_->local_regions(); }
  Vec3d sky_direction(const Vec3d& p, const Vec3d& d) const override { return base_->sky_direction(p, d); }
  Eigen::Matrix3d sky_frame(const Vec3d& p) const override { return base_->sky_frame(p); }
  double earth_radius() const override { return base_->earth_radius(); }
  double straight_above() const override { return base_->straight_above(); }

  const FieldPtr& base() const { return base_; }
  double scale() const { return *scale_; }
  double wavelength() const { return wavelength_; }  // NaN where not known
  // Where the scale is read (shared with fields retuned alike: TabulatedCurvedEarth).
  const std::shared_ptr<const double>& scale_source() const { return scale_; }

 private:
  // The index of the base's `wavelength` parameter, or -1.
  int wavelength_index() const;

  FieldPtr base_;
  std::shared_ptr<const double> scale_;
  double wavelength_ = std::numeric_limits<double>::quiet_NaN();
};

// The field at `wavelength_nm` [nm]: a DispersedField by air_dispersion_scale(wavelength,
// reference) (none: field_reference_wavelength(*field); given, in air_dispersion_scale's range,
// else std::invalid_argument: a 0 or negative one passed as "none"); CurvedEarth through its
// base; the field itself when the scale is 1.
FieldPtr dispersed_field(const FieldPtr& field, double wavelength_nm, std::optional<double> reference_nm = std::nullopt);

// The field dispersed by the scale `scale` points to, retuned whenever its owner changes it (the
// DispersedField constructor above): CurvedEarth through its base, as dispersed_field.
FieldPtr tunable_dispersed_field(const FieldPtr& field, const std::shared_ptr<const double>& scale);

}  // namespace refracta
