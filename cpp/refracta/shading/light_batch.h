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
// Samples a direction toward the light from each point (Light.sample_li).
//
// points: (N, 3) [m]; normals: (N, 3) unit geometric normals (rows may be 0) or None; u: (N, 2) in
// [0, 1). Returns (wi (N, 3) unit toward the light, L (N, 3) RGB radiance arriving [W/(m^2 sr)]
// (point and spot: I/r^2), pdf (N,) per steradian (delta lights: 1), distance (N,) [m] (infinite
// lights: inf)). A point the light cannot reach gets wi = 0, L = 0, pdf = 0, distance = 0.
RgbLightSamples sample_li_rgb(const Light& light, const std::vector<LightSampleContext>& contexts,
                              const std::vector<double>& u);

// The solid-angle density (N,) with which sample_li picks unit wi (N, 3) at points (N, 3). Area
// lights need the point p_light (N, 3) where the ray along wi hits the light and its normal
// n_light (N, 3) (each empty: zeros; else one per point).
std::vector<double> pdf_li_all(const Light& light, const std::vector<LightSampleContext>& contexts,
                               const std::vector<Vec3d>& wi, const std::vector<Vec3d>& p_light,
                               const std::vector<Vec3d>& n_light);

// Infinite lights: RGB radiance (N, 3) seen looking along unit dirs (N, 3); 0 for others.
std::vector<Vec3d> Le_rgb(const Light& light, const std::vector<Vec3d>& dirs);

// Area lights: RGB radiance (N, 3) leaving points (N, 3) with the light's front normals (N, 3)
// toward unit dirs (N, 3).
std::vector<Vec3d> L_rgb(const Light& light, const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                         const std::vector<Vec3d>& dirs);

// The front normal of an area light's triangle (unit; 0 for a zero-area one; ValueError for an
// index past its triangles).
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
