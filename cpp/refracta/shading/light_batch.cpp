#include "refracta/shading/light_batch.h"

#include "refracta/core/error.h"

#include <cmath>

namespace refracta {

namespace {

Vec3d rgb(const Spectrum& s) { return Vec3d(s[0], s[1], s[2]); }

}  // namespace

const char* light_type_name(LightType type) {
  switch (type) {
    case LightType::kDeltaPosition: return "delta_position";
    case LightType::kDeltaDirection: return "delta_direction";
    case LightType::kArea: return "area";
    case LightType::kInfinite: return "infinite";
  }
  return "unknown";
}

std::vector<LightSampleContext> light_contexts(const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals) {
  if (!normals.empty() && normals.size() != points.size()) throw_invalid("normals must have shape (", points.size(), ", 3)");
  std::vector<LightSampleContext> contexts(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    contexts[i].p = points[i];
    if (!normals.empty()) contexts[i].n = normals[i];
  }
  return contexts;
}

RgbLightSamples sample_li_rgb(const Light& light, const std::vector<LightSampleContext>& contexts,
                              const std::vector<double>& u) {
  const size_t n = contexts.size();
  if (u.size() != 2 * n) throw_invalid("u must have shape (", n, ", 2)");
  const SampledWavelengths lambda = SampledWavelengths::rgb();
  RgbLightSamples out{std::vector<Vec3d>(n, Vec3d::Zero()), std::vector<Vec3d>(n, Vec3d::Zero()),
                      std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  for (size_t i = 0; i < n; ++i) {
    if (auto s = light.sample_li(contexts[i], Vec2d(u[2 * i], u[2 * i + 1]), lambda)) {
      out.wi[i] = s->wi;
      out.L[i] = rgb(s->L);
      out.pdf[i] = s->pdf;
      out.distance[i] = s->distance;
    }
  }
  return out;
}

std::vector<double> pdf_li_all(const Light& light, const std::vector<LightSampleContext>& contexts,
                               const std::vector<Vec3d>& wi, const std::vector<Vec3d>& p_light,
                               const std::vector<Vec3d>& n_light) {
  const size_t n = contexts.size();
  if (wi.size() != n) throw_invalid("wi must have shape (", n, ", 3)");
  if (!p_light.empty() && p_light.size() != n) throw_invalid("p_light must have shape (", n, ", 3)");
  if (!n_light.empty() && n_light.size() != n) throw_invalid("n_light must have shape (", n, ", 3)");
  std::vector<double> pdf(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3d p = p_light.empty() ? Vec3d::Zero() : p_light[i];
    pdf[i] = light.pdf_li(contexts[i], wi[i], p, n_light.empty() ? Vec3d::Zero() : n_light[i]);
  }
  return pdf;
}

std::vector<Vec3d> Le_rgb(const Light& light, const std::vector<Vec3d>& dirs) {
  const SampledWavelengths lambda = SampledWavelengths::rgb();
  std::vector<Vec3d> out(dirs.size());
  for (size_t i = 0; i < dirs.size(); ++i) out[i] = rgb(light.Le(dirs[i], lambda));
  return out;
}

std::vector<Vec3d> L_rgb(const Light& light, const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                         const std::vector<Vec3d>& dirs) {
  if (normals.size() != points.size()) throw_invalid("normals must have shape (", points.size(), ", 3)");
  if (dirs.size() != points.size()) throw_invalid("dirs must have shape (", points.size(), ", 3)");
  const SampledWavelengths lambda = SampledWavelengths::rgb();
  std::vector<Vec3d> out(points.size());
  for (size_t i = 0; i < points.size(); ++i) out[i] = rgb(light.L(points[i], normals[i], dirs[i], lambda));
  return out;
}

Vec3d area_light_normal(const AreaLight& light, size_t triangle) {
  const size_t count = light.mesh().triangles.size();
  if (triangle >= count) throw_invalid("triangle must be < ", count, " (got ", triangle, ")");
  return light.normal(triangle);
}

std::vector<Vec2d> directions_to_uv(const EnvironmentLight& light, const std::vector<Vec3d>& dirs) {
  std::vector<Vec2d> uv(dirs.size());
  for (size_t i = 0; i < dirs.size(); ++i) {
    const Vec3d& d = dirs[i];
    if (!(d.allFinite() && d.cwiseAbs().maxCoeff() > 0.0)) {
      throw_invalid("EnvironmentLight.direction_to_uv: dirs[", i, "] must be a finite non-zero vector (got (", d.x(),
                    ", ", d.y(), ", ", d.z(), "))");
    }
    uv[i] = light.direction_to_uv(d.stableNormalized());
  }
  return uv;
}

std::vector<Vec3d> uv_to_directions(const EnvironmentLight& light, const std::vector<Vec2d>& uv) {
  std::vector<Vec3d> dirs(uv.size());
  for (size_t i = 0; i < uv.size(); ++i) {
    // The map's (u, v) cover [0, 1] each (v pole to pole: beyond it is no direction; u wraps, so a
    // u outside was a mistake too).
    if (!std::isfinite(uv[i].x()) || !std::isfinite(uv[i].y())) throw_invalid("uv must be finite");
    if (!(uv[i].x() >= 0.0 && uv[i].x() <= 1.0 && uv[i].y() >= 0.0 && uv[i].y() <= 1.0)) {
      throw_invalid("uv must be in [0, 1] (got row ", i, ": (", uv[i].x(), ", ", uv[i].y(), "))");
    }
    dirs[i] = light.uv_to_direction(uv[i]);
  }
  return dirs;
}

LightChoices sample_lights(const LightSampler& sampler, const std::vector<double>& u) {
  LightChoices out{std::vector<long long>(u.size()), std::vector<double>(u.size())};
  for (size_t i = 0; i < u.size(); ++i) {
    const auto chosen = sampler.sample(u[i]);
    if (!chosen) throw_invalid("LightSampler: no lights to sample");
    out.index[i] = (long long)chosen->index;
    out.probability[i] = chosen->probability;
  }
  return out;
}

}  // namespace refracta
