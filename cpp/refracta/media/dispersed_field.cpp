// Dispersion of the air (dispersed_field.h).
#include "refracta/media/dispersed_field.h"

#include "refracta/core/error.h"
#include "refracta/media/air.h"

#include <cmath>
#include <limits>

namespace refracta {

namespace {

double dry_air_k(double wavelength_nm, const char* what) {
  if (!(wavelength_nm >= 230.0 && wavelength_nm <= 2000.0)) {
    throw_invalid(what, " must be in [230, 2000] nm (got ", wavelength_nm, ")");
  }
  return air_index(kStandardPressure, kStandardGroundTemperature, 0.0, wavelength_nm).n_minus_1;
}

}  // namespace

double air_dispersion_scale(double wavelength_nm, double reference_nm) {
  return dry_air_k(wavelength_nm, "wavelength") / dry_air_k(reference_nm, "reference wavelength");
}

double field_reference_wavelength(const IndexField& field) { return field.reference_wavelength(); }

DispersedField::DispersedField(FieldPtr base, double scale, double wavelength_nm)
    : DispersedField(std::move(base), std::make_shared<const double>(scale), wavelength_nm) {
  if (!(scale > 0.0) || !std::isfinite(scale)) throw_invalid("DispersedField: scale must be > 0 and finite (got ", scale, ")");
}

int DispersedField::wavelength_index() const {
  const std::vector<ParamSpec>& specs = base_->param_specs();
  for (size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].name == "wavelength") return int(i);
  }
  return -1;
}

std::vector<double> DispersedField::param_values() const {
  std::vector<double> values = base_->param_values();
  const int i = wavelength_index();
  if (i >= 0 && std::isfinite(wavelength_)) values[size_t(i)] = wavelength_;
  return values;
}

DispersedField::DispersedField(FieldPtr base, std::shared_ptr<const double> scale, double wavelength_nm)
    : base_(std::move(base)), scale_(std::move(scale)), wavelength_(wavelength_nm) {
  if (!base_) throw_invalid("DispersedField: base must be a field (got None)");
  if (!scale_) throw_invalid("DispersedField: scale must be given");
}

void DispersedField::evaluate(const Vec3d& p, double* n, Vec3d* grad) const {
  base_->evaluate(p, n, grad);
  const double scale = *scale_;
  *n = 1.0 + scale * (*n - 1.0);
  *grad *= scale;
}

void DispersedField::evaluate_height(double h, double* n, double* dn_dh) const {
  base_->evaluate_height(h, n, dn_dh);
  const double scale = *scale_;
  *n = 1.0 + scale * (*n - 1.0);
  *dn_dh *= scale;
}

FieldPtr DispersedField::height_only_part() const {
  const FieldPtr part = base_->height_only_part();
  return part ? std::make_shared<DispersedField>(part, scale_, wavelength_) : nullptr;
}

std::shared_ptr<const IndexField> DispersedField::with_param_values(const std::vector<double>& values) const {
  const int i = wavelength_index();
  if (i < 0 || !std::isfinite(wavelength_) || size_t(i) >= values.size()) {
    return std::make_shared<DispersedField>(base_->with_param_values(values), scale(), wavelength_);  // the scale now
  }
  // The wavelength parameter is this field's: a new one is a new scale over the base, at its own.
  std::vector<double> base_values = values;
  base_values[size_t(i)] = base_->param_values()[size_t(i)];
  const double wavelength = values[size_t(i)];
  const FieldPtr base = base_->with_param_values(base_values);
  return std::make_shared<DispersedField>(base, air_dispersion_scale(wavelength, field_reference_wavelength(*base)),
                                          wavelength);
}

FieldPtr dispersed_field(const FieldPtr& field, double wavelength_nm, std::optional<double> reference_nm) {
  if (!field) throw_invalid("dispersed_field: field must be a field (got None)");
  if (reference_nm) dry_air_k(*reference_nm, "reference wavelength");  // checked as given (0 was "none")
  // The wavelength is the field's to report only when the scale is from its own reference (a
  // reference of the caller's makes an air whose parameters say nothing of it: the base's kept).
  const double own = field_reference_wavelength(*field);
  const bool known = !reference_nm || *reference_nm == own;
  const double reference = reference_nm.value_or(own);
  if (const FieldPtr inner = field->decorated()) {  // disperse the air inside CurvedEarth
    const FieldPtr base = dispersed_field(inner, wavelength_nm, reference);
    return base == inner ? field : field->with_base(base);
  }
  const double scale = air_dispersion_scale(wavelength_nm, reference);
  if (scale == 1.0) return field;
  return std::make_shared<DispersedField>(field, scale, known ? wavelength_nm : std::numeric_limits<double>::quiet_NaN());
}

FieldPtr tunable_dispersed_field(const FieldPtr& field, const std::shared_ptr<const double>& scale) {
  if (!field) throw_invalid("tunable_dispersed_field: field must be a field (got None)");
  if (const FieldPtr inner = field->decorated()) return field->with_base(tunable_dispersed_field(inner, scale));
  return std::make_shared<DispersedField>(field, scale);
}

}  // namespace refracta
