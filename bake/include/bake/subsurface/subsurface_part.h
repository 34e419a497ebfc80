// bake/subsurface/subsurface_part.h — a subsurface bake (bake/subsurface/subsurface_baker.h)
// split across the machines of a farm (docs/FARM.md): each shard samples its rows as an SH
// shard does (bake/transfer_part.h: S_v in double, and for an interreflected bake its gather
// rows), and the merge runs the dipole gather over every vertex, then what follows it (the
// interreflection solve with R_total as the translucent vertices' albedo), through the single
// bake's own code (bake_subsurface_transfer_with): the same bytes for any N.
//
// Why the rows suffice: S_v and the gather rows depend on (seed, vertex) and the geometry only,
// not on the albedo (the solve's albedo is applied after the sampling) nor on whether the inner
// bake keeps the albedo apart (the shadowed subsurface bake does: its S comes back from the
// stored float coefficients, which the merge stores from the parts' doubles by the same
// DirectTransfer store). The subsurface options (materials, scale, gather) and the material of
// every vertex are the merge's other inputs: bake/transfer_part_file.h carries them.
#pragma once

#include <vector>

#include "bake/subsurface/subsurface_baker.h"
#include "bake/transfer_part.h"

namespace prt::bake {

// Throws BakeError (one line) when the subsurface bake cannot be sharded or is not valid
// (validate_subsurface, check_shardable).
void check_subsurface_shardable(const scene::Scene& scene, const BakeOptions& options,
                                const SubsurfaceBakeOptions& subsurface);

// The rows of `shard`: bake_transfer_part with `options` (shadowed or interreflected; the
// interreflected on subsurface_solve_scene, as the single bake).
TransferPart bake_subsurface_part(const scene::Scene& scene, const BakeOptions& options,
                                  const SubsurfaceBakeOptions& subsurface, ShardSpec shard,
                                  ProgressSink* progress = nullptr);

// bake_subsurface_transfer(scene, options, subsurface) from every part of one split, in shard
// order (checked to belong together by the caller), `scene` as shard 0 carries it.
SubsurfaceBakeResult merge_subsurface_parts(const scene::Scene& scene, const BakeOptions& options,
                                            const SubsurfaceBakeOptions& subsurface,
                                            const std::vector<const TransferPart*>& parts,
                                            ProgressSink* progress = nullptr);

}  // namespace prt::bake
