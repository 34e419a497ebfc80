// bake/transfer_baker.h — per-vertex SH transfer vectors for diffuse PRT.
//
// Conventions: SH basis of sh/basis.h (real, orthonormal, no Condon–Shortley phase, index
// k = l(l+1)+m, functions of the scene-frame direction, scene frame = glTF's, +Y up). The
// output T_p satisfies B_p,c = Σ_k T_p,c,k · L_c,k for lighting L = SH coefficients of
// distant *radiance*; T includes albedo/π (albedo_folded = true).
//
// Kinds (Sloan, Kautz & Snyder, SIGGRAPH 2002, §5–6):
//   unshadowed      T = (ρ/π) · rotate_zonal(clamped-cosine zonal coefficients, n): analytic.
//   shadowed        N cosine-weighted directions ω_s (pdf cos/π) per vertex;
//                   T_k = (ρ/N) Σ_s V(ω_s) Y_k(ω_s)   [= (ρ/π)·(π/N)·Σ V Y_k cos / cos].
//   interreflected  T = D + diag(ρ) H T, D the shadowed transfer and H the gather matrix of
//                   bake/interreflection_solver.h (derivation in transfer_baker.cpp).
// Ambient occlusion k_A = (1/N) Σ_s V(ω_s): the cosine-weighted visible fraction. Bent normal:
// the normalised mean of the visible sample directions (cosine-weighted by the sampling); when
// no sample is visible it falls back to the vertex normal.
// Channels: 1 when every vertex albedo is grey (r = g = b), else 3 (RGB). Albedo must lie in
// [0, 1) in every channel; otherwise BakeError names the primitive.
// Sampling (bake/sampling.h): Owen-scrambled Sobol' directions seeded by (seed, vertex), with
// the sample count rounded up to a multiple of 16; vertices run in parallel, each computed
// independently, and the solver reduces in a fixed order, so output is bit-identical for any
// thread count.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "bake/scene.h"
#include "prt/transfer_data.h"

namespace prt::bake {

class ProgressSink;

// Thrown for invalid scenes or options; one line "PATH: problem".
struct BakeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline constexpr int kMaxBakeOrder = 32;         // bands 0..31 (1024 coefficients)
inline constexpr int kMaxBakeSamples = 1 << 20;  // per vertex

struct BakeOptions {
  prt::TransferKind kind = prt::TransferKind::Shadowed;
  int order = 3;      // SH order n (n² coefficients), 1 .. kMaxBakeOrder
  int samples = 256;  // per vertex, rounded up to a multiple of 16
  int bounces = -1;   // interreflected: ≥ 0 exact Jacobi bounces, −1 until converged
  double bounce_tolerance = 1e-4;  // relative residual target of the Krylov solve
  int max_solver_iterations = 2000;
  uint64_t seed = 1;
  int threads = 0;  // 0 = all hardware threads
  bool ao = false;
  bool bent_normals = false;
  prt::Precision precision = prt::Precision::F32;
};

struct BakeStatistics {
  uint64_t vertices = 0;
  uint64_t triangles = 0;
  uint64_t rays = 0;           // rays cast
  int samples_per_vertex = 0;  // after rounding
  double seconds_total = 0;    // wall time of bake_transfer
  double seconds_rays = 0;     // the per-vertex sampling pass (rays + SH accumulation)
  double seconds_solve = 0;    // interreflection solve
  int jacobi_bounces = 0;      // per channel
  int solver_iterations = 0;   // BiCGSTAB iterations, summed over channels
  double solver_residual = 0;  // max over channels
  bool solver_converged = true;
  std::vector<double> bounce_energy;  // per Jacobi bounce, max over channels
  uint64_t back_face_hits = 0;        // interreflected: rays that hit a back face (occlude only)
  uint64_t matrix_entries = 0;        // stored entries of H
  uint64_t matrix_bytes = 0;
  uint64_t skipped_triangles = 0;  // degenerate triangles the loader removed
  uint64_t bvh_bytes = 0;          // Embree's peak memory

  double mrays_per_second() const {
    return seconds_rays > 0 ? static_cast<double>(rays) / seconds_rays * 1e-6 : 0.0;
  }
};

struct BakeResult {
  prt::TransferData data;
  BakeStatistics stats;
};

// Checks the options and the scene's albedo; throws BakeError.
void validate_bake_inputs(const Scene& scene, const BakeOptions& options);

// Bakes transfer for every vertex of `scene`. Throws BakeError (bad input) or
// std::runtime_error (Embree). `progress` may be null.
BakeResult bake_transfer(const Scene& scene, const BakeOptions& options,
                         ProgressSink* progress = nullptr);

// "unshadowed" / "shadowed" / "interreflected" / "haar".
const char* transfer_kind_name(prt::TransferKind kind);

}  // namespace prt::bake
