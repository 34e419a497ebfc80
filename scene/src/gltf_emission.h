// gltf_emission.h — a glTF material's emitted radiance: emissiveFactor × the
// KHR_materials_emissive_strength extension's emissiveStrength (1 when absent). Values are
// returned as stored (the radiosity solver refuses negative or non-finite emission).
#pragma once

#include <glm/glm.hpp>

namespace tinygltf {
struct Material;
}

namespace prt::scene {

glm::vec3 gltf_emission(const tinygltf::Material& material);

}  // namespace prt::scene
