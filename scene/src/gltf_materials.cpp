#include "gltf_materials.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <tiny_gltf.h>

#include "scene_file_errors.h"

namespace prt::scene::detail {
namespace {

// A number of an extension object, or `fallback` when absent or not a number.
double extension_number(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

const tinygltf::Value* find_extension(const tinygltf::Material& m, const char* name) {
  const auto found = m.extensions.find(name);
  return found != m.extensions.end() && found->second.IsObject() ? &found->second : nullptr;
}

double checked(const std::string& path, const tinygltf::Material& m, const char* what, double v,
               double lo, double hi) {
  if (v >= lo && v <= hi) return v;
  char text[160];
  std::snprintf(text, sizeof text, "%s %.9g outside [%g, %g]", what, v, lo, hi);
  fail(path, "material '" + m.name + "': " + text);
}

brdf::Rgb rgb(const glm::dvec3& c) {
  return brdf::Rgb{c.x, c.y, c.z};
}

}  // namespace

GltfParameters gltf_factors(const std::string& path, const tinygltf::Material& m) {
  const tinygltf::PbrMetallicRoughness& pbr = m.pbrMetallicRoughness;
  GltfParameters out;
  out.metalness = checked(path, m, "metallicFactor", pbr.metallicFactor, 0.0, 1.0);
  out.roughness = checked(path, m, "roughnessFactor", pbr.roughnessFactor, 0.0, 1.0);
  if (const tinygltf::Value* specular = find_extension(m, "KHR_materials_specular")) {
    out.specular = checked(path, m, "specularFactor",
                           extension_number(*specular, "specularFactor", 1.0), 0.0, 1.0);
    if (specular->Has("specularColorFactor")) {
      const tinygltf::Value& c = specular->Get("specularColorFactor");
      for (int k = 0; k < 3 && c.IsArray() && c.ArrayLen() == 3; ++k)
        out.specular_color[k] = c.Get(k).IsNumber() ? c.Get(k).GetNumberAsDouble() : 1.0;
      for (int k = 0; k < 3; ++k)
        checked(path, m, "specularColorFactor", out.specular_color[k], 0.0, 1e6);
    }
  }
  if (const tinygltf::Value* aniso = find_extension(m, "KHR_materials_anisotropy"))
    out.anisotropy = checked(path, m, "anisotropyStrength",
                             extension_number(*aniso, "anisotropyStrength", 0.0), 0.0, 1.0);
  return out;
}

double gltf_anisotropy_rotation(const std::string& path, const tinygltf::Material& m) {
  const tinygltf::Value* aniso = find_extension(m, "KHR_materials_anisotropy");
  const double rotation = aniso ? extension_number(*aniso, "anisotropyRotation", 0.0) : 0.0;
  if (!std::isfinite(rotation)) {
    char text[96];
    std::snprintf(text, sizeof text, "anisotropyRotation %g is not finite", rotation);
    fail(path, "material '" + m.name + "': " + text);
  }
  return rotation;
}

GltfBrdf gltf_brdf(const std::string& path, const tinygltf::Material& m,
                   const glm::vec3& base_color, const GltfParameters* parameters) {
  const GltfParameters factors = gltf_factors(path, m);
  const double rotation = gltf_anisotropy_rotation(path, m);
  const GltfParameters& p = parameters ? *parameters : factors;
  const auto unit = [](double v) { return std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0); };
  const double metallic = unit(p.metalness), roughness = unit(p.roughness);

  double f0_ior = 0.04;
  if (const tinygltf::Value* ior = find_extension(m, "KHR_materials_ior")) {
    const double eta = extension_number(*ior, "ior", 1.5);
    if (eta >= 1.0 && std::isfinite(eta)) f0_ior = std::pow((eta - 1.0) / (eta + 1.0), 2.0);
  }
  glm::dvec3 f0_dielectric(f0_ior);
  const tinygltf::Value* specular = find_extension(m, "KHR_materials_specular");
  if (specular) {
    const glm::dvec3 color = glm::max(p.specular_color, glm::dvec3(0.0));
    f0_dielectric = glm::min(f0_ior * color, glm::dvec3(1.0)) * unit(p.specular);
  }
  const glm::dvec3 base(base_color);
  const glm::dvec3 f0 = f0_dielectric * (1.0 - metallic) + base * metallic;

  GltfBrdf out;
  const bool no_specular = f0.x == 0.0 && f0.y == 0.0 && f0.z == 0.0;
  if (metallic == 0.0 && (no_specular || (roughness == 1.0 && specular == nullptr))) return out;

  const double alpha = std::max(roughness * roughness, kGltfMinAlpha);
  brdf::Material material;
  material.model = brdf::MaterialModel::kGltf;
  material.distribution = brdf::NormalDistribution::kGgx;
  material.fresnel = brdf::FresnelMode::kSchlick;
  material.diffuse = rgb(glm::clamp(base, 0.0, 1.0));
  material.specular = rgb(glm::clamp(f0_dielectric, 0.0, 1.0));
  material.metallic = metallic;
  material.alpha_x = material.alpha_y = alpha;
  if (find_extension(m, "KHR_materials_anisotropy")) {
    const double strength = unit(p.anisotropy);
    material.alpha_x = alpha + (1.0 - alpha) * strength * strength;
    out.anisotropy_rotation = static_cast<float>(rotation);
  }
  out.brdf = material;
  return out;
}

}  // namespace prt::scene::detail
