// relight/transfer_glb.h — a coefficient file as application-specific data of a binary glTF
// (`prt export-gltf`), for web engines: web/prt-relight.js relights it in any three.js app
// (docs/VIEWER.md, "Exporting to glTF").
//
// glTF 2.0 lets an application add vertex attributes whose names begin with an underscore
// (§3.7.2.1, "Meshes"); viewers that do not know them ignore them and still show the mesh.
// Written per vertex (float accessors, in the scene's vertex order, split per primitive as
// scene/glb_writer.h splits the mesh):
//   _PRT_SH0 … _PRT_SH{P−1}   VEC4: the transfer vector, coefficient i = c·order² + k (channel c,
//                             SH index k = l(l+1)+m) in component i mod 4 of _PRT_SH⌊i/4⌋,
//                             zero-padded; P = ⌈channels·order²/4⌉
//   _PRT_AO                   SCALAR, when the file has ambient occlusion
//   _PRT_BENT_NORMAL          VEC3, when the file has bent normals
//   _PRT_ALBEDO               VEC3, the vertex albedo, when the file keeps the albedo apart
//                             (albedo_folded = false: multiply the shaded value by it)
// Every mesh's extras.prt: format "prt-transfer-gltf 1", kind, order, channels, albedo_folded,
// attribute_prefix, attribute_count (P), the SH basis in words. With lighting, the scene's
// extras.prt.lighting: {order, coefficients: 3·order² channel-major radiance SH (unwindowed,
// unrotated), source}. Coefficients are written as float32 (the file's values exactly for an F32
// file). Conventions: docs/CONVENTIONS.md; B_c = Σ_k T_c,k L_c,k (prt/formats/transfer_data.h).
#pragma once

#include <string>

#include "prt/formats/transfer_data.h"
#include "prt/lighting/sh_lighting.h"
#include "scene/glb_writer.h"

namespace prt::relight {

// Attribute names: kTransferAttributePrefix + j.
constexpr const char* kTransferAttributePrefix = "_PRT_SH";

// `lighting` (optional) goes to the scene's extras with `lighting_source` (e.g. the map's path).
scene::GlbCustomData transfer_glb_data(const prt::TransferData& data, const scene::Scene& scene,
                                       const prt::ShLighting* lighting = nullptr,
                                       const std::string& lighting_source = "");

}  // namespace prt::relight
