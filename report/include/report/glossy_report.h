// report/glossy_report.h — `prt report --glossy`: the error of glossy PRT (bake/glossy_transfer_
// baker.h, prt/glossy/relighter.h, compressed by prt/glossy/cpca_transfer.h) against its cost,
// measured against the independent glossy ground truth of report/glossy_ground_truth.h.
//
// What is measured: the exit radiance toward an eye point of a subset of vertices (below), from
// the PRT path — bake, SH projection of the map at the bake's order
// (ShLighting::from_env_map), GlossyRelighter::shade — against the ground truth of the same
// vertices toward the same eye. Error = RGB-norm relative RMS over the subset's vertices and
// channels and over the eyes, √(Σ |prt − truth|²) / √(Σ |truth|²), the metric of
// report/report_metrics.h. It includes the ground truth's own noise; its relative RMS standard
// error s is reported (and drawn) as the noise floor: error² ≈ true error² + s².
//
// Sweep: one axis at a time around a base setting (order 6, 256 samples per vertex, 1 bounce;
// full mode 1024 samples), then CPCA of the base bake (cluster count × vectors per cluster,
// reconstructed matrices relit by the same relighter):
//   quick: order {3, 4, 6, 8}, samples {64, 256, 1024}, bounces {0, 1, 3},
//          CPCA {16×4, 16×8, 64×8};
//   full:  order {2, 3, 4, 5, 6, 8, 10}, samples {64, 256, 1024, 4096}, bounces {0, 1, 2, 4},
//          CPCA {16×4, 16×8, 32×16, 64×8, 64×16, 128×32}.
// Costs per row: bake wall time (all threads), CPCA compression time, relighter creation (the
// BRDF projections), one shading pass of every vertex (one thread, averaged over the eyes), and
// the storage of the transfer (uncompressed: channels · n⁴ floats per vertex; CPCA: its
// payload_bytes()), without geometry or materials.
// Eyes: the scene's first camera's eye (or the automatic camera's, relight/camera.h); the full
// mode adds that eye turned by ±90° about the vertical line through the camera's target.
// Vertices: per eye, an equal share from each primitive among the vertices that face the eye
// (n·(eye − p) > 0), evenly spaced in index order: quick 192, full 768 per eye.
// Ground truth: seed + 1000 (independent of the bakes), 64 samples per vertex doubled until
// s ≤ 0.02 (quick) / 0.01 (full) or 8192 / 65536 samples.
// Materials: the scene's own, after material_overrides (scene/material_override.h, the syntax
// and matching of `prt bake --material`) applied at load time, so the bakes and the ground
// truth see the same BRDFs; the overrides as given and the resulting material of every
// primitive (describe_materials) are written to summary.md.
// Outputs in the output directory (atomically): results.csv, pareto.svg (error against
// storage), error_vs_bake_time.svg, their PNGs when rsvg-convert is installed, summary.md.
// Errors: std::runtime_error / BakeError with "PATH: problem" (unreadable scene or map, a
// material make_brdf refuses, an output that cannot be written); std::invalid_argument
// "--material TEXT: no material or primitive named 'NAME' in PATH (...)" for an override that
// matches nothing. Nothing is written before the scene and the map have been read.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bake/progress.h"
#include "scene/material_override.h"

namespace prt::report {

struct GlossyReportOptions {
  std::string scene_path, environment_path, output_dir;
  bool quick = false;
  uint64_t seed = 1;
  // Applied in order (a later one wins) when the scene is loaded; empty: the scene's own.
  std::vector<scene::MaterialOverride> material_overrides;
  uint64_t memory_limit = 0;  // every bake's and compression's memory_limit; 0: none
  // One line per step to `log` when set; the ground truth's passes to `progress` when not null.
  std::function<void(const std::string&)> log;
  bake::ProgressSink* progress = nullptr;
};

struct GlossyReportRow {
  std::string axis;  // "order", "samples", "bounces" (joined with '+' when shared), "cpca"
  int order = 0, samples = 0, bounces = 0;
  uint32_t clusters = 0, vectors = 0;  // CPCA; 0 for uncompressed transfer
  uint32_t channels = 0;
  uint64_t bytes = 0;
  double bake_seconds = 0, compress_seconds = 0, relighter_seconds = 0, shade_seconds = 0;
  double relative_rms = 0;
  double relative_rms_non_grazing = 0;  // the same without views within ~6° of the tangent plane
  double cpca_matrix_error = 0;         // CPCA: relative RMS of the reconstructed matrices
  std::vector<double> primitive_rms;    // the error over each primitive's vertices alone
  bool front_storage = false, front_bake_time = false;  // Pareto-optimal (error vs that cost)
};

struct GlossyReportResult {
  std::vector<GlossyReportRow> rows;
  std::vector<std::array<double, 3>> eyes;
  std::vector<std::string> primitive_names;  // material name (or primitive name) per primitive
  std::vector<std::string> materials;        // scene::describe_materials after the overrides
  std::size_t vertices_per_eye = 0;
  int ground_truth_samples = 0;  // the largest over the eyes
  double ground_truth_relative_se = 0, ground_truth_seconds = 0;
  std::vector<std::string> files_written;
};

GlossyReportResult run_glossy_report(const GlossyReportOptions& options);

// The files run_glossy_report writes (names inside the output directory).
std::vector<std::string> glossy_report_file_names();

}  // namespace prt::report
