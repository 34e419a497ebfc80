// report/src/report_state.cpp — setting up `prt report`: the output directory, the inputs and
// the ground-truth integrator every phase shares (report_state.h).
#include "report_state.h"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "prt/haar/cube_map.h"
#include "relight/auto_camera.h"
#include "relight/environment_input.h"
#include "scene/scene_loader.h"

namespace prt::report::detail {

// Throws for a --haar-cubes size that is not a power of two in [8, 128].
void check_haar_cubes(const ReportOptions& opt) {
  if (opt.haar_cubes)
    for (int cube : *opt.haar_cubes)
      if (!prt::is_valid_cube_size(cube))
        throw std::runtime_error("report: Haar cube size " + std::to_string(cube) +
                                 " is not a power of two in [8, 128]");
}

void create_output_dir(const ReportOptions& opt) {
  std::error_code ec;
  std::filesystem::create_directories(opt.output_dir, ec);
  if (ec) throw std::runtime_error(opt.output_dir + ": cannot create directory: " + ec.message());
}

namespace {

GroundTruthOptions report_ground_truth_options(const ReportOptions& opt) {
  GroundTruthOptions gto;
  gto.seed = opt.seed + 1000;
  gto.initial_samples = 64;
  gto.max_samples = 1 << 16;
  return gto;
}

// The largest SH order the sweep projects the map to (the reference's).
int largest_sweep_order(bool quick) {
  return quick ? base_setting(true).order : 16;
}

// The map, checked and screened for the largest order of the sweep (relight/environment_input.h).
sh::EnvMap read_report_environment(const ReportOptions& opt, std::string* layout_note) {
  relight::EnvironmentUse use;
  use.sh_order = largest_sweep_order(opt.quick);
  relight::EnvironmentInput in =
      relight::read_checked_environment(opt.environment_path, opt.layout, use);
  *layout_note = in.layout_note;
  return std::move(in.env);
}

}  // namespace

ReportInputs::ReportInputs(const ReportOptions& opt, const ReportLog& log)
    : scene(scene::load_scene(opt.scene_path)),
      env(read_report_environment(opt, &layout_note)),
      caster(scene),
      V(scene.vertex_count()) {
  log(opt.scene_path + ": " + std::to_string(V) + " vertices; " + opt.environment_path + ": " +
      layout_note);
  ropt.width = opt.image_width, ropt.height = opt.image_height, ropt.samples_per_axis = 2;
  const relight::CameraChoice chosen = relight::choose_camera(
      "auto", scene, caster, static_cast<float>(ropt.width) / static_cast<float>(ropt.height));
  camera = chosen.camera;
  log(relight::describe_camera(chosen));
  // Pixels fully covered by the scene: a rendering of radiance 1 everywhere is 1 there.
  const std::vector<float> ones = render_radiance(std::vector<float>(3 * V, 1.f));
  mask.resize(ones.size() / 3);
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = ones[3 * i] > 0.999f ? 1 : 0;
}

// Everything the phases of run_report share: the inputs, the ground truth, the sweep's caches

ReportState::ReportState(const ReportOptions& options, Clock::time_point start)
    : opt(options),
      log{options.log, start},
      base(base_setting(options.quick)),
      in(options, log),
      gto(report_ground_truth_options(options)),
      gt(in.scene, in.env, gto),
      progress(options.progress),
      budget(options.quick
                 ? std::min(options.ground_truth_budget_seconds, kQuickGroundTruthBudgetSeconds)
                 : options.ground_truth_budget_seconds),
      reference_order(largest_sweep_order(options.quick)),
      reference_samples(options.quick ? 1024 : 8192) {}

}  // namespace prt::report::detail
