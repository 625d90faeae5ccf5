// Spectral rendering through dispersive air (renderer.cpp): each sample's rays -- camera ray,
// bounces, shadow rays -- bend through the field at its hero wavelength, n - 1 scaled by
// K(hero) / K(reference) (media/dispersed_field.h), and the secondary wavelengths are terminated
// (the path is the hero's alone; Wilkie et al. 2014, section 4).
//
// One caster and one integrator per worker thread serve every sample that thread renders: built
// on its first sample over a DispersedField whose scale the thread retunes to each sample's hero
// wavelength (for_wavelength). The air is then exactly what dispersed_field(field, hero) builds
// -- the same n and grad n, bit for bit -- without building a field, a caster and an integrator
// per sample. Per thread rather than one per render: the integrators ask their caster for n and
// for the layered air (Caster::ior, Caster::layered, in direct_lighting.cpp and
// path_integrator.cpp) without a wavelength, so a caster shared by every thread would need the
// wavelength passed through each of those calls. A sample runs on one thread from start to end
// (no sample spawns parallel work), so a thread's air cannot change under a sample.
#pragma once

#include "refracta/media/index_field.h"
#include "refracta/render/caster.h"
#include "refracta/render/integrator.h"
#include "refracta/render/render_options.h"
#include "refracta/render/render_scene.h"

#include <tbb/enumerable_thread_specific.h>

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

  struct Hero {
    const Caster& caster;
    const Integrator& integrator;
  };
  // The calling thread's caster and integrator, their air retuned to `wavelength_nm` [nm].
  Hero for_wavelength(double wavelength_nm) const;

 private:
  struct PerThread;
  const RenderScene& scene_;
  FieldPtr field_;
  const RenderOptions& options_;
  std::optional<IorFloors> floors_;
  double spread_;
  double reference_;  // the field's reference wavelength [nm]
  mutable tbb::enumerable_thread_specific<std::unique_ptr<PerThread>> threads_;
};

}  // namespace refracta
