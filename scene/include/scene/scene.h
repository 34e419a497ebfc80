// scene/scene.h — a triangle scene, flattened to world space, as the baker and renderer see it.
//
// Frame: glTF's (right-handed, +Y up, cameras look down −Z); units are the file's.
// Vertices keep the file's order, primitive by primitive (glTF: nodes of the default scene
// in depth-first order, then primitives in order; OBJ: shapes in order), so a coefficient
// file can be mapped back to the source meshes. Node transforms are applied; normals are
// transformed by the inverse transpose and renormalised.
//
// Albedo (linear RGB reflectance, each channel in [0, 1)): a primitive is either flat (its
// `albedo`, copied to its vertices) or textured (`base_color_texture`: factor × a texture read at
// the vertices' `texcoords`, scene/texture.h). For a textured primitive, `albedo` is factor × the
// texture's mean (what the surface looks like from afar, and what a GLB written from the scene
// carries) and each vertex's `albedo` is the texture sampled (bilinear) at that vertex: the
// vertex's own albedo. albedo_at() gives the albedo anywhere on a triangle: the interpolated
// vertex albedo of a flat primitive, the filtered texture of a textured one.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/brdf/material.h"
#include "scene/texture.h"

namespace prt::scene {

// The albedo (grey) of a primitive whose material gives no colour the loaders read.
inline constexpr float kDefaultAlbedo = 0.8f;

// A glTF material's KHR_materials_volume and KHR_materials_diffuse_transmission as written
// (scene units; a value that is not a number reads as NaN), with KHR_materials_ior's ior.
// `prt bake --subsurface gltf` derives dipole coefficients from them (docs/SUBSURFACE.md).
struct GltfTranslucency {
  bool volume = false, diffuse_transmission = false;
  double attenuation_distance = 0;  // 0: absent (glTF's default is +infinity)
  glm::dvec3 attenuation_color{1.0};
  double thickness = 0;
  double diffuse_transmission_factor = 0;
  glm::dvec3 diffuse_transmission_color{1.0};
  double ior = 1.5;  // glTF's default when KHR_materials_ior is absent
};

struct ScenePrimitive {
  std::string name;           // "mesh/primitive" or OBJ shape name
  uint32_t first_vertex = 0;  // into Scene::positions
  uint32_t vertex_count = 0;
  uint32_t first_triangle = 0;  // into Scene::triangles
  uint32_t triangle_count = 0;
  glm::vec3 albedo{0.8f};  // linear RGB reflectance in [0, 1) (textured: factor × mean)
  std::optional<BaseColorTexture> base_color_texture;  // none: a flat albedo
  // Emitters (radiosity): the material's name ("" when none) and the exit radiance its front
  // faces emit, linear RGB (glTF emissiveFactor × KHR_materials_emissive_strength; OBJ Ke).
  std::string material;
  glm::vec3 emission{0.f};
  // The surface's BRDF when it is not plain Lambert with `albedo` (glossy materials: glTF
  // pbrMetallicRoughness, OBJ Ks/Ns, or a command-line override); see prt/brdf/material.h.
  // Absent: Lambert with `albedo`. The diffuse transfer ignores it.
  std::optional<brdf::Material> brdf;
  // Rotation (radians, counter-clockwise from the tangent toward the bitangent) of the
  // direction along which `brdf`'s α_x applies, in the vertex tangent frames
  // (glTF KHR_materials_anisotropy's anisotropyRotation); scene/tangent_frames.h applies it.
  float anisotropy_rotation = 0.f;
  // The same per vertex (the primitive's vertices in order), replacing anisotropy_rotation when
  // it has vertex_count entries: glTF's anisotropyTexture direction (RG remapped to [−1, 1]²)
  // turned by anisotropyRotation, i.e. atan2(y, x) + anisotropyRotation. Empty otherwise.
  std::vector<float> anisotropy_rotation_of_vertex;
  // Per-vertex variants of `brdf` when a texture varies its parameters (glTF
  // metallicRoughnessTexture, specular and anisotropy textures: scene/brdf_variants.h): at most
  // kMaxBrdfVariants materials and, for each of the primitive's vertices (in order), the index of
  // its own. Empty otherwise; used only when brdf_variant_of_vertex has vertex_count entries.
  // `brdf` is then the material of the texture's mean (what the surface looks like from afar;
  // absent when that is Lambert).
  std::vector<brdf::Material> brdf_variants;
  std::vector<uint32_t> brdf_variant_of_vertex;
  // The parameters the textures vary, for messages: "roughness/metalness", "specular",
  // "specular colour", "anisotropy" joined by ", " (empty without textured parameters).
  std::string brdf_textured;
  // A texture the BRDF needs that could not be used, as one line ("material 'M':
  // metallicRoughnessTexture FILE: problem", or specularTexture, specularColorTexture,
  // anisotropyTexture); "" when none (the first problem when several). The loader uses the factors
  // and prints nothing (describe_materials lists it); a glossy bake refuses the scene with it.
  std::string brdf_texture_problem;
  // The material's translucency extensions (glTF); absent when it has neither.
  std::optional<GltfTranslucency> translucency;
};

struct SceneCamera {
  glm::vec3 eye{0.f}, target{0.f, 0.f, -1.f}, up{0.f, 1.f, 0.f};
  float yfov_radians = 0.8f;
  std::string name;
};

struct Scene {
  std::vector<glm::vec3> positions;  // world space
  std::vector<glm::vec3> normals;    // unit length, one per vertex
  std::vector<glm::vec3> albedo;     // per vertex (its primitive's albedo, or its texture here)
  std::vector<glm::vec2> texcoords;  // per vertex, or empty (never when a primitive is textured)
  // Per-vertex tangent frames from the file (glTF TANGENT: xyz a unit tangent ⊥ normal, w = ±1
  // the bitangent's handedness, bitangent = w · cross(normal, tangent)), or empty when the file
  // has none; zero (0, 0, 0, 0) marks a vertex without one (a primitive without TANGENT, or an
  // invalid value). scene/tangent_frames.h gives frames for every vertex either way.
  std::vector<glm::vec4> tangents;
  std::vector<glm::uvec3> triangles;  // indices into positions; degenerate ones removed
  std::vector<ScenePrimitive> primitives;
  std::vector<SceneCamera> cameras;  // glTF cameras, if any, in node order

  std::size_t skipped_degenerate_triangles = 0;  // zero-area or repeated-index triangles
  std::size_t computed_normal_vertices = 0;      // vertices whose normal was computed
  // glTF primitives whose material gives no colour (no material, or neither a factor nor a
  // usable texture): they got kDefaultAlbedo grey. The loader prints nothing
  // about them; a command that uses the albedo (prt bake) says so.
  std::size_t default_albedo_primitives = 0;

  std::string source_path;

  std::size_t vertex_count() const { return positions.size(); }
  // Axis-aligned bounds of all vertices.
  glm::vec3 bounds_min() const;
  glm::vec3 bounds_max() const;
  // Length of the bounding-box diagonal (0 for an empty scene).
  float extent() const;

  // True when some primitive has a base-colour texture.
  bool textured() const;
  // The primitive whose triangle range holds triangle t (null when none does).
  const ScenePrimitive* primitive_of_triangle(std::size_t t) const;
  // The albedo at the point of triangle t with Embree barycentrics (u, v), i.e.
  // (1−u−v)·p0 + u·p1 + v·p2, for a sample standing for `footprint` world units of surface
  // (0: a point; textures are then read bilinearly, see scene/texture.h).
  glm::vec3 albedo_at(std::size_t t, float u, float v, float footprint = 0.f) const;
  // The width in UV units of `world_width` world units on triangle t (the square root of its
  // UV-area-to-area ratio; 0 for an untextured or degenerate triangle).
  float uv_footprint(std::size_t t, float world_width) const;
};

// Thrown by the loaders with a one-line message "PATH: problem".
struct SceneError : std::exception {
  explicit SceneError(std::string m) : message(std::move(m)) {}
  const char* what() const noexcept override { return message.c_str(); }
  std::string message;
};

}  // namespace prt::scene
