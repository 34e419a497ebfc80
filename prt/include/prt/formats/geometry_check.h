// prt/formats/geometry_check.h — is the engine's mesh the one a coefficient file was baked for?
//
// A coefficient file stores one transfer vector per vertex, in the vertex order of the baked
// mesh, plus the positions and a 64-bit fingerprint of them. Before shading, an engine
// checks that its own vertex buffer matches.
//
// Fingerprint: FNV-1a-64 (Fowler–Noll–Vo; offset basis 0xcbf29ce484222325, prime
// 0x100000001b3) applied to 32-bit words instead of bytes — first the vertex count as two
// words (low, high), then the IEEE binary32 bit pattern of every coordinate x0 y0 z0 x1 …
// with −0 replaced by +0 — followed by the splitmix64 finaliser (Steele et al. 2014):
// numerics::WordHash of numerics/hash.h. Each step is a bijection of the state, so changing any
// single coordinate (even by 1 ulp) always changes the fingerprint. Positions are in the scene
// frame (glTF, +Y up), scene units. Compiles as C++17. References: [17] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <cstdint>

#include "prt/core/status.h"
#include "prt/formats/transfer_data.h"

namespace prt {

// Fingerprint of vertex_count positions (3 floats each, x y z).
uint64_t geometry_fingerprint(const float* positions_xyz, std::size_t vertex_count) noexcept;

// Ok when the caller's mesh is the one `data` was baked for:
//   1. the vertex counts must be equal;
//   2. if the fingerprints are equal, it matches;
//   3. otherwise every caller position must lie within
//        tolerance_fraction_of_extent × (diagonal of the stored positions' bounding box)
//      of the stored position (Euclidean distance), so a re-export with tiny float
//      differences still passes. The error reports the largest deviation and its vertex.
// Non-finite caller positions, a negative or NaN tolerance, or missing stored positions
// are errors.
Status check_geometry(const TransferData& data, const float* positions_xyz,
                      std::size_t vertex_count, float tolerance_fraction_of_extent);

}  // namespace prt
