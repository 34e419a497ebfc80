// `prt bake SCENE -o OUT.prt [...]`: bake per-vertex SH transfer (bake/transfer_baker.h) and
// write a coefficient file (prt/formats/transfer_file.h).
//
// Defaults: --transfer shadowed, --order 3 (9 coefficients: what irradiance needs), --samples
// 256 (cosine-weighted Owen-scrambled Sobol': AO error well under 1% on typical meshes),
// --bounces -1 (interreflected: BiCGSTAB until --tolerance 1e-4), --seed 1, all threads, f32.
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bake/adaptive/adaptive_baker.h"
#include "bake/haar_baker.h"
#include "bake/obscurance_falloff.h"
#include "bake/progress.h"
#include "bake/transfer_baker.h"
#include "bake/transfer_part_file.h"
#include "bake_summary.h"
#include "cli_parsing.h"
#include "command_registry.h"
#include "glossy_cli.h"
#include "glossy_shard.h"
#include "haar_cli.h"
#include "material_option.h"
#include "option_rules.h"
#include "output_safety.h"
#include "progress_reporter.h"
#include "prt/formats/part_file.h"
#include "prt/formats/transfer_file.h"
#include "prt/haar/cube_map.h"
#include "relight/environment_input.h"
#include "run_record.h"
#include "scene/material_assignment.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"
#include "sh/projection.h"
#include "shard_cli.h"
#include "subsurface_cli.h"
#include "subsurface_shard.h"

namespace prt::cli {
namespace {

struct BakeArguments {
  std::string scene, output;
  std::string transfer = "shadowed";
  int order = 3;
  int samples = 256;
  int bounces = -1;
  double tolerance = 1e-4;
  std::vector<std::string> albedo;     // r,g,b for every material, or MATERIAL=r,g,b (repeatable)
  std::optional<double> max_edge;      // subdivide (scene/subdivide.h) before baking
  std::vector<std::string> materials;  // --material overrides (cli/material_option.h)
  bool ao = false, bent_normals = false;
  std::optional<double> ao_distance;  // --ao-distance: obscurance (bake/obscurance_falloff.h)
  std::string ao_falloff = "linear";
  uint64_t seed = 1;
  int threads = 0;
  uint64_t memory_limit = 0;  // --memory-limit (option_rules.h); 0: not given
  std::string precision = "f32";
  std::string bounce_precision = "f32";  // --bounce-precision: interreflection only
  bool quiet = false;
  HaarBakeArguments haar;          // --basis haar and its options (haar_cli.h)
  bool automatic = false;          // --auto (bake/adaptive/adaptive_baker.h)
  bool glossy = false;             // --glossy: transfer matrices (cli/glossy_cli.h)
  std::string env;                 // --env: lighting that --auto chooses the SH order for
  SubsurfaceArguments subsurface;  // --subsurface and its options (subsurface_cli.h)
  bool tolerance_given = false, transfer_given = false;
  std::string shard;                          // --shard I/N | auto | auto/N (cli/shard_cli.h)
  std::optional<bake::ShardSpec> shard_spec;  // resolved before the run
};

// "r,g,b" or a single grey value; each in [0, 1).
glm::vec3 parse_albedo(const std::string& text) {
  std::vector<double> values = parse_number_list("--albedo", text);
  if (values.size() == 1) values = {values[0], values[0], values[0]};
  if (values.size() != 3) throw UsageError("--albedo " + text + ": expected r,g,b or one value");
  glm::vec3 albedo;
  for (int c = 0; c < 3; ++c) {
    albedo[c] = static_cast<float>(values[c]);
    if (!(albedo[c] >= 0.f && albedo[c] < 1.f))
      throw UsageError("--albedo " + text + ": every component must be in [0, 1)");
  }
  return albedo;
}

// --albedo values: at most one for every material (LoadOptions::albedo_override) and any
// number of MATERIAL=r,g,b (each component in [0, 1)).
struct AlbedoChoice {
  std::optional<glm::vec3> every;
  std::vector<scene::MaterialColour> per_material;
};

AlbedoChoice parse_albedo_options(const std::vector<std::string>& texts) {
  AlbedoChoice choice;
  for (const std::string& text : texts) {
    if (text.find('=') == std::string::npos) {
      if (choice.every)
        throw UsageError("--albedo " + text + ": only one value for every material");
      choice.every = parse_albedo(text);
      continue;
    }
    scene::MaterialColour value;
    try {
      value = scene::parse_material_colour("--albedo", text);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    for (int c = 0; c < 3; ++c)
      if (!(value.rgb[c] < 1.f))
        throw UsageError("--albedo " + text + ": every component must be in [0, 1)");
    choice.per_material.push_back(value);
  }
  return choice;
}

// Loads the scene with the --albedo values (a material's own value drops its texture) and
// subdivides it when --max-edge is given.
scene::Scene load_bake_scene(const BakeArguments& args) {
  const AlbedoChoice albedo = parse_albedo_options(args.albedo);
  scene::LoadOptions load;
  load.albedo_override = albedo.every;
  load.material_overrides = parse_material_options(args.materials);
  scene::Scene scene = scene::load_scene(args.scene, load);
  try {
    scene::apply_albedo(scene, albedo.per_material);
    for (const scene::MaterialColour& value : albedo.per_material)
      for (std::size_t i : scene::matched_primitives(scene, value))
        scene.primitives[i].base_color_texture.reset();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  try {  // an edge length far too small for the scene is the command line's fault
    if (args.max_edge) scene = scene::subdivide_to_edge_length(scene, *args.max_edge);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return scene;
}

prt::TransferKind parse_kind(const std::string& text) {
  if (text == "unshadowed") return prt::TransferKind::Unshadowed;
  if (text == "shadowed") return prt::TransferKind::Shadowed;
  if (text == "interreflected") return prt::TransferKind::Interreflected;
  throw UsageError("--transfer " + text + ": expected unshadowed, shadowed or interreflected");
}

// Options that do not apply to this bake are refused by name (`given`: on the command line).
void check_applicable(const BakeArguments& a, const CLI::App& cmd, prt::TransferKind kind) {
  const auto given = [&cmd](const std::string& option) { return cmd.count(option) > 0; };
  const auto refuse_given = [&given](const std::vector<std::string>& options,
                                     const std::string& why) {
    for (const std::string& option : options)
      if (given(option)) throw UsageError(option + " " + why);
  };
  if (a.haar.basis == "haar") {
    if (a.automatic) throw UsageError("--auto does not apply to --basis haar (it plans SH bakes)");
    refuse_given({"--order"}, "does not apply to --basis haar (see --cube)");
    refuse_given({"--samples"}, "does not apply to --basis haar (see --haar-supersample)");
    refuse_given({"--precision"}, "does not apply to --basis haar (see --haar-bits)");
    refuse_given({"--ao", "--bent-normals"}, "does not apply to --basis haar (not stored)");
  } else {
    refuse_given(
        {"--cube", "--haar-threshold", "--haar-terms", "--haar-bits", "--haar-supersample"},
        "applies to --basis haar only");
  }
  if (!a.automatic) {
    refuse_given({"--env"}, "applies to --auto only (the lighting it chooses the order for)");
    if (kind != prt::TransferKind::Interreflected)
      refuse_given({"--bounces", "--tolerance"}, "applies to --transfer interreflected only");
    if (a.bounces >= 0)
      refuse_given({"--tolerance"}, "applies to a solve to convergence (--bounces -1) only");
  } else {
    refuse_given({"--samples", "--bounces"}, "does not apply to --auto (it chooses them)");
    if (!a.env.empty()) refuse_given({"--order"}, "does not apply to --auto --env (it chooses it)");
  }
}

// --ao-distance D [--ao-falloff F]: obscurance in the AO (and bent normals), fixed recipe only.
void check_obscurance(const BakeArguments& a, const CLI::App& cmd) {
  refuse_unless(cmd, a.ao, {"--ao-distance", "--ao-falloff"}, "--ao");
  refuse_unless(cmd, a.ao_distance.has_value(), {"--ao-falloff"}, "--ao-distance");
  if (!a.ao_distance) return;
  if (!(*a.ao_distance > 0.0 && std::isfinite(*a.ao_distance)))
    throw UsageError("--ao-distance: must be a finite length > 0 (scene units)");
  if (!bake::parse_obscurance_falloff(a.ao_falloff))
    throw UsageError("--ao-falloff " + a.ao_falloff +
                     ": expected linear, exponential, smoothstep or constant");
  if (a.automatic) throw UsageError("--ao-distance does not apply to --auto (fixed recipe only)");
}

// Values out of range, refused before any file is read.
void check_values(const BakeArguments& a, const CLI::App& cmd) {
  if (a.order < 1 || a.order > bake::kMaxBakeOrder)
    throw UsageError("--order " + std::to_string(a.order) + ": must be in [1, " +
                     std::to_string(bake::kMaxBakeOrder) + "]");
  if (a.samples < 1 || a.samples > bake::kMaxBakeSamples)
    throw UsageError("--samples " + std::to_string(a.samples) + ": must be in [1, " +
                     std::to_string(bake::kMaxBakeSamples) + "]");
  if (a.bounces < -1)
    throw UsageError("--bounces " + std::to_string(a.bounces) +
                     ": must be >= 0, or -1 (until converged)");
  if (!(a.tolerance > 0 && a.tolerance < 1)) throw UsageError("--tolerance: must be in (0, 1)");
  if (a.max_edge && !(*a.max_edge > 0.0 && std::isfinite(*a.max_edge)))
    throw UsageError("--max-edge: must be a finite positive length");
  if (a.threads < 0) throw UsageError("--threads " + std::to_string(a.threads) + ": must be >= 0");
  check_obscurance(a, cmd);
  if (a.precision != "f32" && a.precision != "f16")
    throw UsageError("--precision " + a.precision + ": expected f32 or f16");
  const HaarBakeArguments& h = a.haar;
  if (!prt::is_valid_cube_size(h.cube))
    throw UsageError("--cube " + std::to_string(h.cube) + ": must be a power of two in [" +
                     std::to_string(prt::kMinCubeSize) + ", " + std::to_string(prt::kMaxCubeSize) +
                     "]");
  if (cmd.count("--haar-threshold") && !(h.threshold >= 0 && h.threshold < 1))
    throw UsageError("--haar-threshold: must be in [0, 1)");
  if (cmd.count("--haar-terms") && h.terms < 1)
    throw UsageError("--haar-terms " + std::to_string(h.terms) +
                     ": must be >= 1 (leave it out to keep every term above --haar-threshold)");
  if (h.supersample < 1 || h.supersample > bake::kMaxHaarSupersample)
    throw UsageError("--haar-supersample " + std::to_string(h.supersample) + ": must be in [1, " +
                     std::to_string(bake::kMaxHaarSupersample) + "]");
}

// The loader's count of primitives that got the default albedo, said once (not with --quiet).
void note_default_albedo(const scene::Scene& scene, bool quiet) {
  if (quiet || scene.default_albedo_primitives == 0) return;
  std::fprintf(stderr,
               "prt bake: note: %s: %zu primitive(s) have no material colour (none, or a texture "
               "that is not read): albedo %.2f grey (--albedo r,g,b overrides it)\n",
               scene.source_path.c_str(), scene.default_albedo_primitives,
               double(scene::kDefaultAlbedo));
}

// What the bake reads and writes (checked by main before the run, command_registry.h).
CommandFiles bake_files(const BakeArguments& a) {
  CommandFiles files;
  files.add_scene(a.scene);
  if (!a.env.empty()) files.add_environment(a.env);
  if (a.shard_spec)
    files.add_output_file("-o", a.output, {".prtpart"}, "a part file (--shard)");
  else if (a.glossy)
    files.add_output_file("-o", a.output, {".prtg"}, "a glossy transfer file");
  else
    files.add_output_file("-o", a.output, {".prt"}, "a coefficient file");
  files.add_run_record(a.output);
  return files;
}

// The scene as the bake reads it: --albedo and --max-edge applied, the default-albedo note.
scene::Scene load_for_bake(const BakeArguments& args) {
  scene::Scene scene = load_bake_scene(args);
  if (args.albedo.empty()) note_default_albedo(scene, args.quiet);
  return scene;
}

// `--glossy`: transfer matrices into a glossy transfer file (cli/glossy_cli.h).
GlossyBakeRequest glossy_request(const BakeArguments& args, const CLI::App& cmd) {
  GlossyBakeRequest r;
  r.scene = args.scene;
  r.output = args.output;
  if (args.transfer_given) r.transfer = args.transfer;
  r.order = cmd.count("--order") > 0 ? args.order : 5;
  r.samples = args.samples;
  r.bounces = args.bounces;
  r.bounces_given = cmd.count("--bounces") > 0;
  r.tolerance = args.tolerance;
  r.tolerance_given = args.tolerance_given;
  r.seed = args.seed;
  r.threads = args.threads;
  r.memory_limit = memory_limit_or_default(args.memory_limit);
  r.precision = args.precision;
  r.bounce_precision = args.bounce_precision;
  r.quiet = args.quiet;
  return r;
}

// The command line's own refusals, before any file is looked at.
void check_usage(BakeArguments& args, const CLI::App& cmd) {
  check_values(args, cmd);
  check_subsurface_usage(args.subsurface, cmd,
                         args.glossy                     ? "--glossy"
                         : args.haar.basis == "haar"     ? "--basis haar"
                         : args.automatic                ? "--auto"
                         : args.transfer == "unshadowed" ? "--transfer unshadowed"
                                                         : "");
  if (!args.shard.empty()) {
    if (args.automatic)
      throw UsageError("--shard does not apply to --auto (shards bake the fixed recipe)");
    args.shard_spec = resolve_shard(args.shard, process_environment());
  }
  if (!args.glossy && cmd.count("--bounce-precision") > 0) {
    if (args.bounce_precision != "f32" && args.bounce_precision != "f16")
      throw UsageError("--bounce-precision " + args.bounce_precision + ": expected f32 or f16");
    if (args.haar.basis == "haar" || args.automatic || args.subsurface.given() ||
        parse_kind(args.transfer) != prt::TransferKind::Interreflected)
      throw UsageError(
          "--bounce-precision applies to --transfer interreflected (SH, fixed "
          "recipe) and --glossy interreflection only");
  }
  if (args.glossy) {
    check_glossy_applicable(cmd);
    check_glossy_request(glossy_request(args, cmd));
  } else {
    check_applicable(args, cmd, parse_kind(args.transfer));
  }
}

void run_glossy(const BakeArguments& args, const CLI::App& cmd) {
  if (args.shard_spec)
    return run_glossy_shard(load_for_bake(args), glossy_request(args, cmd), *args.shard_spec);
  run_glossy_bake(load_for_bake(args), glossy_request(args, cmd));
}

// The bake's phases for the run record (run_record.h).
void record_bake(const bake::BakeStatistics& st) {
  run_record().phase("rays", st.seconds_rays);
  if (st.seconds_solve > 0) run_record().phase("interreflection solve", st.seconds_solve);
  run_record().phase("bake", st.seconds_total);
  if (st.cpu_seconds_total <= 0) return;
  RunRecord& r = run_record();
  r.cpu_phase("bvh", st.cpu_seconds_bvh);
  r.cpu_phase("gather setup", st.cpu_seconds_gather_setup);
  r.cpu_phase("rays", st.cpu_seconds_rays - st.cpu_seconds_bvh - st.cpu_seconds_gather_setup);
  if (st.cpu_seconds_solve > 0) r.cpu_phase("interreflection solve", st.cpu_seconds_solve);
  r.cpu_phase("bake", st.cpu_seconds_total);
}

double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// `--auto`: --tolerance (default 0.01) becomes the accuracy target; without --transfer the
// most complete kind (interreflected) is requested and the analysis drops what is not needed.
void run_auto(const BakeArguments& args, const scene::Scene& scene, const bake::BakeOptions& fixed,
              ProgressReporter& progress) {
  bake::AutoBakeOptions o;
  o.tolerance = args.tolerance_given ? args.tolerance : 0.01;
  o.bake = fixed;
  o.bake.kind = args.transfer_given ? fixed.kind : prt::TransferKind::Interreflected;
  if (!args.env.empty()) {
    const prt::sh::EnvMap env = relight::read_checked_environment(args.env, std::nullopt).env;
    o.lighting_order = bake::auto_lighting_order(env);
    o.lighting = prt::sh::project(env, o.lighting_order, nullptr,
                                  progress.projection("projecting " + args.env));
    progress.finish();
    if (o.lighting.empty()) throw CommandError(args.env + ": cannot project the environment");
  }
  const bake::AutoBakeResult result = bake::bake_transfer_auto(scene, o, &progress);
  const prt::Status written = prt::write_transfer_file(args.output, result.bake.data);
  if (!written.ok()) throw CommandError(written.message());
  run_record().phase("analysis", result.report.analysis_seconds);
  run_record().phase("pilot", result.report.pilot_seconds);
  record_bake(result.bake.stats);
  if (args.quiet) return;
  const bake::AutoBakeReport& r = result.report;
  const bake::BakeStatistics& st = result.bake.stats;
  std::printf(
      "prt bake --auto %s: %s transfer, order %d, %u channel%s; %llu rays in %.2f s "
      "(total %.2f s); predicted error %.3g (truncation %.3g, skipped vertices <= %.3g, "
      "sampling %.3g; tolerance %.3g; excludes the mesh's interpolation of interreflected "
      "light)\n",
      args.scene.c_str(), bake::transfer_kind_name(r.stored_kind), r.order,
      result.bake.data.channels, result.bake.data.channels == 1 ? "" : "s",
      static_cast<unsigned long long>(st.rays), st.seconds_rays, st.seconds_total,
      r.predicted_error, r.predicted_truncation_error, r.predicted_skip_error,
      r.predicted_sampling_error, o.tolerance);
  for (const std::string& line : r.left_out) std::printf("  left out: %s\n", line.c_str());
  std::printf("  wrote %s\n", args.output.c_str());
}

// `--shard I/N`: the shard's rows into a part file (bake/transfer_part_file.h), which
// `prt merge` joins with the other shards' parts.
void run_shard(const BakeArguments& args, const scene::Scene& scene,
               const bake::BakeOptions& options, ProgressReporter& progress) {
  const bake::ShardSpec shard = *args.shard_spec;
  bake::check_shardable(scene, options);
  announce_shard(args.scene, scene.vertex_count(), shard, args.quiet);
  const bake::TransferPart part = bake::bake_transfer_part(scene, options, shard, &progress);
  const prt::Status written = prt::write_part_file(
      args.output, bake::encode_transfer_part(part, scene, options, prt_version()));
  if (!written.ok()) throw CommandError(written.message());
  run_record().phase("bvh", part.stats.seconds_bvh);
  run_record().phase("rays", part.stats.seconds_rays);
  run_record().phase("bake", part.stats.seconds_total);
  summarise_shard(args.scene, args.output, scene.vertex_count(), shard, part.rays,
                  part.stats.seconds_rays, args.quiet);
}

// `--basis haar --shard I/N`: the Haar bake's rows into a part file (bake/haar_part.h).
void run_haar_shard(const BakeArguments& args, const scene::Scene& scene,
                    const bake::BakeOptions& sh) {
  const bake::ShardSpec shard = *args.shard_spec;
  const bake::HaarBakeOptions options = haar_bake_options(
      sh.kind, args.haar, args.seed, args.threads, args.bounces, args.tolerance, sh.memory_limit);
  bake::check_haar_shardable(scene, options);
  announce_shard(args.scene, scene.vertex_count(), shard, args.quiet);
  ProgressReporter progress(args.quiet);
  const bake::HaarPart part = bake::bake_haar_part(scene, options, shard, &progress);
  const prt::Status written = prt::write_part_file(
      args.output, bake::encode_haar_part(part, scene, options, prt_version()));
  if (!written.ok()) throw CommandError(written.message());
  run_record().phase("rays", part.stats.seconds_rays);
  run_record().phase("bake", part.stats.seconds_total);
  summarise_shard(args.scene, args.output, scene.vertex_count(), shard, part.rays,
                  part.stats.seconds_rays, args.quiet);
}

void run(const BakeArguments& args, const CLI::App& cmd) {
  run_record().threads = resolved_threads(args.threads);
  if (args.glossy) return run_glossy(args, cmd);
  bake::BakeOptions options;
  options.kind = parse_kind(args.transfer);
  options.order = args.order;
  options.samples = args.samples;
  options.bounces = args.bounces;
  options.bounce_tolerance = args.tolerance;
  options.seed = args.seed;
  options.threads = args.threads;
  options.memory_limit = memory_limit_or_default(args.memory_limit);
  options.ao = args.ao;
  options.bent_normals = args.bent_normals;
  if (args.ao_distance) {
    options.obscurance.distance = *args.ao_distance;
    options.obscurance.falloff = *bake::parse_obscurance_falloff(args.ao_falloff);
  }
  options.precision = args.precision == "f16" ? prt::Precision::F16 : prt::Precision::F32;
  options.bounce_precision =
      args.bounce_precision == "f16" ? prt::Precision::F16 : prt::Precision::F32;

  const double cpu_load = cpu_seconds();
  const scene::Scene scene = load_for_bake(args);
  const double cpu_loaded = cpu_seconds();
  if (args.haar.basis == "haar" && args.shard_spec) return run_haar_shard(args, scene, options);
  if (args.haar.basis == "haar") {
    run_haar_bake(scene, args.output, options.kind, args.haar, args.seed, args.threads,
                  args.bounces, args.tolerance, args.quiet, options.memory_limit);
    return;
  }

  if (args.subsurface.given() && args.shard_spec)
    return run_subsurface_shard(args.scene, scene, args.output, options, args.subsurface,
                                *args.shard_spec, args.quiet);
  if (args.subsurface.given())
    return run_subsurface_bake(scene, args.output, options, args.subsurface, args.quiet);
  ProgressReporter progress(args.quiet);
  if (args.shard_spec) return run_shard(args, scene, options, progress);
  if (args.automatic) return run_auto(args, scene, options, progress);
  const bake::BakeResult result = bake::bake_transfer(scene, options, &progress);
  const double cpu_write = cpu_seconds();
  const prt::Status written = prt::write_transfer_file(args.output, result.data);
  if (!written.ok()) throw CommandError(written.message());
  run_record().cpu_phase("scene load", cpu_loaded - cpu_load);
  record_bake(result.stats);
  run_record().cpu_phase("write", cpu_seconds() - cpu_write);

  const bake::BakeStatistics& st = result.stats;
  warn_unconverged_solve("prt bake", args.scene, options, st);
  if (args.quiet) return;
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(args.output, ec);
  std::printf(
      "baked %s transfer of %s: %llu vertices, %llu triangles, order %d (%u channel%s), "
      "%d samples per vertex; %llu rays in %.2f s (%.2f Mrays/s)",
      bake::transfer_kind_name(options.kind), args.scene.c_str(),
      static_cast<unsigned long long>(st.vertices), static_cast<unsigned long long>(st.triangles),
      options.order, result.data.channels, result.data.channels == 1 ? "" : "s",
      st.samples_per_vertex, static_cast<unsigned long long>(st.rays), st.seconds_rays,
      st.mrays_per_second());
  std::printf("%s", interreflection_summary(options, st).c_str());
  if (!result.data.albedo_folded) std::printf("; albedo kept apart (textures apply per pixel)");
  std::printf("; total %.2f s; wrote %s (%llu bytes, %s)", st.seconds_total, args.output.c_str(),
              static_cast<unsigned long long>(ec ? 0 : bytes), args.precision.c_str());
  std::printf("; %llu degenerate triangles skipped.\n",
              static_cast<unsigned long long>(st.skipped_triangles));
}

Command register_bake(CLI::App& app) {
  auto args = std::make_shared<BakeArguments>();
  CLI::App* cmd = app.add_subcommand("bake", "Bake per-vertex SH transfer into a .prt file");
  cmd->add_option("scene", args->scene, "Scene (.glb, .gltf, .obj)")->required();
  cmd->add_option("-o,--output", args->output, "Coefficient file to write (.prt)")->required();
  cmd->add_option("--transfer", args->transfer, "unshadowed | shadowed | interreflected")
      ->capture_default_str();
  cmd->add_option("--order", args->order, "SH order n (n² coefficients), 1..32")
      ->capture_default_str();
  cmd->add_option("--samples", args->samples, "Rays per vertex (rounded up to a multiple of 16)")
      ->capture_default_str();
  cmd->add_option("--bounces", args->bounces,
                  "Interreflected: exactly N Jacobi bounces; -1 = solve until converged")
      ->capture_default_str();
  cmd->add_option("--tolerance", args->tolerance, "Relative residual of the interreflection solve")
      ->capture_default_str();
  add_material_option(*cmd, args->materials);
  cmd->add_option("--albedo", args->albedo,
                  "Override every material's albedo (textures dropped): r,g,b in [0, 1); or "
                  "MATERIAL=r,g,b for one material (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--max-edge", args->max_edge,
                  "Subdivide the scene until no edge is longer than this (scene units), as "
                  "prt radiosity --max-edge does: the same vertices");
  cmd->add_flag("--ao", args->ao, "Also store ambient occlusion per vertex");
  cmd->add_flag("--bent-normals", args->bent_normals, "Also store bent normals per vertex");
  cmd->add_option("--ao-distance", args->ao_distance,
                  "With --ao: obscurance instead of AO, hits weighted by a falloff of their "
                  "distance that reaches 1 at D (scene units); bent normals weighted alike");
  cmd->add_option("--ao-falloff", args->ao_falloff,
                  "With --ao-distance: linear | exponential | smoothstep | constant")
      ->capture_default_str();
  cmd->add_option("--seed", args->seed, "Sampling seed")->capture_default_str();
  cmd->add_option("--threads", args->threads, "Worker threads (0 = all)")->capture_default_str();
  add_memory_limit_option(*cmd, &args->memory_limit);
  cmd->add_option("--precision", args->precision, "Coefficient storage: f32 | f16")
      ->capture_default_str();
  cmd->add_option("--bounce-precision", args->bounce_precision,
                  "Interreflected (SH or --glossy): the bounce the gather reads held in f32 | "
                  "f16 (half the memory; docs/GLOSSY.md, docs/BENCHMARKS.md)")
      ->capture_default_str();
  cmd->add_flag("--quiet", args->quiet, "No progress, summary or notes (warnings still print)");
  add_haar_bake_options(cmd, &args->haar);
  add_subsurface_options(cmd, &args->subsurface);
  cmd->add_flag("--auto", args->automatic,
                "Analyse the scene and bake only what it needs for --tolerance (default 0.01)");
  cmd->add_option("--env", args->env, "--auto: lighting whose band energy picks the SH order");
  cmd->add_option("--shard", args->shard,
                  "Bake one shard of a farm bake into a part file (.prtpart) for prt merge: I/N "
                  "(0-based), auto (Slurm array) or auto/N (Kubernetes Indexed Job or Slurm)");
  cmd->add_flag("--glossy", args->glossy,
                "Bake glossy transfer matrices (order 1..10, default 5) into a .prtg file");
  const auto check = [args, cmd] {
    args->tolerance_given = cmd->count("--tolerance") > 0;
    args->transfer_given = cmd->count("--transfer") > 0;
    check_usage(*args, *cmd);
  };
  return {cmd, check, [args] { return bake_files(*args); }, [args, cmd] { run(*args, *cmd); }};
}

}  // namespace

PRT_REGISTER_COMMAND(20, register_bake);

}  // namespace prt::cli
