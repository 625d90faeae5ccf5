// A pool of casters and integrators for spectral renders through dispersive air (hero_casters.h).
#include "refracta/render/hero_casters.h"

#include "refracta/media/dispersed_field.h"

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

}  // namespace refracta
