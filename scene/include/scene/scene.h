// scene/scene.h — a triangle scene, flattened to world space, as the baker and renderer see it.
//
// Frame: glTF's (right-handed, +Y up, cameras look down −Z); units are the file's.
// Vertices keep the file's order, primitive by primitive (glTF: nodes of the default scene
// in depth-first order, then primitives in order; OBJ: shapes in order), so a coefficient
// file can be mapped back to the source meshes. Node transforms are applied; normals are
// transformed by the inverse transpose and renormalised.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace prt::scene {

// The albedo (grey) of a primitive whose material gives no colour the loaders read.
inline constexpr float kDefaultAlbedo = 0.8f;

struct ScenePrimitive {
  std::string name;           // "mesh/primitive" or OBJ shape name
  uint32_t first_vertex = 0;  // into Scene::positions
  uint32_t vertex_count = 0;
  uint32_t first_triangle = 0;  // into Scene::triangles
  uint32_t triangle_count = 0;
  glm::vec3 albedo{0.8f};  // linear RGB reflectance in [0, 1)
  // Emitters (radiosity): the material's name ("" when none) and the exit radiance its front
  // faces emit, linear RGB (glTF emissiveFactor × KHR_materials_emissive_strength; OBJ Ke).
  std::string material;
  glm::vec3 emission{0.f};
};

struct SceneCamera {
  glm::vec3 eye{0.f}, target{0.f, 0.f, -1.f}, up{0.f, 1.f, 0.f};
  float yfov_radians = 0.8f;
  std::string name;
};

struct Scene {
  std::vector<glm::vec3> positions;   // world space
  std::vector<glm::vec3> normals;     // unit length, one per vertex
  std::vector<glm::vec3> albedo;      // per vertex (copied from its primitive's material)
  std::vector<glm::uvec3> triangles;  // indices into positions; degenerate ones removed
  std::vector<ScenePrimitive> primitives;
  std::vector<SceneCamera> cameras;  // glTF cameras, if any, in node order

  std::size_t skipped_degenerate_triangles = 0;  // zero-area or repeated-index triangles
  std::size_t computed_normal_vertices = 0;      // vertices whose normal was computed
  // glTF primitives whose material gives no colour the loader reads (no material, or a texture
  // that is not read): they got kDefaultAlbedo grey. The loader prints nothing
  // about them; a command that uses the albedo (prt bake) says so.
  std::size_t default_albedo_primitives = 0;

  std::string source_path;

  std::size_t vertex_count() const { return positions.size(); }
  // Axis-aligned bounds of all vertices.
  glm::vec3 bounds_min() const;
  glm::vec3 bounds_max() const;
  // Length of the bounding-box diagonal (0 for an empty scene).
  float extent() const;
};

// Thrown by the loaders with a one-line message "PATH: problem".
struct SceneError : std::exception {
  explicit SceneError(std::string m) : message(std::move(m)) {}
  const char* what() const noexcept override { return message.c_str(); }
  std::string message;
};

}  // namespace prt::scene
