// scene/src/vertex_materials.cpp — the material of every vertex (scene/vertex_materials.h).
#include "scene/vertex_materials.h"

#include <algorithm>
#include <limits>

namespace prt::scene {
namespace {

bool same_rgb(const brdf::Rgb& a, const brdf::Rgb& b) {
  return a.r == b.r && a.g == b.g && a.b == b.b;
}

brdf::Material lambert(const glm::vec3& albedo) {
  brdf::Material m;
  m.model = brdf::MaterialModel::kLambert;
  m.diffuse = {albedo.x, albedo.y, albedo.z};
  return m;
}

}  // namespace

bool same_material(const brdf::Material& a, const brdf::Material& b) {
  return a.model == b.model && same_rgb(a.diffuse, b.diffuse) && same_rgb(a.specular, b.specular) &&
         a.exponent == b.exponent && a.alpha_x == b.alpha_x && a.alpha_y == b.alpha_y &&
         a.ward_form == b.ward_form && a.distribution == b.distribution && a.fresnel == b.fresnel &&
         a.eta == b.eta && a.metallic == b.metallic && a.merl_path == b.merl_path;
}

uint32_t material_index(std::vector<brdf::Material>& materials, const brdf::Material& m) {
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (same_material(materials[i], m)) return static_cast<uint32_t>(i);
  materials.push_back(m);
  return static_cast<uint32_t>(materials.size() - 1);
}

void vertex_materials(const Scene& scene, std::vector<brdf::Material>& materials,
                      std::vector<uint32_t>& material_of_vertex) {
  materials.clear();
  const uint32_t none = std::numeric_limits<uint32_t>::max();
  material_of_vertex.assign(scene.vertex_count(), none);
  for (const ScenePrimitive& p : scene.primitives) {
    const std::size_t end =
        std::min<std::size_t>(scene.vertex_count(), std::size_t(p.first_vertex) + p.vertex_count);
    if (!p.brdf_variants.empty() && p.brdf_variant_of_vertex.size() == p.vertex_count) {
      std::vector<uint32_t> index(p.brdf_variants.size());
      for (std::size_t k = 0; k < index.size(); ++k)
        index[k] = material_index(materials, p.brdf_variants[k]);
      for (std::size_t v = p.first_vertex; v < end; ++v) {
        const uint32_t k = p.brdf_variant_of_vertex[v - p.first_vertex];
        material_of_vertex[v] = k < index.size() ? index[k] : index[0];
      }
      continue;
    }
    const uint32_t index = material_index(materials, p.brdf ? *p.brdf : lambert(p.albedo));
    for (std::size_t v = p.first_vertex; v < end; ++v) material_of_vertex[v] = index;
  }
  for (std::size_t v = 0; v < material_of_vertex.size(); ++v) {
    if (material_of_vertex[v] != none) continue;
    const glm::vec3 a = scene.albedo.empty() ? glm::vec3(kDefaultAlbedo) : scene.albedo[v];
    material_of_vertex[v] = material_index(materials, lambert(a));
  }
}

}  // namespace prt::scene
