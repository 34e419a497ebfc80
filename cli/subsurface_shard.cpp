// cli/subsurface_shard.cpp — subsurface shards and their merge (subsurface_shard.h).
#include "subsurface_shard.h"

#include <cstdio>

#include "bake/subsurface/subsurface_part.h"
#include "bake_summary.h"
#include "command_registry.h"
#include "option_rules.h"
#include "progress_reporter.h"
#include "prt/formats/part_file.h"
#include "prt/formats/transfer_file.h"
#include "run_record.h"
#include "shard_cli.h"

namespace prt::cli {

void run_subsurface_shard(const std::string& scene_path, const scene::Scene& scene,
                          const std::string& output, const bake::BakeOptions& options,
                          const SubsurfaceArguments& args, bake::ShardSpec shard, bool quiet) {
  const bake::SubsurfaceBakeOptions ss = subsurface_bake_options(scene, args);
  bake::check_subsurface_shardable(scene, options, ss);
  announce_shard(scene_path, scene.vertex_count(), shard, quiet);
  ProgressReporter progress(quiet);
  const bake::TransferPart part = bake::bake_subsurface_part(scene, options, ss, shard, &progress);
  const prt::Status written = prt::write_part_file(
      output, bake::encode_transfer_part(part, scene, options, prt_version(), &ss));
  if (!written.ok()) throw CommandError(written.message());
  run_record().phase("bvh", part.stats.seconds_bvh);
  run_record().phase("rays", part.stats.seconds_rays);
  run_record().phase("bake", part.stats.seconds_total);
  summarise_shard(scene_path, output, scene.vertex_count(), shard, part.rays,
                  part.stats.seconds_rays, quiet);
}

void merge_subsurface_parts(const std::vector<const bake::TransferPartFile*>& ordered,
                            const std::string& output, int threads, uint64_t memory_limit,
                            bool quiet) {
  const scene::Scene& scene = *ordered[0]->scene;
  bake::BakeOptions options = ordered[0]->options;
  options.threads = threads;
  options.memory_limit = memory_limit_or_default(memory_limit);
  const bake::SubsurfaceBakeOptions& ss = *ordered[0]->subsurface;
  std::vector<const bake::TransferPart*> parts;
  for (const bake::TransferPartFile* f : ordered) parts.push_back(&f->part);
  ProgressReporter progress(quiet);
  const bake::SubsurfaceBakeResult r =
      bake::merge_subsurface_parts(scene, options, ss, parts, &progress);
  const prt::Status written = prt::write_transfer_file(output, r.bake.data);
  if (!written.ok()) throw CommandError(written.message());
  if (r.bake.stats.seconds_solve > 0)
    run_record().phase("interreflection solve", r.bake.stats.seconds_solve);
  run_record().phase("subsurface sum", r.subsurface.seconds_gather);
  run_record().phase("merge", r.bake.stats.seconds_total);
  warn_unconverged_solve("prt merge", scene.source_path, options, r.bake.stats);
  if (quiet) return;
  std::printf(
      "merged %zu parts of %s (%s subsurface transfer, %llu vertices, %llu translucent, %llu "
      "rays); %s sum in %.2f s; wrote %s\n",
      parts.size(), scene.source_path.c_str(), bake::transfer_kind_name(options.kind),
      static_cast<unsigned long long>(r.bake.stats.vertices),
      static_cast<unsigned long long>(r.subsurface.translucent_vertices),
      static_cast<unsigned long long>(r.bake.stats.rays),
      ss.gather.reference ? "direct" : "hierarchical", r.subsurface.seconds_gather, output.c_str());
}

}  // namespace prt::cli
