// relight/glossy_material_override.h — `prt relight --material NAME=MODEL[:KEY=VALUE,...]` for
// glossy transfer files: a look-dev change of a material's BRDF without baking again.
//
// A glossy file's matrices M_p (prt/glossy/transfer.h) carry transport only: the vertex's own
// BRDF f_p enters at shading time, through b_i(ω_o) = ∫ y_i f_p cos⁺θ_i. Replacing f_p of the
// vertices of a material therefore changes exactly what a bake with that material would change
// in the light those vertices reflect DIRECTLY toward the eye — for a shadowed (bounces 0) bake
// the result is the bake's own. What is NOT redone: an interreflected file's M already holds the
// light that other surfaces (and the overridden one itself) bounced with the BAKED materials, so
// that indirect light stays as baked; and the tangent frames stay the file's (an anisotropic
// override's α_x lies along the file's tangent, including any KHR_materials_anisotropy rotation
// the bake applied). Bake again for those.
//
// Matching and syntax are scene/material_override.h's (NAME a material or primitive name of the
// SCENE given to `prt relight`, `*` every primitive); the vertices of the matched primitives get
// the material a bake with the same overrides would store for them (scene/vertex_materials.h).
// Materials no vertex uses any more are dropped, so the relighter builds no table for them.
#pragma once

#include <vector>

#include "prt/glossy/transfer.h"
#include "scene/material_override.h"
#include "scene/scene.h"

namespace prt::relight {

// Applies `overrides` (in order, a later one wins) to data.materials / material_of_vertex.
// `scene` is the scene the file was baked from (same vertex count, checked by the caller).
// Throws std::invalid_argument "--material TEXT: no material or primitive named 'NAME' in
// SCENE (materials: ...)" when an override matches nothing; `data` is then unchanged.
void override_glossy_materials(prt::GlossyTransferData& data, const scene::Scene& scene,
                               const std::vector<scene::MaterialOverride>& overrides);

}  // namespace prt::relight
