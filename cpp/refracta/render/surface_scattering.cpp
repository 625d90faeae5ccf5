// BSDFs at surfaces with nested dielectrics (surface_scattering.h).
#include "refracta/render/surface_scattering.h"

namespace refracta {

const MediumStack::Entry* MediumStack::highest_except(int material) const {
  const Entry* best = nullptr;
  for (int i = 0; i < size_; ++i) {
    if (entries_[i].material == material) continue;
    if (!best || entries_[i].priority > best->priority) best = &entries_[i];
  }
  return best;
}

bool MediumStack::contains(int material) const {
  for (int i = 0; i < size_; ++i) {
    if (entries_[i].material == material) return true;
  }
  return false;
}

void MediumStack::push(const Entry& entry) {
  if (size_ < kCapacity) entries_[size_++] = entry;
}

void MediumStack::remove(int material) {
  for (int i = 0; i < size_; ++i) {
    if (entries_[i].material != material) continue;
    for (int j = i + 1; j < size_; ++j) entries_[j - 1] = entries_[j];
    --size_;
    return;
  }
}

Scattering scattering_at(const RenderScene& scene, const SurfaceInteraction& si, const MediumStack& media,
                         double air_ior, SampledWavelengths& lambda, ScratchBuffer& scratch) {
  Scattering out;
  const Material& material = scene.material(si.material);
  MaterialContext context;
  context.lambda = &lambda;
  context.textures = &scene.geometry.textures();
  context.eta_outside = air_ior;
  if (const auto ior = material.interior_ior(lambda)) {
    out.dielectric = si.material;
    out.priority = material.priority();
    out.interior_ior = *ior;
    const MediumStack::Entry* other = media.highest_except(si.material);
    if (other && other->priority > out.priority) {
      out.false_hit = true;
      return out;
    }
    if (other) context.eta_outside = other->ior;
  }
  const Bsdf* bsdf = material.bsdf(si, context, scratch);
  if (!bsdf) return out;
  out.bsdf.bsdf = bsdf;
  out.bsdf.ng = si.n;
  out.bsdf.frame = Frame::from_normal_tangent(si.ns, si.dpdu);
  return out;
}

void cross_interface(const Scattering& s, const SurfaceInteraction& si, const Vec3d& wi, MediumStack* media) {
  if (s.dielectric < 0) return;
  const bool entering = wi.dot(si.n) < 0.0;  // leaving toward the inside of the geometric normal
  if (entering) {
    if (!media->contains(s.dielectric)) media->push({s.dielectric, s.priority, s.interior_ior});
  } else {
    media->remove(s.dielectric);
  }
}

}  // namespace refracta
