// Camera rays through a turbulent layer, faster (issue 21 goal 1, RenderOptions::turbulence_trace
// 'perturbed'; its speed goals are not yet met: README, bench_realism.py shimmer_fast): the
// turbulent ray followed as its deviation from the calm ray (media/turbulence_path.h), in fixed
// steps of the turbulence's cells, its chords tested against the scene as it goes; where the calm
// path leaves the layer for good, the calm air's caster takes over from the deviated state (above
// the layer the air is the calm air exactly). The eye's ElevationTable says which rays reach the
// layer and where they leave it for good; the calm path of those is traced exactly (CalmPath, to
// the render's tol): the table's paths are only as close as a quarter of the pixel's footprint
// (10 cm at 300 m for 48 pixels across the hot road), where the layer's n changes over
// centimetres and the turbulence moves rays by millimetres -- following the table's path was most
// of the fast path's error (0.148 of the turbulence's effect; traced: one knife-edge pixel, 64
// samples of which agree with the strict trace to 2e-5, bench_realism.py shimmer_fast). Rays that
// never reach the layer are the calm caster's, exactly as the strict caster's legs give them.
// Over hot spots the calm air is not height-only and the table's paths are not its paths: every
// camera ray's calm path is traced whole (rk45 to tol, the strict integrator for such air), and the
// deviation feels the calm air's full gradient (turbulence_path.h). On the hot road under the
// README's spot, the mirage band's rows agree with the strict trace to 0.0002 (compact) and 0.048
// (gaussian: one knife-edge pixel) of the turbulence's effect, 30-35x faster (tests/render/test_shimmer.py).
//
// The small-perturbation criterion: nothing is linearised, but the deviation is followed in fixed
// steps with no error control, along the calm path, whose table was refined for the calm ray's
// geometry. That is sound while the turbulence perturbs the calm ray rather than replaces it: it
// falls back to the strict trace (the whole ray, rk45 under error control through the full field)
// when the turbulent ray's direction departs from the calm ray's by more than
// kLargeDeviation = 5 mrad -- comparable with a hot road mirage's whole bending (its critical
// angle, 0.31 deg = 5.4 mrad, examples.hot_road): a deflection that large decides which branch
// (direct or mirrored) the ray takes, so it is not a perturbation of the calm path. Tatarskii's
// geometric-optics angle-of-arrival variance ("Wave Propagation in a Turbulent Medium", 1961,
// ch. 6; for a point aperture 3.28 C_n^2 L l0^(-1/3) per axis, Andrews & Phillips 2005 ch. 6,
// refracta.turbulence.tilt_variance) puts the default hot-road turbulence (C_n^2 <= 1e-10, 300 m,
// l0 one 5 cm cell) at <= 0.5 mrad: the fast path serves its rays; one of C_n^2 = 1e-6 (~50 mrad)
// falls back (tests/render/test_shimmer.py).
//
// Lighting rays (renderer.cpp): a sample whose camera ray took the perturbed walk (not the strict
// fallback) casts its shadow and bounce rays through the calm air. They start on a surface and
// leave the layer within metres (its 0.69 m top: 1.4 m toward the hot road's 30-deg sun), turned
// by the default turbulence by ~0.05 mrad (trace_ray from the road: 0.053 mrad at 30 deg, 0.28 at
// 5 deg, 0.89 at 1 deg), against the sun disc's 4.65 mrad radius and a sky that changes over
// degrees: what that turn changes is a sample flipping at the disc's limb or a shadow's edge, and
// the blurred disc's irradiance is the disc's. The strict render does not show that at any
// practical spp: its sun samples are drawn inside the disc, so the turn can only push them out
// (~1 % of them: a 0.05 mrad rim of a 4.65 mrad disc, half outward), while light turned in from
// outside arrives only through BSDF samples landing by the disc's rim (estimated ~1e-7 of them).
// Measured (C_n^2 1e-10 on a 64^3 grid, the near road's rows 16-17 at 48 x 18, 64 spp): strict
// 0.20 % darker than with calm lighting on average (max 4.8 %), the turbulence's whole effect
// there 0.42 %; its camera rays hardly move there. The camera ray's own criterion
// (kLargeDeviation over its hundreds of metres in the layer) bounds its lighting rays' turn over
// their metres: where it falls back the sample is the strict one, lighting and all.
#pragma once

#include "refracta/media/index_field.h"
#include "refracta/media/turbulence.h"
#include "refracta/media/turbulence_path.h"
#include "refracta/rays/elevation_table.h"
#include "refracta/rays/trace_options.h"
#include "refracta/render/caster.h"
#include "refracta/render/render_options.h"
#include "refracta/scene/camera.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

// Fall back to the strict trace beyond this angle between the turbulent and the calm ray [rad] (above).
constexpr double kLargeDeviation = 5e-3;
// Steps through the layer where its envelope is small: a segment of the calm path whose lowest
// point's envelope E is below kFullStepEnvelope steps 2^floor(log2(kFullStepEnvelope / E)) times
// turbulence_step, at most kLongestStepStretch times. A longer step aliases the pattern's gradient
// (2 cells: 11-15 % of the displacement pixel by pixel with no envelope, tests/render/
// test_shimmer.py's wall), but there the turbulence is at most 5 % of its strength at the ground,
// so its share of a ray's deviation is small. Measured on the hot road (96 x 36, rows 16-36,
// default turbulence): the hit displacements' variance against the strict trace's 0.983-0.997 with
// and 0.982-0.997 without, pixel by pixel 2.9-5.6 % and 3.0-5.5 % of it; the image's error 0.0007
// and 0.0006 of the turbulence's effect (48 x 18, the knife-edge pixel aside); 1.4-2x faster on
// 160 x 60. Stretching from E < 0.2, up to 8: displacement error 7.4 % along the road.
constexpr double kFullStepEnvelope = 0.05;
constexpr double kLongestStepStretch = 4.0;
// The chords' tolerance in the layer, as a fraction of RenderOptions::sagitta (shimmer_cast.cpp walk).
constexpr double kLayerSagittaFraction = 0.1;

// A camera ray's calm path traced exactly as far as `length` [m], with the lowest height from each
// node on (ShimmerCaster's walk).
class CalmPath {
 public:
  CalmPath() = default;
  // Throws NumericalError where the trace does (n <= 0 or non-finite).
  CalmPath(const IndexField& calm, const TraceOptions& options, const Vec3d& eye, const Vec3d& dir, double length);
  size_t size() const { return nodes_.size(); }
  const RayNode<double>& node(size_t k) const { return nodes_[k]; }
  double lowest_from(size_t k) const { return lowest_[k]; }

 private:
  std::vector<RayNode<double>> nodes_;
  std::vector<double> lowest_;
};

// Why options.turbulence_trace 'perturbed' cannot serve a render through `field` from `camera`
// (empty: it can, or 'strict' or 'auto' was asked, or the field has no turbulence): the fast path follows
// the eye table's calm paths (renderer.cpp eye_table: calm air that is height-only or hot spots
// over such air, RGB, curved rays, the table on and stratified, a pinhole camera, paths over a
// spherical Earth no longer than kTableLongestPath). ShimmerCaster::make's rule; render() and animate() (Python)
// warn with it, as the render then traces strictly.
std::string perturbed_trace_refusal(const IndexField* field, const RenderOptions& options, const Camera& camera);
// Whether the render's camera rays take the perturbed trace: the field carries turbulence,
// turbulence_trace is 'perturbed' or 'auto', and nothing above refuses it.
bool perturbed_trace_serves(const IndexField* field, const RenderOptions& options, const Camera& camera);

class ShimmerCaster {
 public:
  // Null unless options.turbulence_trace is 'perturbed' or 'auto' and the fast path applies: a field
  // carrying turbulence whose calm part (the field without it) is `layered` (height-only) or hot
  // spots over it, camera rays served by the eye's `table`. Keeps references to its arguments.
  static std::unique_ptr<ShimmerCaster> make(const Scene& scene, const IndexField& field, const FieldPtr& layered,
                                             const ElevationTable* table, const Vec3d& eye, double pixel_angle,
                                             const std::optional<IorFloors>& floors, const RenderOptions& options);

  // The end of the camera ray from origin along unit dir (spread: the pixel's angle, as
  // Caster::cast); `strict` casts the rays the fast path hands back. `perturbed` (if given): true
  // where the ray was followed through the layer as a small deviation (the renderer then sends its
  // lighting rays through the calm air: above), false where it met the scene before the layer, never
  // entered it, or the strict trace served it.
  PathEnd cast(const Caster& strict, const Vec3d& origin, const Vec3d& dir, double spread,
               bool* perturbed = nullptr) const;
  // The calm air's caster (footprints of camera rays: their neighbours' calm paths).
  const Caster& calm() const { return calm_; }

  // `calm`: the field without its turbulence; `layered`: its height-only part (calm itself, the
  // same object, or the air under its hot spots).
  ShimmerCaster(const Scene& scene, FieldPtr calm, FieldPtr layered, std::shared_ptr<const Turbulence> turbulence,
                const ElevationTable* table, const Vec3d& eye, double pixel_angle, const RenderOptions& options);

 private:
  // The turbulent ray along the calm `path` from the eye; `truncated`: the path stops short of the
  // ray's end (the calm caster continues from the deviated state).
  PathEnd walk(const Caster& strict, const CalmPath& path, bool truncated, const Vec3d& origin, const Vec3d& dir,
               double spread, bool* perturbed) const;

  // How many times turbulence_step a segment of the calm path from a to b may step (envelope).
  double envelope_stretch(const RayNode<double>& a, const RayNode<double>& b) const;

  const Scene& scene_;
  FieldPtr calm_field_;  // the calm air: layered_, or hot spots over it (spotted_)
  FieldPtr layered_;
  bool spotted_;
  std::shared_ptr<const Turbulence> turbulence_;
  const ElevationTable* table_;
  Vec3d eye_;
  const RenderOptions& options_;
  Caster calm_;
  double top_, step_;
  DeviationStepper stepper_;
  TraceOptions trace_options_;
  bool stretch_steps_ = false;  // the exact calm paths' (the table's, to options.tol)
};

}  // namespace refracta
