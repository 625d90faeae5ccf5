// The material interface: what a surface is made of, turned into a BSDF at a surface point for
// the path's wavelengths, its textures applied (DESIGN.md: scene/ refers to materials by id).
// Dielectrics also say their index and priority for nested dielectrics (Schmidt & Budge 2002,
// shared/SHADING.md section 4).
#pragma once

#include "refracta/core/scratch.h"
#include "refracta/core/spectrum.h"
#include "refracta/scene/surface_interaction.h"
#include "refracta/scene/textures.h"
#include "refracta/shading/bsdf.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace refracta {

struct MaterialContext {
  SampledWavelengths* lambda = nullptr;  // a dispersive material may terminate the secondary wavelengths
  const Textures* textures = nullptr;
  // Index of refraction of the medium on the outside of the surface (the side its geometric
  // normal points to): the air field's n at the hit, or the enclosing dielectric's index.
  double eta_outside = 1.0;
};

class Material {
 public:
  virtual ~Material() = default;
  // The BSDF in the shading frame at si (allocated in scratch), or nullptr for a surface that
  // does not scatter (an interface to be passed through).
  virtual const Bsdf* bsdf(const SurfaceInteraction& si, const MaterialContext& context, ScratchBuffer& scratch) const = 0;
  // Dielectrics that bound a medium: their index of refraction at the hero wavelength (RGB
  // rendering: at 550 nm); nullopt for everything else (thin dielectrics included).
  virtual std::optional<double> interior_ior(const SampledWavelengths& /*lambda*/) const { return std::nullopt; }
  // Whether light passes through the surface (dielectrics, thin ones and water included).
  virtual bool transmits() const { return false; }
  // Nested dielectrics: a surface whose priority is below the highest of the media the path is
  // inside is a false hit. Larger wins.
  virtual int priority() const { return 0; }
  // Opacity in [0, 1] for render_raster's transparency (MTL d).
  virtual double alpha() const { return 1.0; }
  // A short description for repr and errors, e.g. "Diffuse(reflectance=(0.5, 0.5, 0.5))".
  virtual std::string describe() const = 0;
  // A copy whose texture files are registered in `textures` (a scene's table) and looked up there
  // by id, or null when the material names no texture file. RenderScene::add_material calls it,
  // so one material object can be added to several scenes.
  virtual std::shared_ptr<const Material> with_textures(Textures& /*textures*/) const { return nullptr; }
  // Whether a texture multiplies a colour of this material (its geometry then needs uvs).
  virtual bool textured() const { return false; }
};

using MaterialPtr = std::shared_ptr<const Material>;

}  // namespace refracta
