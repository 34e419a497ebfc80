// Wavefront OBJ reading through tinyobjloader (see obj_loader.h and scene/scene_loader.h).
#include "obj_loader.h"
#include "scene_file_errors.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include <tiny_obj_loader.h>

namespace prt::scene::detail {
namespace {

constexpr float kDefaultObjAlbedo = 0.8f;

// tinyobjloader reads a coordinate it cannot parse ("nan", "inf", "1.0x") as 0 without a word,
// so every `v` line is checked here first: each of its first three fields must be a finite
// number, or the file is refused naming the line.
void check_vertex_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  std::string line;
  std::size_t line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string::npos || line.compare(i, 2, "v ") != 0) {
      if (i == std::string::npos || line.compare(i, 2, "v\t") != 0) continue;
    }
    std::istringstream fields(line.substr(i + 2));
    for (int axis = 0; axis < 3; ++axis) {
      std::string token;
      if (!(fields >> token))
        fail(path, "line " + std::to_string(line_number) + ": a vertex needs 3 coordinates");
      char* end = nullptr;
      const double value = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(value)) {
        fail(path, "line " + std::to_string(line_number) + ": vertex coordinate '" + token +
                       "' is not a finite number");
      }
    }
  }
}

}  // namespace

Scene read_obj_scene(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    const std::string message = condense(reader.Error());
    fail(path, "cannot load OBJ: " + (message.empty() ? "unknown error" : message));
  }
  check_vertex_lines(path);
  // Printed only once the file has been accepted, so a refusal stays a single line.
  const std::string warnings = condense(reader.Warning());

  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const std::vector<tinyobj::material_t>& materials = reader.GetMaterials();
  const std::size_t position_count = attrib.vertices.size() / 3;
  const std::size_t normal_count = attrib.normals.size() / 3;

  std::size_t non_empty_shapes = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    non_empty_shapes += shape.mesh.indices.empty() ? 0 : 1;
  }
  const bool single_shape = non_empty_shapes == 1;

  Scene scene;
  std::size_t mixed_material_shapes = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    if (mesh.indices.empty()) continue;
    if (mesh.indices.size() % 3 != 0) fail(path, "shape '" + shape.name + "' is not triangulated");
    const std::string name =
        shape.name.empty() ? "shape" + std::to_string(scene.primitives.size()) : shape.name;
    bool all_normals = true;
    for (const tinyobj::index_t& index : mesh.indices) {
      if (index.vertex_index < 0 ||
          static_cast<std::size_t>(index.vertex_index) >= position_count) {
        fail(path, "shape '" + name + "': vertex index " + std::to_string(index.vertex_index + 1) +
                       " out of range (" + std::to_string(position_count) + " vertices)");
      }
      if (index.normal_index < 0) {
        all_normals = false;
      } else if (static_cast<std::size_t>(index.normal_index) >= normal_count) {
        fail(path, "shape '" + name + "': normal index " + std::to_string(index.normal_index + 1) +
                       " out of range (" + std::to_string(normal_count) + " normals)");
      }
    }

    ScenePrimitive primitive;
    primitive.name = name;
    primitive.first_vertex = static_cast<uint32_t>(scene.positions.size());
    primitive.first_triangle = static_cast<uint32_t>(scene.triangles.size());
    primitive.albedo = glm::vec3(kDefaultObjAlbedo);
    const int material = mesh.material_ids.empty() ? -1 : mesh.material_ids.front();
    if (material >= 0 && static_cast<std::size_t>(material) < materials.size()) {
      const tinyobj::real_t* kd = materials[static_cast<std::size_t>(material)].diffuse;
      primitive.albedo = glm::vec3(kd[0], kd[1], kd[2]);
      const tinyobj::material_t& m = materials[static_cast<std::size_t>(material)];
      primitive.material = m.name;
      primitive.emission = glm::vec3(m.emission[0], m.emission[1], m.emission[2]);  // Ke
    }
    if (std::any_of(mesh.material_ids.begin(), mesh.material_ids.end(),
                    [&](int id) { return id != material; })) {
      ++mixed_material_shapes;
    }

    const auto position_of = [&](int i) {
      const std::size_t k = static_cast<std::size_t>(i) * 3;
      return glm::vec3(attrib.vertices[k], attrib.vertices[k + 1], attrib.vertices[k + 2]);
    };
    // Maps the file's index key to this primitive's local vertex index.
    std::vector<uint32_t> local_index(mesh.indices.size());
    if (all_normals) {
      // One vertex per unique (position, normal) pair, in first-seen order.
      std::map<std::pair<int, int>, uint32_t> seen;
      for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
        const tinyobj::index_t& index = mesh.indices[c];
        const auto key = std::make_pair(index.vertex_index, index.normal_index);
        auto [it, inserted] = seen.emplace(key, static_cast<uint32_t>(seen.size()));
        if (inserted) {
          const std::size_t k = static_cast<std::size_t>(index.normal_index) * 3;
          scene.positions.push_back(position_of(index.vertex_index));
          scene.normals.emplace_back(attrib.normals[k], attrib.normals[k + 1],
                                     attrib.normals[k + 2]);
        }
        local_index[c] = it->second;
      }
    } else {
      // Positions only: the file's `v` entries in file order, normals computed later. A file
      // with a single shape keeps every `v` (unused ones too, so vertex i is the file's i-th
      // `v`); with several shapes each takes the entries it uses.
      std::vector<uint32_t> remap(position_count, UINT32_MAX);
      for (const tinyobj::index_t& index : mesh.indices) {
        remap[static_cast<std::size_t>(index.vertex_index)] = 0;
      }
      uint32_t next = 0;
      for (std::size_t v = 0; v < position_count; ++v) {
        if (remap[v] == UINT32_MAX && !single_shape) continue;
        remap[v] = next++;
        scene.positions.push_back(position_of(static_cast<int>(v)));
        scene.normals.emplace_back(0.f);  // missing: computed by load_scene
      }
      for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
        local_index[c] = remap[static_cast<std::size_t>(mesh.indices[c].vertex_index)];
      }
    }
    primitive.vertex_count = static_cast<uint32_t>(scene.positions.size()) - primitive.first_vertex;
    for (std::size_t c = 0; c < local_index.size(); c += 3) {
      scene.triangles.emplace_back(
          glm::uvec3(local_index[c], local_index[c + 1], local_index[c + 2]) +
          primitive.first_vertex);
    }
    primitive.triangle_count =
        static_cast<uint32_t>(scene.triangles.size()) - primitive.first_triangle;
    scene.albedo.resize(scene.positions.size(), primitive.albedo);
    scene.primitives.push_back(std::move(primitive));
  }
  if (mixed_material_shapes > 0) {
    std::fprintf(
        stderr,
        "%s: warning: %zu shape(s) use several materials; each takes its first face's material\n",
        path.c_str(), mixed_material_shapes);
  }
  if (!warnings.empty()) std::fprintf(stderr, "%s: warning: %s\n", path.c_str(), warnings.c_str());
  return scene;
}

}  // namespace prt::scene::detail
