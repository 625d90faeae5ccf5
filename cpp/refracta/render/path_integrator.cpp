// The two integrators (integrator.h): 'path' -- unidirectional path tracing with next-event
// estimation and MIS (Veach 1997; pbrt-v4 PathIntegrator), Russian roulette from rr_depth on
// (survival min(0.95, max throughput), shared/SHADING.md section 6) -- and 'direct', the same walk
// stopped after the first non-specular scattering event's direct lighting. Radiance is carried
// as basic radiance L / n^2 through the air (conserved along curved rays, Ament et al. 2014):
// a segment from n_a to n_b scales what arrives by (n_a / n_b)^2.
#include "refracta/render/integrator.h"

#include "refracta/core/low_discrepancy.h"
#include "refracta/render/surface_scattering.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace refracta {

namespace {

constexpr double kMaxSurvival = 0.95;

// The directional albedo of `bsdf` toward wo, in [0, 1]: the mean weight of 64 samples at fixed
// quasi-random points (the path's sampler is not drawn from, so the image is the same with or
// without readouts; fixed, so the estimate varies smoothly with wo, as the denoiser's guide must).
Vec3d directional_albedo(const SurfaceBsdf& bsdf, const Vec3d& wo) {
  // The first points of Roberts' R3 sequence (core/low_discrepancy.h): the lobe's choice and the
  // direction spread over the cube together. A 4 x 4 grid whose row also chose the lobe was
  // biased: a rough gold 15 % high, a red plastic's green 28 % low (a trial). Points shifted per
  // sample were unbiased but noisy, and the denoiser kept a sea's noise as the guide's texture.
  constexpr int kCount = 64;
  static const std::vector<std::vector<double>> points = [] {
    const QuasiRandom sequence(3);
    std::vector<std::vector<double>> out;
    for (int i = 0; i < kCount; ++i) out.push_back(sequence.point(i));
    return out;
  }();
  Spectrum sum = Spectrum::Zero();
  for (const std::vector<double>& u : points) {
    const auto bs = bsdf.sample(wo, u[0], Vec2d(u[1], u[2]));
    if (bs && bs->weight.isFinite().all()) sum += bs->weight;
  }
  return (sum.head<3>() / kCount).max(0.0).min(1.0).matrix();
}

class PathTracer : public Integrator {
 public:
  PathTracer(const RenderScene& scene, const Caster& caster, const RenderOptions& options, bool direct_only)
      : Integrator(scene, caster, options), direct_only_(direct_only) {}

  Spectrum li_after(const Vec3d& origin, const Vec3d& dir, const PathEnd& first, double pixel_angle,
                    SampledWavelengths& lambda, Sampler& sampler, ScratchBuffer& scratch,
                    SurfaceAovs* aovs) const override {
    return walk<false>(origin, dir, first, pixel_angle, lambda, sampler, scratch, aovs);
  }

  void surface_after(const Vec3d& origin, const Vec3d& dir, const PathEnd& first, double pixel_angle,
                     SampledWavelengths& lambda, Sampler& sampler, ScratchBuffer& scratch,
                     SurfaceAovs& aovs) const override {
    walk<true>(origin, dir, first, pixel_angle, lambda, sampler, scratch, &aovs);
  }

 private:
  // The path from the camera ray's end `first` on; kSurfaceOnly: no light gathered, the walk ends
  // at the first non-specular surface once its albedo and normal are in `aovs` (surface_after).
  template <bool kSurfaceOnly>
  Spectrum walk(const Vec3d& origin, const Vec3d& dir, const PathEnd& first, double pixel_angle,
                SampledWavelengths& lambda, Sampler& sampler, ScratchBuffer& scratch, SurfaceAovs* aovs) const {
    Spectrum L = Spectrum::Zero(), beta = Spectrum::Ones();
    Vec3d o = origin, d = dir;
    double ior_here = caster_.curved() ? caster_.ior(o) : 1.0;  // straight rays: no air to ask
    double bsdf_pdf = 0.0, eta_scale = 1.0, travelled = 0.0;
    bool specular = true;  // the camera ray counts as specular: emitters it sees are not MIS-weighted
    SurfaceInteraction previous;
    bool has_previous = false, emission_only = false;
    MediumStack media;
    int depth = 0;
    const int max_depth = options_.max_depth;
    PathEnd cast;  // the ends of later segments (the camera ray's is not copied)
    // The width of the pixel's cone a bounce ray leaves with (Caster::cast's origin_width): the
    // footprint as the ray sees it (SurfaceInteraction::cone_width_along); none after a specular
    // event (a curved mirror or a lens may narrow the cone) or an interface passed straight.
    double origin_width = 0.0;
    // Surfaces met, index-matched interfaces passed straight included, at most 4 per scattering
    // event and 64 more; in 64 bits (a max_depth of 1e9 wrapped the bound negative: a trial).
    const int64_t pass_limit = 4 * int64_t(max_depth) + 64;
    for (int64_t passes = 0; passes < pass_limit; ++passes) {
      if (passes > 0) cast = caster_.cast(o, d, 0.0, 0.0, origin_width);
      const PathEnd& end = passes == 0 ? first : cast;
      travelled += end.length;
      if (kSurfaceOnly && !end.hit) break;
      if (!end.hit) {
        const double n_top = caster_.curved() ? lighting_.distant_ior(o, end.direction) * ior_here / caster_.ior(o) : ior_here;
        L += beta * lighting_.escaped(end, d, has_previous ? &previous : nullptr, o.y(), bsdf_pdf, specular, lambda) *
             sqr(ior_here / n_top);
        break;
      }
      // The camera ray's footprint from its differentials where the renderer gave them, else the cone.
      const double cone_width = pixel_angle * travelled;
      SurfaceInteraction si = passes == 0 && first.footprint
                                  ? scene_.geometry.interaction(*end.hit, end.direction, *first.footprint)
                                  : scene_.geometry.interaction(*end.hit, end.direction, cone_width);
      si.cone_width = cone_width;
      // The air between: its in-scatter arrives, and it dims everything from the hit on. A path
      // that escapes sees the sky, which already holds the air all the way out.
      if (air_ && !kSurfaceOnly) {
        const AerialPerspective::Segment air = air_->along(o, si.p, air_frame_, lambda);
        L += beta * air.inscatter;
        beta *= air.transmittance;
      }
      if (caster_.curved()) {
        const double ior_hit = caster_.ior(si.p);
        beta *= sqr(ior_here / ior_hit);
        ior_here = ior_hit;
      }
      if (!kSurfaceOnly) L += beta * lighting_.emitted(si, has_previous ? &previous : nullptr, bsdf_pdf, specular, lambda);
      if (depth >= max_depth || emission_only) break;
      scratch.reset();
      const Scattering s = scattering_at(scene_, si, media, ior_here, lambda, scratch);
      if (!s.bsdf) {  // a false hit or a pure interface: continue straight through
        // A false hit still enters or leaves its medium (Schmidt & Budge 2002): without this a
        // glass's cavity floor met inside higher-priority water was never entered, and the
        // water's lower face then took the air, not the glass, as its outside.
        if (s.false_hit) cross_interface(s, si, d, &media);
        o = si.offset_toward(d);
        origin_width = 0.0;
        continue;
      }
      const bool smooth = s.bsdf.bsdf->has_delta_only();
      if (aovs && !smooth) {
        record_surface(si, s, media, ior_here, lambda, scratch, aovs);
        aovs = nullptr;  // the first non-specular hit only
        if (kSurfaceOnly) break;
      }
      if (!smooth) L += beta * lighting_.sample_lights(si, s.bsdf, lambda, sampler);
      const double uc = sampler.uniform();
      const auto bs = s.bsdf.sample(si.wo, uc, sampler.uniform2());
      if (!bs) break;
      if (si.leaks(bs->wi, bs->is_transmission())) break;
      ++depth;
      beta *= bs->weight;
      bsdf_pdf = bs->pdf;
      specular = bs->is_specular();
      if (bs->is_transmission()) {
        eta_scale *= sqr(bs->eta);
        cross_interface(s, si, bs->wi, &media);
      }
      previous = si;
      has_previous = true;
      o = si.offset_toward(bs->wi);
      origin_width = specular ? 0.0 : si.cone_width_along(bs->wi);
      d = bs->wi;
      // 'direct' stops once a non-specular event has taken its direct lighting; its BSDF ray
      // still finds the emitters it hits (the MIS partner of the light sample) in one more pass.
      emission_only = direct_only_ && !specular;
      if (!(beta.maxCoeff() > 0.0)) break;
      if (depth >= options_.rr_depth) {
        const double survival = std::min(kMaxSurvival, (beta * eta_scale).maxCoeff());
        if (sampler.uniform() >= survival) break;
        beta /= survival;
      }
    }
    return L;
  }

  // The albedo (in RGB whatever the render's wavelengths) and the shading normal facing the path.
  void record_surface(const SurfaceInteraction& si, const Scattering& s, const MediumStack& media, double ior_here,
                      const SampledWavelengths& lambda, ScratchBuffer& scratch, SurfaceAovs* aovs) const {
    Vec3d n = s.bsdf.frame.n;
    aovs->normal = n.dot(si.wo) < 0.0 ? Vec3d(-n) : n;
    if (!lambda.spectral) {
      aovs->albedo = directional_albedo(s.bsdf, si.wo);
      return;
    }
    SampledWavelengths rgb = SampledWavelengths::rgb();
    const Scattering in_rgb = scattering_at(scene_, si, media, ior_here, rgb, scratch);
    if (in_rgb.bsdf) aovs->albedo = directional_albedo(in_rgb.bsdf, si.wo);
  }

  bool direct_only_;
};

}  // namespace

std::unique_ptr<Integrator> make_integrator(const RenderScene& scene, const Caster& caster, const RenderOptions& options) {
  return std::make_unique<PathTracer>(scene, caster, options, options.transport == Transport::kDirect);
}

}  // namespace refracta
