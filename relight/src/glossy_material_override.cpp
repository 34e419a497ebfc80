// relight/src/glossy_material_override.cpp — material overrides for glossy files
// (relight/glossy_material_override.h).
#include "relight/glossy_material_override.h"

#include <cstdint>
#include <limits>
#include <stdexcept>

#include "scene/vertex_materials.h"

namespace prt::relight {
namespace {

// Drops the materials no vertex uses and renumbers the indices (order kept).
void drop_unused_materials(prt::GlossyTransferData& data) {
  const uint32_t unused = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> renumber(data.materials.size(), unused);
  for (uint32_t m : data.material_of_vertex) renumber[m] = 0;
  std::vector<brdf::Material> kept;
  for (std::size_t m = 0; m < data.materials.size(); ++m) {
    if (renumber[m] == unused) continue;
    renumber[m] = static_cast<uint32_t>(kept.size());
    kept.push_back(data.materials[m]);
  }
  for (uint32_t& m : data.material_of_vertex) m = renumber[m];
  data.materials = std::move(kept);
}

}  // namespace

void override_glossy_materials(prt::GlossyTransferData& data, const scene::Scene& scene,
                               const std::vector<scene::MaterialOverride>& overrides) {
  if (overrides.empty()) return;
  if (data.material_of_vertex.size() != scene.vertex_count())
    throw std::invalid_argument(scene.source_path + ": " + std::to_string(scene.vertex_count()) +
                                " vertices, the glossy file " +
                                std::to_string(data.material_of_vertex.size()));
  std::vector<char> overridden(scene.vertex_count(), 0);
  for (const scene::MaterialOverride& o : overrides)
    for (std::size_t i : scene::matched_primitives(scene, o)) {
      const scene::ScenePrimitive& p = scene.primitives[i];
      for (std::size_t v = p.first_vertex; v < std::size_t(p.first_vertex) + p.vertex_count; ++v)
        if (v < overridden.size()) overridden[v] = 1;
    }
  scene::Scene changed = scene;
  scene::apply_material_overrides(changed, overrides);
  std::vector<brdf::Material> materials;
  std::vector<uint32_t> material_of_vertex;
  scene::vertex_materials(changed, materials, material_of_vertex);
  std::vector<uint32_t> into_data(materials.size(), std::numeric_limits<uint32_t>::max());
  for (std::size_t v = 0; v < overridden.size(); ++v) {
    if (!overridden[v]) continue;
    uint32_t& index = into_data[material_of_vertex[v]];
    if (index == std::numeric_limits<uint32_t>::max())
      index = scene::material_index(data.materials, materials[material_of_vertex[v]]);
    data.material_of_vertex[v] = index;
  }
  drop_unused_materials(data);
}

}  // namespace prt::relight
