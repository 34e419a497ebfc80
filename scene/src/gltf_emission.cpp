#include "gltf_emission.h"

#include <tiny_gltf.h>

namespace prt::scene {

glm::vec3 gltf_emission(const tinygltf::Material& material) {
  const std::vector<double>& factor = material.emissiveFactor;
  if (factor.size() < 3) return glm::vec3(0.f);
  double strength = 1.0;
  const auto found = material.extensions.find("KHR_materials_emissive_strength");
  if (found != material.extensions.end() && found->second.IsObject() &&
      found->second.Has("emissiveStrength")) {
    const tinygltf::Value& value = found->second.Get("emissiveStrength");
    if (value.IsNumber()) strength = value.GetNumberAsDouble();
  }
  return glm::vec3(glm::dvec3(factor[0], factor[1], factor[2]) * strength);
}

}  // namespace prt::scene
