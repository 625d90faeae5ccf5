// CurvedEarth: a height-only atmosphere over a spherical Earth, mapped to flat coordinates by the
// conformal Earth-flattening transform (e.g. Born & Wolf 3.2; used for radio ducting):
//   x' = R phi (distance along the surface),  y' = R ln(r / R),  n'(y') = n(h) r / R = n(h) e^(y'/R),
//   with h = r - R = R (e^(y'/R) - 1) the true height.
// In the vertical plane of a ray it is exact: Bouguer's invariant on the sphere, n r cos e = const,
// becomes n' cos e' = const on the plane. Scene heights y' differ from true heights by
// h^2 / (2R) (0.8 mm at 100 m); true_height() and flat_height() convert.
#pragma once

#include "refracta/media/index_field.h"

#include <cmath>

namespace refracta {

constexpr double kEarthRadius = 6371e3;  // [m], mean radius

// n'(y') and dn'/dy' of the flattened atmosphere from a height-only base with
// base.evaluate_height(h, &n, &dn_dh); templated so editing differentiates through it.
template <class T, class Base>
void flattened_height(const Base& base, const T& radius, const T& y, T* n, T* dn_dy) {
  using std::expm1;
  // h = R (e^(y/R) - 1) by expm1: e^(y/R) - 1 in two steps rounds h to R eps ~ 1e-9 m, a jitter
  // that rk45's error control saw as structure near a hot road (its steps collapsed at tol 1e-6).
  const T grown = expm1(y / radius);
  const T scale = grown + T(1.0);  // r / R = dh/dy'
  T n_base, dn_base;
  base.evaluate_height(radius * grown, &n_base, &dn_base);
  *n = n_base * scale;
  *dn_dy = scale * (dn_base * scale + n_base / radius);
}

// A height-only atmosphere over a spherical Earth, in flat coordinates (conformal Earth-flattening
// transform): x' = distance along the surface, y' = R ln(r/R), n' = n(h) e^(y'/R). Exact for rays in
// their vertical plane; scene heights y' differ from true heights by h^2/(2R) (0.8 mm at 100 m):
// true_height(y') and flat_height(h) convert. Use it for anything seen over kilometres (horizons,
// looming, Fata Morgana).
class CurvedEarth : public IndexField {
 public:
  // base must be height-only; radius [m] at least kMinRadius: a body that holds an atmosphere is
  // far larger (Pluto's is 1.19e6 m), the flat frame's n = e^(y/R) n(h) overflows double 115 R
  // above the ground (a scene file's curved_earth = 1, meant as true, was a 1 m Earth), and the
  // Earth's radius in km, 6371, is caught (a trial: a 6.4 km Earth, k = -0.01, accepted).
  static constexpr double kMinRadius = 1e5;
  CurvedEarth(FieldPtr base, double radius = kEarthRadius);

  std::string type_name() const override { return "CurvedEarth"; }
  void evaluate(const Vec3d& p, double* n, Vec3d* grad) const override;
  bool height_only() const override { return true; }
  void evaluate_height(double y, double* n, double* dn_dy) const override;
  // The base field's parameters, then earth_radius.
  const std::vector<ParamSpec>& param_specs() const override { return specs_; }
  std::vector<double> param_values() const override;
  std::shared_ptr<const IndexField> with_param_values(const std::vector<double>& values) const override;
  std::vector<std::string> gauge_params() const override { return base_->gauge_params(); }
  // The flat frame's x' = R phi: at horizontal distance rho from the origin the local vertical is
  // tilted by phi = rho / R toward rho's direction, and a flat-frame direction's elevation e' is
  // e' there (the map is conformal): turned back by phi into the origin's frame.
  Vec3d sky_direction(const Vec3d& p, const Vec3d& d) const override;
  // The same turn as one matrix (one Turn for all three axes; DirectLighting turns every shading
  // point's light samples by it).
  Eigen::Matrix3d sky_frame(const Vec3d& p) const override;
  // The true sphere behind a flat frame of radius R: a flat-frame point's position [m] from the
  // sphere's centre, the origin's vertical along +y (r = R e^(y'/R), phi = rho / R toward rho's
  // direction); and a direction at flat-frame point p turned by p's central angle into the
  // origin's frame, where the sphere's true directions are (to_origin), or back from it.
  static Vec3d sphere_point(const Vec3d& flat, double radius);
  static Vec3d turned(const Vec3d& p, const Vec3d& d, double radius, bool to_origin);
  // That turn at p, kept to apply to several directions.
  struct Turn {
    Turn(const Vec3d& p, double radius, bool to_origin);
    Vec3d operator()(const Vec3d& d) const;
    Vec3d out = Vec3d::Zero();  // horizontal unit away from the origin (zero at the origin: no turn)
    double c = 1.0, s = 0.0;    // cos and (signed) sin of the central angle
  };
  double earth_radius() const override { return radius_; }
  double straight_above() const override;

  std::shared_ptr<const IndexField> decorated() const override { return base_; }
  std::shared_ptr<const IndexField> with_base(std::shared_ptr<const IndexField> base) const override;
  double base_height(double y) const override { return true_height(y); }

  const FieldPtr& base() const { return base_; }
  double radius() const { return radius_; }
  // True height h [m] of flat-frame heights y'.
  double true_height(double flat_y) const;
  // Flat-frame height y' of true heights h [m].
  double flat_height(double height) const;

 private:
  FieldPtr base_;
  double radius_;
  std::vector<ParamSpec> specs_;
};

}  // namespace refracta
