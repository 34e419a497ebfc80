// cli/shard_cli.h — `prt bake --shard` and `prt merge` (docs/FARM.md): a bake split across the
// tasks of a job array (Slurm, Kubernetes Indexed Jobs) into part files, and their merge.
//
// --shard values:
//   I/N      shard I (0-based) of N, 0 ≤ I < N ≤ 65536;
//   auto     I = SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN (MIN 0 when unset),
//            N = SLURM_ARRAY_TASK_COUNT;
//   auto/N   N given; I = JOB_COMPLETION_INDEX (Kubernetes Indexed Job) when set, else from the
//            Slurm variables (SLURM_ARRAY_TASK_COUNT, when set, must equal N).
// A value that does not parse, or a missing or malformed variable, is a UsageError naming it
// (one line, exit 2) raised before any file is read or written. Without --shard the environment
// is not looked at.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "bake/transfer_part.h"

namespace prt::cli {

inline constexpr uint32_t kMaxShards = 65536;

// The environment as --shard reads it (getenv by default; tests pass their own).
using Environment = std::function<std::optional<std::string>(const std::string&)>;
Environment process_environment();

// The shard `text` (the --shard value) names; throws UsageError.
bake::ShardSpec resolve_shard(const std::string& text, const Environment& env);

// "I/N".
std::string shard_text(bake::ShardSpec shard);

// The prt version written into part files (and compared by prt merge).
const char* prt_version();

}  // namespace prt::cli
