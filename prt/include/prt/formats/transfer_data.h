// prt/formats/transfer_data.h — the in-memory contents of a coefficient (.prt) file.
//
// A coefficient file stores per-vertex transfer vectors T_p such that, under distant
// lighting whose *radiance* has SH coefficients L (channel c, index k), the exit radiance
// at vertex p is   B_p,c = Σ_k T_p,c,k · L_c,k .
// For diffuse surfaces T includes albedo/π (albedo_folded = true); a file with
// albedo_folded = false stores grey transfer and the engine multiplies by its own albedo.
// The SH basis is the one of sh/basis.h (real, orthonormal, no Condon–Shortley phase,
// index k = l(l+1)+m, scene frame +Y up). The on-disk format is in docs/FORMAT.md.
// Compiles as C++17.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace prt {

enum class TransferKind : uint32_t {
  Unshadowed = 0,      // albedo/π · max(n·ω, 0)
  Shadowed = 1,        // … × visibility
  Interreflected = 2,  // shadowed + diffuse interreflections
  Haar = 3,            // all-frequency Haar-wavelet transfer on a cube map (reserved)
};

enum class Precision : uint32_t { F32 = 0, F16 = 1 };

// A run of consecutive vertices that came from one mesh primitive of the scene file,
// in file order, so an engine can map coefficients back to its own meshes.
struct PrimitiveRange {
  uint64_t first_vertex = 0;
  uint64_t vertex_count = 0;
  std::string name;
};

struct TransferData {
  TransferKind kind = TransferKind::Unshadowed;
  uint32_t order = 3;                  // SH order n: n² coefficients per channel
  uint32_t channels = 1;               // 1 (grey albedo) or 3 (RGB)
  Precision storage = Precision::F32;  // precision of the coefficients on disk
  bool albedo_folded = true;
  uint64_t vertex_count = 0;
  uint64_t fingerprint = 0;  // geometry_fingerprint() of `positions`
  std::vector<PrimitiveRange> primitives;

  std::vector<float> positions;  // 3 · vertex_count, scene frame, scene units
  std::vector<float> normals;    // 3 · vertex_count, unit

  // Vertex-major: coefficients[(v · channels + c) · order² + k].
  std::vector<float> coefficients;

  std::vector<float> ao;            // vertex_count values in [0, 1], or empty
  std::vector<float> bent_normals;  // 3 · vertex_count unit vectors, or empty

  // Bake parameters and anything descriptive, as a JSON object (opaque to the runtime).
  std::string metadata_json;

  uint32_t coefficients_per_channel() const { return order * order; }
};

// The kind's name as written in metadata and reports: "unshadowed" / "shadowed" /
// "interreflected" / "haar" ("unknown" for a value outside the enumeration).
const char* transfer_kind_name(TransferKind kind);

}  // namespace prt
