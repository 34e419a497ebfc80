// report/radiosity_report.h — `prt report --radiosity`: error against cost of radiosity solutions
// (radiosity/form_factors.h, radiosity/solver.h) for a scene lit by its own emitters, measured
// against the path-traced patch averages of report/emitter_ground_truth.h.
//
// Sweep: every form-factor method (analytic 3-point, rays, hemicube) × patch count (one
// subdivision per --max-edge value) × solver (Gauss–Seidel, Jacobi, progressive). The matrix
// solvers share one form-factor matrix per (method, patch count); progressive computes its own
// rows on the fly. Cost: total seconds = form factors + solve (progressive: its whole run).
// Re-solve: the emitters' emission is changed (scaled per channel by kResolveScale) and the
// matrix solver run again on the same form factors; its seconds are the cost of relighting with
// new emission (progressive keeps its rows inside the solver, so it has no re-solve).
// Error: per patch count, the ground truth integrates a systematic sample of K non-emitting
// patches (indices ⌊(k + ½)·n/K⌋ of the n non-emitting ones, k < K; all when K ≥ n) with S paths
// each; the error of a solution is the area-weighted relative RMS over those patches,
//     e = √(Σ_p A_p |L_p − L̂_p|²) / √(Σ_p A_p |L̂_p|²)   (RGB norm, L̂ the ground truth),
// and, since the ground truth's noise adds to it in quadrature (E[e²] = e_true² + s², s its
// relative RMS standard error), also e_corrected = √max(0, e² − s²). Emitting patches are left
// out (their emission is exact in both and would swamp the reflected light).
// Surfaces: the scene's original triangles grouped by primitive and plane (normal within 1e-3),
// each integrated as a whole by the ground truth (S_surface paths per triangle) and compared with
// the area-weighted mean of its patches in the most accurate solution of the finest patch count;
// the table also gives each surface's escape fraction (cosine rays that leave the scene). Outputs
// in the output directory: radiosity_results.csv, radiosity_results.json, radiosity_pareto.svg/png
// (error against total seconds, log–log, one series per method and solver, the Pareto front
// marked), radiosity_patches.csv (the finest patch count's evaluated patches: centroid, normal,
// area, ground truth, its SE and the most accurate solution), and radiosity_summary.md. Written
// atomically. Errors throw std::runtime_error / std::invalid_argument with one line naming the file
// or option.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/form_factors.h"
#include "radiosity/solver.h"
#include "scene/material_assignment.h"

namespace prt::report {

// The per-channel scale of the emitters' emission for the re-solve.
inline const glm::dvec3 kResolveScale{0.5, 1.0, 2.0};

struct RadiosityReportOptions {
  std::string scene_path, output_dir;
  std::vector<scene::MaterialColour> emission, albedo;  // per-material values
  bool quick = false;
  std::vector<double> max_edges;  // empty: the mode's default (default_max_edges)
  std::vector<radiosity::FormFactorMethod> methods = {radiosity::FormFactorMethod::Analytic,
                                                      radiosity::FormFactorMethod::Rays,
                                                      radiosity::FormFactorMethod::Hemicube};
  std::vector<radiosity::SolverKind> solvers = {radiosity::SolverKind::GaussSeidel,
                                                radiosity::SolverKind::Jacobi,
                                                radiosity::SolverKind::Progressive};
  int rays_per_patch = 1024;     // rays method (as `prt radiosity`)
  int hemicube_resolution = 64;  // hemicube method
  double tolerance = 1e-4;       // relative unshot power of every solver
  int ground_truth_patches = 0;  // K; 0: the mode's default
  int ground_truth_samples = 0;  // S; 0: the mode's default
  int surface_samples = 0;       // S_surface; 0: the mode's default
  uint64_t seed = 1;
  std::function<void(const std::string&)> log;  // one line per step, when set
};

// Defaults: quick {200, 100} scene units per edge, K = 512, S = 1024, S_surface = 16384;
// full {200, 100, 70, 50}, K = 1024, S = 4096, S_surface = 65536.
std::vector<double> default_max_edges(bool quick);

struct RadiosityReportRow {
  double max_edge = 0;
  std::size_t patches = 0;
  radiosity::FormFactorMethod method = radiosity::FormFactorMethod::Analytic;
  radiosity::SolverKind solver = radiosity::SolverKind::GaussSeidel;
  double form_factor_seconds = 0;  // progressive: 0 (its rows are in solve_seconds)
  double solve_seconds = 0;
  double total_seconds = 0;
  double resolve_seconds = -1;  // −1: no re-solve (progressive)
  std::size_t iterations = 0;   // sweeps or shots
  bool converged = false;
  double relative_rms = 0, relative_rms_corrected = 0;
  bool on_pareto_front = false;
};

struct RadiosityGroundTruthLevel {  // the ground truth of one patch count
  double max_edge = 0;
  std::size_t patches = 0, evaluated = 0;
  int samples = 0;
  double relative_se = 0, seconds = 0;
};

struct RadiositySurface {
  std::string primitive;
  glm::dvec3 normal{0.0};
  double area = 0;
  glm::dvec3 truth{0.0}, truth_se{0.0}, radiosity{0.0};
  double escape = 0;  // fraction of cosine rays from the surface that leave the scene
};

struct RadiosityPatchRow {  // an evaluated patch of the finest patch count
  uint32_t patch = 0;
  glm::dvec3 centroid{0.0}, normal{0.0};
  double area = 0;
  glm::dvec3 truth{0.0}, truth_se{0.0}, radiosity{0.0};  // radiosity: the most accurate row's
};

struct RadiosityReportResult {
  std::vector<RadiosityReportRow> rows;
  std::vector<RadiosityGroundTruthLevel> ground_truth;
  std::vector<RadiositySurface> surfaces;
  std::vector<RadiosityPatchRow> patches;  // the finest patch count's evaluated patches
  double surfaces_max_edge = 0;            // the patch count the surface table compares
  int surface_samples = 0;
  double seconds = 0;
  std::vector<std::string> files_written;
};

std::vector<std::string> radiosity_report_file_names();

std::string method_name(radiosity::FormFactorMethod m);
std::string solver_name(radiosity::SolverKind s);

// Runs the sweep and writes the files.
RadiosityReportResult run_radiosity_report(const RadiosityReportOptions& options);

}  // namespace prt::report
