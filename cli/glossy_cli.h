// cli/glossy_cli.h — the glossy parts of `prt bake` and `prt info` (bake/glossy_transfer_baker.h,
// prt/glossy_transfer_file.h), kept apart so the SH commands change by a few lines only.
//   prt bake SCENE --glossy -o OUT.prtg [--transfer shadowed|interreflected] [--order n]
//            [--samples N] [--bounces k] [--tolerance x] [--seed s] [--threads t]
//            [--precision f32|f16] [--albedo r,g,b] [--quiet]
//   prt info FILE.prtg [--json | --csv]
// Defaults for --glossy: order 5, shadowed; --bounces k > 0 (or --transfer interreflected,
// then until converged) adds interreflection. Materials come from the scene (ScenePrimitive::brdf,
// Lambert with the albedo where absent).
#pragma once

#include <cstdint>
#include <string>

#include <CLI/CLI.hpp>

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
  std::string precision = "f32";
  bool quiet = false;
};

// Options of `prt bake` that do not apply with --glossy, refused by name (`cmd` counts them).
void check_glossy_applicable(const CLI::App& cmd);

// Checks the glossy values (order, transfer, bounces, tolerance). Throws UsageError.
void check_glossy_request(const GlossyBakeRequest& request);

// Checks the values, bakes, writes and reports. Throws UsageError / CommandError / BakeError.
void run_glossy_bake(const scene::Scene& scene, const GlossyBakeRequest& request);

// True when `path` starts with the glossy magic (then `prt info` describes it here).
bool is_glossy_file(const std::string& path);

// `prt info` of a glossy file. Throws CommandError.
void describe_glossy_file(const std::string& path, bool json, bool csv);

}  // namespace prt::cli
