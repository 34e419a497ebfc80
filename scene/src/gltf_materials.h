// scene/src/gltf_materials.h (private) — the BRDF a glTF material describes.
//
// glTF 2.0's metallic-roughness material (§3.9.2, Appendix B) with the KHR_materials_specular,
// KHR_materials_ior and KHR_materials_anisotropy extensions, as a prt::brdf::Material
// (prt/brdf/material.h): MaterialModel::kGltf, the spec's mix of a Lambert layer weighted by
// 1 − F and a GGX lobe with Schlick's Fresnel (prt/brdf/gltf_pbr.h).
//   α        = roughnessFactor² (the spec's "alphaRoughness"), raised to 0.001 (the smallest
//              roughness the microfacet model takes; glTF's 0 is a mirror);
//   anisotropy (strength s, rotation r): α_x = mix(α, 1, s²) along the tangent rotated by r
//              (counter-clockwise toward the bitangent), α_y = α across it — the extension's
//              "at" and "ab"; r goes to ScenePrimitive::anisotropy_rotation;
//   F0_dielectric = min(((ior − 1)/(ior + 1))² · specularColorFactor, 1) · specularFactor
//              (ior 1.5 → 0.04 by default), the Material's `specular`; the metal's F0 is
//              baseColor, mixed by metallic inside the BRDF;
//   baseColor = the primitive's albedo (baseColorFactor, × the texture's mean when textured).
// Defaults are the spec's: metallicFactor 1, roughnessFactor 1, baseColorFactor 1 — so a
// material object with no pbrMetallicRoughness is a rough (α = 1) white metal. (A primitive with
// NO material keeps prt's Lambert 0.8 grey, see scene/scene_loader.h.)
// Textures (the loader samples them per vertex and passes the products here as GltfParameters,
// scene/src/gltf_brdf_textures.h): "factor × texture" for every parameter, as the specs say —
// metallicRoughnessTexture G, B (linear); specularTexture A (linear) × specularFactor;
// specularColorTexture RGB (sRGB-encoded, decoded to linear) × specularColorFactor, inside the
// min(…, 1) above; anisotropyTexture B (linear) × anisotropyStrength. The anisotropyTexture's
// direction (RG) is a rotation of the tangent frame, not a BRDF parameter (the loader's).
// Departures from the spec, stated: specularFactor scales F0 but f90 stays 1; baseColor stays
// the primitive's (the base-colour texture's mean), so a textured metal's F0 does not follow its
// base-colour texture.
// Plain Lambert (no BRDF set) when metallic = 0 and either F0 = 0 (specularFactor 0: the spec's
// pure diffuse) or roughness = 1 with no KHR_materials_specular (prt's convention for a matte
// surface: what prt's own writer and most exporters write for a diffuse material).
// Errors: SceneError "PATH: material 'NAME': FIELD V outside [lo, hi]" for factors outside
// their ranges (NaN and infinities included), "… anisotropyRotation V is not finite".
// Specs: [112] (Appendix B), [110] (KHR_materials_specular), [111] (KHR_materials_anisotropy) of
// docs/REFERENCES.md.
#pragma once

#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "prt/brdf/material.h"

namespace tinygltf {
struct Material;
}

namespace prt::scene::detail {

struct GltfBrdf {
  std::optional<brdf::Material> brdf;  // none: plain Lambert with the albedo
  float anisotropy_rotation = 0.f;     // radians
};

// The smallest α the loader writes (prt::brdf's roughness floor).
inline constexpr double kGltfMinAlpha = 1e-3;

// A material's parameters at one point: each the factor × the texture's value there (the factor
// alone without a texture). Defaults are the specs' factors.
struct GltfParameters {
  double roughness = 1.0;          // roughnessFactor × metallicRoughnessTexture G
  double metalness = 1.0;          // metallicFactor × metallicRoughnessTexture B
  double specular = 1.0;           // specularFactor × specularTexture A
  glm::dvec3 specular_color{1.0};  // specularColorFactor × specularColorTexture RGB (linear)
  double anisotropy = 0.0;         // anisotropyStrength × anisotropyTexture B
};

// The factors of `material`, checked (errors above).
GltfParameters gltf_factors(const std::string& path, const tinygltf::Material& material);

// anisotropyRotation (radians; 0 without the extension), checked to be finite.
double gltf_anisotropy_rotation(const std::string& path, const tinygltf::Material& material);

// The BRDF for `parameters` (clamped: roughness, metalness, specular and anisotropy to [0, 1],
// specular_color to ≥ 0), or for the material's factors when null; the factors are checked
// either way.
GltfBrdf gltf_brdf(const std::string& path, const tinygltf::Material& material,
                   const glm::vec3& base_color, const GltfParameters* parameters = nullptr);

}  // namespace prt::scene::detail
