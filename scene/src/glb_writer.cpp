// Binary glTF writing through tinygltf's serializer (see scene/glb_writer.h).
#include "scene/glb_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include <tiny_gltf.h>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "prt/core/atomic_file.h"
#include "scene_file_errors.h"

namespace prt::scene {
namespace {

using detail::fail;

// Appends raw bytes to the buffer (4-byte aligned) and returns a new buffer view's index.
int add_buffer_view(tinygltf::Model& model, const void* bytes, std::size_t size, int target) {
  std::vector<unsigned char>& data = model.buffers[0].data;
  while (data.size() % 4 != 0) data.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  const auto* first = static_cast<const unsigned char*>(bytes);
  data.insert(data.end(), first, first + size);
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size() - 1);
}

int add_vec3_accessor(tinygltf::Model& model, const glm::vec3* values, std::size_t count,
                      bool with_bounds) {
  tinygltf::Accessor accessor;
  accessor.bufferView =
      add_buffer_view(model, values, count * sizeof(glm::vec3), TINYGLTF_TARGET_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  accessor.type = TINYGLTF_TYPE_VEC3;
  accessor.count = count;
  if (with_bounds && count > 0) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (std::size_t i = 0; i < count; ++i) {
      lo = glm::min(lo, values[i]);
      hi = glm::max(hi, values[i]);
    }
    accessor.minValues = {lo.x, lo.y, lo.z};
    accessor.maxValues = {hi.x, hi.y, hi.z};
  }
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

constexpr const char* kUnlitExtension = "KHR_materials_unlit";
constexpr const char* kSpecularExtension = "KHR_materials_specular";
constexpr const char* kAnisotropyExtension = "KHR_materials_anisotropy";
constexpr const char* kEmissiveStrengthExtension = "KHR_materials_emissive_strength";

void use_extension(tinygltf::Model& model, const char* name) {
  if (std::find(model.extensionsUsed.begin(), model.extensionsUsed.end(), name) ==
      model.extensionsUsed.end())
    model.extensionsUsed.push_back(name);
}

tinygltf::Value number(double v) {
  return tinygltf::Value(v);
}

// A glTF BRDF (MaterialModel::kGltf) as itself: baseColor, metallic, and, unless a pure metal,
// KHR_materials_specular with specularColorFactor = F0_dielectric / 0.04. A GGX + Schlick
// microfacet BRDF as the nearest metallic-roughness material (the loader reads it back as the
// spec's mix, not the added layer): a pure lobe (no Lambert layer) is a metal with
// baseColor = F0; otherwise a dielectric with baseColor = the Lambert layer and
// KHR_materials_specular's specularColorFactor = F0 / 0.04 (always written, so that a
// roughness of 1 is not read back as Lambert). α_x ≠ α_y: KHR_materials_anisotropy with
// α = the smaller and strength s from α_large = mix(α, 1, s²); when α_y is the larger the
// rotation gains π/2.
void write_microfacet(tinygltf::Model& model, tinygltf::Material& material, const brdf::Material& m,
                      float rotation) {
  auto& pbr = material.pbrMetallicRoughness;
  const bool gltf = m.model == brdf::MaterialModel::kGltf;
  const bool metal =
      gltf ? m.metallic == 1.0 : m.diffuse.r == 0.0 && m.diffuse.g == 0.0 && m.diffuse.b == 0.0;
  const brdf::Rgb base = gltf || !metal ? m.diffuse : m.specular;
  pbr.metallicFactor = gltf ? m.metallic : metal ? 1.0 : 0.0;
  pbr.baseColorFactor = {base.r, base.g, base.b, 1.0};
  if (!metal) {
    tinygltf::Value::Object specular;
    specular["specularFactor"] = number(1.0);
    specular["specularColorFactor"] = tinygltf::Value(tinygltf::Value::Array{
        number(m.specular.r / 0.04), number(m.specular.g / 0.04), number(m.specular.b / 0.04)});
    material.extensions[kSpecularExtension] = tinygltf::Value(specular);
    use_extension(model, kSpecularExtension);
  }
  const double small = std::min(m.alpha_x, m.alpha_y), large = std::max(m.alpha_x, m.alpha_y);
  pbr.roughnessFactor = std::sqrt(small);
  if (large > small && small < 1.0) {
    const double strength = std::sqrt(std::clamp((large - small) / (1.0 - small), 0.0, 1.0));
    const double turn = m.alpha_x >= m.alpha_y ? 0.0 : std::acos(0.0);
    tinygltf::Value::Object anisotropy;
    anisotropy["anisotropyStrength"] = number(strength);
    anisotropy["anisotropyRotation"] = number(double(rotation) + turn);
    material.extensions[kAnisotropyExtension] = tinygltf::Value(anisotropy);
    use_extension(model, kAnisotropyExtension);
  }
}

// Emission as glTF holds it: emissiveFactor in [0, 1], times KHR_materials_emissive_strength
// when a channel exceeds 1 (the factor is then the colour over its largest channel).
void write_emission(tinygltf::Model& model, tinygltf::Material& material, glm::vec3 emission) {
  const double largest = std::max({emission.x, emission.y, emission.z});
  if (!(largest > 0.0)) return;
  const double scale = largest > 1.0 ? largest : 1.0;
  material.emissiveFactor = {emission.x / scale, emission.y / scale, emission.z / scale};
  if (scale > 1.0) {
    tinygltf::Value::Object strength;
    strength["emissiveStrength"] = number(scale);
    material.extensions[kEmissiveStrengthExtension] = tinygltf::Value(strength);
    use_extension(model, kEmissiveStrengthExtension);
  }
}

// A diffuse material of the primitive's albedo; with baked colours, an unlit white one, so that
// a viewer shows COLOR_0 as it is instead of lighting it (and multiplying by the albedo) again.
tinygltf::Material make_material(tinygltf::Model& model, const ScenePrimitive& primitive,
                                 bool baked_colors) {
  tinygltf::Material material;
  material.name = primitive.material.empty() ? primitive.name : primitive.material;
  material.pbrMetallicRoughness.metallicFactor = 0.0;
  material.pbrMetallicRoughness.roughnessFactor = 1.0;
  if (baked_colors) {
    material.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
    material.extensions[kUnlitExtension] = tinygltf::Value(tinygltf::Value::Object());
  } else {
    material.pbrMetallicRoughness.baseColorFactor = {primitive.albedo.x, primitive.albedo.y,
                                                     primitive.albedo.z, 1.0};
    write_emission(model, material, primitive.emission);
    const std::optional<brdf::Material>& b = primitive.brdf;
    if (b && (b->model == brdf::MaterialModel::kGltf ||
              (b->model == brdf::MaterialModel::kMicrofacet &&
               b->distribution == brdf::NormalDistribution::kGgx &&
               b->fresnel == brdf::FresnelMode::kSchlick)))
      write_microfacet(model, material, *b, primitive.anisotropy_rotation);
  }
  return material;
}

// Rotation taking the camera's local frame (looks down -Z, up +Y) to the look-at frame.
glm::dquat look_at_rotation(const SceneCamera& camera) {
  const glm::dvec3 forward = glm::normalize(glm::dvec3(camera.target) - glm::dvec3(camera.eye));
  const glm::dvec3 z = -forward;
  glm::dvec3 x = glm::cross(glm::dvec3(camera.up), z);
  if (glm::length(x) < 1e-9) x = glm::cross(glm::dvec3(0, 0, 1), z);  // up parallel to view
  if (glm::length(x) < 1e-9) x = glm::dvec3(1, 0, 0);
  x = glm::normalize(x);
  const glm::dvec3 y = glm::cross(z, x);
  return glm::normalize(glm::quat_cast(glm::dmat3(x, y, z)));
}

// Whether every tangent of the primitive is a valid glTF TANGENT (finite unit xyz, w = ±1).
bool has_tangents(const Scene& scene, const ScenePrimitive& primitive) {
  if (scene.tangents.size() != scene.positions.size() || primitive.vertex_count == 0) return false;
  for (uint32_t v = primitive.first_vertex; v < primitive.first_vertex + primitive.vertex_count;
       ++v) {
    const glm::vec4 t = scene.tangents[v];
    const float length = glm::length(glm::vec3(t));
    if (!(std::fabs(length - 1.f) < 1e-3f) || std::fabs(t.w) != 1.f) return false;
  }
  return true;
}

// A JSON value as tinygltf's Value (for extras).
tinygltf::Value to_value(const nlohmann::json& j) {
  if (j.is_object()) {
    tinygltf::Value::Object object;
    for (auto it = j.begin(); it != j.end(); ++it) object[it.key()] = to_value(it.value());
    return tinygltf::Value(std::move(object));
  }
  if (j.is_array()) {
    tinygltf::Value::Array array;
    for (const nlohmann::json& item : j) array.push_back(to_value(item));
    return tinygltf::Value(std::move(array));
  }
  if (j.is_boolean()) return tinygltf::Value(j.get<bool>());
  if (j.is_number_integer() && j.get<double>() == double(int(j.get<double>())))
    return tinygltf::Value(j.get<int>());
  if (j.is_number()) return tinygltf::Value(j.get<double>());
  if (j.is_string()) return tinygltf::Value(j.get<std::string>());
  return tinygltf::Value();
}

tinygltf::Value parse_extras(const std::string& path, const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (!j.is_object()) fail(path, "extras must be a JSON object");
  return to_value(j);
}

void check_custom(const std::string& path, const Scene& scene, const GlbCustomData& custom) {
  for (const GlbCustomAttribute& a : custom.attributes) {
    if (a.name.size() < 2 || a.name[0] != '_')
      fail(path, "attribute '" + a.name + "': application-specific names begin with '_'");
    if (a.components < 1 || a.components > 4 ||
        a.values.size() != std::size_t(a.components) * scene.vertex_count())
      fail(path, "attribute '" + a.name + "' does not hold " + std::to_string(a.components) +
                     " floats per vertex");
  }
}

int add_custom_accessor(tinygltf::Model& model, const GlbCustomAttribute& a,
                        const ScenePrimitive& primitive) {
  tinygltf::Accessor accessor;
  const std::size_t n = std::size_t(a.components);
  accessor.bufferView =
      add_buffer_view(model, a.values.data() + n * primitive.first_vertex,
                      n * primitive.vertex_count * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  static constexpr int kTypes[] = {TINYGLTF_TYPE_SCALAR, TINYGLTF_TYPE_VEC2, TINYGLTF_TYPE_VEC3,
                                   TINYGLTF_TYPE_VEC4};
  accessor.type = kTypes[a.components - 1];
  accessor.count = primitive.vertex_count;
  model.accessors.push_back(accessor);
  return static_cast<int>(model.accessors.size() - 1);
}

tinygltf::Model build_model(const std::string& path, const Scene& scene,
                            const std::vector<glm::vec3>* vertex_colors,
                            const GlbCustomData* custom) {
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "prt make-scene / write_glb";
  model.buffers.resize(1);
  tinygltf::Scene gltf_scene;
  gltf_scene.name = "scene";

  for (const ScenePrimitive& primitive : scene.primitives) {
    if (static_cast<std::size_t>(primitive.first_vertex) + primitive.vertex_count >
            scene.positions.size() ||
        static_cast<std::size_t>(primitive.first_triangle) + primitive.triangle_count >
            scene.triangles.size()) {
      fail(path, "primitive '" + primitive.name + "' has ranges outside the scene");
    }
    std::vector<uint32_t> indices;
    indices.reserve(primitive.triangle_count * 3u);
    for (uint32_t t = 0; t < primitive.triangle_count; ++t) {
      const glm::uvec3& tri = scene.triangles[primitive.first_triangle + t];
      for (int k = 0; k < 3; ++k) {
        if (tri[k] < primitive.first_vertex ||
            tri[k] - primitive.first_vertex >= primitive.vertex_count) {
          fail(path, "primitive '" + primitive.name + "' has a triangle using another's vertex");
        }
        indices.push_back(tri[k] - primitive.first_vertex);
      }
    }
    tinygltf::Primitive gltf_primitive;
    gltf_primitive.mode = TINYGLTF_MODE_TRIANGLES;
    gltf_primitive.attributes["POSITION"] = add_vec3_accessor(
        model, scene.positions.data() + primitive.first_vertex, primitive.vertex_count, true);
    gltf_primitive.attributes["NORMAL"] = add_vec3_accessor(
        model, scene.normals.data() + primitive.first_vertex, primitive.vertex_count, false);
    if (has_tangents(scene, primitive)) {
      tinygltf::Accessor tangents;
      tangents.bufferView =
          add_buffer_view(model, scene.tangents.data() + primitive.first_vertex,
                          primitive.vertex_count * sizeof(glm::vec4), TINYGLTF_TARGET_ARRAY_BUFFER);
      tangents.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
      tangents.type = TINYGLTF_TYPE_VEC4;
      tangents.count = primitive.vertex_count;
      model.accessors.push_back(tangents);
      gltf_primitive.attributes["TANGENT"] = static_cast<int>(model.accessors.size() - 1);
    }
    if (vertex_colors) {
      gltf_primitive.attributes["COLOR_0"] = add_vec3_accessor(
          model, vertex_colors->data() + primitive.first_vertex, primitive.vertex_count, false);
    }
    if (custom)
      for (const GlbCustomAttribute& a : custom->attributes)
        gltf_primitive.attributes[a.name] = add_custom_accessor(model, a, primitive);
    tinygltf::Accessor index_accessor;
    index_accessor.bufferView = add_buffer_view(model, indices.data(), indices.size() * 4,
                                                TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    index_accessor.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    index_accessor.type = TINYGLTF_TYPE_SCALAR;
    index_accessor.count = indices.size();
    model.accessors.push_back(index_accessor);
    gltf_primitive.indices = static_cast<int>(model.accessors.size() - 1);

    model.materials.push_back(make_material(model, primitive, vertex_colors != nullptr));
    gltf_primitive.material = static_cast<int>(model.materials.size() - 1);

    tinygltf::Mesh mesh;
    mesh.name = primitive.name;
    mesh.primitives.push_back(gltf_primitive);
    if (custom && !custom->mesh_extras_json.empty())
      mesh.extras = parse_extras(path, custom->mesh_extras_json);
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = primitive.name;
    node.mesh = static_cast<int>(model.meshes.size() - 1);
    model.nodes.push_back(node);
    gltf_scene.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  }

  const double far_plane = std::max(1.0, 100.0 * static_cast<double>(scene.extent()));
  for (const SceneCamera& camera : scene.cameras) {
    tinygltf::Camera gltf_camera;
    gltf_camera.type = "perspective";
    gltf_camera.name = camera.name;
    gltf_camera.perspective.yfov = camera.yfov_radians;
    gltf_camera.perspective.znear = far_plane * 1e-5;
    gltf_camera.perspective.zfar = far_plane;
    model.cameras.push_back(gltf_camera);
    tinygltf::Node node;
    node.name = camera.name.empty() ? "camera" : camera.name;
    node.camera = static_cast<int>(model.cameras.size() - 1);
    node.translation = {camera.eye.x, camera.eye.y, camera.eye.z};
    const glm::dquat q = look_at_rotation(camera);
    node.rotation = {q.x, q.y, q.z, q.w};
    model.nodes.push_back(node);
    gltf_scene.nodes.push_back(static_cast<int>(model.nodes.size() - 1));
  }
  if (custom && !custom->scene_extras_json.empty())
    gltf_scene.extras = parse_extras(path, custom->scene_extras_json);
  model.scenes.push_back(gltf_scene);
  model.defaultScene = 0;
  if (vertex_colors) use_extension(model, kUnlitExtension);
  return model;
}

}  // namespace

void write_glb(const std::string& path, const Scene& scene,
               const std::vector<glm::vec3>* vertex_colors, const GlbCustomData* custom) {
  if (scene.normals.size() != scene.positions.size()) {
    fail(path, "the scene has " + std::to_string(scene.normals.size()) + " normals for " +
                   std::to_string(scene.positions.size()) + " vertices");
  }
  if (vertex_colors && vertex_colors->size() != scene.positions.size()) {
    fail(path, "got " + std::to_string(vertex_colors->size()) + " vertex colours for " +
                   std::to_string(scene.positions.size()) + " vertices");
  }
  if (custom) check_custom(path, scene, *custom);
  const tinygltf::Model model = build_model(path, scene, vertex_colors, custom);
  // Into memory first, then one checked atomic write: tinygltf's own file writer does not check
  // the stream, so a full disk would leave a truncated file behind a success.
  std::ostringstream bytes;
  tinygltf::TinyGLTF writer;
  if (!writer.WriteGltfSceneToStream(&model, bytes, /*prettyPrint=*/false, /*writeBinary=*/true))
    fail(path, "cannot encode the binary glTF");
  const std::string data = bytes.str();
  const Status written = write_file_atomically(path, data.data(), data.size());
  if (!written.ok()) throw SceneError(written.message());
}

}  // namespace prt::scene
