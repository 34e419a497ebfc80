// Scene loading: extension dispatch and the common finishing steps (see scene/scene_loader.h).
#include "scene/scene_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "gltf_loader.h"
#include "obj_loader.h"
#include "scene/mesh_normals.h"

namespace prt::scene {
namespace {

bool is_finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The primitive holding vertex v, or null (for error messages).
const ScenePrimitive* find_primitive_of_vertex(const Scene& scene, std::size_t v) {
  for (const ScenePrimitive& p : scene.primitives) {
    if (v >= p.first_vertex && v < static_cast<std::size_t>(p.first_vertex) + p.vertex_count) {
      return &p;
    }
  }
  return nullptr;
}

// Textured primitives: albedo = factor × the texture's mean, each vertex's albedo the texture at
// its coordinates; one note for the textures whose albedo had to be clamped (scene/texture.h).
void apply_textures(Scene& scene, const std::string& path) {
  if (!scene.textured()) {
    // Kept only for tangents of anisotropic materials (scene/tangent_frames.h).
    const bool anisotropic =
        std::any_of(scene.primitives.begin(), scene.primitives.end(),
                    [](const ScenePrimitive& p) { return p.brdf && !p.brdf->isotropic(); });
    if (anisotropic && !scene.texcoords.empty())
      scene.texcoords.resize(scene.positions.size(), glm::vec2(0.f));
    else
      scene.texcoords.clear();
    return;
  }
  scene.texcoords.resize(scene.positions.size(), glm::vec2(0.f));
  std::size_t clamped = 0;
  for (ScenePrimitive& p : scene.primitives) {
    if (!p.base_color_texture) continue;
    const BaseColorTexture& t = *p.base_color_texture;
    const glm::vec3 mean(t.image->mean());
    p.albedo = glm::clamp(t.factor * mean, glm::vec3(0.f), glm::vec3(kMaxTexturedAlbedo));
    const glm::vec3 peak = t.factor * t.image->maximum();
    if (peak.x > kMaxTexturedAlbedo || peak.y > kMaxTexturedAlbedo || peak.z > kMaxTexturedAlbedo)
      ++clamped;
    for (uint32_t v = p.first_vertex; v < p.first_vertex + p.vertex_count; ++v)
      scene.albedo[v] = t.albedo(scene.texcoords[v]);
  }
  if (clamped > 0)
    std::fprintf(stderr,
                 "%s: note: %zu textured primitive(s) reach albedo %.2f or more: clamped to %.2f "
                 "(an albedo of 1 would reflect all light)\n",
                 path.c_str(), clamped, double(kMaxTexturedAlbedo), double(kMaxTexturedAlbedo));
}

// Validation, albedo override, textures, degenerate-triangle removal and normals, shared by all
// formats.
void finish_scene(Scene& scene, const std::string& path, const LoadOptions& options) {
  for (std::size_t v = 0; v < scene.positions.size(); ++v) {
    if (!is_finite(scene.positions[v])) {
      const ScenePrimitive* p = find_primitive_of_vertex(scene, v);
      const std::size_t local = p ? v - p->first_vertex : v;
      const std::string owner = p ? p->name : std::string("?");
      throw SceneError(path + ": vertex " + std::to_string(local) + " of '" + owner +
                       "' has a NaN or infinite position");
    }
  }
  for (const glm::uvec3& t : scene.triangles) {
    if (std::max({t.x, t.y, t.z}) >= scene.positions.size()) {
      throw SceneError(path + ": triangle index out of range");
    }
  }
  if (options.albedo_override) {  // a flat colour everywhere: textures are dropped
    for (ScenePrimitive& p : scene.primitives) {
      p.albedo = *options.albedo_override;
      p.base_color_texture.reset();
    }
    std::fill(scene.albedo.begin(), scene.albedo.end(), *options.albedo_override);
  }
  scene.source_path = path;
  apply_material_overrides(scene, options.material_overrides);
  apply_textures(scene, path);
  // File normals must be unit length (an OBJ `vn 5 1 0` is not, found by fuzzing): normalise
  // them; zero or non-finite ones are treated as missing and computed below.
  for (glm::vec3& n : scene.normals) {
    const float length = glm::length(n);
    n = (std::isfinite(length) && length > 0.f) ? n / length : glm::vec3(0.f);
  }
  remove_degenerate_triangles(scene);
  if (scene.triangles.empty())
    throw SceneError(path + ": the scene has no (non-degenerate) triangles");
  const NormalComputation normals = compute_vertex_normals(scene, /*only_missing=*/true);
  if (normals.fallback > 0) {
    std::fprintf(stderr,
                 "%s: warning: %zu vertex normal(s) could not be computed (unused vertex or "
                 "cancelling faces); set to +Y\n",
                 path.c_str(), normals.fallback);
  }
  scene.source_path = path;
}

}  // namespace

Scene load_scene(const std::string& path, const LoadOptions& options) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  Scene scene;
  const bool textures = !options.albedo_override;  // an override drops them: do not decode them
  try {
    if (extension == ".gltf") {
      scene = detail::read_gltf_scene(path, /*binary=*/false, textures);
    } else if (extension == ".glb") {
      scene = detail::read_gltf_scene(path, /*binary=*/true, textures);
    } else if (extension == ".obj") {
      scene = detail::read_obj_scene(path, textures);
    } else {
      throw SceneError(path + ": unsupported scene format '" + extension +
                       "' (expected .gltf, .glb or .obj)");
    }
  } catch (const SceneError&) {
    throw;
  } catch (const std::out_of_range&) {
    // e.g. a glTF primitive naming an accessor that does not exist (found by fuzzing).
    throw SceneError(path + ": the file refers to an element that does not exist");
  }
  finish_scene(scene, path, options);
  return scene;
}

}  // namespace prt::scene
