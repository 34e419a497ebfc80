// cli/glossy_shard.cpp — glossy shards and their merge (glossy_shard.h).
#include "glossy_shard.h"

#include <cstdio>

#include "bake/glossy_part.h"
#include "bake_summary.h"
#include "command_registry.h"
#include "option_rules.h"
#include "output_safety.h"
#include "progress_reporter.h"
#include "prt/formats/part_file.h"
#include "run_record.h"
#include "shard_cli.h"

namespace prt::cli {

void run_glossy_shard(const scene::Scene& scene, const GlossyBakeRequest& r,
                      bake::ShardSpec shard) {
  check_glossy_request(r);
  const bake::GlossyBakeOptions o = glossy_bake_options(r);
  bake::check_glossy_shardable(scene, o);
  announce_shard(r.scene, scene.vertex_count(), shard, r.quiet);
  ProgressReporter progress(r.quiet);
  const bake::GlossyPart part = bake::bake_glossy_part(scene, o, shard, &progress);
  const bake::GlossyInputs inputs = bake::glossy_inputs(scene);
  const prt::Status written = prt::write_part_file(
      r.output, bake::encode_glossy_part(part, scene, inputs, o, prt_version()));
  if (!written.ok()) throw CommandError(written.message());
  run_record().phase("rays", part.stats.seconds_rays);
  run_record().phase("bake", part.stats.seconds_total);
  summarise_shard(r.scene, r.output, scene.vertex_count(), shard, part.rays,
                  part.stats.seconds_rays, r.quiet);
}

void merge_glossy_parts(const std::vector<const bake::TransferPartFile*>& ordered,
                        const std::string& output, int threads, uint64_t memory_limit, bool quiet) {
  check_output_file("-o", output, {".prtg"}, "a glossy transfer file (the parts are glossy)");
  const scene::Scene& scene = *ordered[0]->scene;
  bake::GlossyBakeOptions o = ordered[0]->glossy_options;
  o.threads = threads;
  o.memory_limit = memory_limit_or_default(memory_limit);
  std::vector<const bake::GlossyPart*> parts;
  for (const bake::TransferPartFile* f : ordered) parts.push_back(&f->glossy_part);
  ProgressReporter progress(quiet);
  const bake::GlossyBakeResult result = bake::merge_glossy_parts_to_file(
      scene, *ordered[0]->glossy_inputs, o, parts, output, &progress);
  const bake::GlossyBakeStatistics& st = result.stats;
  if (result.data.interreflected) {
    run_record().phase("BRDF projections", st.seconds_projection);
    run_record().phase("bounces", st.seconds_bounces);
  }
  run_record().phase("merge", st.seconds_total);
  if (o.bounces < 0 && !st.converged)
    std::fprintf(stderr, "prt merge: %s: warning: glossy bounces stopped after %d (change %.3g)\n",
                 scene.source_path.c_str(), st.bounces,
                 st.bounce_change.empty() ? 0.0 : st.bounce_change.back());
  if (quiet) return;
  std::printf("merged %zu parts of %s (glossy %s transfer, order %d, %llu vertices, %llu rays",
              parts.size(), scene.source_path.c_str(),
              result.data.interreflected ? "interreflected" : "shadowed", o.order,
              static_cast<unsigned long long>(st.vertices),
              static_cast<unsigned long long>(st.rays));
  if (result.data.interreflected) std::printf(", %d bounces", st.bounces);
  std::printf("); wrote %s\n", output.c_str());
}

}  // namespace prt::cli
