// The Earth-flattening transform.
#include "refracta/media/curved_earth.h"

#include "refracta/core/error.h"

#include <cmath>

namespace refracta {

CurvedEarth::CurvedEarth(FieldPtr base, double radius) : base_(std::move(base)), radius_(radius) {
  if (!base_) throw_invalid("CurvedEarth: needs a base field");
  if (!base_->height_only()) {
    throw_invalid("CurvedEarth: the base field must depend on height only (", base_->type_name(), " does not)");
  }
  if (!(radius >= kMinRadius) || !std::isfinite(radius)) {
    throw_invalid("CurvedEarth: radius must be a planet's, at least ", kMinRadius, " m (in metres: the Earth's is ",
                  kEarthRadius, " m; got ", radius, ")");
  }
  // Flattening twice would bend the rays by the Earth's curvature twice (and name earth_radius twice).
  if (std::isfinite(base_->earth_radius())) {
    throw_invalid("CurvedEarth: the base field is already over a curved Earth (", base_->type_name(),
                  ", earth_radius ", base_->earth_radius(), " m); give it its flat base instead");
  }
  specs_ = base_->param_specs();
  specs_.push_back({"earth_radius", kEarthRadius, 6000e3, 1e9, "m", "radius of curvature of the ground"});
}

double CurvedEarth::true_height(double y) const {
  const double h = radius_ * std::expm1(y / radius_);
  if (!std::isfinite(h)) throw_invalid("CurvedEarth: flat height y = ", y, " m has no finite true height");
  return h;
}

double CurvedEarth::flat_height(double h) const {
  // h <= -R is at or below the Earth's centre, where the flattening (y = R ln(1 + h/R)) is undefined.
  if (!(h > -radius_)) {
    throw_invalid("CurvedEarth: true height h must be > -radius = ", -radius_, " m (got ", h, " m)");
  }
  return radius_ * std::log1p(h / radius_);
}

void CurvedEarth::evaluate_height(double y, double* n, double* dn_dy) const {
  flattened_height(*base_, radius_, y, n, dn_dy);
}

void CurvedEarth::evaluate(const Vec3d& p, double* n, Vec3d* grad) const {
  double dn;
  evaluate_height(p.y(), n, &dn);
  *grad = Vec3d(0.0, dn, 0.0);
}

double CurvedEarth::straight_above() const {
  const double top = base_->uniform_above();
  return std::isfinite(top) ? flat_height(top) : top;
}

Vec3d CurvedEarth::sky_direction(const Vec3d& p, const Vec3d& d) const {
  return turned(p, d, radius_, true).normalized();
}

Eigen::Matrix3d CurvedEarth::sky_frame(const Vec3d& p) const {
  // One turn (a sine and cosine) for all three axes.
  const Turn turn(p, radius_, true);
  Eigen::Matrix3d rotation;
  for (int axis = 0; axis < 3; ++axis) rotation.col(axis) = turn(Vec3d::Unit(axis));
  return rotation;
}

Vec3d CurvedEarth::sphere_point(const Vec3d& flat, double radius) {
  const double rho = std::hypot(flat.x(), flat.z()), phi = rho / radius;
  const double r = radius + radius * std::expm1(flat.y() / radius);
  const double s = rho > 0.0 ? std::sin(phi) / rho : 1.0 / radius;  // sin(phi) per metre of rho
  return r * Vec3d(flat.x() * s, std::cos(phi), flat.z() * s);
}

CurvedEarth::Turn::Turn(const Vec3d& p, double radius, bool to_origin) {
  const double rho = std::sqrt(p.x() * p.x() + p.z() * p.z());
  if (!(rho > 0.0)) return;
  const double phi = rho / radius;
  out = Vec3d(p.x() / rho, 0.0, p.z() / rho);  // horizontal, away from the origin
  c = std::cos(phi), s = to_origin ? std::sin(phi) : -std::sin(phi);
}

Vec3d CurvedEarth::Turn::operator()(const Vec3d& d) const {
  if (out.isZero()) return d;
  // Rotation by phi taking the local vertical (the origin frame's y turned toward `out`) back:
  // y -> cos(phi) y - sin(phi) out, out -> cos(phi) out + sin(phi) y, the perpendicular kept
  // (and by -phi the other way).
  const double along = d.dot(out), up = d.y();
  const Vec3d across = d - along * out - up * Vec3d::UnitY();
  return across + (c * along + s * up) * out + (c * up - s * along) * Vec3d::UnitY();
}

Vec3d CurvedEarth::turned(const Vec3d& p, const Vec3d& d, double radius, bool to_origin) {
  return Turn(p, radius, to_origin)(d);
}

std::shared_ptr<const IndexField> CurvedEarth::with_base(std::shared_ptr<const IndexField> base) const {
  return std::make_shared<CurvedEarth>(std::move(base), radius_);
}

std::vector<double> CurvedEarth::param_values() const {
  std::vector<double> values = base_->param_values();
  values.push_back(radius_);
  return values;
}

std::shared_ptr<const IndexField> CurvedEarth::with_param_values(const std::vector<double>& values) const {
  if (values.size() != specs_.size()) {
    throw_invalid("CurvedEarth: expected ", specs_.size(), " parameters, got ", values.size());
  }
  std::vector<double> base_values(values.begin(), values.end() - 1);
  return std::make_shared<CurvedEarth>(base_->with_param_values(base_values), values.back());
}

}  // namespace refracta
