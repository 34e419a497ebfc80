// cli/bake_summary.h — what `prt bake` and `prt merge` say about an SH bake's interreflection
// solve, one implementation for both (the merge runs the single bake's solve), and what a shard
// says (`prt bake --shard`, every kind of bake).
#pragma once

#include <string>

#include "bake/transfer_baker.h"
#include "bake/transfer_part.h"

namespace prt::cli {

// On stderr, when an interreflected bake's solve stopped short of its tolerance:
// "COMMAND: LABEL: warning: interreflection solve stopped at relative residual R (tolerance T)
// after I iterations". Nothing otherwise.
void warn_unconverged_solve(const char* command, const std::string& label,
                            const bake::BakeOptions& options, const bake::BakeStatistics& st);

// The summary's clause on the solve ("; 2 bounces" or "; interreflection solved in J+I
// iterations to residual R (S s)"); empty for a bake without interreflection.
std::string interreflection_summary(const bake::BakeOptions& options,
                                    const bake::BakeStatistics& st);

// The shard's first line on stderr (the scheduler's log): "prt bake: SCENE: shard I/N, rows
// A..B of V (Morton order)". Nothing when `quiet`.
void announce_shard(const std::string& scene, std::size_t vertices, bake::ShardSpec shard,
                    bool quiet);

// The shard's summary on stdout: rows, rays, seconds, the part written and its size.
void summarise_shard(const std::string& scene, const std::string& output, std::size_t vertices,
                     bake::ShardSpec shard, uint64_t rays, double seconds_rays, bool quiet);

}  // namespace prt::cli
