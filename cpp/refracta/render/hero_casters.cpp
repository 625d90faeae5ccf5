// One caster and one integrator per thread for spectral renders through dispersive air (hero_casters.h).
#include "refracta/render/hero_casters.h"

#include "refracta/media/dispersed_field.h"

namespace refracta {

// A thread's dispersed air, its caster and integrator: built once, never moved (the integrator
// holds the caster by reference, the caster the air).
struct HeroCasters::PerThread {
  PerThread(const HeroCasters& owner)
      : scale(std::make_shared<double>(1.0)),
        air(tunable_dispersed_field(owner.field_, scale)),
        caster(owner.scene_.geometry, air.get(), owner.options_) {
    if (owner.floors_) caster.set_ior_floors(*owner.floors_);
    caster.set_secondary_spread(owner.spread_);
    integrator = make_integrator(owner.scene_, caster, owner.options_);
  }

  std::shared_ptr<double> scale;  // K(hero) / K(reference), read by `air` at every evaluation
  FieldPtr air;
  Caster caster;
  std::unique_ptr<Integrator> integrator;
};

HeroCasters::HeroCasters(const RenderScene& scene, FieldPtr field, const RenderOptions& options,
                         std::optional<IorFloors> floors, double spread)
    : scene_(scene),
      field_(std::move(field)),
      options_(options),
      floors_(std::move(floors)),
      spread_(spread),
      reference_(field_reference_wavelength(*field_)) {}

HeroCasters::~HeroCasters() = default;

HeroCasters::Hero HeroCasters::for_wavelength(double wavelength_nm) const {
  std::unique_ptr<PerThread>& mine = threads_.local();
  if (!mine) mine = std::make_unique<PerThread>(*this);
  *mine->scale = air_dispersion_scale(wavelength_nm, reference_);
  return Hero{mine->caster, *mine->integrator};
}

}  // namespace refracta
