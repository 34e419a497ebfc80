// prt/glossy/transfer.h — the in-memory contents of a glossy transfer file: one transfer
// MATRIX per vertex (Sloan, Kautz & Snyder 2002, §6; [2] of docs/REFERENCES.md).
//
// Under distant lighting whose radiance has SH coefficients L (global frame, sh/basis.h), the
// radiance ARRIVING at vertex p — shadowed, and interreflected when the bake asked for bounces —
// has SH coefficients
//     L'_p,c,i = Σ_j M_p,c,i,j · L_c,j,      i, j < n², n = order,
// expressed in the vertex's LOCAL tangent frame (scene/tangent_frames.h; the frame of
// prt/brdf/brdf.h: +z normal, +x tangent, +y bitangent = w · cross(n, t)). The change of frame
// is an SH rotation, exact within each band, so it is folded into M at bake time and the
// runtime never rotates SH per vertex: the view direction is moved into the tangent frame
// instead. Exit radiance toward a unit direction ω_o (local frame) is then
//     L_o = Σ_i b_i(ω_o) · L'_p,c,i,   b_i(ω_o) = ∫ y_i(ω_i) f(ω_i, ω_o) cos⁺θ_i dω_i,
// with f the vertex's BRDF (materials[material_of_vertex[p]]). M carries no albedo or BRDF:
// it is radiance transport only (channels = 3 when coloured interreflection makes it RGB).
// Compiles as C++17.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "prt/brdf/material.h"
#include "prt/formats/transfer_data.h"

namespace prt {

struct GlossyTransferData {
  uint32_t order = 5;                  // SH order n: n² × n² matrices
  uint32_t channels = 1;               // 1 (grey transport) or 3 (RGB)
  Precision storage = Precision::F32;  // precision of the matrices on disk
  bool interreflected = false;         // bounces included
  uint64_t vertex_count = 0;
  uint64_t fingerprint = 0;  // geometry_fingerprint() of `positions`
  std::vector<PrimitiveRange> primitives;

  std::vector<float> positions;  // 3 · vertex_count, scene frame, scene units
  std::vector<float> normals;    // 3 · vertex_count, unit
  std::vector<float> tangents;   // 4 · vertex_count: unit tangent ⊥ normal, then w = ±1

  // The BRDFs, and which one each vertex has.
  std::vector<brdf::Material> materials;
  std::vector<uint32_t> material_of_vertex;  // vertex_count indices into `materials`

  // Vertex-major, row-major: matrices[((v · channels + c) · n² + i) · n² + j] = M_v,c,i,j.
  std::vector<float> matrices;

  // Bake parameters and anything descriptive, as a JSON object (opaque to the runtime).
  std::string metadata_json;

  uint32_t coefficients() const { return order * order; }
  std::size_t matrix_floats() const { return std::size_t(coefficients()) * coefficients(); }
};

}  // namespace prt
