// cli/glossy_shard.h — `prt bake --glossy --shard I/N` and the merge of its parts
// (bake/glossy_part.h, docs/FARM.md): a glossy bake split across the tasks of a job array.
#pragma once

#include <string>
#include <vector>

#include "bake/transfer_part_file.h"
#include "glossy_cli.h"

namespace prt::cli {

// Bakes the rows of `shard` into the part file request.output (.prtpart), with the shard's
// lines on stderr and stdout (cli/bake_summary.h) and its run record's phases.
void run_glossy_shard(const scene::Scene& scene, const GlossyBakeRequest& request,
                      bake::ShardSpec shard);

// `prt merge` of glossy parts (checked to belong together, in shard order) into `output`
// (.prtg): the bytes of the single `prt bake --glossy`. Throws UsageError / CommandError.
void merge_glossy_parts(const std::vector<const bake::TransferPartFile*>& ordered,
                        const std::string& output, int threads, uint64_t memory_limit, bool quiet);

}  // namespace prt::cli
