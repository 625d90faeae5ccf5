// The emissive triangle mesh (area_light.h).
#include "refracta/shading/area_light.h"

#include "refracta/shading/light_common.h"

namespace refracta {

AreaLight::AreaLight(std::shared_ptr<const Mesh> mesh, const Color& emission, bool two_sided)
    : mesh_(std::move(mesh)), emission_(emission), two_sided_(two_sided) {
  if (!mesh_) throw_invalid("AreaLight: mesh must not be null");
  detail::check_emission(emission, "AreaLight: emission");
  const auto& v = mesh_->vertices;
  const auto& tris = mesh_->triangles;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!is_finite(v[i])) throw_invalid("AreaLight: vertices[", i, "] must be finite (got (", v[i].x(), ", ", v[i].y(), ", ", v[i].z(), "))");
  }
  if (tris.empty()) throw_invalid("AreaLight: triangles must not be empty");
  std::vector<double> areas(tris.size());
  normals_.resize(tris.size(), Vec3d::Zero());
  for (size_t t = 0; t < tris.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (tris[t][k] < 0 || size_t(tris[t][k]) >= v.size()) {
        throw_invalid("AreaLight: triangles[", t, "] indexes vertex ", tris[t][k], " of ", v.size());
      }
    }
    const Vec3d c = (v[tris[t][1]] - v[tris[t][0]]).cross(v[tris[t][2]] - v[tris[t][0]]);
    const double len = c.norm();
    areas[t] = 0.5 * len;
    if (len > 0.0 && std::isfinite(len)) normals_[t] = c / len;
    else if (!(len > 0.0)) areas[t] = 0.0;  // degenerate; an overflowing one keeps inf for the message
    area_ += areas[t];
  }
  if (!(area_ > 0.0) || !std::isfinite(area_)) throw_invalid("AreaLight: the mesh must have a positive, finite area (got ", area_, " m^2)");
  distribution_ = PiecewiseConstant1D(areas);
}

std::optional<LightLiSample> AreaLight::sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                                  const SampledWavelengths& lambda) const {
  // A triangle by area, then u.x re-used within its cell.
  size_t t = 0;
  const double x = distribution_.sample(u.x(), nullptr, &t);
  const double n = double(distribution_.size());
  const double u0 = std::clamp(x * n - double(t), 0.0, std::nextafter(1.0, 0.0));
  const Vec3d b = sample_uniform_triangle(Vec2d(u0, u.y()));
  const auto& tri = mesh_->triangles[t];
  const auto& v = mesh_->vertices;
  LightLiSample s;
  s.p_light = b[0] * v[tri[0]] + b[1] * v[tri[1]] + b[2] * v[tri[2]];
  const Vec3d d = s.p_light - ctx.p;
  const double r2 = d.squaredNorm();
  if (!(r2 > 0.0)) return std::nullopt;
  s.distance = std::sqrt(r2);
  s.wi = d / s.distance;
  const double cos_l = normals_[t].dot(-s.wi);
  if (cos_l == 0.0 || (!two_sided_ && cos_l < 0.0)) return std::nullopt;
  s.pdf = r2 / (std::abs(cos_l) * area_);
  if (!std::isfinite(s.pdf)) return std::nullopt;
  s.L = emission_.sample(lambda);
  return s;
}

double AreaLight::pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light,
                         const Vec3d& n_light) const {
  const double r2 = (p_light - ctx.p).squaredNorm();
  const double len = n_light.norm();
  const double cos_l = len > 0.0 ? std::abs(n_light.dot(wi)) / len : 0.0;
  if (!(cos_l > 0.0) || !(r2 > 0.0)) return 0.0;
  const double pdf = r2 / (cos_l * area_);
  return std::isfinite(pdf) ? pdf : 0.0;
}

Spectrum AreaLight::L(const Vec3d& /*p_light*/, const Vec3d& n_light, const Vec3d& w, const SampledWavelengths& lambda) const {
  const double c = n_light.dot(w);
  if (two_sided_ ? c == 0.0 : !(c > 0.0)) return Spectrum::Zero();
  return emission_.sample(lambda);
}

double AreaLight::power() const { return (two_sided_ ? 2.0 : 1.0) * kPi * area_ * detail::luminance(emission_.rgb()); }

std::string AreaLight::describe() const {
  return concat("AreaLight(triangles=", mesh_->triangles.size(), ", area=", area_, ", emission=(", emission_.rgb().x(), ", ",
                emission_.rgb().y(), ", ", emission_.rgb().z(), "), two_sided=", two_sided_ ? "True" : "False", ")");
}

}  // namespace refracta
