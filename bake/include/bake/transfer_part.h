// bake/transfer_part.h — a diffuse SH bake split across the machines of a farm: each shard
// samples one range of vertices into a part, and the merge of every part runs the
// interreflection solve and gives the transfer a single bake_transfer gives, bit for bit.
//
// Rows: the vertices in the Morton order of bake/compact_gather.h (make_morton_order of the
// positions), the order of the compact gather's rows. Shard i of N takes the rows
// [⌊i·V/N⌋, ⌊(i+1)·V/N⌋): a function of (V, N) only, every row in exactly one shard, the
// shards' sizes within one row of each other (a shard may be empty when N > V). A shard's rows
// are a run of the single bake's gather rows, so the merge concatenates them, and vertices close
// in space, so a shard's rays stay in one part of the BVH. docs/FARM.md says why.
//
// Determinism: a vertex's directions depend on (seed, vertex) only (bake/sampling.h), its
// direct transfer S_v, AO, bent normal and gather row on its own rays only; so a shard computes
// exactly the rows bake_transfer computes for its vertices, for any thread count and any N.
// merge_transfer_parts stores them where bake_transfer's sampling pass would have (the same
// DirectTransfer store, the same gather blocks of 64 rows), then runs the same solve and writes
// the same metadata (ray and back-face-hit counts are the parts' sums).
//
// What can be sharded: the fixed recipe (no BakeOptions::adaptive) with the albedo folded (no
// texture, no keep_albedo_apart), every kind; interreflected through the compact gather only
// (not dense_gather). check_shardable throws BakeError otherwise.
#pragma once

#include <cstdint>
#include <vector>

#include "bake/compact_gather.h"
#include "bake/transfer_baker.h"

namespace prt::bake {

struct ShardSpec {
  uint32_t index = 0, count = 1;  // shard `index` (0-based) of `count` ≥ 1
};

struct RowRange {
  uint64_t first = 0, end = 0;  // [first, end)
  uint64_t size() const { return end - first; }
};

// [⌊i·rows/N⌋, ⌊(i+1)·rows/N⌋) for shard i of N (computed without overflow).
RowRange shard_rows(uint64_t rows, ShardSpec shard);

// What one shard computed for its rows (row r of the range is vertex order[first + r]).
struct TransferPart {
  ShardSpec shard;
  uint64_t vertices = 0;  // V of the scene (the rows of every shard)
  RowRange rows;
  int coefficients = 0;               // K = order²
  std::vector<double> direct;         // rows × K: S_v (shadowed and interreflected)
  std::vector<float> ao;              // rows (BakeOptions::ao)
  std::vector<float> bent;            // 3 × rows (BakeOptions::bent_normals)
  std::vector<uint32_t> gather_rows;  // interreflected: hits per row
  // The rows' hits, as the shard cast them: a shard keeps them in its sampling pass's blocks
  // (whole rows each, in row order: no copy into one array before they are written); a part
  // decoded from a file (bake/transfer_part_file.h) points into the file's mapping instead, as
  // it does for `direct` (left empty then). Read both through the accessors below. The merge
  // releases a decoded part's pages once it has copied its rows (prt::release_part_pages).
  std::vector<CompactGather::Block> gather_blocks;
  const double* direct_view = nullptr;
  uint64_t direct_count = 0;
  const CompactHit* hits_view = nullptr;
  uint64_t hit_count = 0;
  uint64_t rays = 0, back_face_hits = 0;
  double ray_offset_max = 0.0;  // the scene's largest ray offset (the same in every part)
  BakeStatistics stats;         // of the shard's run (times; not part of the file)

  const double* direct_values() const { return direct_view ? direct_view : direct.data(); }
  uint64_t direct_size() const { return direct_view ? direct_count : direct.size(); }
  // The hits as runs of whole rows, in row order (one run for a decoded part).
  struct HitRun {
    const CompactHit* data;
    std::size_t size;
  };
  std::vector<HitRun> hit_runs() const;
  uint64_t hit_size() const;
};

// Throws BakeError "SCENE: a sharded bake needs ..." when (scene, options) cannot be sharded.
void check_shardable(const scene::Scene& scene, const BakeOptions& options);

// Samples the rows of `shard` (progress: phase "bake", one unit per row). Throws as
// bake_transfer does, and BakeError for an unshardable bake or a bad shard.
TransferPart bake_transfer_part(const scene::Scene& scene, const BakeOptions& options,
                                ShardSpec shard, ProgressSink* progress = nullptr);

// The single bake's result from every part of one split, in shard order (parts[i].shard.index
// = i, ranges as shard_rows gives them, sizes consistent: the caller has checked that they
// belong together). Throws BakeError when they do not fit the scene or each other. `options` may
// keep the albedo apart when the bake is not interreflected (the parts hold S without albedo):
// the subsurface merge's shadowed bake does (bake/subsurface/subsurface_part.h).
BakeResult merge_transfer_parts(const scene::Scene& scene, const BakeOptions& options,
                                const std::vector<const TransferPart*>& parts,
                                ProgressSink* progress = nullptr);

}  // namespace prt::bake
