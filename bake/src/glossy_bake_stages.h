// bake/src/glossy_bake_stages.h — the glossy bake (glossy_transfer_baker.cpp) in two stages, for
// the farm split (bake/glossy_part.h): the sampling pass over a list of vertices, and the rest of
// the bake (bounces, metadata, streamed file) from the sampling results of every vertex. The
// single bake runs both at once; these give the same values (docs/FARM.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bake/glossy_part.h"

namespace prt::bake::detail {

// What the sampling pass found for a list of vertices, in the list's order.
struct GlossySampled {
  std::vector<float> direct;          // count × K²: S_v (one channel)
  std::vector<uint64_t> hit_offset;   // count + 1 (interreflected; {0} otherwise)
  std::vector<GlossyHitRecord> hits;  // interreflected: front-face hits, vertex by vertex
  uint64_t rays = 0, back_face_hits = 0;
};

// The sampling pass over `vertices` (any subset, any order) of `scene`; statistics (rays, time)
// into `st`. Throws as bake_glossy_transfer does.
GlossySampled sample_glossy_vertices(const scene::Scene& scene, const GlossyBakeOptions& options,
                                     const GlossyInputs& inputs,
                                     const std::vector<uint32_t>& vertices, ProgressSink* progress,
                                     GlossyBakeStatistics& st);

// The bake of `scene` with `inputs`, its sampling pass replaced by `all` (every vertex, in vertex
// order; its arrays are taken), written to `path` as bake_glossy_transfer_to_file writes it.
GlossyBakeResult finish_glossy_bake_to_file(const scene::Scene& scene,
                                            const GlossyBakeOptions& options,
                                            const GlossyInputs& inputs, GlossySampled& all,
                                            const std::string& path, ProgressSink* progress);

}  // namespace prt::bake::detail
