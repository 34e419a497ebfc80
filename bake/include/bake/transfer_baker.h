// bake/transfer_baker.h — per-vertex SH transfer vectors for diffuse PRT.
//
// Conventions: SH basis of sh/basis.h (real, orthonormal, no Condon–Shortley phase, index
// k = l(l+1)+m, functions of the scene-frame direction, scene frame = glTF's, +Y up). The
// output T_p satisfies B_p,c = Σ_k T_p,c,k · L_c,k for lighting L = SH coefficients of
// distant *radiance*; T includes albedo/π (albedo_folded = true).
//
// Albedo kept apart (albedo_folded = false): when the scene is textured (Scene::textured(), a
// base-colour texture on some primitive) or BakeOptions::keep_albedo_apart is set, the file holds
// G_p with B = ρ · Σ_k G_p,k L_k, ρ the receiving surface's albedo wherever it is shaded (the
// texture per pixel, scene/texture.h): the receiver's albedo is left out, the albedo of every
// surface light bounces off is kept in. Unshadowed and shadowed: G = S (grey, 1 channel);
// interreflected: G = S + H_ρ G, where a sample hitting triangle (v0, v1, v2) at barycentrics b
// adds b_i·ρ(hit)/N to H_ρ[p, v_i], ρ(hit) the albedo at the hit point (the texture read
// bilinearly at the hit's interpolated coordinates: an unbiased point sample of the texture, the
// N rays of a vertex averaging it over the surface they see) — this is T = diag(ρ)·G of the
// folded system with the hit's albedo taken from the texture instead of its vertices.
//
// Kinds (Sloan, Kautz & Snyder, SIGGRAPH 2002, §5–6):
//   unshadowed      T = (ρ/π) · rotate_zonal(clamped-cosine zonal coefficients, n): analytic.
//   shadowed        N cosine-weighted directions ω_s (pdf cos/π) per vertex;
//                   T_k = (ρ/N) Σ_s V(ω_s) Y_k(ω_s)   [= (ρ/π)·(π/N)·Σ V Y_k cos / cos].
//   interreflected  T = D + diag(ρ) H T, D the shadowed transfer and H the gather matrix of
//                   bake/interreflection_solver.h (derivation in transfer_baker.cpp). The fixed
//                   recipe with the albedo folded stores H per hit ray (bake/compact_gather.h: 8
//                   bytes a hit, barycentrics quantised to 16 bits, unknowns in Morton order) and
//                   solves by Neumann bounces to a max-norm error bound of bounce_tolerance·‖D‖
//                   (BiCGSTAB finishes stiff systems); BakeOptions::dense_gather and the other
//                   bakes use merged CSR entries and BiCGSTAB.
// Memory: the large buffers (coefficients, visibility sums, gather, solver blocks) are charged
// to a prt::MemoryBudget of BakeOptions::memory_limit before they are allocated; the gather block
// by block as the sampling pass fills it. A bake over the limit throws MemoryBudgetExceeded
// (one line) before the buffer that would exceed it exists. docs/BENCHMARKS.md has bytes per
// vertex.
// Ambient occlusion k_A = (1/N) Σ_s V(ω_s): the cosine-weighted visible fraction. Bent normal:
// the normalised mean of the visible sample directions (cosine-weighted by the sampling); when
// no sample is visible it falls back to the vertex normal.
// Obscurance (BakeOptions::obscurance enabled, bake/obscurance_falloff.h): the AO section holds
// W = (1/N) Σ_s ρ(d_s) instead, d_s the distance to the sample's first hit (∞ when it escapes),
// and the bent normal is the normalised Σ_s ρ(d_s) ω_s; the transfer is unchanged. Fixed recipe
// only (BakeError with adaptive sampling).
// Channels: 1 when every vertex albedo is grey (r = g = b), else 3 (RGB); with the albedo kept
// apart, 1 for unshadowed and shadowed transfer, and for interreflected 1 when every albedo and
// texture is grey, else 3. Albedo must lie in
// [0, 1) in every channel; otherwise BakeError names the primitive.
// Sampling (bake/sampling.h): Owen-scrambled Sobol' directions seeded by (seed, vertex), with
// the sample count rounded up to a multiple of 16; vertices run in parallel, each computed
// independently, and the solver reduces in a fixed order, so output is bit-identical for any
// thread count.
//
// Adaptive sampling (BakeOptions::adaptive, used by `prt bake --auto`,
// bake/adaptive/adaptive_baker.h):
//   - vertices marked kAnalyticVertex get the unshadowed transfer with no rays (the caller has
//     proved their hemisphere unoccluded, bake/adaptive/scene_analysis.h); kSkipVertex leaves zeros
//     (a pilot bake of a vertex subset);
//   - sampled vertices use the analytic unshadowed transfer U as a control variate,
//       S_k = U_k − (1/N) Σ_s (1 − V(ω_s)) Y_k(ω_s),
//     unbiased like the plain estimator (E[(1/N) Σ Y_k] = U_k under pdf cos/π), and exact where no
//     sample is occluded;
//   - cap sampling (AdaptiveSampling::cap_sampling): a vertex whose blockable directions fit in
//     a few small cones (bake/adaptive/occluder_caps.h) draws its directions inside them with
//     weights w_s (bake/adaptive/cap_sampling.h) and its estimator becomes U_k − (1/N) Σ_s w_s(1 −
//     V)Y_k (w = 1 for hemisphere sampling); rays below its horizon are not cast. AO and the bent
//     normal of such a vertex use 1 and (2/3)·n (their unoccluded values) as control variates too;
//   - sample counts: x_s = w_s·(1 − V(ω_s))·L(ω_s), L the lighting's luminance (up to the
//     transfer's order) in direction ω_s over its mean (1 without lighting). Every sampled
//     vertex first takes min_samples samples (capped vertices min_cap_samples); then rounds of
//     Neyman allocation with costs (bake/adaptive/sample_allocation.h: n_v ∝ a_v/√c_v, c_v the cost
//     of a sample: its ray, 3× for one that hits) move every vertex toward its target at
//     max_samples, growing it at most 4× per round, until the scene's relative RMS sampling error
//     is predicted ≤ rms_error. The prediction is Σ_v a_v²/n_v over Σ_v B_v², a_v = c·ρ̄_v·σ_v (ρ̄:
//     luminance albedo; σ_v²: the successive-difference variance of x over the point pairs (2i, 2i
//     + 1), which share elementary intervals of the scrambled Sobol' net, floored at the Jeffreys
//     (w_max)²·p(1 − p) of its occluded count) and B_v the direct exit radiance plus the first
//     bounce read from the phase-1 rows of H (a lower bound: the budget stays conservative). c is
//     measured by audit vertices: every 8th sampled vertex draws from two independently scrambled
//     sequences in alternate packets (counts multiples of 32), and the spread of the two means is
//     an unbiased estimate of its actual error; c is measured per class (hemisphere, caps) when a
//     class has 64 audits (qmc_calibration, _caps). The other vertices use the fixed recipe's
//     single sequence. Hits are gathered into H in every round; vertex_standard_error is
//     c·σ_v/√n_v. The allocation reads every vertex in a fixed order: thread-count independent;
//   - the interreflection solve is skipped when H is empty or every albedo is zero; otherwise
//     Jacobi bounces stop when a bounce adds less than bounce_tolerance × max|D| (BiCGSTAB takes
//     over after 200 bounces); the stored kind is the simplest that is exact (unshadowed when
//     every vertex was analytic, shadowed when no sample hit a front face).
// With adaptive.enabled = false the bake is exactly the fixed recipe above (bit-identical).
// References: [2], [10], [15], [16] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bake/adaptive/triangle_hierarchy.h"
#include "bake/obscurance_falloff.h"
#include "prt/formats/transfer_data.h"
#include "scene/scene.h"
#include "sh/constants.h"

namespace prt::scene {
class RayCaster;
}  // namespace prt::scene

namespace prt::bake {

class ProgressSink;

// Thrown for invalid scenes or options; one line "PATH: problem".
struct BakeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline constexpr int kMaxBakeOrder = 32;         // bands 0..31 (1024 coefficients)
inline constexpr int kMaxBakeSamples = 1 << 20;  // per vertex

// Per-vertex treatment under adaptive sampling (AdaptiveSampling::vertex_mode).
inline constexpr uint8_t kSampleVertex = 0;    // cast rays
inline constexpr uint8_t kAnalyticVertex = 1;  // provably unoccluded: unshadowed transfer, no rays
inline constexpr uint8_t kSkipVertex = 2;      // not baked (zeros)

struct AdaptiveSampling {
  bool enabled = false;
  std::vector<uint8_t> vertex_mode;  // one per vertex, or empty (= every vertex sampled)
  int min_samples = 64;              // rounded up to a multiple of 32 (two replicas)
  int max_samples = 1024;
  double rms_error = 0.01;  // relative RMS sampling error of the exit radiance over the scene
  // Luminance SH coefficients of the lighting's radiance (any order ≥ 1; empty = uniform sky).
  std::vector<double> lighting;
  int lighting_order = 0;
  double bounce_tolerance = 0.0025;  // a bounce adding < this × max|D| is the last
  // Cap sampling (bake/adaptive/occluder_caps.h, bake/adaptive/cap_sampling.h): a sampled vertex
  // whose blockable directions fit in ≤ max_caps cones of total solid angle ≤ max_cap_solid_angle
  // draws its rays inside them only (w ≤ Ω/π ≤ ½ of the hemisphere estimator's weight) and starts
  // at min_cap_samples; one whose caps all lie below its horizon gets the analytic transfer.
  bool cap_sampling = true;
  int max_caps = 8;
  double max_cap_solid_angle = sh::kHalfPi;  // π/2 sr
  int min_cap_samples = 16;  // rounded up to a multiple of 16 (of 32 on audit vertices)
  // The scene's triangle hierarchy when the caller has one (built here when null).
  std::shared_ptr<const TriangleHierarchy> hierarchy;
  // A ray caster over this scene's geometry (same positions, normals and triangles; the albedo
  // may differ) when the caller has one (built here when null).
  std::shared_ptr<const scene::RayCaster> caster;
  // Shadowed or unshadowed only: TransferData::coefficients holds rows for the vertices that are
  // not kSkipVertex, in vertex order, instead of one per vertex (the file writer needs the
  // full layout; this is for in-memory callers such as the --auto pilot).
  bool compact_output = false;
};

struct BakeOptions {
  prt::TransferKind kind = prt::TransferKind::Shadowed;
  int order = 3;      // SH order n (n² coefficients), 1 .. kMaxBakeOrder
  int samples = 256;  // per vertex, rounded up to a multiple of 16
  int bounces = -1;   // interreflected: ≥ 0 exact Jacobi bounces, −1 until converged
  double bounce_tolerance = 1e-4;  // relative residual target of the Krylov solve
  int max_solver_iterations = 2000;
  uint64_t seed = 1;
  int threads = 0;            // 0 = all hardware threads
  uint64_t memory_limit = 0;  // bytes the bake may hold (prt/core/memory_budget.h); 0: none
  bool ao = false;
  bool bent_normals = false;
  ObscuranceOptions obscurance;  // distance > 0: AO and bent normals as obscurance (above)
  prt::Precision precision = prt::Precision::F32;
  // Interreflected through the compact gather: the bounce the gather reads held in binary16 (half
  // the bytes of its scattered reads; interreflection_solver.h solve_by_bounces). BakeError on
  // any other path.
  prt::Precision bounce_precision = prt::Precision::F32;
  AdaptiveSampling adaptive;  // off by default
  // Keep the albedo apart (above) although the scene is not textured (textured scenes always do).
  bool keep_albedo_apart = false;
  // Interreflected, fixed recipe, albedo folded: the reference path (H as merged CSR entries,
  // Jacobi warm-up + BiCGSTAB, interreflection_solver.h) instead of the compact gather with
  // Neumann bounces (compact_gather.h, solve_by_bounces). Adaptive bakes and bakes with the albedo
  // kept apart always take the reference path.
  bool dense_gather = false;
  // Interreflected, not adaptive: the direct term D of T = D + diag(ρ) H T is the caller's
  // instead of ρ_c·S. Called once after the sampling pass with S (V × K doubles, (1/N) Σ V Y_k,
  // no albedo) and returns V × 3 × K doubles; the bake then has 3 channels. The subsurface bake
  // uses it (bake/subsurface/subsurface_baker.h).
  std::function<std::vector<double>(const std::vector<double>& s)> direct_override;
};

struct BakeStatistics {
  uint64_t vertices = 0;
  uint64_t triangles = 0;
  uint64_t rays = 0;           // rays cast
  int samples_per_vertex = 0;  // after rounding
  double seconds_total = 0;    // wall time of bake_transfer
  double seconds_rays = 0;     // the per-vertex sampling pass (rays + SH accumulation)
  double seconds_solve = 0;    // interreflection solve
  double seconds_bvh = 0;      // building the BVH (part of seconds_rays)
  // Process CPU seconds (every thread, std::clock) of the same phases: the BVH and the gather's
  // row order and triangle table (both part of cpu_seconds_rays), the sampling pass, the solve.
  double cpu_seconds_bvh = 0, cpu_seconds_gather_setup = 0, cpu_seconds_rays = 0;
  double cpu_seconds_solve = 0, cpu_seconds_total = 0;
  int jacobi_bounces = 0;      // per channel
  int solver_iterations = 0;   // BiCGSTAB iterations, summed over channels
  double solver_residual = 0;  // max over channels
  bool solver_converged = true;
  std::vector<double> bounce_energy;  // per Jacobi bounce, max over channels
  uint64_t back_face_hits = 0;        // interreflected: rays that hit a back face (occlude only)
  uint64_t matrix_entries = 0;        // stored entries of H (compact gather: hits)
  uint64_t matrix_bytes = 0;
  uint64_t skipped_triangles = 0;  // degenerate triangles the loader removed
  uint64_t bvh_bytes = 0;          // Embree's peak memory
  uint64_t budget_peak_bytes = 0;  // the largest total charged to the memory budget
  bool compact_gather = false;     // the interreflection used the compact gather
  // Adaptive sampling only:
  std::vector<uint32_t> vertex_samples;      // rays cast per vertex (0: analytic or skipped)
  std::vector<float> vertex_standard_error;  // calibrated SE of the mean of x (see above)
  bool allocation_budget_met = true;         // false: max_samples everywhere was not enough
  double qmc_calibration = 1.0;       // c: audit-measured error / i.i.d. error, at the final counts
  double qmc_calibration_caps = 1.0;  // the same for cap-sampled vertices (their own audits)
  uint64_t cap_vertices = 0;          // sampled inside their occluder caps
  uint64_t cap_open_vertices = 0;     // every cap below the horizon: analytic, no rays
  double seconds_caps = 0.0;          // finding the caps
  int allocation_rounds = 0;          // rounds of allocation after the first min_samples
  uint64_t analytic_vertices = 0;     // unshadowed transfer without rays
  uint64_t empty_gather_rows = 0;     // sampled vertices that saw no other surface
  bool interreflection_solved = false;  // false: skipped (H empty or albedo zero)
  prt::TransferKind stored_kind = prt::TransferKind::Unshadowed;

  double mrays_per_second() const {
    return seconds_rays > 0 ? static_cast<double>(rays) / seconds_rays * 1e-6 : 0.0;
  }
};

struct BakeResult {
  prt::TransferData data;
  BakeStatistics stats;
};

// Checks the options and the scene's albedo; throws BakeError.
void validate_bake_inputs(const scene::Scene& scene, const BakeOptions& options);

// Bakes transfer for every vertex of `scene`. Throws BakeError (bad input) or
// std::runtime_error (Embree). `progress` may be null.
BakeResult bake_transfer(const scene::Scene& scene, const BakeOptions& options,
                         ProgressSink* progress = nullptr);

// "unshadowed" / "shadowed" / "interreflected" / "haar" (defined by the runtime,
// prt/formats/transfer_data.h).
using prt::transfer_kind_name;

}  // namespace prt::bake
