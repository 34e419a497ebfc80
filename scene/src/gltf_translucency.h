// gltf_translucency.h (private) — a glTF material's KHR_materials_volume
// (attenuationDistance, attenuationColor, thicknessFactor), KHR_materials_diffuse_transmission
// (diffuseTransmissionFactor, diffuseTransmissionColorFactor) and KHR_materials_ior (ior), read
// as written; absent when the material has neither of the first two. A member that is present
// but not a number (or not three numbers) reads as NaN so that its user can refuse it by name.
#pragma once

#include <optional>

#include "scene/scene.h"

namespace tinygltf {
struct Material;
}

namespace prt::scene {

std::optional<GltfTranslucency> gltf_translucency(const tinygltf::Material& material);

}  // namespace prt::scene
