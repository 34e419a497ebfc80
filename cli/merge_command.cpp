// `prt merge PART... -o OUT`: the parts a sharded `prt bake --shard I/N` wrote (any order) into the
// file a single `prt bake` with the same options writes, byte for byte (docs/FARM.md); the parts
// of `prt radiosity --shard I/N` into the form-factor cache `--form-factor-cache` writes.
//
// The parts are read and checked first (prt/formats/part_file.h: size, checksum; then
// bake/transfer_part_file.h: one prt version, scene, seed, settings and split, every shard once);
// a part that does not fit is named in one line and nothing is written. Then the interreflection
// solve (when the bake asked for it) and the coefficient file, with its run record.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bake/transfer_part_file.h"
#include "bake_summary.h"
#include "command_registry.h"
#include "glossy_shard.h"
#include "option_rules.h"
#include "progress_reporter.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/formats/part_file.h"
#include "prt/formats/transfer_file.h"
#include "radiosity_shard.h"
#include "run_record.h"
#include "subsurface_shard.h"

namespace prt::cli {
namespace {

struct MergeArguments {
  std::vector<std::string> parts;
  std::string output;
  int threads = 0;
  uint64_t memory_limit = 0;
  bool quiet = false;
};

CommandFiles merge_files(const MergeArguments& a) {
  CommandFiles files;
  files.add_inputs("part", a.parts);
  files.add_output_file("-o", a.output);  // .prt, or a form-factor cache (checked in run)
  files.add_run_record(a.output);
  return files;
}

std::vector<bake::TransferPartFile> read_parts(const std::vector<std::string>& paths) {
  std::vector<bake::TransferPartFile> parts;
  for (const std::string& path : paths) {
    prt::PartFile file;
    const prt::Status read = prt::read_part_file(path, &file);
    if (!read.ok()) throw CommandError(read.message());
    parts.push_back(bake::decode_transfer_part(file, path));
  }
  return parts;
}

// Haar parts: the single Haar bake's file (bake/haar_part.h).
void merge_haar(const MergeArguments& args,
                const std::vector<const bake::TransferPartFile*>& ordered) {
  const scene::Scene& scene = *ordered[0]->scene;
  bake::HaarBakeOptions options = ordered[0]->haar_options;
  options.threads = args.threads;
  options.memory_limit = memory_limit_or_default(args.memory_limit);
  std::vector<const bake::HaarPart*> parts;
  for (const bake::TransferPartFile* f : ordered) parts.push_back(&f->haar_part);
  ProgressReporter progress(args.quiet);
  const bake::HaarBakeResult result = bake::merge_haar_parts(scene, options, parts, &progress);
  const prt::Status written = prt::write_haar_transfer_file(args.output, result.file);
  if (!written.ok()) throw CommandError(written.message());
  if (result.stats.seconds_solve > 0)
    run_record().phase("interreflection solve", result.stats.seconds_solve);
  run_record().phase("merge", result.stats.seconds_total);
  if (!args.quiet)
    std::printf("merged %zu parts of %s (Haar %s transfer, cube %d, %llu vertices); wrote %s\n",
                parts.size(), scene.source_path.c_str(),
                bake::transfer_kind_name(options.transport), options.cube_size,
                static_cast<unsigned long long>(result.stats.vertices), args.output.c_str());
}

void run(const MergeArguments& args) {
  const auto t0 = std::chrono::steady_clock::now();
  run_record().threads = resolved_threads(args.threads);
  const std::vector<bake::TransferPartFile> files = read_parts(args.parts);
  const std::vector<const bake::TransferPartFile*> ordered = bake::check_parts_fit(files);
  const double read_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  run_record().phase("read parts", read_seconds);
  if (ordered[0]->form_factors) return merge_form_factor_parts(ordered, args.output, args.quiet);
  if (ordered[0]->glossy)
    return merge_glossy_parts(ordered, args.output, args.threads, args.memory_limit, args.quiet);
  check_output_file("-o", args.output, {".prt"}, "a coefficient file");
  if (ordered[0]->haar) return merge_haar(args, ordered);
  if (ordered[0]->subsurface)
    return merge_subsurface_parts(ordered, args.output, args.threads, args.memory_limit,
                                  args.quiet);
  const scene::Scene& scene = *ordered[0]->scene;
  bake::BakeOptions options = ordered[0]->options;
  options.threads = args.threads;
  options.memory_limit = memory_limit_or_default(args.memory_limit);
  std::vector<const bake::TransferPart*> parts;
  for (const bake::TransferPartFile* f : ordered) parts.push_back(&f->part);
  ProgressReporter progress(args.quiet);
  const bake::BakeResult result = bake::merge_transfer_parts(scene, options, parts, &progress);
  const prt::Status written = prt::write_transfer_file(args.output, result.data);
  if (!written.ok()) throw CommandError(written.message());
  if (result.stats.seconds_solve > 0)
    run_record().phase("interreflection solve", result.stats.seconds_solve);
  run_record().phase("merge", result.stats.seconds_total);
  const bake::BakeStatistics& st = result.stats;
  warn_unconverged_solve("prt merge", scene.source_path, options, st);
  if (args.quiet) return;
  std::printf("merged %zu parts of %s (%s transfer, %llu vertices, %llu rays)%s", parts.size(),
              scene.source_path.c_str(), bake::transfer_kind_name(options.kind),
              static_cast<unsigned long long>(st.vertices),
              static_cast<unsigned long long>(st.rays),
              interreflection_summary(options, st).c_str());
  std::printf("; wrote %s\n", args.output.c_str());
}

Command register_merge(CLI::App& app) {
  auto args = std::make_shared<MergeArguments>();
  CLI::App* cmd = app.add_subcommand(
      "merge",
      "Merge the part files of prt bake --shard I/N (any order) into the file one prt bake writes");
  cmd->add_option("parts", args->parts, "Part files (.prtpart), one per shard")->required();
  cmd->add_option("-o,--output", args->output, "Coefficient file to write (.prt)")->required();
  cmd->add_option("--threads", args->threads, "Worker threads (0 = all)")->capture_default_str();
  add_memory_limit_option(*cmd, &args->memory_limit);
  cmd->add_flag("--quiet", args->quiet, "No progress or summary (warnings still print)");
  const auto check = [args] {
    if (args->threads < 0)
      throw UsageError("--threads " + std::to_string(args->threads) + ": must be >= 0");
  };
  return {cmd, check, [args] { return merge_files(*args); }, [args] { run(*args); }};
}

}  // namespace

PRT_REGISTER_COMMAND(21, register_merge);

}  // namespace prt::cli
