// scene/brdf_variants.h — per-vertex material parameters read from textures (glTF
// metallicRoughnessTexture, KHR_materials_specular's specularTexture and specularColorTexture,
// KHR_materials_anisotropy's anisotropyTexture), reduced to a bounded number of material
// variants.
//
// PRT is per vertex, and both the glossy bake and `prt relight` build one SH projection table
// b(ω_o) per distinct material (prt/glossy/brdf_projection.h), so a textured roughness cannot give
// every vertex its own material: the (roughness, metalness) pairs sampled at the vertices of one
// source material are quantised to at most kMaxBrdfVariants (64) pairs, and each vertex is mapped
// to one of them (ScenePrimitive::brdf_variants, brdf_variant_of_vertex).
//
// Quantisation (per source material, deterministic):
//   - at most 64 distinct pairs: kept exactly (no error);
//   - else each parameter is quantised on its own grid over its own range [lo, hi] of the
//     samples: a parameter with at most L distinct values keeps them (L = 8 for the axis that
//     has few values; the other axis gets ⌊64 / count⌋ levels), otherwise uniform bins over
//     [lo, hi] whose value is the bin's centre. Both axes continuous: 16 roughness × 4 metalness
//     levels. The error per vertex is then at most half a bin: |Δroughness| ≤ (hi − lo)/32 (or
//     (hi − lo)/(2·⌊64/count⌋) with metalness exact), |Δmetalness| ≤ (hi − lo)/8.
// What that costs (docs/BRDF.md "Textured material parameters"): with glTF's α = r², Δα ≈ 2 r Δr,
// and the GGX peak D(0) = 1/(π α²) changes by ≈ 2 Δα/α = 4 Δr/r: for r ≥ 0.3 and Δr ≤ 1/32, under
// 42 % at the peak of an unfiltered lobe (much less once SH order ≤ 10 has blurred it); the
// reported max_*_error are the errors actually made, which the loader prints when non-zero.
//
// More parameters (quantise_parameters: a vector of K values per vertex, e.g. roughness,
// metalness, specular, specular colour RGB, anisotropy strength):
//   - at most 64 distinct vectors: kept exactly;
//   - else, when only the first two components vary: quantise_metal_roughness's grid above;
//   - else a grid with L_k levels on component k (exact values when L_k reaches its count of
//     distinct values, else uniform bins over its [lo, hi] valued at their centres), the L_k
//     grown one at a time, always on the component whose bin width (hi − lo)/L_k is largest
//     (ties: the lower k), while Π L_k ≤ 64; each vertex takes its cell's centre, so the error
//     of component k is at most (hi − lo)/(2 L_k); max_error reports the errors made.
// (The anisotropyTexture's direction is not a BRDF parameter: it rotates the tangent frame per
// vertex, ScenePrimitive::anisotropy_rotation_of_vertex, and is not quantised.)
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace prt::scene {

inline constexpr int kMaxBrdfVariants = 64;

struct QuantisedParameters {
  std::vector<glm::dvec2> levels;    // the variants' (roughness, metalness), ≤ max_variants
  std::vector<uint32_t> level_of;    // one per sample, into `levels`
  double max_roughness_error = 0.0;  // max over the samples of |quantised − sampled|
  double max_metalness_error = 0.0;
};

// Quantises (roughness, metalness) samples (each in [0, 1]; NaN is read as 0) to at most
// max_variants (1 .. kMaxBrdfVariants; 64 by default) levels as described above.
QuantisedParameters quantise_metal_roughness(const std::vector<glm::dvec2>& samples,
                                             int max_variants = kMaxBrdfVariants);

struct QuantisedVectors {
  std::vector<std::vector<double>> levels;  // the variants' parameter vectors, ≤ max_variants
  std::vector<uint32_t> level_of;           // one per sample, into `levels`
  std::vector<double> max_error;            // per component: max over the samples of |error|
};

// Quantises parameter vectors (all of one length K ≥ 1; NaN is read as 0) to at most
// max_variants (1 .. kMaxBrdfVariants) levels as described above. std::invalid_argument when
// max_variants is outside that range or the vectors' lengths differ.
QuantisedVectors quantise_parameters(const std::vector<std::vector<double>>& samples,
                                     int max_variants = kMaxBrdfVariants);

}  // namespace prt::scene
