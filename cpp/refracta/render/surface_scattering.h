// The BSDF a path meets at a surface, with nested dielectrics by priority (Schmidt & Budge 2002,
// "Simple Nested Dielectrics in Ray Traced Images", JGT 7(2); shared/SHADING.md section 4): a
// path carries the dielectric media it is inside; a surface whose priority is below the highest
// of them is a false hit and is passed through; at a true interface the outside index is the
// highest-priority other medium, or the air field's n at the hit when there is none.
#pragma once

#include "refracta/core/scratch.h"
#include "refracta/core/spectrum.h"
#include "refracta/render/render_scene.h"
#include "refracta/shading/bsdf.h"

#include <array>

namespace refracta {

class MediumStack {
 public:
  struct Entry {
    int material;
    int priority;
    double ior;
  };
  static constexpr int kCapacity = 8;  // media nested deeper than this are ignored (documented limit)

  // The highest-priority entry other than `material` (nullptr when none).
  const Entry* highest_except(int material) const;
  bool contains(int material) const;
  void push(const Entry& entry);
  void remove(int material);
  int size() const { return size_; }

 private:
  // Only the first size_ entries are ever read: not zeroed (a path tracer's every path starts an
  // empty stack; zeroing its 136 bytes was ~1 % of a diffuse scene's render, benchmarks/bench_shading.py).
  std::array<Entry, kCapacity> entries_;
  int size_ = 0;
};

struct Scattering {
  SurfaceBsdf bsdf;          // empty: the surface does not scatter (a false hit or a pure interface)
  bool false_hit = false;    // passed through without scattering (nested dielectrics)
  int dielectric = -1;       // the material id when the surface bounds a dielectric medium
  int priority = 0;
  double interior_ior = 1.0;
};

// The BSDF at si for a path inside `media`, the air's index there being air_ior.
Scattering scattering_at(const RenderScene& scene, const SurfaceInteraction& si, const MediumStack& media,
                         double air_ior, SampledWavelengths& lambda, ScratchBuffer& scratch);

// Updates the media after the path crossed the surface of `s` (a sampled transmission).
void cross_interface(const Scattering& s, const SurfaceInteraction& si, const Vec3d& wi, MediumStack* media);

}  // namespace refracta
