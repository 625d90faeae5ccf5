// Astronomical refraction (issue 10): how much higher a star appears than it is, seen through a
// spherical atmosphere. The ray from the eye at apparent elevation e0 is traced through the
// height-only air over a spherical Earth (media/curved_earth.h: in flat coordinates, exact in
// the ray's vertical plane) by the stratified tracer, up to the top of the air (where it is
// uniform, so the ray then goes straight). There, at central angle phi = x'/R from the eye, the
// ray's elevation above the local horizon is e_top (the flattening is conformal), so its
// direction -- the star's, after the vacuum beyond the top (cos e = n_top cos e_top, Bouguer's
// invariant at the top's radius) -- lies at e - phi above the eye's horizon, and
//   refraction = e0 - (e - phi).
// Checked against the refraction integral R = -int (dn/dr) / n tan z dr with n r sin z constant
// (tests/rays/test_astronomical_refraction.py).
#pragma once

#include "refracta/core/parallel.h"
#include "refracta/media/curved_earth.h"  // kEarthRadius
#include "refracta/media/index_field.h"

#include <optional>
#include <vector>

namespace refracta {

struct AstronomicalRefractionOptions {
  double eye_height = 0.0;   // [m] above the ground (h = 0), below kSceneReach
  // The top of the air [m]: above it n is uniform (unset: the field's uniform_above(), e.g. 86 km
  // for PhysicalAtmosphere, or a metre above an eye higher than that; a field without one needs
  // it given).
  std::optional<double> top;
  double earth_radius = kEarthRadius;  // [m], the mean radius
  double tol = 1e-7;             // the tracer's position tolerance [m]

  void validate() const;
};

// Refraction [rad] of a star seen at `apparent_elevation` [rad] in [-pi/2, pi/2] through the
// height-only `field` (true heights: a base field, not a CurvedEarth). Throws std::invalid_argument
// for a field that is not height-only, an elevation outside the range, a top at or below the eye,
// or a ray that meets the ground (h = 0) before it leaves the air; NumericalError for a ray that
// cannot leave (ducted, or turned back where n drops to 1 above a low top).
double astronomical_refraction(const FieldPtr& field, double apparent_elevation,
                               const AstronomicalRefractionOptions& options);
// The same at many apparent elevations [rad], in parallel; options validated first.
std::vector<double> astronomical_refraction(const FieldPtr& field, const std::vector<double>& apparent_elevations,
                                            const AstronomicalRefractionOptions& options, WorkControl& control);

}  // namespace refracta
