// The Trowbridge-Reitz (GGX) microfacet distribution, isotropic or anisotropic (shared/SHADING.md
// section 2; Walter et al. 2007; pbrt-v4 TrowbridgeReitzDistribution). Local frame: z = normal,
// alpha_x along x (the surface's s tangent), alpha_y along y.
//
// Masking-shadowing: refracta uses the HEIGHT-CORRELATED Smith function
// G2 = 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014, "Understanding the Masking-Shadowing
// Function in Microfacet-Based BRDFs", JCGT 3(2), eq. 99), as pbrt-v4 does. Mitsuba 3 uses the
// separable G1(wo) G1(wi), which is larger by up to a few percent at grazing angles; comparisons
// allow that difference. Sampling: visible normals (Heitz 2018, "Sampling the GGX Distribution
// of Visible Normals", JCGT 7(4)), pdf D_wo(m) = G1(wo) |wo.m| D(m) / |cos theta_o|.
#pragma once

#include "refracta/core/error.h"
#include "refracta/core/math.h"
#include "refracta/core/sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

// The GGX microfacet distribution: D, Lambda, G1, height-correlated G, the visible-normal density
// and sampler. Directions: (N, 3) unit vectors in the local frame.
class TrowbridgeReitz {
 public:
  // Roughness below kMinAlpha is raised to it: narrower lobes put D beyond what double-precision
  // directions resolve (D peaks at 1/(pi alpha^2)); use the smooth materials for mirrors.
  static constexpr double kMinAlpha = 1e-4;
  // Roughness above this is refused: slopes ~100 (facets within 0.6 deg of vertical) are no surface,
  // and alpha = 1e300 was taken and reflected nothing (its D and G underflow).
  static constexpr double kMaxAlpha = 100.0;

  // Validates alpha (finite, in [0, kMaxAlpha]; `name` goes into the message) and applies the clamp.
  static double checked_alpha(double alpha, const char* name) {
    if (!std::isfinite(alpha) || alpha < 0.0) throw_invalid(name, " must be finite and >= 0 (got ", alpha, ")");
    if (alpha > kMaxAlpha) throw_invalid(name, " must be at most ", kMaxAlpha, " (got ", alpha, ")");
    return std::max(alpha, kMinAlpha);
  }

  TrowbridgeReitz() = default;
  TrowbridgeReitz(double alpha_x, double alpha_y) : alpha_x_(alpha_x), alpha_y_(alpha_y) {}

  double alpha_x() const { return alpha_x_; }
  double alpha_y() const { return alpha_y_; }

  // D(m): microfacet normals per unit solid angle and unit area; int D(m) cos theta_m dm = 1.
  double D(const Vec3d& m) const {
    if (!(m.z() > 0.0)) return 0.0;  // facets face out of the surface
    const double cos2 = m.z() * m.z();
    const double sin2 = std::max(0.0, 1.0 - cos2);
    const double tan2 = sin2 / cos2;
    if (std::isinf(tan2)) return 0.0;
    double cos2_phi = 1.0, sin2_phi = 0.0;
    if (sin2 > 0.0) {
      cos2_phi = m.x() * m.x() / sin2;
      sin2_phi = m.y() * m.y() / sin2;
    }
    const double e = tan2 * (cos2_phi / (alpha_x_ * alpha_x_) + sin2_phi / (alpha_y_ * alpha_y_));
    return 1.0 / (kPi * alpha_x_ * alpha_y_ * cos2 * cos2 * (1.0 + e) * (1.0 + e));
  }

  // Smith's Lambda(w) = (-1 + sqrt(1 + alpha(w)^2 tan^2 theta)) / 2.
  double lambda(const Vec3d& w) const {
    const double cos2 = w.z() * w.z();
    const double sin2 = std::max(0.0, 1.0 - cos2);
    if (!(cos2 > 0.0)) return std::numeric_limits<double>::infinity();
    const double tan2 = sin2 / cos2;
    const double alpha2 = sin2 > 0.0 ? (w.x() * w.x() * alpha_x_ * alpha_x_ + w.y() * w.y() * alpha_y_ * alpha_y_) / sin2
                                     : alpha_x_ * alpha_x_;
    return 0.5 * (std::sqrt(1.0 + alpha2 * tan2) - 1.0);
  }
  double G1(const Vec3d& w) const { return 1.0 / (1.0 + lambda(w)); }
  // Height-correlated masking-shadowing (Heitz 2014).
  double G(const Vec3d& wo, const Vec3d& wi) const { return 1.0 / (1.0 + lambda(wo) + lambda(wi)); }
  // Separable masking-shadowing G1(wo) G1(wi) (Mitsuba 3's choice; used by the Principled BRDF
  // as disney.brdf writes it).
  double G_separable(const Vec3d& wo, const Vec3d& wi) const { return G1(wo) * G1(wi); }

  // The distribution of normals visible from w, D_w(m) = G1(w) |w.m| D(m) / |cos theta_w|; it is
  // the density (per solid angle of m) of sample_wm(w, u).
  // The density of sample_wm (the rough dielectric lobe's name for it, as Beckmann's).
  double sampling_pdf(const Vec3d& w, const Vec3d& m) const { return D_visible(w, m); }
  double D_visible(const Vec3d& w, const Vec3d& m) const {
    const double cos_w = std::abs(w.z());
    if (!(cos_w > 0.0)) return 0.0;
    return G1(w) / cos_w * D(m) * std::abs(w.dot(m));
  }

  // A microfacet normal (z > 0) visible from w, by Heitz 2018: stretch w into the hemisphere
  // configuration, sample the projected disc of visible normals, unstretch. w below the surface
  // is mirrored first (the distribution is symmetric).
  Vec3d sample_wm(const Vec3d& w, const Vec2d& u) const {
    Vec3d wh = Vec3d(alpha_x_ * w.x(), alpha_y_ * w.y(), w.z()).normalized();
    if (wh.z() < 0.0) wh = -wh;
    const Vec3d t1 = wh.z() < 0.99999 ? Vec3d::UnitZ().cross(wh).normalized() : Vec3d::UnitX();
    const Vec3d t2 = wh.cross(t1);
    Vec2d p = sample_uniform_disk_concentric(u);
    const double h = std::sqrt(std::max(0.0, 1.0 - p.x() * p.x()));
    const double s = 0.5 * (1.0 + wh.z());
    p.y() = (1.0 - s) * h + s * p.y();
    const double pz = std::sqrt(std::max(0.0, 1.0 - p.squaredNorm()));
    const Vec3d nh = p.x() * t1 + p.y() * t2 + pz * wh;
    return Vec3d(alpha_x_ * nh.x(), alpha_y_ * nh.y(), std::max(1e-6, nh.z())).normalized();
  }

 private:
  double alpha_x_ = 0.5, alpha_y_ = 0.5;
};

}  // namespace refracta
