// A subsurface bake's shards and their merge (bake/subsurface/subsurface_part.h).
#include "bake/subsurface/subsurface_part.h"

namespace prt::bake {

void check_subsurface_shardable(const scene::Scene& scene, const BakeOptions& options,
                                const SubsurfaceBakeOptions& subsurface) {
  validate_subsurface(scene, options, subsurface);
  check_shardable(scene, options);
}

TransferPart bake_subsurface_part(const scene::Scene& scene, const BakeOptions& options,
                                  const SubsurfaceBakeOptions& subsurface, ShardSpec shard,
                                  ProgressSink* progress) {
  check_subsurface_shardable(scene, options, subsurface);
  // Interreflected: the scene the single bake's inner bake sees (translucent vertices' albedo
  // R_total), so that a shard accepts what it accepts; the rows do not depend on the albedo.
  if (options.kind == prt::TransferKind::Interreflected)
    return bake_transfer_part(subsurface_solve_scene(scene, subsurface), options, shard, progress);
  return bake_transfer_part(scene, options, shard, progress);
}

SubsurfaceBakeResult merge_subsurface_parts(const scene::Scene& scene, const BakeOptions& options,
                                            const SubsurfaceBakeOptions& subsurface,
                                            const std::vector<const TransferPart*>& parts,
                                            ProgressSink* progress) {
  check_subsurface_shardable(scene, options, subsurface);
  return bake_subsurface_transfer_with(scene, options, subsurface,
                                       [&](const scene::Scene& s, const BakeOptions& o) {
                                         return merge_transfer_parts(s, o, parts, progress);
                                       });
}

}  // namespace prt::bake
