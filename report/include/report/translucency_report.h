// report/translucency_report.h — `prt report --translucency`: the real-time approximations of
// subsurface scattering (bake/subsurface_approx/subsurface_approximations.h) measured against
// the dipole bake (bake/subsurface/subsurface_baker.h) on the same scene, material and lighting,
// and the dipole bake's time against vertex count.
//
// Per scene: the translucent vertices (every primitive but those named opaque) take one preset of
// prt/subsurface/dipole.h at the scene's mm per unit (0: the dipole bake's automatic rule); one
// shadowed bake S (albedo kept apart, fixed seed) feeds the approximations, the dipole bake
// samples the same S. Both are relit under the environment's SH turned two ways (a rotation
// taking its dominant direction, the l = 1 band of its luminance, to 20° above −Z: "back", the
// light behind the objects as the bundled scene's camera at +Z sees them; to 20° above +Z:
// "front"). Error: relative RMS over the translucent vertices and RGB,
// sqrt(Σ|B − B_dipole|² / Σ|B_dipole|²), for the scene and for each translucent primitive;
// vertices that no triangle uses (never drawn; a scan's stray points) are left out.
// Timing: lone spheres (scene/translucent_scene.h's, radius 10 mm, marble by default) of growing
// ring counts: the hierarchical dipole gather, the O(n²) reference (up to kReferenceMaxVertices)
// and mesh-space diffusion, each the wall time of its own call (shared machine: noisy).
// Files: translucency_errors.csv, translucency_timing.csv, translucency.json,
// translucency_errors.svg/.png, translucency_timing.svg/.png, translucency_summary.md; every
// value in them is the same for any thread count except the times.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sh/env_map.h"

namespace prt::report {

inline constexpr std::size_t kReferenceMaxVertices = 9000;

struct TranslucencyScene {
  std::string path;
  double mm_per_unit = 0;  // 0: the dipole bake's default
};

struct TranslucencyReportOptions {
  std::vector<TranslucencyScene> scenes;
  std::string environment_path;
  std::optional<sh::EnvLayout> layout;
  std::string output_dir;
  std::string preset = "marble";
  std::vector<std::string> opaque;  // primitive or material names kept Lambert; the rest translucent
  int order = 5, samples = 256;
  uint64_t seed = 1;
  bool quick = false;
  uint64_t memory_limit = 0;  // bytes each bake may hold (prt/core/memory_budget.h); 0: none
  std::function<void(const std::string&)> log;
};

struct TranslucencyErrorRow {
  std::string scene, part, lighting, approximation;
  std::size_t vertices = 0;
  double relative_rms = 0;
};

struct TranslucencyTimingRow {
  std::size_t vertices = 0;
  double seconds_hierarchical = 0, seconds_reference = -1, seconds_mesh_diffusion = 0;
  double reference_relative_rms = -1;  // hierarchical against the reference (−1: not run)
};

struct TranslucencyReportResult {
  std::vector<TranslucencyErrorRow> errors;
  std::vector<TranslucencyTimingRow> timing;
  std::vector<std::string> files_written;
};

// The files written into the output folder for these scene paths.
std::vector<std::string> translucency_report_file_names(const std::vector<std::string>& scenes);
// The transfer file of one scene and kind ("dipole" or an approximation's name).
std::string translucency_transfer_name(const std::string& scene_path, const std::string& kind);

// Throws std::runtime_error (one line) on inputs that cannot be used.
TranslucencyReportResult run_translucency_report(const TranslucencyReportOptions& options);

}  // namespace prt::report
