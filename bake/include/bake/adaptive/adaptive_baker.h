// bake/adaptive/adaptive_baker.h — `prt bake --auto`: analyse the scene, do only the work it needs
// for a stated accuracy, and say what was left out and the predicted error.
//
// Conventions: those of bake/transfer_baker.h (SH basis of sh/basis.h, no Condon–Shortley
// phase, k = l(l+1)+m, glTF frame +Y up, T includes albedo/π). Lighting: channel-major RGB SH
// coefficients of distant radiance (sh::project of an environment map).
//
// Steps (each one conservative or measured; see the headers cited):
//  1. bake/adaptive/scene_analysis.h: vertices with a provably open hemisphere get the analytic
//     unshadowed transfer with no rays; grey albedo → one channel; zero albedo → no
//     interreflection.
//  2. with lighting: a pilot bake (order pilot_order, or lighting_order + 1 when that is lower:
//     bands the lighting lacks carry nothing; pilot_samples rays on pilot_vertices vertices, one
//     at random from each of pilot_vertices equal index ranges) and bake/adaptive/order_selection.h
//     choose the smallest SH order whose predicted truncation error is ≤ tolerance/2; bands above
//     it are dropped (the file simply has a lower order). The pilot's noise only adds to the
//     prediction, so when no order meets it the pilot is repeated with 4× the samples (up to
//     max_pilot_samples); when none meets it then, the smallest order whose truncation stays
//     within 80% of the tolerance is baked (sampling gets the rest), and when there is none,
//     max_order is baked and Haar is recommended unless the predicted total (step 5) still
//     meets the tolerance.
//  3. bake/adaptive/occlusion_bound.h: vertices whose blockable projected solid angle is bounded,
//  without
//     rays, below bounded_skip_cutoff are ranked by their exit-radiance error bound ρ·G·M
//     (adaptive_baker.cpp) and skip rays, smallest first, while the bounds' relative RMS stays
//     ≤ bounded_skip_share × tolerance.
//  4. the bake with BakeOptions::adaptive (bake/transfer_baker.h): min_samples rays per sampled
//     vertex, then Neyman allocation up to max_samples until the calibrated sampling error
//     (audit vertices with two independent scrambles measure the points' actual error) meets
//     what is left of the tolerance; interreflection skipped when no sample hit another surface;
//     bounces stop when one adds < tolerance/4 × max direct.
//  5. predicted error = [(truncation + skip)² + sampling²]^½: truncation and the skip bias are
//     deterministic and may share a sign (added), the sampling error is zero-mean (squares
//     add); sampling = [Σ_v,c (ρ_c·L̄_c·SE_v)²]^½ / [Σ B²]^½ with the calibrated SE.
//     Without lighting, B and L̄ are those of a uniform white sky.
// The report goes to AutoBakeReport::json() and into the file's metadata as "auto".
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "bake/adaptive/order_selection.h"
#include "bake/transfer_baker.h"
#include "scene/scene.h"
#include "sh/constants.h"
#include "sh/env_check.h"

namespace prt::bake {

// Default BakeOptions asking for transfer of `kind`.
inline BakeOptions bake_options_of_kind(prt::TransferKind kind) {
  BakeOptions options;
  options.kind = kind;
  return options;
}

struct AutoBakeOptions {
  double tolerance = 0.01;  // relative RMS error of the exit radiance
  // What a fixed bake would be asked for, composed rather than copied: `kind` is the most the
  // scene may need (interreflected by default), `order` the SH order when no lighting is given;
  // seed, threads, AO, bent normals and precision pass through to the bakes --auto makes. Its
  // samples and bounces are not used: --auto chooses them.
  BakeOptions bake = bake_options_of_kind(prt::TransferKind::Interreflected);
  std::vector<double> lighting;  // 3 × lighting_order² (channel-major), or empty
  int lighting_order = 0;
  int max_order = 12;  // highest SH order the lighting may ask for
  // > max_order, so the pilot sees bands beyond the cap; at most lighting_order + 1 are baked.
  // The lighting's own order by default (kMaxBakeOrder for `prt bake --auto --env`): bands the
  // pilot does not see enter only through a Cauchy–Schwarz bound, which with a sun dwarfed the
  // rest (data/demo.glb under data/sky.hdr, order 12: a pilot of order 16 predicted 0.064 plus
  // a bound of 3.2; of order 32 with 256 samples, 0.16 with no bound; with 4096 samples (see
  // max_pilot_samples), 0.04; `prt report` measures 0.038 against the ground truth for a
  // converged order-12 bake, mesh interpolation included).
  int pilot_order = kMaxBakeOrder;
  int pilot_vertices = 256;
  int pilot_samples = 256;
  // When no order ≤ max_order meets the target, the pilot is repeated with 4× the samples while
  // that stays ≤ max_pilot_samples: its noise inflates the predicted truncation (a sun).
  int max_pilot_samples = 4096;
  int min_samples = 64;
  int max_samples = 1024;
  // Vertices whose occlusion is bounded without rays (bake/adaptive/occlusion_bound.h) below
  // bounded_skip_cutoff of the cosine-weighted hemisphere may skip rays while their summed
  // error bound stays ≤ bounded_skip_share × tolerance (relative RMS); 0 turns this off.
  double bounded_skip_share = 0.25;
  double bounded_skip_cutoff = 0.05;
  // Vertices whose blockable directions fit in a few small cones draw their rays inside them
  // (bake/adaptive/occluder_caps.h, bake/adaptive/cap_sampling.h).
  bool cap_sampling = true;
  int max_caps = 8;
  double max_cap_solid_angle = sh::kHalfPi;  // π/2 sr
};

// The lighting order `prt bake --auto --env` projects a map to: kMaxBakeOrder, or fewer bands
// when the map resolves fewer (sh/env_check.h): the bands beyond hold only sampling noise,
// whose "energy" would make the order selection ask for bands the lighting does not have.
inline int auto_lighting_order(const sh::EnvMap& env) {
  return std::min(kMaxBakeOrder, sh::resolved_band(env) + 1);
}

struct AutoBakeReport {
  std::size_t vertices = 0;
  std::size_t open_vertices = 0;          // analytic, no rays
  std::size_t bounded_skip_vertices = 0;  // analytic within the error bound, no rays
  double predicted_skip_error = 0;        // bound of their bias, relative RMS
  double analysis_seconds = 0, pilot_seconds = 0;
  int pilot_samples = 0;  // per pilot vertex, of the last pilot (0: no pilot)
  bool grey = true;
  prt::TransferKind stored_kind = prt::TransferKind::Shadowed;
  int order = 3;
  bool order_chosen = false;  // from the lighting
  OrderChoice order_choice;   // valid when order_chosen
  double predicted_truncation_error = 0;
  double predicted_sampling_error = 0;
  double predicted_error = 0;         // [(truncation + skip)² + sampling²]^½
  double mean_samples = 0;            // over sampled vertices
  std::vector<std::string> left_out;  // "what: why", one line each
  std::string json() const;           // the "auto" object of the metadata (no wall times)
};

struct AutoBakeResult {
  BakeResult bake;
  AutoBakeReport report;
};

// Throws BakeError (bad input) or std::runtime_error (Embree). `progress` may be null.
AutoBakeResult bake_transfer_auto(const scene::Scene& scene, const AutoBakeOptions& options,
                                  ProgressSink* progress = nullptr);

// Exit radiance B_v,c = Σ_k T_v,c,k L_c,k of every vertex and channel (3 per vertex; a
// one-channel file is applied to all three lighting channels). lighting: 3 × lighting_order².
std::vector<double> exit_radiance(const prt::TransferData& data,
                                  const std::vector<double>& lighting, int lighting_order);

// Relative RMS difference [Σ (b − ref)²]^½ / [Σ ref²]^½ of two exit radiance vectors.
double relative_rms_error(const std::vector<double>& b, const std::vector<double>& reference);

}  // namespace prt::bake
