// cli/shard_cli.cpp — resolving `--shard` (shard_cli.h).
#include "shard_cli.h"

#include <cerrno>
#include <cstdlib>

#include "command_registry.h"

#ifndef PRT_VERSION
#define PRT_VERSION "unknown"
#endif

namespace prt::cli {
namespace {

// A decimal integer in [0, 2³²) with nothing else around it; nullopt otherwise.
std::optional<uint64_t> parse_count(const std::string& text) {
  if (text.empty() || text.size() > 10) return std::nullopt;
  for (char c : text)
    if (c < '0' || c > '9') return std::nullopt;
  const uint64_t v = std::strtoull(text.c_str(), nullptr, 10);
  if (v > 0xffffffffull) return std::nullopt;
  return v;
}

bake::ShardSpec checked(uint64_t index, uint64_t count, const std::string& where) {
  if (count < 1 || count > kMaxShards)
    throw UsageError(where + ": the shard count must be in [1, " + std::to_string(kMaxShards) +
                     "], not " + std::to_string(count));
  if (index >= count)
    throw UsageError(where + ": shard index " + std::to_string(index) + " is not below the count " +
                     std::to_string(count) + " (indices are 0-based)");
  return {static_cast<uint32_t>(index), static_cast<uint32_t>(count)};
}

uint64_t env_number(const Environment& env, const std::string& name, const std::string& why) {
  const std::optional<std::string> value = env(name);
  if (!value) throw UsageError("--shard auto: " + name + " is not set (" + why + ")");
  const std::optional<uint64_t> n = parse_count(*value);
  if (!n) throw UsageError("--shard auto: " + name + "='" + *value + "' is not a whole number");
  return *n;
}

// The Slurm array task's index (ID − MIN) and, when set, its count.
bake::ShardSpec from_slurm(const Environment& env, std::optional<uint64_t> count) {
  const std::string where = "--shard auto";
  const uint64_t id = env_number(env, "SLURM_ARRAY_TASK_ID", "not in a Slurm job array");
  const uint64_t min =
      env("SLURM_ARRAY_TASK_MIN") ? env_number(env, "SLURM_ARRAY_TASK_MIN", "") : 0;
  if (id < min)
    throw UsageError(where + ": SLURM_ARRAY_TASK_ID " + std::to_string(id) +
                     " is below SLURM_ARRAY_TASK_MIN " + std::to_string(min));
  if (!count || env("SLURM_ARRAY_TASK_COUNT")) {
    const uint64_t slurm = env_number(env, "SLURM_ARRAY_TASK_COUNT", "not in a Slurm job array");
    if (count && slurm != *count)
      throw UsageError(where + "/" + std::to_string(*count) + ": SLURM_ARRAY_TASK_COUNT is " +
                       std::to_string(slurm) + ", not " + std::to_string(*count));
    count = slurm;
  }
  return checked(id - min, *count, where);
}

}  // namespace

Environment process_environment() {
  return [](const std::string& name) -> std::optional<std::string> {
    const char* v = std::getenv(name.c_str());
    if (!v) return std::nullopt;
    return std::string(v);
  };
}

bake::ShardSpec resolve_shard(const std::string& text, const Environment& env) {
  const std::string where = "--shard " + text;
  if (text == "auto") return from_slurm(env, std::nullopt);
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos || text.find('/', slash + 1) != std::string::npos)
    throw UsageError(where + ": expected I/N (shard I of N, 0-based), auto or auto/N");
  const std::string head = text.substr(0, slash);
  const std::optional<uint64_t> count = parse_count(text.substr(slash + 1));
  if (!count) throw UsageError(where + ": the shard count is not a whole number");
  if (head == "auto") {
    if (const std::optional<std::string> k = env("JOB_COMPLETION_INDEX")) {
      const std::optional<uint64_t> index = parse_count(*k);
      if (!index)
        throw UsageError(where + ": JOB_COMPLETION_INDEX='" + *k + "' is not a whole number");
      return checked(*index, *count, where);
    }
    if (!env("SLURM_ARRAY_TASK_ID"))
      throw UsageError(where +
                       ": neither JOB_COMPLETION_INDEX (Kubernetes) nor SLURM_ARRAY_TASK_ID "
                       "(Slurm) is set");
    return from_slurm(env, *count);
  }
  const std::optional<uint64_t> index = parse_count(head);
  if (!index) throw UsageError(where + ": the shard index is not a whole number");
  return checked(*index, *count, where);
}

std::string shard_text(bake::ShardSpec shard) {
  return std::to_string(shard.index) + "/" + std::to_string(shard.count);
}

const char* prt_version() {
  return PRT_VERSION;
}

}  // namespace prt::cli
