// A scene as the renderers see it: the Embree geometry, the material table its geometry ids
// refer to, and the lights (area lights tied to the geometry that emits). What Python's
// refracta.Scene holds.
#pragma once

#include "refracta/scene/embree_scene.h"
#include "refracta/shading/aerial_perspective.h"
#include "refracta/shading/light.h"
#include "refracta/shading/material.h"

#include <memory>
#include <vector>

namespace refracta {

class PhysicalSkyLight;
class SpotLight;
class SunLight;

// The physical sky a scene light is (set_physical_sky's, perhaps scaled: its scale in `scale`), or null.
const PhysicalSkyLight* physical_sky_of(const Light& light, double* scale);

// Geometry (Embree), materials (refracta.shading) and lights. Scene() starts empty: no sun, no sky,
// black. Every add_* takes material= (any refracta.shading material); without it the Blinn-Phong
// shorthand kd (diffuse albedo, RGB in [0, 1]), ks (specular albedo), ns (Phong exponent) applies.
// Meshes and spheres with emission= [W/(m^2 sr), RGB] are area lights (one-sided on the triangles'
// counter-clockwise front unless two_sided). Units: metres, y up.
class RenderScene {
 public:
  Scene geometry;

  // Adds a material to the table (a copy with its texture files registered in the geometry's
  // table when it names any: Material::with_textures); returns its id.
  int add_material(MaterialPtr material);
  // Gives a geometry a new material (added to the table; the old entry stays, unused).
  void set_material(unsigned geometry_id, MaterialPtr material);
  // Removes a geometry (Scene::remove: other ids unchanged) and the area light it emits.
  void remove(unsigned geometry_id);
  const Material& material(int id) const { return *materials_.at(size_t(id)); }
  const MaterialPtr& material_ptr(int id) const { return materials_.at(size_t(id)); }
  size_t material_count() const { return materials_.size(); }

  // Adds a light; an area light names the geometry whose surface emits it (-1 for none).
  size_t add_light(LightPtr light, int emitter = -1);
  const std::vector<LightPtr>& lights() const { return lights_; }
  // The geometry an area light is emitted by, or -1.
  int emitter_of(size_t light) const { return geometry_of_light_.at(light); }
  // The area light a geometry emits, or -1.
  int light_of(unsigned geometry) const {
    return geometry < light_of_geometry_.size() ? light_of_geometry_[geometry] : -1;
  }
  // Removes every infinite light (set_environment / set_sky / set_physical_sky replace them).
  void remove_infinite_lights();

  // The lights by role (render_scene.cpp is the one place that tells them apart by type):
  // the sun (the first SunLight) or null, and the spot lights in the order they were added
  // (render_raster's `lights=` numbers them so).
  const SunLight* sun() const;
  std::vector<const SpotLight*> spots() const;
  // Replaces the sun (null: none), keeping the sky.
  void set_sun(LightPtr sun);
  // Replaces every infinite light but the sun (the sky or environment; null: none).
  void set_sky(LightPtr sky);
  // Removes lights for which `drop` is true (keeps area-light links consistent).
  template <class Predicate>
  void remove_lights_if(const Predicate& drop);

  // Aerial perspective (aerial_perspective.h) from the scene's physical sky light (set_physical_sky,
  // possibly scaled): every segment the renderers cast is then dimmed by the air and gains its
  // in-scatter. Throws std::invalid_argument when the scene has no physical sky. It lasts while
  // that light does (replacing the sky ends it).
  void enable_aerial_perspective();
  void disable_aerial_perspective();
  // Null without aerial perspective.
  const AerialPerspective* aerial_perspective() const { return aerial_.get(); }
  const Light* aerial_source() const { return aerial_source_; }  // the sky light it was made from
  const std::shared_ptr<AerialPerspective>& aerial_perspective_ptr() const { return aerial_; }

  // A spot light's disc radius [m] for render_raster's soft-shadow reference ('embree' shadows
  // of an area spot light: 64 stratified shadow rays), 0 for a point.
  void set_shadow_radius(size_t light, double radius);
  double shadow_radius(size_t light) const;

  // Called before rendering: commits the geometry, tells the lights the scene's bounds.
  void prepare() const;

 private:
  std::vector<MaterialPtr> materials_;
  std::vector<LightPtr> lights_;
  std::vector<int> light_of_geometry_;
  std::vector<int> geometry_of_light_;
  std::vector<std::pair<const Light*, double>> shadow_radius_;
  std::shared_ptr<AerialPerspective> aerial_;
  const Light* aerial_source_ = nullptr;  // the sky light aerial_ was made from

  void forget_aerial_if_gone();

  void remove_lights_if_emitted_by(int geometry_id);
};

template <class Predicate>
void RenderScene::remove_lights_if(const Predicate& drop) {
  geometry.check_unchanging("remove lights");
  std::vector<LightPtr> kept;
  std::vector<int> kept_geometry;
  for (size_t i = 0; i < lights_.size(); ++i) {
    if (drop(*lights_[i])) continue;
    kept.push_back(lights_[i]);
    kept_geometry.push_back(geometry_of_light_[i]);
  }
  lights_ = std::move(kept);
  geometry_of_light_ = std::move(kept_geometry);
  std::fill(light_of_geometry_.begin(), light_of_geometry_.end(), -1);
  for (size_t i = 0; i < lights_.size(); ++i) {
    if (geometry_of_light_[i] >= 0) light_of_geometry_[size_t(geometry_of_light_[i])] = int(i);
  }
  forget_aerial_if_gone();
}

}  // namespace refracta
