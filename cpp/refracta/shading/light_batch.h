// Lights evaluated at many points at once in RGB rendering: what Python's Light.sample_li, pdf_li,
// Le and L, EnvironmentLight's uv maps and LightSampler.sample compute (bindings/bind_lights.cpp),
// for tests and users' own integrators. Row i of every result belongs to row i of the inputs.
#pragma once

#include "refracta/shading/area_light.h"
#include "refracta/shading/environment_light.h"
#include "refracta/shading/light.h"
#include "refracta/shading/light_sampler.h"

#include <vector>

namespace refracta {

// 'delta_position', 'delta_direction', 'area' or 'infinite'.
const char* light_type_name(LightType type);

// Receiving points with their geometric normals (normals empty: none; else one per point, rows may be 0).
std::vector<LightSampleContext> light_contexts(const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals);

// sample_li at each context with the numbers u (2 per context). A point the light cannot reach
// gets wi = 0, L = 0, pdf = 0, distance = 0.
struct RgbLightSamples {
  std::vector<Vec3d> wi, L;  // unit toward the light; RGB radiance arriving [W/(m^2 sr)]
  std::vector<double> pdf, distance;  // per steradian (delta lights: 1); [m] (infinite lights: inf)
};
RgbLightSamples sample_li_rgb(const Light& light, const std::vector<LightSampleContext>& contexts,
                              const std::vector<double>& u);

// pdf_li at each context toward unit wi; area lights need the point p_light where the ray hits
// and its normal n_light (each empty: zeros; else one per context).
std::vector<double> pdf_li_all(const Light& light, const std::vector<LightSampleContext>& contexts,
                               const std::vector<Vec3d>& wi, const std::vector<Vec3d>& p_light,
                               const std::vector<Vec3d>& n_light);

// Le along each unit direction (infinite lights; 0 for others), RGB.
std::vector<Vec3d> Le_rgb(const Light& light, const std::vector<Vec3d>& dirs);

// L leaving each point with the light's front normal toward each unit direction (area lights), RGB.
std::vector<Vec3d> L_rgb(const Light& light, const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                         const std::vector<Vec3d>& dirs);

// An area light's front normal of a triangle (ValueError for an index past its triangles).
Vec3d area_light_normal(const AreaLight& light, size_t triangle);

// An environment map's (u, v) of directions (normalised here), and the directions of (u, v) (finite).
std::vector<Vec2d> directions_to_uv(const EnvironmentLight& light, const std::vector<Vec3d>& dirs);
std::vector<Vec3d> uv_to_directions(const EnvironmentLight& light, const std::vector<Vec2d>& uv);

// One light chosen per number u in [0, 1), with the probability of choosing it (ValueError without lights).
struct LightChoices {
  std::vector<long long> index;
  std::vector<double> probability;
};
LightChoices sample_lights(const LightSampler& sampler, const std::vector<double>& u);

}  // namespace refracta
