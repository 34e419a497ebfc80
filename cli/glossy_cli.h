// cli/glossy_cli.h — the glossy parts of `prt bake` and `prt info` (bake/glossy_transfer_baker.h,
// prt/formats/glossy_transfer_file.h), kept apart so the SH commands change by a few lines only.
//   prt bake SCENE --glossy -o OUT.prtg [--transfer shadowed|interreflected] [--order n]
//            [--samples N] [--bounces k] [--tolerance x] [--seed s] [--threads t]
//            [--precision f32|f16] [--albedo r,g,b] [--quiet]
//   prt info FILE.prtg|FILE.prtq [--json | --csv]
//   prt compress IN.prtg -o OUT.prtq [--clusters Q] [--vectors K | --target-error E
//                [--max-vectors K]] [--iterations n] [--seed s] [--threads t] [--quiet]
// Defaults for --glossy: order 5, shadowed; --bounces k > 0 (or --transfer interreflected,
// then until converged) adds interreflection. Materials come from the scene (ScenePrimitive::brdf,
// Lambert with the albedo where absent).
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

#include "bake/glossy_transfer_baker.h"
#include "output_safety.h"
#include "scene/scene.h"

namespace prt::cli {

struct GlossyBakeRequest {
  std::string scene, output;
  std::string transfer;  // "" (not given), "shadowed" or "interreflected"
  int order = 5;
  int samples = 256;
  int bounces = 0;
  bool bounces_given = false, tolerance_given = false;
  double tolerance = 1e-4;
  uint64_t seed = 1;
  int threads = 0;
  uint64_t memory_limit = 0;  // GlossyBakeOptions::memory_limit
  std::string precision = "f32";
  std::string bounce_precision = "f32";  // GlossyBakeOptions::bounce_precision
  bool quiet = false;
};

struct GlossyCompressRequest {
  std::string input, output;
  int clusters = 64;
  int vectors = 16;
  double target_error = 0;  // > 0: choose K (prt::CpcaOptions::target_relative_rms)
  int max_vectors = 32;
  std::string metric = "relit";     // "relit" (bake/cpca/relit_metric.h) or "matrix" (plain)
  bool max_vectors_given = false;   // refused without target_error
  bool target_error_given = false;  // then target_error must be in (0, 1)
  int iterations = 6;
  uint64_t seed = 1;
  int threads = 0;            // 0: std::thread::hardware_concurrency()
  uint64_t memory_limit = 0;  // --memory-limit as given (0: not given, the default applies)
  bool quiet = false;
};

// `prt compress`: check_compress_request refuses bad values (UsageError, before anything is
// read); compress_files declares the input and the .prtq (checked by main). The run reads the
// glossy file, refuses --vectors / --max-vectors beyond its matrices' dimension D =
// channels·order⁴ (more vectors than that cannot lower the error, only grow the file), compresses
// it, writes the .prtq atomically with a source section (geometry, frames, materials) and reports
// sizes and the errors (plain matrix, and relit metric when that was used). Throws UsageError /
// CommandError.
void check_compress_request(const GlossyCompressRequest& request);
CommandFiles compress_files(const GlossyCompressRequest& request);
void run_glossy_compress(const GlossyCompressRequest& request);

// Options of `prt bake` that do not apply with --glossy, refused by name (`cmd` counts them).
void check_glossy_applicable(const CLI::App& cmd);

// Checks the glossy values (order, transfer, bounces, tolerance). Throws UsageError.
void check_glossy_request(const GlossyBakeRequest& request);

// The bake options the request means (--bounces, or −1 / 0 from --transfer).
bake::GlossyBakeOptions glossy_bake_options(const GlossyBakeRequest& request);

// Checks the values, bakes, writes and reports. Throws UsageError / CommandError / BakeError.
void run_glossy_bake(const scene::Scene& scene, const GlossyBakeRequest& request);

// True when `path` starts with the glossy magic "PRTG" or the CPCA magic "PRCP" (then
// `prt info` describes it here and `prt relight` relights it as a glossy file).
bool is_glossy_file(const std::string& path);

// `prt info` of a glossy or CPCA file (--csv: glossy files only). Throws CommandError.
void describe_glossy_file(const std::string& path, bool json, bool csv);

}  // namespace prt::cli
