// `prt compress`: clustered PCA of a glossy transfer file (bake/cpca/compressor.h) into a CPCA
// file (.prtq, prt/formats/cpca_file.h) that `prt relight` and `prt info` read like the .prtg it
// came from.
//
//   prt compress IN.prtg -o OUT.prtq [--clusters Q] [--vectors K]
//                [--target-error E [--max-vectors K]] [--metric relit|matrix]
//                [--iterations n] [--seed s] [--threads t] [--memory-limit SIZE] [--quiet]
//
// Argument mapping only; the work is run_glossy_compress (cli/glossy_cli.h).
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "glossy_cli.h"
#include "option_rules.h"

namespace prt::cli {
namespace {

Command register_compress(CLI::App& app) {
  auto r = std::make_shared<GlossyCompressRequest>();
  CLI::App* cmd = app.add_subcommand(
      "compress",
      "Compress a glossy transfer file (.prtg) by clustered PCA into a .prtq that prt relight "
      "reads in its place");
  cmd->add_option("input", r->input, "Glossy transfer file (.prtg) from prt bake --glossy")
      ->required();
  cmd->add_option("-o,--output", r->output, "Output CPCA file (.prtq)")->required();
  CLI::Option* clusters = cmd->add_option("--clusters", r->clusters,
                                          "Clusters Q (default 64; at most the vertex count)");
  CLI::Option* vectors =
      cmd->add_option("--vectors", r->vectors, "Principal vectors K per cluster (default 16)");
  CLI::Option* target = cmd->add_option(
      "--target-error", r->target_error,
      "Instead of --vectors: the smallest K whose relative RMS error (in --metric) is at most "
      "E (e.g. 0.02)");
  CLI::Option* max_vectors = cmd->add_option(
      "--max-vectors", r->max_vectors, "With --target-error: the largest K tried (default 32)");
  vectors->excludes(target);
  (void)clusters;
  cmd->add_option("--metric", r->metric,
                  "What the compression minimises: relit (default: the expected error of the "
                  "relit image under the file's own BRDFs) or matrix (the plain matrix error)")
      ->check(CLI::IsMember({"relit", "matrix"}));
  cmd->add_option("--iterations", r->iterations,
                  "Rounds of PCA and reassignment (default 6; stops early when stable)");
  cmd->add_option("--seed", r->seed, "Seed of the cluster seeding (default 1)");
  cmd->add_option("--threads", r->threads, "Worker threads (default 0: every core)");
  add_memory_limit_option(*cmd, &r->memory_limit);
  cmd->add_flag("--quiet", r->quiet, "Print nothing on success");
  const auto check = [r, max_vectors, target] {
    r->max_vectors_given = max_vectors->count() > 0;
    r->target_error_given = target->count() > 0;
    check_compress_request(*r);
  };
  return {cmd, check, [r] { return compress_files(*r); }, [r] { run_glossy_compress(*r); }};
}

}  // namespace

PRT_REGISTER_COMMAND(22, register_compress);

}  // namespace prt::cli
