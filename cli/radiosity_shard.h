// cli/radiosity_shard.h — `prt radiosity SCENE --shard I/N -o PART.prtpart` (the form-factor rows
// of one range of senders, radiosity::compute_form_factor_shard) and the merge of such parts into
// the form-factor cache a single `prt radiosity --form-factor-cache` writes (docs/FARM.md).
#pragma once

#include <string>
#include <vector>

#include "bake/transfer_part_file.h"
#include "radiosity/scene_solve.h"

namespace CLI {
class App;
}

namespace prt::cli {

// Refuses (UsageError) every option of `prt radiosity` that does not apply to a shard: the solve,
// its outputs and images, moves and refinement.
void check_radiosity_shard(const CLI::App& cmd);

// Computes the shard's rows and writes the part file `output`.
void run_radiosity_shard(const radiosity::SceneSolveRequest& request, bake::ShardSpec shard,
                         const std::string& output, bool quiet);

// `prt merge` of form-factor parts (in shard order): the cache file `output`.
void merge_form_factor_parts(const std::vector<const bake::TransferPartFile*>& parts,
                             const std::string& output, bool quiet);

}  // namespace prt::cli
