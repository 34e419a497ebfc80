// bake/adaptive_baker.h — `prt bake --auto`: analyse the scene, do only the work it needs for a
// stated accuracy, and say what was left out and the predicted error.
//
// Conventions: those of bake/transfer_baker.h (SH basis of sh/basis.h, no Condon–Shortley
// phase, k = l(l+1)+m, glTF frame +Y up, T includes albedo/π). Lighting: channel-major RGB SH
// coefficients of distant radiance (sh::project of an environment map).
//
// Steps (each one conservative or measured; see the headers cited):
//  1. bake/scene_analysis.h: vertices with a provably open hemisphere get the analytic
//     unshadowed transfer with no rays; grey albedo → one channel; zero albedo → no
//     interreflection.
//  2. with lighting: a pilot bake (order pilot_order, pilot_samples rays, pilot_vertices vertices
//     spread evenly over the index range) and bake/order_selection.h choose the smallest SH order
//     whose predicted truncation error is ≤ tolerance/2; bands above it are dropped (the file
//     simply has a lower order). When no order ≤ max_order meets it, Haar is recommended.
//  3. the bake with BakeOptions::adaptive: per-vertex sample counts from min_samples to
//     max_samples until the standard error of the exit radiance is ≤ tolerance × the sky's mean
//     radiance; interreflection skipped when no sample hit another surface; bounces stop when
//     one adds < tolerance/4 × max direct.
//  4. predicted error = [truncation² + sampling²]^½ (the truncation error is deterministic and
//     the sampling error zero-mean, so their squares add in the RMS), with sampling =
//     [Σ_v,c (ρ_c·L̄_c·SE_v)²]^½ / [Σ B²]^½ from the i.i.d. standard error, which over-estimates
//     the error of scrambled Sobol' points (conservative).
//     Without lighting, B and L̄ are those of a uniform white sky.
// The report goes to AutoBakeReport::json() and into the file's metadata as "auto".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bake/order_selection.h"
#include "bake/scene.h"
#include "bake/transfer_baker.h"

namespace prt::bake {

struct AutoBakeOptions {
  double tolerance = 0.01;  // relative RMS error of the exit radiance
  prt::TransferKind kind = prt::TransferKind::Interreflected;  // the most the scene may need
  int order = 3;                                               // SH order when no lighting is given
  std::vector<double> lighting;  // 3 × lighting_order² (channel-major), or empty
  int lighting_order = 0;
  int max_order = 12;    // highest SH order the lighting may ask for
  int pilot_order = 16;  // > max_order, so the pilot sees bands beyond the cap
  int pilot_vertices = 256;
  int pilot_samples = 256;
  int min_samples = 64;
  int max_samples = 1024;
  uint64_t seed = 1;
  int threads = 0;
  bool ao = false, bent_normals = false;
  prt::Precision precision = prt::Precision::F32;
};

struct AutoBakeReport {
  std::size_t vertices = 0;
  std::size_t open_vertices = 0;  // analytic, no rays
  double analysis_seconds = 0, pilot_seconds = 0;
  bool grey = true;
  prt::TransferKind stored_kind = prt::TransferKind::Shadowed;
  int order = 3;
  bool order_chosen = false;  // from the lighting
  OrderChoice order_choice;   // valid when order_chosen
  double predicted_truncation_error = 0;
  double predicted_sampling_error = 0;
  double predicted_error = 0;         // [truncation² + sampling²]^½
  double mean_samples = 0;            // over sampled vertices
  std::vector<std::string> left_out;  // "what: why", one line each
  std::string json() const;           // the "auto" object of the metadata
};

struct AutoBakeResult {
  BakeResult bake;
  AutoBakeReport report;
};

// Throws BakeError (bad input) or std::runtime_error (Embree). `progress` may be null.
AutoBakeResult bake_transfer_auto(const Scene& scene, const AutoBakeOptions& options,
                                  ProgressSink* progress = nullptr);

// Exit radiance B_v,c = Σ_k T_v,c,k L_c,k of every vertex and channel (3 per vertex; a
// one-channel file is applied to all three lighting channels). lighting: 3 × lighting_order².
std::vector<double> exit_radiance(const prt::TransferData& data,
                                  const std::vector<double>& lighting, int lighting_order);

// Relative RMS difference [Σ (b − ref)²]^½ / [Σ ref²]^½ of two exit radiance vectors.
double relative_rms_error(const std::vector<double>& b, const std::vector<double>& reference);

}  // namespace prt::bake
