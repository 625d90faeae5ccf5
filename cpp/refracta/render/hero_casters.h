// Spectral rendering through dispersive air (renderer.cpp): each sample's rays -- camera ray,
// bounces, shadow rays -- bend through the field at its hero wavelength, n - 1 scaled by
// K(hero) / K(reference) (media/dispersed_field.h), and the secondary wavelengths are terminated
// (the path is the hero's alone; Wilkie et al. 2014, section 4).
//
// A small pool of casters and integrators, one per sample in flight (as many as the render's
// threads), serves every sample: each is built once over a DispersedField whose scale a sample
// retunes to its hero wavelength while it holds that caster (for_wavelength's lease). The air is
// then exactly what dispersed_field(field, hero) builds -- the same n and grad n, bit for bit --
// without building a field, a caster and an integrator per sample; which caster of the pool a
// sample gets changes nothing. One per sample in flight rather than one per render: the
// integrators ask their caster for n and for the layered air (Caster::ior, Caster::layered, in
// direct_lighting.cpp and path_integrator.cpp) without a wavelength, so a caster shared by
// concurrent samples would need the wavelength passed through each of those calls.
#pragma once

#include "refracta/media/index_field.h"
#include "refracta/rays/elevation_table.h"
#include "refracta/render/caster.h"
#include "refracta/render/integrator.h"
#include "refracta/render/render_options.h"
#include "refracta/render/render_scene.h"
#include "refracta/render/sun_exit_map.h"

#include <tbb/concurrent_queue.h>

#include <functional>
#include <memory>
#include <optional>

namespace refracta {

class HeroCasters {
 public:
  // field: the render's air (non-null, its rays curved); floors: the ior floors over every
  // wavelength (IorFloors::merge); spread: set_secondary_spread's. Keeps references to scene and
  // options, which must outlive it.
  // raised_sky: the render's (DirectLighting::use_raised_sky), given to every hero's lighting.
  HeroCasters(const RenderScene& scene, FieldPtr field, const RenderOptions& options, std::optional<IorFloors> floors,
              double spread, std::shared_ptr<const RaisedSky> raised_sky = nullptr);
  ~HeroCasters();

 private:
  struct Hero;  // one dispersed air, its caster and integrator (hero_casters.cpp)

 public:
  // A caster and integrator of the pool, held by one sample until the lease ends.
  class Lease {
   public:
    Lease(const HeroCasters& pool, std::unique_ptr<Hero> hero);
    Lease(Lease&& other) noexcept;
    Lease& operator=(const Lease&) = delete;
    ~Lease();
    const Caster& caster() const;
    const Integrator& integrator() const;
    double scale() const;  // the air's dispersion scale K(hero) / K(reference)

   private:
    const HeroCasters& pool_;
    std::unique_ptr<Hero> hero_;
  };
  // A caster and integrator nobody else holds, their air retuned to `wavelength_nm` [nm].
  Lease for_wavelength(double wavelength_nm) const;

 private:
  const RenderScene& scene_;
  FieldPtr field_;
  const RenderOptions& options_;
  std::optional<IorFloors> floors_;
  double spread_;
  double reference_;  // the field's reference wavelength [nm]
  // Over a spherical Earth with a sun, every hero's lowest launches below the horizon and the sun's
  // exit map above it (DirectLighting::use_sun_tables); null: each is cast, or launched along the sample.
  std::shared_ptr<const LowestLaunches> lowest_launches_;
  std::shared_ptr<const SunExitMap> sun_exits_;
  std::shared_ptr<const RaisedSky> raised_sky_;
  mutable tbb::concurrent_queue<std::unique_ptr<Hero>> idle_;  // built and not held
};

// Camera rays of a spectral render from the eye of a height-only air (issue 21 goal 5): the eye's
// ElevationTable at kScales dispersion scales spread evenly over those of the sampled wavelengths
// (each over its own air, fixed at its scale, with its own caster), and a sample's camera ray, at
// its hero's scale s between two of them, cast through both tables. Where their ends agree to the
// pixel's tolerance (sagitta_pixels of its footprint: what a traced camera ray may stray) -- the
// same surface, the paths at the hits that close across the ray; or both in the sky, their
// directions that close -- the end is interpolated linearly in s; elsewhere (the ends part near
// a mirage's fold, a silhouette or the sun's rim) the ray is traced at s, as without the tables.
// A ray's end moves monotonically with the air's n - 1 (its bending grows with it) between two
// close scales: the exact end then lies between the tables' ends, within their difference of the
// interpolated one.
class SpectralEyeTables {
 public:
  // The eye's table over `air` (renderer.cpp's eye_table, its entries ending by `escape` when set).
  using TableFactory = std::function<std::unique_ptr<ElevationTable>(const FieldPtr& air, const PlaneEscape& escape)>;
  // Dispersion scales tabulated: 2.4e-3 of n - 1 apart (3.6 % from 830 to 360 nm): a level ray's
  // 0.5 deg of refraction at the horizon differs by 2e-5 rad between neighbours, a quarter pixel
  // of 0.7 deg over 64 rows is 4.8e-5 rad.
  static constexpr int kScales = 16;

  // field: the render's height-only air (tabulated); escape: end the tables' entries where they
  // leave the air (over a spherical Earth). Keeps references to scene and options.
  SpectralEyeTables(const RenderScene& scene, const FieldPtr& field, const RenderOptions& options,
                    const std::optional<IorFloors>& floors, const Vec3d& eye, double spread, bool escape,
                    const TableFactory& make_table);
  ~SpectralEyeTables();

  // The end of the camera ray from `origin` along `dir` at dispersion scale `scale`; `exact`
  // (the sample's caster, its air at that scale) casts it where the tables do not serve it.
  PathEnd cast(const Caster& exact, double scale, const Vec3d& origin, const Vec3d& dir, double spread) const;

 private:
  struct Slice;  // one scale's air, caster and table (hero_casters.cpp)
  const RenderOptions& options_;
  Vec3d eye_;
  std::vector<std::unique_ptr<Slice>> slices_;  // ascending scale
};

}  // namespace refracta
