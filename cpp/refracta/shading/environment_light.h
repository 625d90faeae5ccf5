// An equirectangular (latitude-longitude) environment map (shared/SHADING.md section 5): an
// infinite light at the end of every escaping ray (constant_environment.h: the uniform case).
//
// Sampling: a PiecewiseConstant2D over the W x (H - 1) bilinear patches, each weighted by the
// mean luminance of its four corner texels (the exact mean of the bilinear Y over the patch, and
// zero only where the radiance is zero) times the mean of sin(theta) over its rows; a point
// uniform in the patch; pdf_w = pdf_uv / (2 pi^2 sin theta). Spectral rendering: a texel's RGB c,
// m = max(c), gives m * reflectance_spectrum(c / m) * D65 (Color::illuminant's convention, applied
// at lookup time after the bilinear interpolation in RGB).
//
// Integrator: an escaping ray (or a shadow ray's exit direction in curved air) adds Le(dir);
// next-event estimation uses sample_li (distance = inf, p_light unused) and MIS with pdf_li(ctx,
// wi, ., .). power() is pi R^2 * integral of Y(L) over the sphere: call preprocess(centre, R)
// before building a LightSampler (R = 1 m until then, as Mitsuba's unit bounding sphere).
#pragma once

#include "refracta/core/image.h"
#include "refracta/shading/color.h"
#include "refracta/shading/light.h"

#include <Eigen/Core>

#include <atomic>
#include <string>
#include <vector>

namespace refracta {

using Mat3d = Eigen::Matrix3d;

// An equirectangular environment map (H, W, 3) of float linear RGB, rows top (up, +y) to
// bottom: radiance [W/(m^2 sr)] = scale x the map, rotated by rotation (degrees about +y or a
// 3 x 3 map-to-world matrix). Mitsuba 3's envmap orientation and interpolation
// (src/emitters/envmap.cpp): in the map's frame d = rotation^T x world direction,
// u = atan2(d.x, -d.z) / (2 pi) wrapped into [0, 1), v = acos(d.y) / pi; back: theta = pi v,
// phi = 2 pi u, d = (sin phi sin theta, cos theta, -cos phi sin theta). So u = 0 looks along -z,
// u = 1/4 along +x, u = 1/2 (the centre column) along +z. Column i is centred at u = (i + 1/2) / W
// and wraps around; row j is at v = j / (H - 1) (the first and last rows are the poles);
// radiance is bilinear between the four surrounding texels.
class EnvironmentLight final : public Light {
 public:
  // image: width >= 1, height >= 2, 1 (grey), 3 or 4 (alpha ignored) channels, every texel
  // finite and >= 0; scale finite >= 0; rotation a proper rotation (orthonormal to 1e-6, det +1).
  EnvironmentLight(const Image& image, double scale = 1.0, const Mat3d& rotation = Mat3d::Identity());

  LightType type() const override { return LightType::kInfinite; }
  std::optional<LightLiSample> sample_li(const LightSampleContext& ctx, const Vec2d& u,
                                         const SampledWavelengths& lambda) const override;
  double pdf_li(const LightSampleContext& ctx, const Vec3d& wi, const Vec3d& p_light,
                const Vec3d& n_light) const override;
  Spectrum Le(const Vec3d& dir, const SampledWavelengths& lambda) const override;
  double power() const override;
  void preprocess(const Vec3d& centre, double radius) override;
  std::string describe() const override;

  // The mapping above (world directions, unit).
  Vec2d direction_to_uv(const Vec3d& dir) const;
  Vec3d uv_to_direction(const Vec2d& uv) const;
  // scale * the bilinear RGB at (u, v).
  Vec3d rgb_at(const Vec2d& uv) const;
  // A rotation about +y by `degrees` (right-handed: +x turns toward -z), for the constructor.
  static Mat3d rotation_about_y(double degrees);
  // Throws (ValueError naming `what`) unless rotation is finite and a proper rotation.
  static void check_rotation(const Mat3d& rotation, const char* what);

  int width() const { return width_; }
  Image image() const;  // the texels as a float image (exact: they came from floats)
  const std::vector<Vec3d>& texels() const { return texels_; }  // RGB, row-major, top row first, unscaled
  // The image file the map was read from ("" for an array): pickling then refers to the file.
  const std::string& source() const { return source_; }
  void set_source(std::string path) { source_ = std::move(path); }
  int height() const { return height_; }
  double scale() const { return scale_; }
  const Mat3d& rotation() const { return rotation_; }

 private:
  // The sampling grid's coordinates: s = u - 1/(2W) wrapped, v; patch (i, j) = [i/W, (i+1)/W) x [j/(H-1), (j+1)/(H-1)).
  double u_to_s(double u) const;
  Spectrum spectrum_of(const Vec3d& rgb, const SampledWavelengths& lambda) const;

  int width_, height_;
  std::vector<Vec3d> texels_;  // row-major, top row first (not scaled)
  double scale_;
  Mat3d rotation_;
  std::string source_;
  PiecewiseConstant2D distribution_;
  Color white_;                // Color::illuminant(1, 1, 1): D65 in spectral rendering
  std::atomic<double> scene_radius_{1.0};  // preprocess writes it while other renders may read it
};

}  // namespace refracta
