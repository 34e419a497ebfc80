// cli/haar_cli.h — the Haar-wavelet options of `prt bake` and `prt relight` (bake/haar_baker.h,
// relight/haar_relight.h), kept apart so the SH commands change by a few lines only.
//   prt bake SCENE -o OUT.prt --basis haar [--cube N] [--haar-threshold X | --haar-terms M]
//            [--haar-bits 8|16|32] [--haar-supersample S]
//   prt relight SCENE FILE.prt ENV -o OUT [--terms K] [--approx nonlinear|linear]
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "bake/haar_baker.h"
#include "prt/formats/transfer_data.h"
#include "relight/relight_pipeline.h"
#include "scene/scene.h"

namespace prt::cli {

struct HaarBakeArguments {
  std::string basis = "sh";
  int cube = 32;
  double threshold = -1.0;  // < 0: not given (then 0.001 unless --haar-terms)
  int64_t terms = 0;        // 0: no limit
  int bits = 16;
  int supersample = 1;
};

void add_haar_bake_options(CLI::App* command, HaarBakeArguments* args);

// Bakes, writes and reports (stored vs dense size); the phases go to the run record
// (run_record.h). `memory_limit`: HaarBakeOptions::memory_limit. Throws CommandError / BakeError.
// The Haar baker's options of the command line's values (the one mapping of `prt bake --basis
// haar`, whole or sharded).
bake::HaarBakeOptions haar_bake_options(prt::TransferKind kind, const HaarBakeArguments& args,
                                        uint64_t seed, int threads, int bounces, double tolerance,
                                        uint64_t memory_limit);

void run_haar_bake(const scene::Scene& scene, const std::string& output, prt::TransferKind kind,
                   const HaarBakeArguments& args, uint64_t seed, int threads, int bounces,
                   double tolerance, bool quiet, uint64_t memory_limit);

struct HaarRelightArguments {
  int64_t terms = 200;
  std::string approx = "nonlinear";
};

void add_haar_relight_options(CLI::App* command, HaarRelightArguments* args);

// When request.transfer_path is a Haar file: relights it, prints the summary (unless quiet)
// and returns true; otherwise returns false and does nothing.
bool relight_if_haar(const relight::RelightRequest& request, const HaarRelightArguments& args,
                     bool quiet);

}  // namespace prt::cli
