// A pool of casters and integrators for spectral renders through dispersive air (hero_casters.h).
#include "refracta/render/hero_casters.h"

#include "refracta/core/parallel.h"
#include "refracta/core/spectrum.h"
#include "refracta/media/dispersed_field.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace refracta {

// A dispersed air, its caster and integrator: built once, never moved (the integrator holds the
// caster by reference, the caster the air).
struct HeroCasters::Hero {
  explicit Hero(const HeroCasters& owner)
      : scale(std::make_shared<double>(1.0)),
        air(tunable_dispersed_field(owner.field_, scale)),
        caster(owner.scene_.geometry, air.get(), owner.options_) {
    if (owner.floors_) caster.set_ior_floors(*owner.floors_);
    caster.set_secondary_spread(owner.spread_);
    integrator = make_integrator(owner.scene_, caster, owner.options_);
    integrator->lighting().use_raised_sky(owner.raised_sky_);
    if (owner.lowest_launches_ || owner.sun_exits_) {
      integrator->lighting().use_sun_tables(owner.lowest_launches_, owner.sun_exits_, scale);
    }
  }

  std::shared_ptr<double> scale;  // K(hero) / K(reference), read by `air` at every evaluation
  FieldPtr air;
  Caster caster;
  std::unique_ptr<Integrator> integrator;
};

HeroCasters::HeroCasters(const RenderScene& scene, FieldPtr field, const RenderOptions& options,
                         std::optional<IorFloors> floors, double spread, std::shared_ptr<const RaisedSky> raised_sky)
    : scene_(scene),
      field_(std::move(field)),
      options_(options),
      floors_(std::move(floors)),
      spread_(spread),
      reference_(field_reference_wavelength(*field_)),
      raised_sky_(std::move(raised_sky)) {
  // The lowest launches at SpectralEyeTables' dispersion scales (2.4e-3 of n - 1 apart), each
  // scale's air cast as a hero's is (DirectLighting::launch_below_horizon's sun over a sphere).
  if (scene.sun() == nullptr || !field_->height_only() || !std::isfinite(field_->earth_radius())) return;
  const double lo = air_dispersion_scale(kLambdaMax, reference_), hi = air_dispersion_scale(kLambdaMin, reference_);
  constexpr int kScales = SpectralEyeTables::kScales;
  std::vector<FieldPtr> airs;
  std::vector<std::unique_ptr<Caster>> casters;
  std::vector<const Caster*> views;
  std::vector<double> scales;
  for (int k = 0; k < kScales; ++k) {
    const double s = k + 1 == kScales ? hi : lo + (hi - lo) * k / (kScales - 1);
    airs.push_back(tunable_dispersed_field(field_, std::make_shared<const double>(s)));
    casters.push_back(std::make_unique<Caster>(scene.geometry, airs.back().get(), options));
    if (floors_) casters.back()->set_ior_floors(*floors_);
    casters.back()->set_secondary_spread(spread);
    views.push_back(casters.back().get());
    scales.push_back(s);
  }
  lowest_launches_ = LowestLaunches::build(scene.geometry, views, scales);
  // The sun's exit map at the two extreme scales: a path's refraction is linear in the air's n - 1
  // to first order, and the scales span 2.4 % of it.
  sun_exits_ = SunExitMap::build(scene.geometry, {airs.front().get(), airs.back().get()},
                                 {scales.front(), scales.back()}, field_, options, spread, *scene.sun());
}

HeroCasters::~HeroCasters() = default;

HeroCasters::Lease HeroCasters::for_wavelength(double wavelength_nm) const {
  const double scale = air_dispersion_scale(wavelength_nm, reference_);
  std::unique_ptr<Hero> hero;
  if (!idle_.try_pop(hero)) hero = std::make_unique<Hero>(*this);
  *hero->scale = scale;
  return Lease(*this, std::move(hero));
}

HeroCasters::Lease::Lease(const HeroCasters& pool, std::unique_ptr<Hero> hero) : pool_(pool), hero_(std::move(hero)) {}

HeroCasters::Lease::Lease(Lease&& other) noexcept : pool_(other.pool_), hero_(std::move(other.hero_)) {}

HeroCasters::Lease::~Lease() {
  if (hero_) pool_.idle_.push(std::move(hero_));  // (a lease moved from holds none)
}

const Caster& HeroCasters::Lease::caster() const { return hero_->caster; }

const Integrator& HeroCasters::Lease::integrator() const { return *hero_->integrator; }

double HeroCasters::Lease::scale() const { return *hero_->scale; }

// One dispersion scale's air, its caster (its eye table's escape and camera rays) and table.
struct SpectralEyeTables::Slice {
  Slice(const RenderScene& scene, const FieldPtr& field, const RenderOptions& options,
        const std::optional<IorFloors>& floors, double spread, double s)
      : scale(s), air(tunable_dispersed_field(field, std::make_shared<const double>(s))),
        caster(scene.geometry, air.get(), options) {
    if (floors) caster.set_ior_floors(*floors);
    caster.set_secondary_spread(spread);
  }
  double scale;
  FieldPtr air;
  Caster caster;
  std::unique_ptr<ElevationTable> table;
};

SpectralEyeTables::SpectralEyeTables(const RenderScene& scene, const FieldPtr& field, const RenderOptions& options,
                                     const std::optional<IorFloors>& floors, const Vec3d& eye, double spread,
                                     bool escape, const TableFactory& make_table)
    : options_(options), eye_(eye) {
  const double reference = field_reference_wavelength(*field);
  const double lo = air_dispersion_scale(kLambdaMax, reference), hi = air_dispersion_scale(kLambdaMin, reference);
  // The scales' tables built side by side (each is a pure function of its scale; a table's own
  // traces run in parallel, but its refinement levels, its height tabulation and its stencils do
  // not: one after another the 16 tables kept a second core idle for ~half their time).
  std::vector<std::unique_ptr<Slice>> slices(static_cast<size_t>(kScales));
  WorkControl control;  // the caller's cancel flags stay in force (parallel_for_each)
  parallel_for_each(kScales, 1, control, [&](int64_t k) {
    const double s = k + 1 == kScales ? hi : lo + (hi - lo) * double(k) / (kScales - 1);
    auto slice = std::make_unique<Slice>(scene, field, options, floors, spread, s);
    PlaneEscape plane_escape;
    if (escape) {
      plane_escape = [caster = &slice->caster, spread](const RayNode<double>& node, double remaining) {
        return caster->plane_escape(node, remaining, spread);
      };
    }
    slice->table = make_table(slice->air, plane_escape);
    if (slice->table) slice->caster.use_table(slice->table.get(), eye, spread);
    slices[size_t(k)] = std::move(slice);
  });
  // No table for some scale's air: every camera ray traced.
  if (std::all_of(slices.begin(), slices.end(), [](const auto& slice) { return slice->table != nullptr; })) {
    slices_ = std::move(slices);
  }
}

SpectralEyeTables::~SpectralEyeTables() = default;

PathEnd SpectralEyeTables::cast(const Caster& exact, double scale, const Vec3d& origin, const Vec3d& dir,
                                double spread) const {
  if (slices_.size() < 2 || origin != eye_ || !(scale >= slices_.front()->scale && scale <= slices_.back()->scale)) {
    return exact.cast(origin, dir, 0.0, spread);
  }
  const double first = slices_.front()->scale, step = (slices_.back()->scale - first) / double(slices_.size() - 1);
  const size_t k = std::min(size_t((scale - first) / step), slices_.size() - 2);
  const Slice &lower = *slices_[k], &upper = *slices_[k + 1];
  const PathEnd a = lower.caster.cast(origin, dir, 0.0, spread);
  const PathEnd b = upper.caster.cast(origin, dir, 0.0, spread);
  const double w = std::clamp((scale - lower.scale) / (upper.scale - lower.scale), 0.0, 1.0);
  auto lerp = [w](const auto& x, const auto& y) { return (1.0 - w) * x + w * y; };
  // The pixel's tolerance: sagitta_pixels of its footprint (Caster::cast's), in angle and at the
  // ray's length across it.
  const double angle = options_.sagitta_pixels * spread;
  PathEnd end;
  end.chords = a.chords + b.chords;
  end.direction = lerp(a.direction, b.direction).normalized();
  end.length = lerp(a.length, b.length);
  if (!a.hit && !b.hit) {
    if (std::acos(std::clamp(a.direction.dot(b.direction), -1.0, 1.0)) <= angle) {
      end.end_point = lerp(a.end_point, b.end_point);
      return end;
    }
  } else if (a.hit && b.hit && a.hit->geometry == b.hit->geometry && a.hit->primitive == b.hit->primitive &&
             a.hit->front_face == b.hit->front_face) {
    // Paths within the tolerance of each other meet a grazed surface far apart along it: compare
    // the hits across the ray.
    const Vec3d apart = b.hit->point - a.hit->point;
    const double across = (apart - apart.dot(end.direction) * end.direction).norm();
    if (across <= std::max(options_.sagitta, angle * std::max(a.length, b.length))) {
      Hit hit = *a.hit;
      hit.t = lerp(a.hit->t, b.hit->t);
      hit.point = lerp(a.hit->point, b.hit->point);
      hit.normal = lerp(a.hit->normal, b.hit->normal).normalized();
      hit.b1 = lerp(a.hit->b1, b.hit->b1);
      hit.b2 = lerp(a.hit->b2, b.hit->b2);
      end.hit = hit;
      return end;
    }
  }
  PathEnd traced = exact.cast(origin, dir, 0.0, spread);
  traced.chords += end.chords;
  return traced;
}

}  // namespace refracta
