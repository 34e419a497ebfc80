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
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include <tiny_obj_loader.h>

#include "prt/brdf/energy_check.h"
#include "scene/mesh_normals.h"
#include "texture_decoding.h"

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

// Builds the scene from the parsed file, shape by shape (see scene/scene_loader.h).
class ObjSceneBuilder {
 public:
  ObjSceneBuilder(const std::string& path, const tinyobj::ObjReader& reader, bool textures)
      : path_(path),
        read_textures_(textures),
        attrib_(reader.GetAttrib()),
        materials_(reader.GetMaterials()),
        shapes_(reader.GetShapes()),
        position_count_(attrib_.vertices.size() / 3),
        normal_count_(attrib_.normals.size() / 3),
        texcoord_count_(attrib_.texcoords.size() / 2),
        textures_(materials_.size()) {
    std::size_t non_empty_shapes = 0;
    for (const tinyobj::shape_t& shape : shapes_)
      non_empty_shapes += shape.mesh.indices.empty() ? 0 : 1;
    single_shape_ = non_empty_shapes == 1;
  }

  Scene build() {
    for (const tinyobj::shape_t& shape : shapes_) {
      if (!shape.mesh.indices.empty()) add_shape(shape);
    }
    if (!scene_.texcoords.empty()) scene_.texcoords.resize(scene_.positions.size(), glm::vec2(0.f));
    if (mixed_material_shapes_ > 0) {
      std::fprintf(stderr,
                   "%s: warning: %zu shape(s) use several materials; each takes its first face's "
                   "material\n",
                   path_.c_str(), mixed_material_shapes_);
    }
    return std::move(scene_);
  }

 private:
  // Checks the shape's indices; says whether every corner has a normal and a texture coordinate.
  void check_indices(const tinyobj::mesh_t& mesh, const std::string& name, bool& all_normals,
                     bool& all_texcoords) const {
    all_normals = all_texcoords = true;
    for (const tinyobj::index_t& index : mesh.indices) {
      if (index.vertex_index < 0 ||
          static_cast<std::size_t>(index.vertex_index) >= position_count_) {
        fail(path_, "shape '" + name + "': vertex index " + std::to_string(index.vertex_index + 1) +
                        " out of range (" + std::to_string(position_count_) + " vertices)");
      }
      if (index.normal_index < 0) {
        all_normals = false;
      } else if (static_cast<std::size_t>(index.normal_index) >= normal_count_) {
        fail(path_, "shape '" + name + "': normal index " + std::to_string(index.normal_index + 1) +
                        " out of range (" + std::to_string(normal_count_) + " normals)");
      }
      if (index.texcoord_index < 0) {
        all_texcoords = false;
      } else if (static_cast<std::size_t>(index.texcoord_index) >= texcoord_count_) {
        fail(path_, "shape '" + name + "': texture coordinate index " +
                        std::to_string(index.texcoord_index + 1) + " out of range (" +
                        std::to_string(texcoord_count_) + " vt)");
      }
    }
  }

  // The map_Kd texture of a material (loaded once; a file that cannot be read is warned about
  // and the material keeps its Kd).
  const std::optional<BaseColorTexture>& texture_of(int material) {
    static const std::optional<BaseColorTexture> kNone;
    if (!read_textures_ || material < 0 || static_cast<std::size_t>(material) >= materials_.size())
      return kNone;
    auto& [tried, texture] = textures_[static_cast<std::size_t>(material)];
    if (tried) return texture;
    tried = true;
    const tinyobj::material_t& m = materials_[static_cast<std::size_t>(material)];
    if (m.diffuse_texname.empty()) return texture;
    std::string name = m.diffuse_texname;
    std::replace(name.begin(), name.end(), '\\', '/');  // exported on Windows
    const std::string file = (std::filesystem::path(path_).parent_path() / name).string();
    try {
      BaseColorTexture t;
      t.image = load_texture_file(file, m.diffuse_texopt.colorspace != "linear");
      if (m.diffuse_texopt.clamp) {
        t.sampler.wrap_s = t.sampler.wrap_t = TextureWrap::ClampToEdge;
      }
      texture = std::move(t);
    } catch (const std::runtime_error& e) {
      std::fprintf(stderr, "%s: warning: material '%s': map_Kd not used (%s); Kd used instead\n",
                   path_.c_str(), m.name.c_str(), e.what());
    }
    return texture;
  }

  // The texture coordinate of a corner in glTF's convention (v down), with the MTL's -s and -o.
  glm::vec2 texcoord_of(const tinyobj::index_t& index,
                        const tinyobj::texture_option_t& option) const {
    const std::size_t k = static_cast<std::size_t>(index.texcoord_index) * 2;
    const float s = attrib_.texcoords[k] * option.scale[0] + option.origin_offset[0];
    const float t = attrib_.texcoords[k + 1] * option.scale[1] + option.origin_offset[1];
    return glm::vec2(s, 1.f - t);
  }

  glm::vec3 position_of(int i) const {
    const std::size_t k = static_cast<std::size_t>(i) * 3;
    return glm::vec3(attrib_.vertices[k], attrib_.vertices[k + 1], attrib_.vertices[k + 2]);
  }

  // One vertex per unique (position, normal, texture coordinate) key, -1 for a part not used, in
  // first-seen order; fills local_index. Without file normals, the normals of a textured shape
  // are computed over its positions, so a texture seam (one position, two coordinates) shows no
  // shading seam.
  void add_keyed_vertices(const tinyobj::mesh_t& mesh, bool use_normals,
                          const tinyobj::material_t* textured, std::vector<uint32_t>& local_index) {
    std::map<std::tuple<int, int, int>, uint32_t> seen;
    std::vector<int> position_index;  // of each vertex added
    for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
      const tinyobj::index_t& index = mesh.indices[c];
      const auto key = std::make_tuple(index.vertex_index, use_normals ? index.normal_index : -1,
                                       textured ? index.texcoord_index : -1);
      auto [it, inserted] = seen.emplace(key, static_cast<uint32_t>(seen.size()));
      if (inserted) {
        scene_.positions.push_back(position_of(index.vertex_index));
        position_index.push_back(index.vertex_index);
        glm::vec3 n(0.f);  // missing: computed below or by load_scene
        if (use_normals) {
          const std::size_t k = static_cast<std::size_t>(index.normal_index) * 3;
          n = glm::vec3(attrib_.normals[k], attrib_.normals[k + 1], attrib_.normals[k + 2]);
        }
        scene_.normals.push_back(n);
        if (textured) scene_.texcoords.push_back(texcoord_of(index, textured->diffuse_texopt));
      }
      local_index[c] = it->second;
    }
    if (!use_normals && textured) normals_by_position(mesh, position_index);
  }

  // Normals of the vertices just added (their file positions in position_index), computed on the
  // shape's triangles over file positions (scene/mesh_normals.h). Positions whose normal cannot
  // be computed keep a zero normal, for load_scene to handle and report.
  void normals_by_position(const tinyobj::mesh_t& mesh, const std::vector<int>& position_index) {
    Scene by_position;
    std::map<int, uint32_t> slot;
    std::vector<uint32_t> corner(mesh.indices.size());
    for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
      const int v = mesh.indices[c].vertex_index;
      auto [it, inserted] = slot.emplace(v, static_cast<uint32_t>(slot.size()));
      if (inserted) by_position.positions.push_back(position_of(v));
      corner[c] = it->second;
    }
    for (std::size_t c = 0; c + 2 < corner.size(); c += 3)
      by_position.triangles.emplace_back(corner[c], corner[c + 1], corner[c + 2]);
    remove_degenerate_triangles(by_position);
    std::vector<bool> used(by_position.positions.size(), false);
    for (const glm::uvec3& t : by_position.triangles) used[t.x] = used[t.y] = used[t.z] = true;
    compute_vertex_normals(by_position, /*only_missing=*/false);
    const std::size_t first = scene_.positions.size() - position_index.size();
    for (std::size_t i = 0; i < position_index.size(); ++i) {
      const uint32_t k = slot.at(position_index[i]);
      if (used[k]) scene_.normals[first + i] = by_position.normals[k];
    }
  }

  // Positions only: the file's `v` entries in file order, normals computed later. A file with a
  // single shape keeps every `v` (unused ones too, so vertex i is the file's i-th `v`); with
  // several shapes each takes the entries it uses.
  void add_file_order_vertices(const tinyobj::mesh_t& mesh, std::vector<uint32_t>& local_index) {
    std::vector<uint32_t> remap(position_count_, UINT32_MAX);
    for (const tinyobj::index_t& index : mesh.indices) {
      remap[static_cast<std::size_t>(index.vertex_index)] = 0;
    }
    uint32_t next = 0;
    for (std::size_t v = 0; v < position_count_; ++v) {
      if (remap[v] == UINT32_MAX && !single_shape_) continue;
      remap[v] = next++;
      scene_.positions.push_back(position_of(static_cast<int>(v)));
      scene_.normals.emplace_back(0.f);  // missing: computed by load_scene
    }
    for (std::size_t c = 0; c < mesh.indices.size(); ++c) {
      local_index[c] = remap[static_cast<std::size_t>(mesh.indices[c].vertex_index)];
    }
  }

  void add_shape(const tinyobj::shape_t& shape) {
    const tinyobj::mesh_t& mesh = shape.mesh;
    if (mesh.indices.size() % 3 != 0) fail(path_, "shape '" + shape.name + "' is not triangulated");
    const std::string name =
        shape.name.empty() ? "shape" + std::to_string(scene_.primitives.size()) : shape.name;
    bool all_normals = true, all_texcoords = true;
    check_indices(mesh, name, all_normals, all_texcoords);

    ScenePrimitive primitive;
    primitive.name = name;
    primitive.first_vertex = static_cast<uint32_t>(scene_.positions.size());
    primitive.first_triangle = static_cast<uint32_t>(scene_.triangles.size());
    primitive.albedo = glm::vec3(kDefaultObjAlbedo);
    const int material = mesh.material_ids.empty() ? -1 : mesh.material_ids.front();
    if (material >= 0 && static_cast<std::size_t>(material) < materials_.size()) {
      const tinyobj::real_t* kd = materials_[static_cast<std::size_t>(material)].diffuse;
      primitive.albedo = glm::vec3(kd[0], kd[1], kd[2]);
      const tinyobj::material_t& m = materials_[static_cast<std::size_t>(material)];
      primitive.material = m.name;
      primitive.emission = glm::vec3(m.emission[0], m.emission[1], m.emission[2]);  // Ke
      primitive.brdf = blinn_phong_of(m);
    }
    if (std::any_of(mesh.material_ids.begin(), mesh.material_ids.end(),
                    [&](int id) { return id != material; })) {
      ++mixed_material_shapes_;
    }
    const std::optional<BaseColorTexture>& texture = texture_of(material);
    if (texture && !all_texcoords) {
      std::fprintf(stderr,
                   "%s: warning: shape '%s' has faces without texture coordinates (vt): its "
                   "map_Kd is not used, Kd is\n",
                   path_.c_str(), name.c_str());
    }
    const bool textured = texture && all_texcoords;
    if (textured) {
      primitive.base_color_texture = texture;
      primitive.albedo = glm::vec3(1.f);  // map_Kd replaces Kd; load_scene sets the texture's mean
      scene_.texcoords.resize(scene_.positions.size(), glm::vec2(0.f));
    }

    std::vector<uint32_t> local_index(mesh.indices.size());
    if (all_normals || textured) {
      add_keyed_vertices(mesh, all_normals,
                         textured ? &materials_[static_cast<std::size_t>(material)] : nullptr,
                         local_index);
    } else {
      add_file_order_vertices(mesh, local_index);
    }
    primitive.vertex_count =
        static_cast<uint32_t>(scene_.positions.size()) - primitive.first_vertex;
    for (std::size_t c = 0; c < local_index.size(); c += 3) {
      scene_.triangles.emplace_back(
          glm::uvec3(local_index[c], local_index[c + 1], local_index[c + 2]) +
          primitive.first_vertex);
    }
    primitive.triangle_count =
        static_cast<uint32_t>(scene_.triangles.size()) - primitive.first_triangle;
    scene_.albedo.resize(scene_.positions.size(), primitive.albedo);
    scene_.primitives.push_back(std::move(primitive));
  }

  // The largest directional albedo of the Blinn-Phong lobe alone (k_L = 0, k_G = 1) at exponent
  // s, by the white-furnace quadrature; 1 when s is refused (make_brdf reports it below).
  static double glossy_lobe_albedo(double s) {
    brdf::Material lobe;
    lobe.model = brdf::MaterialModel::kBlinnPhong;
    lobe.diffuse = brdf::grey(0.0);
    lobe.specular = brdf::grey(1.0);
    lobe.exponent = s;
    const Result<std::shared_ptr<const brdf::Brdf>> made = brdf::make_brdf(lobe);
    return made ? brdf::max_furnace_albedo(*made.value(), true).albedo : 1.0;
  }

  // The material's Blinn-Phong BRDF (k_L = Kd, k_G = Ks, s = Ns) when Ks is not zero and
  // illum is not 1 (see scene/scene_loader.h); nullopt otherwise.
  std::optional<brdf::Material> blinn_phong_of(const tinyobj::material_t& m) {
    const brdf::Rgb ks{m.specular[0], m.specular[1], m.specular[2]};
    if ((ks.r == 0.0 && ks.g == 0.0 && ks.b == 0.0) || m.illum == 1) return std::nullopt;
    brdf::Material material;
    material.model = brdf::MaterialModel::kBlinnPhong;
    material.diffuse = brdf::Rgb{m.diffuse[0], m.diffuse[1], m.diffuse[2]};
    material.specular = ks;
    material.exponent = m.shininess;
    double* glossy[3] = {&material.specular.r, &material.specular.g, &material.specular.b};
    const double diffuse[3] = {material.diffuse.r, material.diffuse.g, material.diffuse.b};
    bool lowered = false;
    double lobe = 1.0;  // the glossy lobe's largest albedo at k_G = 1 (≥ 1: the normalisation)
    for (int c = 0; c < 3; ++c) {
      if (diffuse[c] + *glossy[c] > 1.0 && diffuse[c] <= 1.0) {
        if (!lowered) lobe = std::max(1.0, glossy_lobe_albedo(material.exponent));
        *glossy[c] = (1.0 - diffuse[c]) / lobe;
        lowered = true;
      }
    }
    if (lowered && reported_lowered_.insert(m.name).second)
      std::fprintf(stderr,
                   "%s: note: material '%s': Kd + Ks exceeds 1, Ks lowered to (1 - Kd)/%.4g "
                   "(the Blinn-Phong lobe's largest albedo at Ns %g)\n",
                   path_.c_str(), m.name.c_str(), lobe, material.exponent);
    const Result<std::shared_ptr<const brdf::Brdf>> made = brdf::make_brdf(material);
    if (!made) fail(path_, "material '" + m.name + "': " + made.status().message());
    const Status energy = brdf::check_energy_conservation(material);
    if (!energy) fail(path_, "material '" + m.name + "' " + energy.message());
    return material;
  }

  const std::string& path_;
  bool read_textures_;
  const tinyobj::attrib_t& attrib_;
  const std::vector<tinyobj::material_t>& materials_;
  const std::vector<tinyobj::shape_t>& shapes_;
  const std::size_t position_count_, normal_count_, texcoord_count_;
  std::vector<std::pair<bool, std::optional<BaseColorTexture>>> textures_;  // per material
  bool single_shape_ = false;
  std::size_t mixed_material_shapes_ = 0;
  std::set<std::string> reported_lowered_;
  Scene scene_;
};

}  // namespace

Scene read_obj_scene(const std::string& path, bool textures) {
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
  Scene scene = ObjSceneBuilder(path, reader, textures).build();
  if (!warnings.empty()) std::fprintf(stderr, "%s: warning: %s\n", path.c_str(), warnings.c_str());
  return scene;
}

}  // namespace prt::scene::detail
