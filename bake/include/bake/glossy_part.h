// bake/glossy_part.h — a glossy transfer-matrix bake (bake/glossy_transfer_baker.h) split across
// the machines of a farm, as the SH bake is (bake/transfer_part.h): the same rows (Morton order,
// shard i of N takes [⌊i·V/N⌋, ⌊(i+1)·V/N⌋)), and merge_glossy_parts_to_file writes the bytes
// bake_glossy_transfer_to_file writes for the whole scene.
//
// Determinism: a vertex's sample directions depend on (seed, vertex) only and its direct matrix
// S_v (K² floats, before any channel is copied) and front-face hits (sample index, triangle,
// barycentrics, in sample order) on its own rays only; so a shard computes the values the single
// bake's sampling pass computes for those vertices, for any thread count and any N. The merge
// puts them where that pass puts them (shadowed: the file's matrices, block by block;
// interreflected: M⁽⁰⁾ in every channel, S, and the hits in vertex order, quantised into the
// same per-block compact hits and sample masks by the same quantise_hit) and runs the same
// bounces, metadata and streamed writer. Ray and back-face-hit counts are the parts' sums.
//
// What the merge needs besides the rows, carried by shard 0 (no scene file, no Embree at merge
// time): the scene as bake/transfer_part_file.h stores it (positions, normals, albedo, triangles,
// primitives), and GlossyInputs: the tangent frames, the materials and the material of each
// vertex, as the bake derived them from the scene (--material overrides, textured BRDF variants
// included). A MERL material is carried by its path: the merge reads that file again.
//
// What can be sharded: shadowed and interreflected glossy bakes; an interreflected one needs an
// untextured albedo (the bounce reads ρ at the hit point; the part carries vertex albedo only),
// as the SH bake does. check_glossy_shardable throws BakeError otherwise.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bake/glossy_transfer_baker.h"
#include "bake/transfer_part.h"

namespace prt::bake {

// What the glossy bake derives from the scene beyond its geometry.
struct GlossyInputs {
  std::vector<glm::vec4> tangents;  // scene::tangent_frames: tangent xyz, w = handedness
  std::vector<brdf::Material> materials;
  std::vector<uint32_t> material_of_vertex;
};

// scene::tangent_frames and glossy_scene_materials of `scene`.
GlossyInputs glossy_inputs(const scene::Scene& scene);

// One front-face hit of a vertex's sample (16 bytes, as stored in part files; float barycentrics,
// which the merge quantises as the single bake does). A row's hits are in increasing sample order.
struct GlossyHitRecord {
  uint32_t sample = 0, triangle = 0;
  float u = 0.f, v = 0.f;  // Embree barycentrics
};
static_assert(sizeof(GlossyHitRecord) == 16);

struct GlossyPart {
  ShardSpec shard;
  uint64_t vertices = 0;              // V of the scene
  RowRange rows;                      // row r of the range is vertex morton_order[first + r]
  int order = 0;                      // n: matrices of K² = n⁴ floats
  std::vector<float> direct;          // rows × K²: S_v, one channel
  std::vector<uint32_t> hit_counts;   // interreflected: front-face hits per row
  std::vector<GlossyHitRecord> hits;  // interreflected: the rows' hits, in row order
  uint64_t rays = 0, back_face_hits = 0;
  GlossyBakeStatistics stats;  // of the shard's run (times; not part of the file)
  // A part read from a file (bake/transfer_part_file.h): the direct matrices and the hits stay
  // in the file's mapping (these views; `direct` and `hits` empty), which the decoded part
  // holds. The merge copies each part's rows and then releases its pages
  // (prt::release_part_pages), so that it holds one part at a time, not every part.
  const float* direct_view = nullptr;
  uint64_t direct_count = 0;
  const GlossyHitRecord* hits_view = nullptr;
  uint64_t hit_count = 0;

  const float* direct_values() const { return direct_view ? direct_view : direct.data(); }
  uint64_t direct_size() const { return direct_view ? direct_count : direct.size(); }
  const GlossyHitRecord* hit_values() const { return hits_view ? hits_view : hits.data(); }
  uint64_t hit_size() const { return hits_view ? hit_count : hits.size(); }
};

// Throws BakeError "SCENE: a sharded glossy bake needs ..." when it cannot be sharded.
void check_glossy_shardable(const scene::Scene& scene, const GlossyBakeOptions& options);

// Samples the rows of `shard` (progress: phase "glossy bake", one unit per row). Throws as
// bake_glossy_transfer does, and BakeError for an unshardable bake or a bad shard.
GlossyPart bake_glossy_part(const scene::Scene& scene, const GlossyBakeOptions& options,
                            ShardSpec shard, ProgressSink* progress = nullptr);

// Writes to `path` the glossy file of every part of one split, in shard order (checked to belong
// together by the caller), with `scene` and `inputs` from shard 0: byte for byte
// bake_glossy_transfer_to_file(the scene, options, path). Returns its statistics (no matrices).
// The pages of a part read from a file are released once its rows are copied (above).
// Throws BakeError when the parts do not fit the scene or each other; `path` is then untouched.
GlossyBakeResult merge_glossy_parts_to_file(const scene::Scene& scene, const GlossyInputs& inputs,
                                            const GlossyBakeOptions& options,
                                            const std::vector<const GlossyPart*>& parts,
                                            const std::string& path,
                                            ProgressSink* progress = nullptr);

}  // namespace prt::bake
