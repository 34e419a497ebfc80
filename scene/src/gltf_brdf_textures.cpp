// scene/src/gltf_brdf_textures.cpp — per-vertex BRDF parameters from a glTF material's textures
// (gltf_brdf_textures.h).
#include "gltf_brdf_textures.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "gltf_materials.h"
#include "scene/brdf_variants.h"

namespace prt::scene::detail {
namespace {

// The components quantised together, in this order.
enum Component { kRoughness, kMetalness, kSpecular, kColourR, kColourG, kColourB, kAnisotropy };
constexpr std::size_t kComponents = 7;

// One texture slot of a material.
struct Slot {
  const char* name;  // the glTF property, for messages
  GltfTextures::TextureRef ref;
  TextureContent content;
  std::string problem;  // a textureInfo without a valid index
  std::optional<GltfTextures::ParameterTexture> texture;
  std::vector<glm::vec3> samples;  // one per vertex
  glm::dvec3 mean{1.0};
};

// The textureInfo `key` of extension `extension` (index −1 when absent).
Slot extension_slot(const tinygltf::Material& m, const char* extension, const char* key,
                    TextureContent content) {
  Slot slot{key, {}, content, {}, std::nullopt, {}, glm::dvec3(1.0)};
  const auto found = m.extensions.find(extension);
  if (found == m.extensions.end() || !found->second.IsObject() || !found->second.Has(key))
    return slot;
  const tinygltf::Value& info = found->second.Get(key);
  const tinygltf::Value index = info.IsObject() ? info.Get("index") : tinygltf::Value();
  const double i = index.IsNumber() ? index.GetNumberAsDouble() : -1.0;
  if (!(i >= 0.0) || i != std::floor(i) || i > 2e9) {
    slot.problem = "has no valid texture index";
    return slot;
  }
  slot.ref.index = static_cast<int>(i);
  const tinygltf::Value set = info.Get("texCoord");
  if (set.IsNumber()) {
    const double s = set.GetNumberAsDouble();
    if (!(s >= 0.0) || s != std::floor(s) || s > 1e6) {
      slot.problem = "has an invalid texCoord";
      return slot;
    }
    slot.ref.texcoord = static_cast<int>(s);
  }
  return slot;
}

// The four slots of `m`.
std::vector<Slot> material_slots(const tinygltf::Material& m) {
  const tinygltf::TextureInfo& mr = m.pbrMetallicRoughness.metallicRoughnessTexture;
  std::vector<Slot> slots;
  slots.push_back(Slot{"metallicRoughnessTexture",
                       {mr.index, mr.texCoord},
                       TextureContent::kLinear,
                       {},
                       std::nullopt,
                       {},
                       glm::dvec3(1.0)});
  slots.push_back(
      extension_slot(m, "KHR_materials_specular", "specularTexture", TextureContent::kAlpha));
  slots.push_back(extension_slot(m, "KHR_materials_specular", "specularColorTexture",
                                 TextureContent::kSrgbColour));
  slots.push_back(
      extension_slot(m, "KHR_materials_anisotropy", "anisotropyTexture", TextureContent::kLinear));
  return slots;
}

// Decodes and samples every slot; "" or the first problem ("specularTexture PROBLEM").
std::string sample_slots(std::vector<Slot>& slots, GltfTextures& textures,
                         const TexcoordReader& texcoords, std::size_t vertex_count) {
  for (Slot& slot : slots) {
    std::string problem = slot.problem;
    if (problem.empty()) slot.texture = textures.parameter(slot.ref, slot.content, &problem);
    std::vector<glm::vec2> uv;
    if (problem.empty() && slot.texture) uv = texcoords(slot.texture->texcoord, &problem);
    if (!problem.empty()) return std::string(slot.name) + " " + problem;
    if (!slot.texture) continue;
    slot.samples.resize(vertex_count);
    for (std::size_t v = 0; v < vertex_count; ++v)
      slot.samples[v] = slot.texture->image->sample(uv[v], slot.texture->sampler);
    slot.mean = slot.texture->image->mean();
  }
  return "";
}

// factors × the texels `texel` gives for each slot (1 where a slot has no texture).
GltfParameters parameters_of(const GltfParameters& f, const glm::dvec3 texel[4]) {
  GltfParameters p = f;
  p.roughness = f.roughness * texel[0].y;
  p.metalness = f.metalness * texel[0].z;
  p.specular = f.specular * texel[1].x;  // A, replicated
  p.specular_color = f.specular_color * texel[2];
  p.anisotropy = f.anisotropy * texel[3].z;
  return p;
}

std::vector<double> components(const GltfParameters& p) {
  return {p.roughness,        p.metalness,        p.specular,  p.specular_color.x,
          p.specular_color.y, p.specular_color.z, p.anisotropy};
}

GltfParameters from_components(const std::vector<double>& c) {
  GltfParameters p;
  p.roughness = c[kRoughness];
  p.metalness = c[kMetalness];
  p.specular = c[kSpecular];
  p.specular_color = glm::dvec3(c[kColourR], c[kColourG], c[kColourB]);
  p.anisotropy = c[kAnisotropy];
  return p;
}

// The tangent rotation of each vertex from the anisotropyTexture's RG (see the header).
std::vector<float> direction_rotations(const Slot& anisotropy, double rotation) {
  std::vector<float> out(anisotropy.samples.size());
  for (std::size_t v = 0; v < out.size(); ++v) {
    const glm::dvec2 d = 2.0 * glm::dvec2(anisotropy.samples[v]) - 1.0;
    const double angle = glm::length(d) > 1e-9 ? std::atan2(d.y, d.x) : 0.0;
    out[v] = static_cast<float>(angle + rotation);
  }
  return out;
}

std::string textured_label(const std::vector<Slot>& slots) {
  static const char* names[4] = {"roughness/metalness", "specular", "specular colour",
                                 "anisotropy"};
  std::string label;
  for (std::size_t s = 0; s < slots.size(); ++s)
    if (slots[s].texture) label += (label.empty() ? "" : ", ") + std::string(names[s]);
  return label;
}

void note_errors(const std::string& path, const tinygltf::Material& m, const QuantisedVectors& q,
                 std::size_t vertex_count) {
  double colour = 0.0;
  for (std::size_t k = kColourR; k <= kColourB; ++k) colour = std::max(colour, q.max_error[k]);
  double any = colour;
  for (double e : q.max_error) any = std::max(any, e);
  if (!(any > 0.0)) return;
  std::fprintf(stderr,
               "%s: note: material '%s': textured parameters quantised to %zu variants over %zu "
               "vertices (max |error| roughness %.3g, metalness %.3g, specular %.3g, specular "
               "colour %.3g, anisotropy %.3g)\n",
               path.c_str(), m.name.c_str(), q.levels.size(), vertex_count, q.max_error[kRoughness],
               q.max_error[kMetalness], q.max_error[kSpecular], colour, q.max_error[kAnisotropy]);
}

}  // namespace

void read_brdf_textures(const std::string& path, const tinygltf::Material& m,
                        GltfTextures& textures, const TexcoordReader& texcoords,
                        std::size_t vertex_count, const glm::vec3& base, ScenePrimitive& out) {
  std::vector<Slot> slots = material_slots(m);
  const std::string problem = sample_slots(slots, textures, texcoords, vertex_count);
  if (!problem.empty()) {
    // Not printed here: only a glossy bake needs the textures (it refuses the scene with this
    // line); `prt info` lists it with the materials.
    out.brdf_texture_problem = "material '" + m.name + "': " + problem;
    return;
  }
  if (slots[3].texture)
    out.anisotropy_rotation_of_vertex =
        direction_rotations(slots[3], gltf_anisotropy_rotation(path, m));
  if (!slots[0].texture && !slots[1].texture && !slots[2].texture && !slots[3].texture) return;
  const GltfParameters factors = gltf_factors(path, m);
  std::vector<std::vector<double>> samples(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    glm::dvec3 texel[4];
    for (std::size_t s = 0; s < 4; ++s)
      texel[s] = slots[s].texture ? glm::dvec3(slots[s].samples[v]) : glm::dvec3(1.0);
    samples[v] = components(parameters_of(factors, texel));
  }
  const glm::dvec3 means[4] = {slots[0].mean, slots[1].mean, slots[2].mean, slots[3].mean};
  const GltfParameters mean = parameters_of(factors, means);
  out.brdf = gltf_brdf(path, m, base, &mean).brdf;
  const QuantisedVectors q = quantise_parameters(samples);
  out.brdf_textured = textured_label(slots);
  if (q.levels.size() <= 1) {  // one value everywhere: no variants needed
    if (!q.levels.empty()) {
      const GltfParameters only = from_components(q.levels[0]);
      out.brdf = gltf_brdf(path, m, base, &only).brdf;
    }
    return;
  }
  for (const std::vector<double>& level : q.levels) {
    const GltfParameters p = from_components(level);
    const GltfBrdf variant = gltf_brdf(path, m, base, &p);
    brdf::Material lambert;
    lambert.diffuse = {base.x, base.y, base.z};
    out.brdf_variants.push_back(variant.brdf ? *variant.brdf : lambert);
  }
  out.brdf_variant_of_vertex = q.level_of;
  note_errors(path, m, q, vertex_count);
}

}  // namespace prt::scene::detail
