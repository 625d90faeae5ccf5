// The environment map (environment_light.h).
#include "refracta/shading/environment_light.h"

#include "refracta/core/frame.h"
#include "refracta/shading/light_common.h"

namespace refracta {

namespace {
// How far from orthonormal a rotation may be: float-precision matrices from files and numpy.
constexpr double kRotationTolerance = 1e-6;
}  // namespace

// ---- EnvironmentLight --------------------------------------------------------------------

void EnvironmentLight::check_rotation(const Mat3d& rotation, const char* what) {
  for (int i = 0; i < 9; ++i) {
    if (!std::isfinite(rotation.data()[i])) throw_invalid(what, " must be finite");
  }
  const double off = (rotation.transpose() * rotation - Mat3d::Identity()).cwiseAbs().maxCoeff();
  if (!(off <= kRotationTolerance) || !(rotation.determinant() > 0.0)) {
    throw_invalid(what, " must be a proper rotation (orthonormal, det +1); |R^T R - I| = ", off,
                  ", det = ", rotation.determinant());
  }
}

EnvironmentLight::EnvironmentLight(const Image& image, double scale, const Mat3d& rotation)
    : width_(image.width), height_(image.height), scale_(scale), rotation_(rotation) {
  if (image.width < 1 || image.height < 2) throw_invalid("EnvironmentLight: image must be at least 1 x 2 texels (got ", image.width, " x ", image.height, ")");
  const int c = image.channels;
  if (c != 1 && c != 3 && c != 4) throw_invalid("EnvironmentLight: image must have 1, 3 or 4 channels (got ", c, ")");
  if (image.pixels.size() != size_t(image.width) * image.height * c) throw_invalid("EnvironmentLight: image has ", image.pixels.size(), " values for ", image.width, " x ", image.height, " x ", c);
  detail::check_non_negative(scale, "EnvironmentLight: scale");
  check_rotation(rotation, "EnvironmentLight: rotation");
  texels_.resize(size_t(width_) * height_);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const float* p = image.at(x, y);
      const Vec3d rgb = c == 1 ? Vec3d::Constant(p[0]) : Vec3d(p[0], p[1], p[2]);
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(rgb[k]) || rgb[k] < 0.0) {
          throw_invalid("EnvironmentLight: image texel (row ", y, ", column ", x, ") must be finite and >= 0 (got ", rgb[k], ")");
        }
      }
      texels_[size_t(y) * width_ + x] = rgb;
    }
  }
  // The sampling density over the W x (H - 1) bilinear patches.
  const int nu = width_, nv = height_ - 1;
  const double dtheta = kPi / nv;
  std::vector<double> weights(size_t(nu) * nv);
  for (int j = 0; j < nv; ++j) {
    const double mean_sin = (std::cos(j * dtheta) - std::cos((j + 1) * dtheta)) / dtheta;
    for (int i = 0; i < nu; ++i) {
      const int i1 = (i + 1) % width_;
      const double y = detail::luminance(texels_[size_t(j) * width_ + i]) + detail::luminance(texels_[size_t(j) * width_ + i1]) +
                       detail::luminance(texels_[size_t(j + 1) * width_ + i]) + detail::luminance(texels_[size_t(j + 1) * width_ + i1]);
      weights[size_t(j) * nu + i] = 0.25 * y * mean_sin;
    }
  }
  distribution_ = PiecewiseConstant2D(weights, nu, nv);
  white_ = Color::illuminant(Vec3d::Ones());
}

Mat3d EnvironmentLight::rotation_about_y(double degrees) {
  if (!std::isfinite(degrees)) throw_invalid("EnvironmentLight: rotation angle must be finite (got ", degrees, ")");
  const double a = degrees_to_radians(degrees), c = std::cos(a), s = std::sin(a);
  Mat3d r;
  r << c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c;
  return r;
}

Vec2d EnvironmentLight::direction_to_uv(const Vec3d& dir) const {
  const Vec3d d = rotation_.transpose() * dir;
  double u = std::atan2(d.x(), -d.z()) / (2.0 * kPi);
  u -= std::floor(u);
  if (u >= 1.0) u = 0.0;
  return Vec2d(u, std::acos(std::clamp(d.y(), -1.0, 1.0)) / kPi);
}

Vec3d EnvironmentLight::uv_to_direction(const Vec2d& uv) const {
  const double theta = kPi * uv.y(), phi = 2.0 * kPi * uv.x();
  const double st = std::sin(theta);
  return rotation_ * Vec3d(std::sin(phi) * st, std::cos(theta), -std::cos(phi) * st);
}

double EnvironmentLight::u_to_s(double u) const {
  double s = u - 0.5 / width_;
  s -= std::floor(s);
  return s >= 1.0 ? 0.0 : s;
}

Vec3d EnvironmentLight::rgb_at(const Vec2d& uv) const {
  const double x = u_to_s(uv.x()) * width_;
  const double y = std::clamp(uv.y(), 0.0, 1.0) * (height_ - 1);
  const int ix = std::min(int(x), width_ - 1), iy = std::min(int(y), height_ - 2);
  const double fx = x - ix, fy = y - iy;
  const int ix1 = (ix + 1) % width_;
  const Vec3d& a = texels_[size_t(iy) * width_ + ix];
  const Vec3d& b = texels_[size_t(iy) * width_ + ix1];
  const Vec3d& c = texels_[size_t(iy + 1) * width_ + ix];
  const Vec3d& d = texels_[size_t(iy + 1) * width_ + ix1];
  return scale_ * ((1.0 - fy) * ((1.0 - fx) * a + fx * b) + fy * ((1.0 - fx) * c + fx * d));
}

Spectrum EnvironmentLight::spectrum_of(const Vec3d& rgb, const SampledWavelengths& lambda) const {
  if (!lambda.spectral) return Spectrum(rgb.x(), rgb.y(), rgb.z(), 0.0);
  const double m = rgb.maxCoeff();
  if (!(m > 0.0)) return Spectrum::Zero();
  return m * reflectance_spectrum(rgb / m, lambda) * white_.sample(lambda);
}

std::optional<LightLiSample> EnvironmentLight::sample_li(const LightSampleContext& /*ctx*/, const Vec2d& u,
                                                         const SampledWavelengths& lambda) const {
  if (!(distribution_.integral() > 0.0) || scale_ == 0.0) return std::nullopt;  // a black map
  double pdf_uv = 0.0;
  const Vec2d sv = distribution_.sample(u, &pdf_uv);
  if (!(pdf_uv > 0.0)) return std::nullopt;
  double um = sv.x() + 0.5 / width_;
  if (um >= 1.0) um -= 1.0;
  const Vec2d uv(um, sv.y());
  const double theta = kPi * uv.y(), phi = 2.0 * kPi * uv.x();
  const Vec3d d(std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta));
  const double sin_theta = std::sqrt(d.x() * d.x() + d.z() * d.z());
  if (!(sin_theta > 0.0)) return std::nullopt;
  LightLiSample s;
  s.wi = rotation_ * d;
  s.pdf = pdf_uv / (2.0 * kPi * kPi * sin_theta);
  if (!std::isfinite(s.pdf)) return std::nullopt;
  s.L = spectrum_of(rgb_at(uv), lambda);
  return s;
}

double EnvironmentLight::pdf_li(const LightSampleContext& /*ctx*/, const Vec3d& wi, const Vec3d&, const Vec3d&) const {
  if (!(distribution_.integral() > 0.0) || scale_ == 0.0) return 0.0;
  const Vec3d d = rotation_.transpose() * wi;
  // At the map's poles the density in solid angle diverges (sin theta -> 0) wherever the pole's row
  // has light: there it is taken as a finite stand-in for infinity, never 0 -- a BSDF sample exactly
  // at the zenith was weighted fully against light sampling, and render_raster, whose first sample
  // of a level surface is its normal, lit a floor under a bright zenith 3.7x too bright (a trial).
  constexpr double kPoleSine = 1e-12;
  const double sin_theta = std::max(std::sqrt(d.x() * d.x() + d.z() * d.z()), kPoleSine);
  const Vec2d uv = direction_to_uv(wi);
  const double pdf = distribution_.pdf(Vec2d(u_to_s(uv.x()), uv.y())) / (2.0 * kPi * kPi * sin_theta);
  return std::isfinite(pdf) ? pdf : 0.0;
}

Spectrum EnvironmentLight::Le(const Vec3d& dir, const SampledWavelengths& lambda) const {
  return spectrum_of(rgb_at(direction_to_uv(dir)), lambda);
}

double EnvironmentLight::power() const {
  // integral of Y over the sphere = 2 pi^2 * integral over [0,1]^2 of Y(u, v) sin(theta) du dv.
  const double r = scene_radius_;  // one load: another render's preprocess may write it
  return kPi * r * r * 2.0 * kPi * kPi * scale_ * distribution_.integral();
}

void EnvironmentLight::preprocess(const Vec3d& centre, double radius) {
  detail::check_point(centre, "EnvironmentLight.preprocess: centre");
  scene_radius_ = detail::check_positive(radius, "EnvironmentLight.preprocess: radius");
}

std::string EnvironmentLight::describe() const {
  // What tells two maps apart: their file (or size), scale and turn.
  std::string out = source_.empty() ? concat("EnvironmentLight(", width_, " x ", height_, " texels")
                                    : concat("EnvironmentLight('", source_, "', ", width_, " x ", height_, " texels");
  out += concat(", scale=", scale_);
  if (!rotation_.isIdentity(0.0)) {
    out += ", rotation=[";
    for (int r = 0; r < 3; ++r) out += concat(r ? ", [" : "[", rotation_(r, 0), ", ", rotation_(r, 1), ", ", rotation_(r, 2), "]");
    out += "]";
  }
  return out + ")";
}

Image EnvironmentLight::image() const {
  Image out(width_, height_, 3);
  for (size_t i = 0; i < texels_.size(); ++i) {
    for (int k = 0; k < 3; ++k) out.pixels[3 * i + size_t(k)] = float(texels_[i][k]);
  }
  return out;
}

}  // namespace refracta
