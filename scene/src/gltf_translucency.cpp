#include "gltf_translucency.h"

#include <limits>

#include <tiny_gltf.h>

namespace prt::scene {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const tinygltf::Value* extension(const tinygltf::Material& m, const char* name) {
  const auto found = m.extensions.find(name);
  if (found == m.extensions.end() || !found->second.IsObject()) return nullptr;
  return &found->second;
}

void read_number(const tinygltf::Value& object, const char* key, double* out) {
  if (!object.Has(key)) return;
  const tinygltf::Value& v = object.Get(key);
  *out = v.IsNumber() ? v.GetNumberAsDouble() : kNaN;
}

void read_color(const tinygltf::Value& object, const char* key, glm::dvec3* out) {
  if (!object.Has(key)) return;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsArray() || v.ArrayLen() != 3) {
    *out = glm::dvec3(kNaN);
    return;
  }
  for (int c = 0; c < 3; ++c) (*out)[c] = v.Get(c).IsNumber() ? v.Get(c).GetNumberAsDouble() : kNaN;
}

}  // namespace

std::optional<GltfTranslucency> gltf_translucency(const tinygltf::Material& material) {
  const tinygltf::Value* volume = extension(material, "KHR_materials_volume");
  const tinygltf::Value* transmission = extension(material, "KHR_materials_diffuse_transmission");
  if (!volume && !transmission) return std::nullopt;
  GltfTranslucency t;
  if (volume) {
    t.volume = true;
    read_number(*volume, "attenuationDistance", &t.attenuation_distance);
    read_color(*volume, "attenuationColor", &t.attenuation_color);
    read_number(*volume, "thicknessFactor", &t.thickness);
  }
  if (transmission) {
    t.diffuse_transmission = true;
    read_number(*transmission, "diffuseTransmissionFactor", &t.diffuse_transmission_factor);
    read_color(*transmission, "diffuseTransmissionColorFactor", &t.diffuse_transmission_color);
  }
  if (const tinygltf::Value* ior = extension(material, "KHR_materials_ior"))
    read_number(*ior, "ior", &t.ior);
  return t;
}

}  // namespace prt::scene
