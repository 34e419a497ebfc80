// cli/bake_summary.cpp — the solve's warning and summary clause (bake_summary.h).
#include "bake_summary.h"

#include <cstdio>
#include <filesystem>

#include "shard_cli.h"

namespace prt::cli {

void warn_unconverged_solve(const char* command, const std::string& label,
                            const bake::BakeOptions& options, const bake::BakeStatistics& st) {
  if (options.kind != prt::TransferKind::Interreflected || st.solver_converged) return;
  std::fprintf(stderr,
               "%s: %s: warning: interreflection solve stopped at relative residual %.3g "
               "(tolerance %.3g) after %d iterations\n",
               command, label.c_str(), st.solver_residual, options.bounce_tolerance,
               st.solver_iterations);
}

std::string interreflection_summary(const bake::BakeOptions& options,
                                    const bake::BakeStatistics& st) {
  if (options.kind != prt::TransferKind::Interreflected) return {};
  char text[160];
  if (options.bounces >= 0)
    std::snprintf(text, sizeof text, "; %d bounces", st.jacobi_bounces);
  else
    std::snprintf(text, sizeof text,
                  "; interreflection solved in %d+%d iterations to residual %.2g (%.2f s)",
                  st.jacobi_bounces, st.solver_iterations, st.solver_residual, st.seconds_solve);
  return text;
}

void announce_shard(const std::string& scene, std::size_t vertices, bake::ShardSpec shard,
                    bool quiet) {
  if (quiet) return;
  const bake::RowRange rows = bake::shard_rows(vertices, shard);
  std::fprintf(stderr, "prt bake: %s: shard %s, rows %llu..%llu of %zu (Morton order)\n",
               scene.c_str(), shard_text(shard).c_str(),
               static_cast<unsigned long long>(rows.first),
               static_cast<unsigned long long>(rows.end), vertices);
}

void summarise_shard(const std::string& scene, const std::string& output, std::size_t vertices,
                     bake::ShardSpec shard, uint64_t rays, double seconds_rays, bool quiet) {
  if (quiet) return;
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(output, ec);
  std::printf(
      "baked shard %s of %s: %llu of %zu vertices, %llu rays in %.2f s; wrote %s (%llu bytes)\n",
      shard_text(shard).c_str(), scene.c_str(),
      static_cast<unsigned long long>(bake::shard_rows(vertices, shard).size()), vertices,
      static_cast<unsigned long long>(rays), seconds_rays, output.c_str(),
      static_cast<unsigned long long>(ec ? 0 : bytes));
}

}  // namespace prt::cli
