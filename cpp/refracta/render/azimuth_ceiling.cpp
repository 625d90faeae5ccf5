// Highest geometry by azimuth about the eye (azimuth_ceiling.h).
#include "refracta/render/azimuth_ceiling.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace refracta {

namespace {

constexpr int kBins = 2048;      // 3.1 mrad each
constexpr int kNeighbours = 2;   // bins either side read by at()
constexpr double kTwoPi = 2.0 * kPi;

int bin_of(double azimuth) {  // azimuth in [-pi, pi]
  return std::clamp(int(std::floor((azimuth + kPi) / kTwoPi * kBins)), 0, kBins - 1);
}

double azimuth_of(const Vec3d& eye, const Vec3d& p) { return std::atan2(p.z() - eye.z(), p.x() - eye.x()); }

// Whether the triangle's horizontal projection holds the eye's (then every azimuth meets it).
bool around_eye(const Vec3d& eye, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  auto cross = [&](const Vec3d& p, const Vec3d& q) {
    return (q.x() - p.x()) * (eye.z() - p.z()) - (q.z() - p.z()) * (eye.x() - p.x());
  };
  const double ab = cross(a, b), bc = cross(b, c), ca = cross(c, a);
  return (ab >= 0.0 && bc >= 0.0 && ca >= 0.0) || (ab <= 0.0 && bc <= 0.0 && ca <= 0.0);
}

}  // namespace

AzimuthCeiling::AzimuthCeiling(const Scene& scene, const Vec3d& eye) {
  bins_.assign(kBins, -std::numeric_limits<double>::infinity());
  for (unsigned g = 0; g < scene.geometry_count(); ++g) {
    if (!scene.removed(g) && scene.terrain(g)) {
      bins_.assign(kBins, scene.highest());
      return;
    }
  }
  for (const SceneMesh& m : scene.meshes()) {
    if (scene.removed(m.geometry)) continue;
    const auto& v = m.mesh.vertices;
    for (const auto& t : m.mesh.triangles) {
      const Vec3d &a = v[t[0]], &b = v[t[1]], &c = v[t[2]];
      const double top = std::max({a.y(), b.y(), c.y()});
      if (around_eye(eye, a, b, c)) {
        raise(-kPi, kPi, top);
        continue;
      }
      // The smallest arc holding the three azimuths: the circle less its largest gap.
      std::array<double, 3> az = {azimuth_of(eye, a), azimuth_of(eye, b), azimuth_of(eye, c)};
      std::sort(az.begin(), az.end());
      const double gaps[3] = {az[1] - az[0], az[2] - az[1], az[0] + kTwoPi - az[2]};
      const int widest = int(std::max_element(gaps, gaps + 3) - gaps);
      if (widest == 2) {
        raise(az[0], az[2], top);
      } else {  // the arc runs from the gap's far end round through pi
        raise(az[widest + 1], az[widest] + kTwoPi, top);
      }
    }
  }
  for (unsigned g = 0; g < scene.geometry_count(); ++g) {
    const Scene::Spheres* spheres = scene.removed(g) || !scene.is_spheres(g) ? nullptr : scene.spheres(g);
    if (!spheres) continue;
    for (size_t i = 0; i < spheres->centres.size(); ++i) {
      const Vec3d& c = spheres->centres[i];
      const double r = spheres->radii[i], d = std::hypot(c.x() - eye.x(), c.z() - eye.z());
      const double mid = azimuth_of(eye, c);
      if (d <= r) {
        raise(-kPi, kPi, c.y() + r);
      } else {
        const double half = std::asin(r / d);
        raise(mid - half, mid + half, c.y() + r);
      }
    }
  }
}

void AzimuthCeiling::raise(double from, double to, double height) {
  if (to - from >= kTwoPi) from = -kPi, to = kPi;
  auto wrap = [](double a) { return a > kPi ? a - kTwoPi : a < -kPi ? a + kTwoPi : a; };
  const int first = bin_of(wrap(from)), last = bin_of(wrap(to));
  for (int k = first;; k = (k + 1) % kBins) {
    bins_[size_t(k)] = std::max(bins_[size_t(k)], height);
    if (k == last) break;
  }
}

double AzimuthCeiling::at(const Vec3d& dir) const {
  if (bins_.empty()) return std::numeric_limits<double>::infinity();
  const int centre = bin_of(std::atan2(dir.z(), dir.x()));
  double out = -std::numeric_limits<double>::infinity();
  for (int k = centre - kNeighbours; k <= centre + kNeighbours; ++k) out = std::max(out, bins_[size_t((k + kBins) % kBins)]);
  return out;
}

}  // namespace refracta
