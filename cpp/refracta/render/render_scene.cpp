// The renderers' scene (render_scene.h).
#include "refracta/render/render_scene.h"

#include "refracta/core/error.h"
#include "refracta/shading/area_light.h"
#include "refracta/shading/physical_sky.h"
#include "refracta/shading/scaled_light.h"
#include "refracta/shading/spot_light.h"
#include "refracta/shading/sun_light.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace refracta {

int RenderScene::add_material(MaterialPtr material) {
  geometry.check_unchanging("add_material");
  if (!material) throw_invalid("material must not be None");
  if (MaterialPtr bound = material->with_textures(geometry.textures())) material = std::move(bound);
  materials_.push_back(std::move(material));
  return int(materials_.size() - 1);
}

void RenderScene::set_material(unsigned geometry_id, MaterialPtr material) {
  geometry.check_geometry(geometry_id, "set_material");
  geometry.set_material(geometry_id, add_material(std::move(material)));
}

void RenderScene::remove(unsigned geometry_id) {
  geometry.check_geometry(geometry_id, "remove");
  remove_lights_if_emitted_by(int(geometry_id));
  geometry.remove(geometry_id);
}

void RenderScene::remove_lights_if_emitted_by(int geometry_id) {
  std::vector<bool> drop(lights_.size());
  for (size_t i = 0; i < lights_.size(); ++i) drop[i] = geometry_of_light_[i] == geometry_id;
  size_t i = 0;
  remove_lights_if([&](const Light&) { return drop[i++]; });
}

size_t RenderScene::add_light(LightPtr light, int emitter) {
  geometry.check_unchanging("add_light");
  if (!light) throw_invalid("light must not be None");
  // An area light alone lit the scene, but no camera or BSDF ray saw its surface (trials: a mesh's
  // light, and a sphere's taken from another scene's lights).
  if (emitter < 0 && light->type() == LightType::kArea) {
    throw_invalid("add_light: an area light (AreaLight, SphereLight) must be emitted by a surface the rays see: give "
                  "its geometry emission= (add_mesh, add_box, add_sphere, ...) instead");
  }
  if (emitter >= 0) {
    if (size_t(emitter) >= geometry.geometry_count()) throw_invalid("add_light: no geometry ", emitter);
    if (light_of_geometry_.size() < geometry.geometry_count()) light_of_geometry_.resize(geometry.geometry_count(), -1);
    light_of_geometry_[size_t(emitter)] = int(lights_.size());
  }
  lights_.push_back(std::move(light));
  geometry_of_light_.push_back(emitter);
  return lights_.size() - 1;
}

void RenderScene::remove_infinite_lights() {
  remove_lights_if([](const Light& light) { return light.is_infinite(); });
}

const SunLight* RenderScene::sun() const {
  for (const LightPtr& light : lights_) {
    if (const auto* sun = dynamic_cast<const SunLight*>(light.get())) return sun;
  }
  return nullptr;
}

std::vector<const SpotLight*> RenderScene::spots() const {
  std::vector<const SpotLight*> out;
  for (const LightPtr& light : lights_) {
    if (const auto* spot = dynamic_cast<const SpotLight*>(light.get())) out.push_back(spot);
  }
  return out;
}

void RenderScene::set_sun(LightPtr sun) {
  remove_lights_if([](const Light& light) { return dynamic_cast<const SunLight*>(&light) != nullptr; });
  if (sun) add_light(std::move(sun));
}

void RenderScene::set_sky(LightPtr sky) {
  remove_lights_if([](const Light& light) { return light.is_infinite() && !dynamic_cast<const SunLight*>(&light); });
  if (sky) add_light(std::move(sky));
}

const PhysicalSkyLight* physical_sky_of(const Light& light, double* scale) {
  *scale = 1.0;
  const Light* inner = &light;
  if (const auto* scaled = dynamic_cast<const ScaledInfiniteLight*>(inner)) *scale = scaled->scale(), inner = scaled->light().get();
  return dynamic_cast<const PhysicalSkyLight*>(inner);
}

void RenderScene::enable_aerial_perspective() {
  geometry.check_unchanging("enable_aerial_perspective");
  for (const LightPtr& light : lights_) {
    double scale = 1.0;
    if (const PhysicalSkyLight* sky = physical_sky_of(*light, &scale)) {
      aerial_ = std::make_shared<AerialPerspective>(PhysicalSky::shared(sky->settings()), scale);
      aerial_source_ = light.get();
      return;
    }
  }
  throw_invalid("aerial perspective needs the scene's physical sky (Scene.set_physical_sky with scale > 0)");
}

void RenderScene::disable_aerial_perspective() {
  geometry.check_unchanging("disable_aerial_perspective");
  aerial_.reset();
  aerial_source_ = nullptr;
}

void RenderScene::forget_aerial_if_gone() {
  if (!aerial_source_) return;
  for (const LightPtr& light : lights_) {
    if (light.get() == aerial_source_) return;
  }
  aerial_.reset();
  aerial_source_ = nullptr;
}

void RenderScene::set_shadow_radius(size_t light, double radius) {
  geometry.check_unchanging("set_shadow_radius");
  if (!(radius >= 0.0) || !std::isfinite(radius)) throw_invalid("radius must be >= 0 (got ", radius, ")");
  shadow_radius_.emplace_back(lights_.at(light).get(), radius);
}

double RenderScene::shadow_radius(size_t light) const {
  for (const auto& [l, r] : shadow_radius_) {
    if (l == lights_.at(light).get()) return r;
  }
  return 0.0;
}

void RenderScene::prepare() const {
  geometry.commit();
  // The bounding sphere of the geometry (infinite lights' power through it): the scene's box,
  // which also holds terrain grids (they have no triangles in meshes()).
  const Vec3d& lo = geometry.lower();
  const Vec3d& hi = geometry.upper();
  Vec3d centre = Vec3d::Zero();
  double radius = 1.0;
  if (lo.x() <= hi.x()) centre = 0.5 * (lo + hi), radius = std::max(0.5 * (hi - lo).norm(), 1e-3);
  for (const auto& light : lights_) light->preprocess(centre, radius);
}

}  // namespace refracta
