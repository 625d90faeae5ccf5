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
#include "refracta/render/caster.h"
#include "refracta/render/integrator.h"
#include "refracta/render/render_options.h"
#include "refracta/render/render_scene.h"

#include <tbb/concurrent_queue.h>

#include <memory>
#include <optional>

namespace refracta {

class HeroCasters {
 public:
  // field: the render's air (non-null, its rays curved); floors: the ior floors over every
  // wavelength (IorFloors::merge); spread: set_secondary_spread's. Keeps references to scene and
  // options, which must outlive it.
  HeroCasters(const RenderScene& scene, FieldPtr field, const RenderOptions& options, std::optional<IorFloors> floors,
              double spread);
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
  mutable tbb::concurrent_queue<std::unique_ptr<Hero>> idle_;  // built and not held
};

}  // namespace refracta
