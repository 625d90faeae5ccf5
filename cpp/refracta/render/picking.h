// Straight rays over a spherical Earth, and the scene point a pixel sees.
#pragma once

#include "refracta/scene/camera.h"
#include "refracta/media/index_field.h"
#include "refracta/scene/embree_scene.h"

#include <optional>
#include <vector>

namespace refracta {

// The air straight rays cross: none over a flat Earth (field null, or without an Earth radius);
// over a field with an Earth radius R -- a CurvedEarth's flat frame, where y is the height above
// the curved ground -- uniform air (n = 1) over that Earth, whose paths in the flat frame are the
// straight lines of the true geometry: the bulge of the Earth still hides what lies beyond the
// horizon (refracta.without_refraction gives the same field).
FieldPtr straight_air(const IndexField* field);

// The scene point seen at film position (u, v) [pixels] of `camera`: along the straight ray when
// field is null, else along the path through `field` (the render's curved caster, default
// options), at most max_length [m] long (nullopt: as far from the eye as scene coordinates go,
// kSceneReach); nullopt where the ray meets nothing. Throws (ValueError) for a max_length <= 0 or
// one that would leave the scene's reach.
std::optional<Vec3d> picked_point(const Scene& scene, const Camera& camera, const FieldPtr& field, double u, double v,
                                  std::optional<double> max_length);

// (u, v, depth) of each scene point as Camera::project gives it, but over a spherical Earth of
// `earth_radius` [m] (the scene a CurvedEarth's flat frame; inf: Camera::project itself) along the
// true geometry's straight lines: where picked_point through straight_air finds the point (its
// inverse; exact for an eye above the frame's origin, where every ray's vertical plane holds the
// origin, as the flattening assumes). depth [m] along the view axis in the true geometry, <= 0
// behind.
std::vector<Vec3d> projected_over_sphere(const Camera& camera, double earth_radius, std::vector<Vec3d> points);

}  // namespace refracta
