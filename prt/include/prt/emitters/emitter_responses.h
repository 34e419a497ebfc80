// prt/emitters/emitter_responses.h — per-emitter radiosity responses (".prte" files) and relighting
// the emitters by recombining them (precomputed radiosity transfer).
//
// Radiosity is linear in the emission, channel by channel (albedo acts per RGB channel): if
// R_e,v is the exit radiance at vertex v when emitter e alone emits unit white radiance and every
// other emitter is dark, then under emissions c_e (linear RGB, the emitters' exit radiance)
//
//     L_v = Σ_e c_e ⊙ R_e,v          (⊙: per channel)
//
// is the solution of the radiosity equation, up to the solver's stopping tolerance. A file
// stores, for E emitters (an emitter is every primitive with one emitting material), the name
// and the original emission c_e of each (so the default recombination reproduces the plain
// solve), the mesh the responses live on (positions, normals, triangles: what a renderer needs)
// with its geometry fingerprint (prt/formats/geometry_check.h), and the responses R (3 floats per
// vertex per emitter). The byte layout is in docs/FORMAT.md ("Emitter responses"): magic "PRTE",
// version 1, CRC-32C (prt/formats/crc32c.h) over the whole file with the checksum field zeroed.
//
// Nothing here throws or starts threads: errors come back as a Status whose message is one line
// "NAME: problem" (NAME the path, or the name given for a memory buffer). Compiles as C++17.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "prt/core/status.h"

namespace prt {

inline constexpr uint32_t kEmitterResponsesVersion = 1;
inline constexpr uint32_t kMaxEmitters = 65536;
inline constexpr uint32_t kMaxEmitterNameBytes = 1024;
inline constexpr uint64_t kMaxResponseVertices = 0xffffffffull;  // 2^32 − 1

struct EmitterInfo {
  std::string name;                        // the material's name (UTF-8, 1..1024 bytes, unique)
  std::array<float, 3> emission{0, 0, 0};  // its original emission (exit radiance, linear RGB)
};

struct EmitterResponses {
  std::vector<EmitterInfo> emitters;  // E
  std::vector<float> positions;       // 3·V: x, y, z per vertex (scene frame and units)
  std::vector<float> normals;         // 3·V: unit normal per vertex
  std::vector<uint32_t> triangles;    // 3·T: vertex indices, counter-clockwise = front
  // 3·V·E: response of emitter e at vertex v, channel c at index (e·V + v)·3 + c; exit radiance
  // per unit emitted radiance (dimensionless), ≥ 0.
  std::vector<float> responses;
  uint64_t fingerprint = 0;  // geometry_fingerprint(positions); filled in by the writer

  std::size_t vertex_count() const { return positions.size() / 3; }
  std::size_t triangle_count() const { return triangles.size() / 3; }
  std::size_t emitter_count() const { return emitters.size(); }
};

// A new colour for one emitter by name (linear RGB; a grey strength is r = g = b).
struct EmitterColor {
  std::string name;
  std::array<float, 3> rgb{0, 0, 0};
};

// Checks that `data` is storable: 1 ≤ E ≤ kMaxEmitters, names non-empty, unique, at most
// kMaxEmitterNameBytes; emissions finite and ≥ 0; V ≤ kMaxResponseVertices; array sizes
// matching; triangle indices < V; positions and normals finite; responses finite and ≥ 0;
// fingerprint 0 (unset) or equal to geometry_fingerprint(positions).
Status validate_emitter_responses(const EmitterResponses& data, const std::string& name);

// The bytes of a file holding `data` (validated first; the fingerprint is always recomputed).
Result<std::vector<unsigned char>> encode_emitter_responses(const EmitterResponses& data,
                                                            const std::string& name);

// Writes atomically (prt/core/atomic_file.h): nothing is left at PATH on failure.
Status write_emitter_responses(const std::string& path, const EmitterResponses& data);

// Reads and fully checks a file (size, magic, version, checksum, counts, every value, the
// fingerprint). Errors: "NAME: truncated …", "NAME: bad magic", "NAME: checksum mismatch", ….
Result<EmitterResponses> read_emitter_responses(const std::string& path);
Result<EmitterResponses> decode_emitter_responses(const void* bytes, std::size_t size,
                                                  const std::string& name);

// True when the file at PATH starts with the magic "PRTE" (no other check).
bool is_emitter_responses_file(const std::string& path) noexcept;

// The colour of every emitter, 3 floats per emitter in file order: the stored emission, replaced
// by `colors` for the emitters they name (a later entry for the same name wins). Errors (one
// line): a name no emitter has (the known names are listed), a negative, NaN or infinite
// component.
Result<std::vector<float>> emitter_colors(const EmitterResponses& data,
                                          const std::vector<EmitterColor>& colors);

// L_v = Σ_e c_e ⊙ R_e,v for every vertex (accumulated in double per vertex), written to
// out_rgb (3·V floats), or added to what out_rgb holds when `accumulate` is true.
// colors_rgb: 3·E floats (emitter_colors). Errors: a colour array of the wrong size or with a
// negative, NaN or infinite value.
Status recombine_emitters(const EmitterResponses& data, const std::vector<float>& colors_rgb,
                          float* out_rgb, bool accumulate = false);

}  // namespace prt
