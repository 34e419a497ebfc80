// cli/subsurface_shard.h — `prt bake --subsurface --shard I/N` and the merge of its parts
// (bake/subsurface/subsurface_part.h, docs/FARM.md): a shard samples its rows as an SH shard
// does and carries the subsurface options; `prt merge` runs the dipole gather over every vertex
// (and the interreflection solve after it) and writes the single bake's bytes.
#pragma once

#include <string>
#include <vector>

#include "bake/transfer_part_file.h"
#include "subsurface_cli.h"

namespace prt::cli {

// Bakes the rows of `shard` into the part file `output` (.prtpart), with the shard's lines on
// stderr and stdout (cli/bake_summary.h) and its run record's phases.
void run_subsurface_shard(const std::string& scene_path, const scene::Scene& scene,
                          const std::string& output, const bake::BakeOptions& options,
                          const SubsurfaceArguments& args, bake::ShardSpec shard, bool quiet);

// `prt merge` of subsurface parts (checked to belong together, in shard order) into `output`
// (.prt): the bytes of the single `prt bake --subsurface`. Throws CommandError / BakeError.
void merge_subsurface_parts(const std::vector<const bake::TransferPartFile*>& ordered,
                            const std::string& output, int threads, uint64_t memory_limit,
                            bool quiet);

}  // namespace prt::cli
