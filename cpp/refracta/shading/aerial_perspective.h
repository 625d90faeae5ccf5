// Aerial perspective: the air between a viewer and what it sees dims that light and adds the
// sunlight the air scatters toward the viewer (DESIGN.md "One atmosphere, many uses"). The same
// scattering as the physical sky (physical_sky.h, Nishita et al. 1993) -- its coefficients,
// density profiles, phase functions (Rayleigh; Mie by Cornette-Shanks), ozone absorption and sun,
// and its multiple-scattering table (multiple_scattering.h, Hillaire 2020: sigma_s Psi_ms E added
// to every in-scatter, Psi_ms linear along a piece) -- integrated along a segment instead of to the
// top of the atmosphere, so that over a segment that leaves the air the in-scatter is the sky's
// radiance: a black object fades into exactly the sky behind it as its distance grows.
//
// A segment is integrated as its straight chord: the curved paths through the air bend by at most
// a few milliradians over the distances a scene spans, moving heights by metres against the
// densities' scale heights of 1.2 km (Mie) and 8 km (Rayleigh). The chord is cut into pieces
// (each at most kPieceHeight of height change, kPieceLength long); along a piece the relative
// densities are integrated in closed form (exponentials of a height linear along the piece, and
// the ozone tent), and the in-scatter is that piece's scattering column times the sunlight taken
// exponential between the piece's ends, attenuated within the piece in closed form: exact in
// uniform air (Koschmieder's law) and where the sun's optical depth is linear along a piece. The sun's transmittance to a point is
// that of its column (relative densities along the sun's path, the sky's quadrature) from a
// table over the point's height and the sun's elevation above its local horizon: columns vary
// smoothly where transmittances do not.
#pragma once

#include "refracta/core/math.h"
#include "refracta/core/spectrum.h"
#include "refracta/shading/air_optics.h"
#include "refracta/shading/physical_sky.h"

#include <array>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

namespace refracta {

// How scene coordinates sit on the sky's planet (radius 6371 km); the scene's y = 0 lies the
// sky's `altitude` above its sea level:
// - flat scenes (no field, or a field without an Earth radius): the planet's surface touches
//   y = 0 under the origin, so heights above it grow as rho^2 / 2R with horizontal distance rho --
//   the geometry of the sky's own rays, whose horizon radiance the in-scatter then tends to;
// - a CurvedEarth's flat frame (earth_radius finite): y is already the height above the curved
//   ground, and the local vertical at horizontal distance rho is tilted by rho / earth_radius.
struct AirFrame {
  double earth_radius = std::numeric_limits<double>::infinity();

  // Throws (ValueError) unless earth_radius > 0; infinity is the flat scene's frame.
  void validate() const;
  // Throws (ValueError naming `what`) unless a segment's ends a and b lie within the scene's reach
  // (kSceneReach), as every point a render reaches does.
  static void check_segment(const Vec3d& a, const Vec3d& b, const char* what);
};

// Aerial perspective of a physical sky: along a segment of air from a viewer at `a` to a point `b`
// [m] (scene coordinates; y = 0 lies the sky's `altitude` above sea level), the transmittance T and
// the scattered sunlight S the air adds (the sky's coefficients, densities, phase functions, ozone,
// sun and multiple-scattering table): what arrives at a is T L(b) + S. The
// chord is integrated in pieces in closed form (cpp/refracta/shading/aerial_perspective.h).
// earth_radius: a CurvedEarth's radius when the scene is its flat frame (y is then the height above
// the curved ground), inf for a flat scene (the sky's planet touches y = 0 under the origin).
// Scene.set_physical_sky(aerial_perspective=True) makes the renderers apply it to every segment.
class AerialPerspective {
 public:
  // scale multiplies the in-scatter, as it does the sky and the sun (set_physical_sky's scale).
  AerialPerspective(std::shared_ptr<const PhysicalSky> sky, double scale);

  static constexpr double kPieceHeight = 250.0;   // [m] height change along one piece at most
  static constexpr double kPieceLength = 10e3;    // [m] one piece's length at most (sun elevation turns)
  static constexpr int kMaxPieces = 256;

  struct Segment {
    Spectrum transmittance, inscatter;
  };
  // The air between a viewer at a and a point b [m]: what arrives at a from b is
  // transmittance * L(b) + inscatter. Spectral: at lambda's wavelengths, in-scatter in
  // W/(m^2 sr nm) like the sky's Le. RGB: in-scatter in linear sRGB (the sky's Le convention), and
  // the transmittance per channel of a D65-white radiance (rgb(D65 T) / rgb(D65), clamped to [0, 1]).
  Segment along(const Vec3d& a, const Vec3d& b, const AirFrame& frame, const SampledWavelengths& lambda) const;
  // Transmittance alone (shadow rays toward finite lights).
  Spectrum transmittance(const Vec3d& a, const Vec3d& b, const AirFrame& frame, const SampledWavelengths& lambda) const;

  // At one wavelength in [360, 830] nm: (transmittance, in-scatter x scale) as along computes them,
  // and the brute-force reference of the same in-scatter integral: the midpoint rule with `steps`
  // points on the chord, the extinction integrated numerically, every point's sun column traced
  // (4x the sky's quadrature steps, no table) and its multiple scattering from the sky's table.
  std::pair<double, double> along_at(const Vec3d& a, const Vec3d& b, const AirFrame& frame, double lambda_nm) const;
  double inscatter_reference(const Vec3d& a, const Vec3d& b, const AirFrame& frame, double lambda_nm, int steps) const;
  // The sun's transmittance [0, 1] from the top of the atmosphere to height h [m] where it stands
  // `elevation` [rad] above the local horizon (0 where the planet hides it), from the table.
  double sun_transmittance(double height, double elevation, double lambda_nm) const;

  const PhysicalSky& sky() const { return *sky_; }
  double scale() const { return scale_; }

  // A point's height above the sky's sea level [m] and its local vertical (unit).
  struct Located {
    double height;
    Vec3d up;
  };
  Located locate(const Vec3d& p, const AirFrame& frame) const;

 private:
  // The optical data of the wavelengths one integration runs over.
  struct Bands {
    int count = 0;
    std::array<double, air_optics::kNodes> rayleigh{}, ozone{}, irradiance{};  // [1/m], [m^2 1/m^3], [W/(m^2 nm)]
    std::array<double, air_optics::kNodes> lambda{};  // [nm]
    bool at_nodes = false;  // the 48 node wavelengths, in order
  };
  // The sky's multiple-scattering Psi_ms [1/sr] at a point, per band.
  void psi_of(const Located& x, const Bands& bands, double* psi) const;
  Bands bands_at(const double* lambda_nm, int count) const;
  // Integrates the chord a -> b over `bands`: transmittance T and in-scatter S (x scale) per band.
  Bands bands_of(const SampledWavelengths& lambda) const;
  Spectrum rgb_transmittance(const double* transmittance_at_nodes) const;
  void integrate(const Vec3d& a, const Vec3d& b, const AirFrame& frame, const Bands& bands, bool inscatter, double* T,
                 double* S) const;
  // Moves a and b to the ends of the part of their chord below the atmosphere's top (kTop); false
  // when none of it is. Above the top there is no air: the pieces are spent where there is.
  bool clip_to_air(Vec3d* a, Vec3d* b, const AirFrame& frame) const;
  // Table coordinates of a (height, sun elevation).
  struct TableCell {
    int h0, e0;
    double th, te;
  };
  TableCell cell(double height, double elevation) const;
  air_optics::Column sun_column_at(const TableCell& c) const;  // bilinear in the table
  // The sun's transmittance through `column` in one band.
  double sun_at(const air_optics::Column& column, const Bands& bands, int band) const;

  std::shared_ptr<const PhysicalSky> sky_;
  double scale_;
  air_optics::AirComposition air_;
  double altitude_;
  Vec3d sun_;
  Bands nodes_;                                  // the sky's 48 wavelengths (RGB)
  std::array<Vec3d, air_optics::kNodes> rgb_weight_{};  // linear sRGB of a unit spectrum at each node
  std::array<Vec3d, air_optics::kNodes> d65_weight_{};  // rgb_weight_ x D65 (normalised) at each node
  Vec3d rgb_of_d65_ = Vec3d::Ones();             // rgb of the D65 spectrum at the nodes
  std::vector<air_optics::Column> sun_columns_;  // [height][elevation]: the sun's path to the top
};

}  // namespace refracta
