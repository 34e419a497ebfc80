// scene/vertex_materials.h — the BRDF of every vertex of a scene, as a table of distinct
// materials and one index per vertex: what a glossy bake stores (prt/glossy/transfer.h:
// GlossyTransferData::materials, material_of_vertex) and what `prt relight --material` rebuilds
// for the vertices it overrides.
//
// A primitive's vertices get its ScenePrimitive::brdf, or Lambert with its `albedo` when it has
// none — or, when it has per-vertex variants (textured parameters), each vertex its own; a vertex
// outside every primitive gets Lambert with its own albedo (kDefaultAlbedo when the scene has
// none). Equal materials (every field equal) are stored once, in order of first use, so two
// primitives with the same BRDF share one entry (and one b(ω_o) table at runtime).
#pragma once

#include <cstdint>
#include <vector>

#include "prt/brdf/material.h"
#include "scene/scene.h"

namespace prt::scene {

// Every field equal.
bool same_material(const brdf::Material& a, const brdf::Material& b);

// Index of `m` in `materials`, appended when no equal one is there.
uint32_t material_index(std::vector<brdf::Material>& materials, const brdf::Material& m);

// The materials of the scene and each vertex's index into them (see above).
void vertex_materials(const Scene& scene, std::vector<brdf::Material>& materials,
                      std::vector<uint32_t>& material_of_vertex);

}  // namespace prt::scene
