// scene/src/gltf_brdf_textures.h (private) — a glTF material's parameter textures read at the
// vertices of one primitive: the per-vertex BRDF variants (scene/brdf_variants.h) and the
// per-vertex anisotropy direction (ScenePrimitive::anisotropy_rotation_of_vertex).
//
// Textures read (each with its own sampler and TEXCOORD_n, sampled as the sampler says at the
// vertex's coordinates; gltf_textures.h decodes them):
//   pbrMetallicRoughness.metallicRoughnessTexture  linear; G × roughnessFactor, B × metallicFactor
//   KHR_materials_specular.specularTexture         linear; A × specularFactor (no alpha: 1)
//   KHR_materials_specular.specularColorTexture    sRGB-encoded RGB, decoded to linear,
//                                                  × specularColorFactor
//   KHR_materials_anisotropy.anisotropyTexture     linear; B × anisotropyStrength; RG the
//                                                  direction (below)
// ([110], [111] of docs/REFERENCES.md). The products are quantised together (quantise_parameters)
// to at most 64 variants, each turned into a BRDF by gltf_brdf (gltf_materials.h); `brdf` becomes
// the material of the textures' means.
// Direction: (x, y) = 2 · (R, G) − 1 in the tangent/bitangent plane, turned counter-clockwise by
// anisotropyRotation r, is the direction of α_x: the tangent rotated by atan2(y, x) + r, stored per
// vertex. A zero (x, y) has no direction: r alone (the texture's "no direction" default (1, ½)
// gives x = 1, y = 1/255 after 8-bit quantisation, i.e. 0.0039 rad more than r).
// A texture that cannot be used (a missing or undecodable image, a texture index that does not
// exist, a textureInfo without a valid index, or a missing TEXCOORD_n) is recorded in
// ScenePrimitive::brdf_texture_problem ("material 'M': specularTexture PROBLEM", the first one);
// the factors then stay in use for every parameter and nothing is printed.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gltf_textures.h"
#include "scene/scene.h"

namespace prt::scene::detail {

// A primitive's TEXCOORD_set, one per vertex, or empty with *problem set ("mesh 'N' has no
// TEXCOORD_1").
using TexcoordReader = std::function<std::vector<glm::vec2>(int set, std::string* problem)>;

// Reads the textures of `material` for the primitive `out` of `vertex_count` vertices, whose BRDF
// base colour is `base_color`; sets out.brdf, brdf_variants, brdf_variant_of_vertex, brdf_textured,
// anisotropy_rotation_of_vertex or brdf_texture_problem. Prints one note when quantising made
// errors.
void read_brdf_textures(const std::string& path, const tinygltf::Material& material,
                        GltfTextures& textures, const TexcoordReader& texcoords,
                        std::size_t vertex_count, const glm::vec3& base_color, ScenePrimitive& out);

}  // namespace prt::scene::detail
