// Energy-normalised Blinn-Phong BRDF (Blinn 1977; normalisation (ns + 8)/(8 pi), Akenine-Moller
// et al., Real-Time Rendering 4th ed., eq. 9.71): f = kd/pi + ks (ns + 8)/(8 pi) (n.h)^ns.
#pragma once

#include "refracta/core/math.h"
#include "refracta/scene/material.h"

#include <cmath>

namespace refracta {

// wo, wi: unit directions away from the surface; n: unit normal on the side of wo.
inline Vec3d blinn_phong(const Material& m, const Vec3d& n, const Vec3d& wo, const Vec3d& wi) {
  Vec3d f = m.kd / kPi;
  if (m.ks.maxCoeff() > 0.0) {
    const Vec3d h = (wo + wi).normalized();
    f += m.ks * ((m.ns + 8.0) / (8.0 * kPi) * std::pow(std::max(n.dot(h), 0.0), m.ns));
  }
  return f;
}

}  // namespace refracta
