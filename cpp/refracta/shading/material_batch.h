// A material's BSDF evaluated over many directions at once, in the local shading frame (z = the
// shading normal; shared/SHADING.md section 0), at a neutral surface point (no textures: the
// constant colours): what Material.f, pdf and sample expose to Python and the tests use.
//
// wo, wi: unit directions, one side may be a single row (broadcast). wavelengths: none (RGB
// rendering), one row or one per row of four hero wavelengths [nm] in [kLambdaMin, kLambdaMax];
// each spectral row builds the BSDF afresh (a dispersive dielectric may terminate them).
#pragma once

#include "refracta/shading/material.h"
#include "refracta/shading/spectrum_batch.h"

#include <cstdint>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace refracta {

TransportMode transport_mode_from(const std::string& name);  // 'radiance' or 'importance'

// How to evaluate: hero wavelengths (empty: RGB), the index outside (on the normal's side), the mode.
struct BsdfQuery {
  std::optional<RowMatrixX4d> wavelengths;
  double eta_outside = 1.0;
  TransportMode mode = TransportMode::kRadiance;
};

// The BSDF value f(wo, wi) without the cosine [1/sr]: (N, 3) linear RGB, or (N, 4) per wavelength.
// Delta lobes give 0.
RowMatrixXd bsdf_f(const Material& material, const std::vector<Vec3d>& wo, const std::vector<Vec3d>& wi,
                   const BsdfQuery& query);
// Density [1/sr] with which sample(wo, u) produces wi: (N,). It includes the lobe selection
// probabilities; delta lobes contribute 0.
Eigen::VectorXd bsdf_pdf(const Material& material, const std::vector<Vec3d>& wo, const std::vector<Vec3d>& wi,
                         const BsdfQuery& query);

// What Material.sample returns, one row per sample (read-only arrays; bsdf.h's BsdfSample fields):
// wi (N, 3), weight (N, C), f (N, C), pdf (N,), flags (N,) uint32, is_delta (N,), eta (N,), valid
// (N,), terminated (N,); C = 3 (RGB) or 4 (spectral). See Material.sample. s['wi'] (the former
// dict) still works and iteration over the names are deprecated (DeprecationWarning).
struct BsdfSamples {
  using Flags = Eigen::Matrix<uint32_t, Eigen::Dynamic, 1>;
  using Bools = Eigen::Matrix<bool, Eigen::Dynamic, 1>;
  RowMatrixX3d wi;      // Sampled unit directions (N, 3), 0 where invalid.
  RowMatrixXd weight;   // ``f |cos theta_i| / pdf`` (N, C) (delta lobes: albedo / probability).
  RowMatrixXd f;        // The BSDF value (N, C) [1/sr] (delta lobes: as weight's numerator).
  Eigen::VectorXd pdf;  // Density (N,) [1/sr] (delta lobes: the lobe's selection probability).
  Flags flags;          // 1 reflection, 2 transmission, 4 diffuse, 8 glossy, 16 specular (N,).
  Bools is_delta;       // Whether a delta lobe was sampled (N,).
  Eigen::VectorXd eta;  // The relative index crossed (N,), 1 for reflection (and where invalid).
  Bools valid;          // False where no direction was produced (N,).
  Bools terminated;     // True where a dispersive refraction kept the hero wavelength only (N,).
  // The fields in this order (pickling); BsdfSamples{fields...} rebuilds it.
  auto fields() const { return std::make_tuple(wi, weight, f, pdf, flags, is_delta, eta, valid, terminated); }
};
// Sample incident directions for wo (N, 3) from uniform numbers u (N, 3) in [0, 1): u[:, 0] picks
// the lobe, u[:, 1:] the direction; wo or u may be a single row. Returns a BsdfSample of arrays:
// wi (N, 3) (0 where invalid), weight (N, C) = ``f |cos theta_i| / pdf`` (delta lobes: the lobe's
// albedo over its probability), f (N, C), pdf (N,) (delta lobes: the lobe's selection
// probability), flags (N,) uint32 (1 reflection, 2 transmission, 4 diffuse, 8 glossy, 16
// specular/delta), is_delta (N,), eta (N,) the relative index crossed (1 for reflection), valid
// (N,) False where no direction was produced, terminated (N,) True where a dispersive refraction
// kept the hero wavelength only. C = 3 (RGB) or 4 (spectral).
BsdfSamples bsdf_sample(const Material& material, const std::vector<Vec3d>& wo, const RowMatrixXd& u,
                        const BsdfQuery& query);

// The index of the medium a dielectric bounds at a wavelength [nm] in [kLambdaMin, kLambdaMax]
// (none: RGB rendering's), or none for a material bounding no medium.
std::optional<double> interior_ior_at(const Material& material, std::optional<double> wavelength_nm);

}  // namespace refracta
