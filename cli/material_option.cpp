#include "material_option.h"

#include <stdexcept>

#include "command_registry.h"

namespace prt::cli {

void add_material_option(CLI::App& command, std::vector<std::string>& values) {
  command
      .add_option(
          "--material", values,
          "Override a material's BRDF: NAME=MODEL[:KEY=VALUE,...] with MODEL lambert "
          "(kd), blinn-phong (kd, ks, s), ward (rho_d, rho_s, ax, ay), ggx or beckmann "
          "(f0, kd, ax, ay | roughness), gltf (glTF 2.0's BRDF: base, metallic, roughness), "
          "gltf-additive (the same keys, Lambert layer added to the GGX lobe instead of "
          "the spec's Fresnel mix), or NAME=merl:FILE; colours r/g/b; NAME * = all. "
          "A material that reflects more light than arrives (directional albedo above "
          "1) is refused. Repeatable")
      ->take_all()
      ->allow_extra_args(false);
}

std::vector<scene::MaterialOverride> parse_material_options(
    const std::vector<std::string>& values) {
  std::vector<scene::MaterialOverride> out;
  for (const std::string& text : values) {
    try {
      out.push_back(scene::parse_material_override(text, "--material"));
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  return out;
}

}  // namespace prt::cli
