// glTF 2.0 reading through tinygltf (see gltf_loader.h and scene/scene_loader.h).
#include "gltf_loader.h"
#include "gltf_brdf_textures.h"
#include "gltf_emission.h"
#include "gltf_translucency.h"
#include "gltf_extensions.h"
#include "gltf_materials.h"
#include "gltf_textures.h"
#include "scene/scene_loader.h"
#include "scene_file_errors.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>
#include <vector>

#include <tiny_gltf.h>

namespace prt::scene::detail {
namespace {

glm::dmat4 local_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::dmat4 m(1.0);
    for (int c = 0; c < 4; ++c) {
      for (int r = 0; r < 4; ++r) m[c][r] = node.matrix[static_cast<std::size_t>(c * 4 + r)];
    }
    return m;
  }
  glm::dmat4 t(1.0), r(1.0), s(1.0);
  if (node.translation.size() == 3) {
    t[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
  }
  if (node.rotation.size() == 4) {
    // glTF stores (x, y, z, w); normalise in case the file's quaternion is slightly off.
    glm::dvec4 q(node.rotation[0], node.rotation[1], node.rotation[2], node.rotation[3]);
    const double len = glm::length(q);
    if (len > 0.0) q /= len;
    const double x = q.x, y = q.y, z = q.z, w = q.w;
    r[0] = glm::dvec4(1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0);
    r[1] = glm::dvec4(2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0);
    r[2] = glm::dvec4(2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0);
  }
  if (node.scale.size() == 3) {
    s[0][0] = node.scale[0];
    s[1][1] = node.scale[1];
    s[2][2] = node.scale[2];
  }
  return t * r * s;
}

// Albedo of primitives whose material gives no colour we read (see add_mesh).
constexpr float kDefaultGltfAlbedo = kDefaultAlbedo;

class GltfReader {
 public:
  GltfReader(const std::string& path, const tinygltf::Model& model, bool textures)
      : path_(path), model_(model), read_textures_(textures), textures_(path, model) {}

  Scene read() {
    if (model_.scenes.empty()) fail(path_, "the file has no scene (no nodes to load)");
    const int scene_index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (scene_index >= static_cast<int>(model_.scenes.size())) {
      fail(path_, "default scene " + std::to_string(scene_index) + " does not exist");
    }
    visited_.assign(model_.nodes.size(), false);
    for (int node : model_.scenes[static_cast<std::size_t>(scene_index)].nodes) {
      visit(node, glm::dmat4(1.0));
    }
    if (skipped_primitives_ > 0) {
      std::fprintf(stderr, "%s: warning: skipped %zu non-triangle primitive(s)\n", path_.c_str(),
                   skipped_primitives_);
    }
    textures_.report();
    if (invalid_tangents_ > 0)
      std::fprintf(stderr,
                   "%s: warning: %zu TANGENT value(s) are not finite unit vectors with w = +1 or "
                   "-1: their frames are generated instead\n",
                   path_.c_str(), invalid_tangents_);
    if (!scene_.tangents.empty()) scene_.tangents.resize(scene_.positions.size(), glm::vec4(0.f));
    scene_.default_albedo_primitives = defaulted_albedo_primitives_;
    aim_cameras_at_scene();
    return std::move(scene_);
  }

 private:
  void visit(int node_index, const glm::dmat4& parent) {
    if (node_index < 0 || node_index >= static_cast<int>(model_.nodes.size())) {
      fail(path_, "node " + std::to_string(node_index) + " does not exist");
    }
    if (visited_[static_cast<std::size_t>(node_index)]) {
      fail(path_, "node " + std::to_string(node_index) + " appears twice in the hierarchy");
    }
    visited_[static_cast<std::size_t>(node_index)] = true;
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(node_index)];
    const glm::dmat4 world = parent * local_transform(node);
    if (node.mesh >= 0) {
      if (node.mesh >= static_cast<int>(model_.meshes.size())) {
        fail(path_, "node " + std::to_string(node_index) + " refers to missing mesh " +
                        std::to_string(node.mesh));
      }
      add_mesh(node.mesh, world);
    }
    if (node.camera >= 0 && node.camera < static_cast<int>(model_.cameras.size())) {
      add_camera(model_.cameras[static_cast<std::size_t>(node.camera)], world, node.name);
    }
    for (int child : node.children) visit(child, world);
  }

  // glTF gives a camera a direction, not a target: the target becomes the point of the view axis
  // nearest the centre of the scene's bounding box, at least 1% of the box's diagonal ahead
  // (scene_loader.h), so a turntable orbits the scene, not a point in front of the eye.
  void aim_cameras_at_scene() {
    if (scene_.positions.empty()) return;
    const glm::dvec3 lo(scene_.bounds_min()), hi(scene_.bounds_max());
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double least = 0.01 * glm::length(hi - lo);
    if (!(least > 0.0) || !std::isfinite(least)) return;
    for (SceneCamera& camera : scene_.cameras) {
      const glm::dvec3 eye(camera.eye);
      const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - eye);
      const double along = std::max(glm::dot(centre - eye, forward), least);
      camera.target = glm::vec3(eye + along * forward);
    }
  }

  void add_camera(const tinygltf::Camera& camera, const glm::dmat4& world,
                  const std::string& node_name) {
    if (camera.type != "perspective") return;
    SceneCamera out;
    const glm::dvec3 eye(world[3]);
    const glm::dvec3 forward = glm::normalize(glm::dmat3(world) * glm::dvec3(0, 0, -1));
    const glm::dvec3 up = glm::normalize(glm::dmat3(world) * glm::dvec3(0, 1, 0));
    out.eye = glm::vec3(eye);
    out.target = glm::vec3(eye + forward);
    out.up = glm::vec3(up);
    out.yfov_radians = static_cast<float>(camera.perspective.yfov);
    out.name = !camera.name.empty() ? camera.name : node_name;
    scene_.cameras.push_back(out);
  }

  // Byte address of element `index` of an accessor, after checking the whole accessor fits.
  struct AccessorView {
    const unsigned char* data = nullptr;  // null: all zeros (accessor without buffer view)
    std::size_t stride = 0;
    std::size_t count = 0;
  };

  AccessorView view_accessor(int accessor_index, const std::string& what) {
    if (accessor_index < 0 || accessor_index >= static_cast<int>(model_.accessors.size())) {
      fail(path_, what + ": accessor " + std::to_string(accessor_index) + " does not exist");
    }
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(accessor_index)];
    if (accessor.sparse.isSparse) fail(path_, what + ": sparse accessors are not supported");
    AccessorView view;
    view.count = accessor.count;
    if (accessor.bufferView < 0) return view;
    if (accessor.bufferView >= static_cast<int>(model_.bufferViews.size())) {
      fail(path_,
           what + ": buffer view " + std::to_string(accessor.bufferView) + " does not exist");
    }
    const tinygltf::BufferView& buffer_view =
        model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
    if (buffer_view.buffer < 0 || buffer_view.buffer >= static_cast<int>(model_.buffers.size())) {
      fail(path_, what + ": buffer " + std::to_string(buffer_view.buffer) + " does not exist");
    }
    const tinygltf::Buffer& buffer = model_.buffers[static_cast<std::size_t>(buffer_view.buffer)];
    const int element_size =
        tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(accessor.componentType)) *
        tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
    const int stride = accessor.ByteStride(buffer_view);
    if (element_size <= 0 || stride <= 0) fail(path_, what + ": invalid accessor layout");
    view.stride = static_cast<std::size_t>(stride);
    const std::size_t start = buffer_view.byteOffset + accessor.byteOffset;
    const std::size_t needed =
        view.count == 0 ? 0
                        : (view.count - 1) * view.stride + static_cast<std::size_t>(element_size);
    if (accessor.byteOffset + needed > buffer_view.byteLength ||
        start + needed > buffer.data.size()) {
      fail(path_, what + ": accessor " + std::to_string(accessor_index) +
                      " reads past the end of its buffer");
    }
    view.data = buffer.data.data() + start;
    return view;
  }

  std::vector<glm::dvec3> read_vec3(int accessor_index, const std::string& what) {
    const tinygltf::Accessor& accessor =
        model_.accessors.at(static_cast<std::size_t>(accessor_index));
    if (accessor.type != TINYGLTF_TYPE_VEC3 ||
        accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) {
      fail(path_, what + ": only float VEC3 is supported (quantized attributes are not)");
    }
    const AccessorView view = view_accessor(accessor_index, what);
    std::vector<glm::dvec3> out(view.count, glm::dvec3(0.0));
    if (view.data == nullptr) return out;
    for (std::size_t i = 0; i < view.count; ++i) {
      float xyz[3];
      std::memcpy(xyz, view.data + i * view.stride, sizeof xyz);
      out[i] = glm::dvec3(xyz[0], xyz[1], xyz[2]);
    }
    return out;
  }

  // TANGENT: float VEC4 (glTF 2.0 §3.7.2.1), one per vertex. Values that are not a unit-ish
  // finite xyz with w = ±1 are replaced by zero ("missing": scene/tangent_frames.h generates a
  // frame there) and counted for one warning.
  std::vector<glm::dvec4> read_tangents(int accessor_index, const std::string& what,
                                        std::size_t vertex_count) {
    const tinygltf::Accessor& accessor =
        model_.accessors.at(static_cast<std::size_t>(accessor_index));
    if (accessor.type != TINYGLTF_TYPE_VEC4 ||
        accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
      fail(path_, what + ": must be float VEC4");
    const AccessorView view = view_accessor(accessor_index, what);
    if (view.count != vertex_count) fail(path_, what + " and POSITION counts differ");
    std::vector<glm::dvec4> out(view.count, glm::dvec4(0.0));
    for (std::size_t i = 0; i < view.count && view.data != nullptr; ++i) {
      float xyzw[4];
      std::memcpy(xyzw, view.data + i * view.stride, sizeof xyzw);
      const glm::dvec4 t(xyzw[0], xyzw[1], xyzw[2], xyzw[3]);
      const double length = glm::length(glm::dvec3(t));
      if (std::isfinite(length) && length > 1e-6 && std::fabs(std::fabs(t.w) - 1.0) <= 1e-3)
        out[i] = glm::dvec4(glm::dvec3(t) / length, t.w < 0.0 ? -1.0 : 1.0);
      else
        ++invalid_tangents_;
    }
    return out;
  }

  // TEXCOORD_n: float, or normalised unsigned byte or short (glTF 2.0 §3.7.2.1).
  std::vector<glm::vec2> read_texcoords(int accessor_index, const std::string& what) {
    const tinygltf::Accessor& accessor =
        model_.accessors.at(static_cast<std::size_t>(accessor_index));
    const int type = accessor.componentType;
    if (accessor.type != TINYGLTF_TYPE_VEC2 ||
        (type != TINYGLTF_COMPONENT_TYPE_FLOAT && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
         type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT))
      fail(path_, what + ": must be VEC2 of float, or of normalised unsigned byte or short");
    const AccessorView view = view_accessor(accessor_index, what);
    std::vector<glm::vec2> out(view.count, glm::vec2(0.f));
    if (view.data == nullptr) return out;
    for (std::size_t i = 0; i < view.count; ++i) {
      const unsigned char* p = view.data + i * view.stride;
      if (type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
        std::memcpy(&out[i], p, sizeof(glm::vec2));
      } else if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
        out[i] = glm::vec2(p[0], p[1]) / 255.f;
      } else {
        uint16_t st[2];
        std::memcpy(st, p, sizeof st);
        out[i] = glm::vec2(st[0], st[1]) / 65535.f;
      }
    }
    return out;
  }

  // The base-colour texture of `material` and the primitive's coordinates for it, or nullopt
  // (no texture, an unusable image, or no such TEXCOORD_n attribute: warned).
  std::optional<BaseColorTexture> read_texture(const tinygltf::Primitive& primitive,
                                               const std::string& name, std::size_t vertex_count,
                                               std::vector<glm::vec2>& uv) {
    if (!read_textures_) return std::nullopt;
    std::optional<BaseColorTexture> texture = textures_.base_color(primitive.material);
    if (!texture) return std::nullopt;
    const std::string attribute = "TEXCOORD_" + std::to_string(texture->texcoord);
    const auto it = primitive.attributes.find(attribute);
    if (it == primitive.attributes.end()) {
      std::fprintf(stderr,
                   "%s: warning: mesh '%s' has no %s for its base-colour texture: "
                   "baseColorFactor used instead\n",
                   path_.c_str(), name.c_str(), attribute.c_str());
      return std::nullopt;
    }
    uv = read_texcoords(it->second, name + " " + attribute);
    if (uv.size() != vertex_count)
      fail(path_, "mesh '" + name + "': " + attribute + " and POSITION counts differ");
    return texture;
  }

  // Indices are at most 32-bit in glTF (unsigned byte, short or int).
  std::vector<uint32_t> read_indices(int accessor_index, const std::string& what) {
    const tinygltf::Accessor& accessor =
        model_.accessors.at(static_cast<std::size_t>(accessor_index));
    if (accessor.type != TINYGLTF_TYPE_SCALAR) fail(path_, what + ": indices must be SCALAR");
    const AccessorView view = view_accessor(accessor_index, what);
    std::vector<uint32_t> out(view.count, 0);
    if (view.data == nullptr) return out;
    for (std::size_t i = 0; i < view.count; ++i) {
      const unsigned char* p = view.data + i * view.stride;
      switch (accessor.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
          out[i] = *p;
          break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
          uint16_t v;
          std::memcpy(&v, p, sizeof v);
          out[i] = v;
          break;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
          uint32_t v;
          std::memcpy(&v, p, sizeof v);
          out[i] = v;
          break;
        }
        default:
          fail(path_, what + ": indices must be unsigned byte, short or int");
      }
    }
    return out;
  }

  // Room for `more` elements at the end of v, growing geometrically (no copy per primitive).
  template <class T>
  static void reserve_more(std::vector<T>& v, std::size_t more) {
    const std::size_t need = v.size() + more;
    if (need > v.capacity()) v.reserve(std::max(need, 2 * v.capacity()));
  }

  void add_mesh(int mesh_index, const glm::dmat4& world) {
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(mesh_index)];
    const std::string mesh_name =
        mesh.name.empty() ? "mesh" + std::to_string(mesh_index) : mesh.name;
    const glm::dmat3 linear(world);
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    const bool mirrored = glm::determinant(linear) < 0.0;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      const std::string name = mesh_name + "/" + std::to_string(p);
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
        ++skipped_primitives_;
        continue;
      }
      const auto position_it = primitive.attributes.find("POSITION");
      if (position_it == primitive.attributes.end()) {
        fail(path_, "mesh '" + name + "' has no POSITION attribute");
      }
      const std::vector<glm::dvec3> positions = read_vec3(position_it->second, name + " POSITION");
      std::vector<glm::dvec3> normals;
      const auto normal_it = primitive.attributes.find("NORMAL");
      if (normal_it != primitive.attributes.end()) {
        normals = read_vec3(normal_it->second, name + " NORMAL");
        if (normals.size() != positions.size()) {
          fail(path_, "mesh '" + name + "': NORMAL and POSITION counts differ");
        }
      }
      std::vector<uint32_t> indices;
      if (primitive.indices >= 0) {
        indices = read_indices(primitive.indices, name + " indices");
      } else {
        indices.resize(positions.size());
        for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<uint32_t>(i);
      }
      if (indices.size() % 3 != 0) {
        fail(path_, "mesh '" + name + "': index count " + std::to_string(indices.size()) +
                        " is not a multiple of 3");
      }

      ScenePrimitive out;
      out.name = name;
      out.first_vertex = static_cast<uint32_t>(scene_.positions.size());
      out.vertex_count = static_cast<uint32_t>(positions.size());
      out.first_triangle = static_cast<uint32_t>(scene_.triangles.size());
      out.triangle_count = static_cast<uint32_t>(indices.size() / 3);
      // Albedo: the material's baseColorFactor. A primitive with no material, or whose colour
      // comes from a texture we do not read (factor left at its default of 1), would get the
      // glTF default of white — an albedo of 1 that conserves no energy and that the baker
      // refuses — so it gets kDefaultGltfAlbedo instead and is counted for a warning.
      out.albedo = glm::vec3(kDefaultGltfAlbedo);
      std::vector<glm::vec2> uv;
      out.base_color_texture = read_texture(primitive, name, positions.size(), uv);
      bool known_albedo = out.base_color_texture.has_value();
      if (out.base_color_texture) {
        out.albedo = out.base_color_texture->factor;  // load_scene sets factor × texture mean
      } else if (primitive.material >= 0 &&
                 primitive.material < static_cast<int>(model_.materials.size())) {
        const tinygltf::PbrMetallicRoughness& pbr =
            model_.materials[static_cast<std::size_t>(primitive.material)].pbrMetallicRoughness;
        const std::vector<double>& factor = pbr.baseColorFactor;
        const bool default_factor =
            factor.size() >= 3 && factor[0] == 1.0 && factor[1] == 1.0 && factor[2] == 1.0;
        if (factor.size() >= 3 && !(default_factor && pbr.baseColorTexture.index >= 0)) {
          out.albedo = glm::vec3(glm::dvec3(factor[0], factor[1], factor[2]));
          known_albedo = true;
        }
      }
      if (!known_albedo) ++defaulted_albedo_primitives_;
      read_material(primitive, out);
      read_brdf_texture(primitive, name, positions.size(), out);
      const std::vector<glm::dvec4> tangents = read_primitive_tangents(primitive, name, positions);
      if (uv.empty() && tangents.empty() && out.brdf && !out.brdf->isotropic()) {
        // Anisotropic without TANGENT: keep TEXCOORD_0 for tangents from the UVs.
        const auto it = primitive.attributes.find("TEXCOORD_0");
        if (it != primitive.attributes.end()) uv = read_texcoords(it->second, name + " TEXCOORD_0");
        if (uv.size() != positions.size()) uv.clear();
      }

      reserve_more(scene_.positions, positions.size());
      reserve_more(scene_.normals, positions.size());
      reserve_more(scene_.triangles, indices.size() / 3);
      for (std::size_t v = 0; v < positions.size(); ++v) {
        scene_.positions.emplace_back(glm::vec3(glm::dvec3(world * glm::dvec4(positions[v], 1.0))));
        glm::vec3 n(0.f);  // zero marks "missing": computed by load_scene
        if (!normals.empty()) {
          const glm::dvec3 transformed = normal_matrix * normals[v];
          const double length = glm::length(transformed);
          if (length > 0.0 && std::isfinite(length)) n = glm::vec3(transformed / length);
        }
        scene_.normals.push_back(n);
      }
      scene_.albedo.resize(scene_.positions.size(), out.albedo);
      append_tangents(tangents, linear, mirrored, out.first_vertex);
      if (!uv.empty() || !scene_.texcoords.empty()) {
        scene_.texcoords.resize(out.first_vertex, glm::vec2(0.f));
        if (uv.empty()) uv.assign(positions.size(), glm::vec2(0.f));
        scene_.texcoords.insert(scene_.texcoords.end(), uv.begin(), uv.end());
      }
      for (std::size_t t = 0; t < indices.size(); t += 3) {
        for (std::size_t k = 0; k < 3; ++k) {
          if (indices[t + k] >= positions.size()) {
            fail(path_, "mesh '" + name + "': index " + std::to_string(indices[t + k]) +
                            " out of range (" + std::to_string(positions.size()) + " vertices)");
          }
        }
        glm::uvec3 tri(static_cast<uint32_t>(indices[t]), static_cast<uint32_t>(indices[t + 1]),
                       static_cast<uint32_t>(indices[t + 2]));
        if (mirrored) std::swap(tri.y, tri.z);  // keep counter-clockwise after a reflection
        scene_.triangles.push_back(tri + out.first_vertex);
      }
      scene_.primitives.push_back(std::move(out));
    }
  }

  // The material's name, emission and BRDF (gltf_materials.h); the BRDF's base colour is the
  // primitive's albedo as load_scene will set it (factor × the texture's mean when textured).
  void read_material(const tinygltf::Primitive& primitive, ScenePrimitive& out) {
    if (primitive.material < 0 || primitive.material >= static_cast<int>(model_.materials.size()))
      return;
    const tinygltf::Material& m = model_.materials[static_cast<std::size_t>(primitive.material)];
    out.material = m.name;
    out.emission = gltf_emission(m);
    out.translucency = gltf_translucency(m);
    const GltfBrdf read = gltf_brdf(path_, m, brdf_base_color(out));
    out.brdf = read.brdf;
    out.anisotropy_rotation = read.anisotropy_rotation;
  }

  static glm::vec3 brdf_base_color(const ScenePrimitive& out) {
    if (!out.base_color_texture) return out.albedo;
    return glm::clamp(
        out.base_color_texture->factor * glm::vec3(out.base_color_texture->image->mean()),
        glm::vec3(0.f), glm::vec3(kMaxTexturedAlbedo));
  }

  // The material's parameter textures read at each vertex's TEXCOORD_n (gltf_brdf_textures.h).
  void read_brdf_texture(const tinygltf::Primitive& primitive, const std::string& name,
                         std::size_t vertex_count, ScenePrimitive& out) {
    if (primitive.material < 0 || primitive.material >= static_cast<int>(model_.materials.size()))
      return;
    const tinygltf::Material& m = model_.materials[static_cast<std::size_t>(primitive.material)];
    const auto texcoords = [&](int set, std::string* problem) {
      const std::string attribute = "TEXCOORD_" + std::to_string(set);
      const auto it = primitive.attributes.find(attribute);
      if (it == primitive.attributes.end()) {
        *problem = "mesh '" + name + "' has no " + attribute;
        return std::vector<glm::vec2>();
      }
      std::vector<glm::vec2> uv = read_texcoords(it->second, name + " " + attribute);
      if (uv.size() != vertex_count)
        fail(path_, "mesh '" + name + "': " + attribute + " and POSITION counts differ");
      return uv;
    };
    read_brdf_textures(path_, m, textures_, texcoords, vertex_count, brdf_base_color(out), out);
  }

  // The primitive's TANGENT attribute (object space, validated), or empty when it has none.
  std::vector<glm::dvec4> read_primitive_tangents(const tinygltf::Primitive& primitive,
                                                  const std::string& name,
                                                  const std::vector<glm::dvec3>& positions) {
    const auto it = primitive.attributes.find("TANGENT");
    if (it == primitive.attributes.end()) return {};
    return read_tangents(it->second, name + " TANGENT", positions.size());
  }

  // Appends the primitive's tangents in world space (Scene::tangents; zeros for primitives
  // without). The tangent is a surface direction, so it takes the linear part of the node
  // transform; a mirroring transform flips the handedness w, so that w · cross(n, t) is still
  // the transformed bitangent.
  void append_tangents(const std::vector<glm::dvec4>& tangents, const glm::dmat3& linear,
                       bool mirrored, uint32_t first_vertex) {
    if (tangents.empty() && scene_.tangents.empty()) return;
    scene_.tangents.resize(first_vertex, glm::vec4(0.f));
    for (const glm::dvec4& t : tangents) {
      const glm::dvec3 world = linear * glm::dvec3(t);
      const double length = glm::length(world);
      if (t.w == 0.0 || !(length > 0.0) || !std::isfinite(length)) {
        scene_.tangents.emplace_back(0.f);
        continue;
      }
      scene_.tangents.emplace_back(glm::vec3(world / length), mirrored ? -t.w : t.w);
    }
    scene_.tangents.resize(scene_.positions.size(), glm::vec4(0.f));
  }

  const std::string& path_;
  const tinygltf::Model& model_;
  bool read_textures_;
  GltfTextures textures_;
  Scene scene_;
  std::vector<bool> visited_;
  std::size_t skipped_primitives_ = 0;
  std::size_t defaulted_albedo_primitives_ = 0;
  std::size_t invalid_tangents_ = 0;
};

// Lists images whose external file is missing (for filtering tinygltf's warnings about them;
// GltfTextures reports the base-colour ones).
std::vector<std::string> find_missing_images(const std::string& path,
                                             const tinygltf::Model& model) {
  std::vector<std::string> missing;
  const std::filesystem::path base = std::filesystem::path(path).parent_path();
  for (const tinygltf::Image& image : model.images) {
    if (image.uri.empty() || image.uri.rfind("data:", 0) == 0) continue;
    std::error_code ec;
    if (!std::filesystem::exists(base / decode_uri(image.uri), ec)) missing.push_back(image.uri);
  }
  return missing;
}

// Drops tinygltf's warning lines about images (reported separately) and condenses the rest.
std::string filter_warnings(const std::string& warnings,
                            const std::vector<std::string>& missing_images) {
  std::string kept, line;
  std::istringstream in(warnings);
  while (std::getline(in, line)) {
    bool about_image = line.find("for image[") != std::string::npos ||
                       line.find("Image data is empty") != std::string::npos;
    for (const std::string& uri : missing_images) {
      if (line.find(uri) != std::string::npos || line.find(decode_uri(uri)) != std::string::npos) {
        about_image = true;
      }
    }
    if (!about_image) kept += line + "\n";
  }
  return condense(kept);
}

}  // namespace

Scene read_gltf_scene(const std::string& path, bool binary, bool textures) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such file");
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&keep_image_bytes, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  const bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                         : loader.LoadASCIIFromFile(&model, &error, &warning, path);
  check_required_extensions(path, model.extensionsRequired);  // filled even when loading fails
  if (!ok) {
    std::string message = condense(error);
    if (message.empty()) message = condense(warning);
    fail(path, "cannot load glTF: " + (message.empty() ? "unknown error" : message));
  }
  note_optional_extensions(path, model.extensionsUsed, model.extensionsRequired);
  const std::vector<std::string> missing_images = find_missing_images(path, model);
  const std::string other_warnings = filter_warnings(warning, missing_images);
  if (!other_warnings.empty()) {
    std::fprintf(stderr, "%s: warning: %s\n", path.c_str(), other_warnings.c_str());
  }
  return GltfReader(path, model, textures).read();
}

}  // namespace prt::scene::detail
