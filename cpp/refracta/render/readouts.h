// Per-pixel readouts of a render (issue 20 section 3): what each pixel's camera path met and
// where it looks, extra channels of the one film loop (film.h) behind the radiance, albedo and
// normal. Per sample the renderer records the camera ray's direction at the eye and its first
// hit (SurfaceAovs); per pixel the film keeps the NEAREST hit among the samples (a foreground and
// a background in one pixel are never blended into a point in the air; deterministic, as every
// sample is seeded per pixel) with that sample's direction (the samples' mean where none hit),
// and this file turns them into angles and heights. Scene coordinates follow the geographic
// convention (x east, y up, z south;
// azimuth clockwise from north = -z); over a CurvedEarth they are its flat frame (x' = R phi,
// y' = R ln(1 + h/R), media/curved_earth.h), mapped back to the sphere where a straight line in
// the true geometry is meant.
#pragma once

#include "refracta/core/image.h"
#include "refracta/core/math.h"
#include "refracta/core/sampling.h"
#include "refracta/media/index_field.h"

#include <atomic>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace refracta {

// Channels of the readouts, after the 9 of radiance, albedo and normal (RenderOptions::readouts).
enum ReadoutChannel : int {
  kReadoutDistance = 0,           // path length along the camera path to the nearest sample's hit [m]; inf: none
  kReadoutPosition = 1,           // that hit's point, 3 channels [m]; NaN: none
  kReadoutObject = 4,             // its geometry id; -1: none
  kReadoutApparentElevation = 5,  // of the nearest hit's camera ray at the eye (none: the mean ray) [deg]
  kReadoutApparentAzimuth = 6,    // [deg] clockwise from north (-z), in [0, 360)
  kReadoutTrueElevation = 7,      // of the hit from the eye along a straight line in the true geometry [deg]
  kReadoutHiddenHeight = 8,       // hidden height at the hit's vertical: geometric, then refracted [m]
  kReadoutChannels = 10
};
static_assert(kReadoutHiddenHeight + 2 == kReadoutChannels, "the hidden heights are the last two channels");
constexpr int kSurfaceChannels = 9;  // radiance, albedo, normal

// Apparent elevation and azimuth [deg] of a scene direction (need not be unit).
Vec2d apparent_angles(const Vec3d& direction);

// The true length [m] of a camera path whose length in the scene's coordinates is `length`, from
// height y_start to y_end [m] with slopes dy/ds slope_start and slope_end there: over a CurvedEarth
// of radius earth_radius the flat frame scales lengths by r / R = e^(y'/R) (the conformal map's
// scale), integrated by Simpson's rule with the height at the middle from the cubic through the
// ends' heights and slopes. A ray's height is near quadratic in its length (its curvature varies
// little), so that middle is exact to third order; the mean of the ends' scales alone missed the
// ray's sag below its chord (d^2 / 8R ~ 170 m over 93 km): 1.5 m in 93 km (a trial). Unchanged on
// a flat Earth.
double true_path_length(double length, double y_start, double y_end, double slope_start, double slope_end,
                        double earth_radius);

// The derived readouts of one hit, for one render: true elevation and hidden heights.
class ReadoutGeometry {
 public:
  // eye: the camera position (scene frame); field: the render's air (null: none), its
  // earth_radius() the sphere's radius (infinite: a flat Earth); max_length [m]: how far the
  // grazing ray is traced; cancel: polled by its traces (Ctrl-C), or none. Traces the grazing ray
  // once (height-only air, or the field's height-only part; none: the refracted hidden height is
  // the geometric one).
  ReadoutGeometry(const Vec3d& eye, const IndexField* field, double max_length,
                  const std::atomic<bool>* cancel = nullptr);

  // Elevation [deg] of `point` seen from the eye along the straight line in the true geometry:
  // over a sphere both points are mapped from the flat frame back onto it (azimuthal equidistant
  // about the scene origin, true height h = R (e^(y'/R) - 1)) and the angle is taken against the
  // eye's local horizontal; over a flat Earth, the scene's straight line.
  double true_elevation(const Vec3d& point) const;
  // Without refraction: the true height below which the vertical through `point` (its radial
  // line) is hidden from the eye by the sphere's bulge -- the height where the eye's tangent to
  // the sphere crosses it, R (sec(theta - theta0) - 1) for a central angle theta beyond the
  // horizon's theta0 = acos(R / (R + h_eye)), 0 before it (and on a flat Earth).
  double hidden_geometric(const Vec3d& point) const;
  // With refraction: the true height on that vertical of the grazing ray, the lowest ray from the
  // eye that stays above the ground (y' = 0) for max_length of path (found by bisection on its
  // elevation to 1e-11 rad, traced by the stratified integrator to 1e-4 m); 0 up to where
  // it touches the ground;
  // NaN beyond its reach, with the eye at or below the ground, or where every ray from the eye
  // meets the ground (a duct).
  double hidden_refracted(const Vec3d& point) const;

  // The grazing ray's path: horizontal distance from the eye [m] and flat height y' [m] at its
  // nodes, and the horizontal distance where it touches (is lowest); empty if none.
  const std::vector<double>& grazing_distances() const { return r_; }

 private:
  Vec3d sphere_point(const Vec3d& flat) const;  // relative to the sphere's centre
  double true_height(double flat_y) const;

  Vec3d eye_;
  double radius_ = std::numeric_limits<double>::infinity();
  bool has_grazing_ = false;
  std::vector<double> r_, y_, slope_;  // the grazing ray's nodes: distance, height, dy/dr
  double touch_ = 0.0;                 // horizontal distance of its lowest node
};

// Mirage multiplicity: for each pixel that met a surface, how many images of the same point of it
// its column shows. Along each column, rows are cut into runs of consecutive rows meeting the same
// object (object id >= 0, finite true elevation), and each run into monotone branches of the true
// elevation (maximal stretches where it does not reverse; a turning row belongs to both branches
// it joins). A point seen at true elevation c has as many images as branches on the same object,
// in the same column, whose range of true elevations holds c (the transfer characteristic
// apparent -> true elevation has that many branches at c). 0 where the pixel met nothing.
// true_elevation and object_id: (H, W) images of one shape (else std::invalid_argument).
using FloatImage = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using CountImage = Eigen::Matrix<int32_t, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
CountImage mirage_images(const FloatImage& true_elevation, const FloatImage& object_id);

// Where each readout lies among a render's channels with readouts: (name, (first channel, count)),
// in channel order.
std::vector<std::pair<std::string, std::pair<int, int>>> readout_channels();

}  // namespace refracta
