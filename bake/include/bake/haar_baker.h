// bake/haar_baker.h — per-vertex all-frequency transfer on a cube map, compressed in the Haar
// wavelet basis (Ng, Ramamoorthi & Hanrahan, "All-Frequency Shadows Using Non-linear Wavelet
// Lighting Approximation", SIGGRAPH 2003, Sec. 4–5).
//
// Conventions: cube map of prt/haar/cube_map.h (faces +X −X +Y −Y +Z −Z, N×N, glTF frame,
// +Y up); wavelet indices and basis of prt/haar/transform.h; sparse storage of
// prt/haar/transfer.h. Exit radiance B_v,c = Σ_t T_v,t,c · L_t,c with L the cube map's
// radiance, so T includes albedo/π (albedo_folded = true) and the texel solid angle:
//   shadowed   T_v,t = (ρ_v/π) Σ_s V(ω_s) · max(n·ω_s, 0) · Ω_s
//   unshadowed the same without V (no rays),
// over the S×S sub-texels s of texel t (S = supersample; S = 1: the texel centre and the exact
// texel solid angle; S > 1: one jittered direction inside each sub-rectangle, weighted by the
// exact solid angle of the sub-rectangle — the same jitter for every vertex, from the seed, so
// the bake is deterministic and packets stay coherent). Only directions above the vertex's
// horizon are traced, 16 to a packet (RayCaster::occluded_packet, rays sharing the origin).
//
//   interreflected  T = D + diag(ρ) H T (Sloan, Kautz & Snyder 2002, §6; solver of
//   bake/interreflection_solver.h), with D the shadowed transfer above. H is gathered from the
//   same texel rays (intersect_packet): a ray that hits a front face adds b_i · cos·Ω/π to
//   H_{v, vertex i} (the quadrature weight of the texel, the estimator (1/π)∫ cos · b_j dω).
//   Because H acts on each column independently and the Haar transform W is orthonormal, the
//   solve runs on the wavelet coefficients: T̂ = D̂ + diag(ρ) H T̂ (T̂ = T·Wᵀ), in chunks of
//   columns, before the per-vertex truncation. Trade-off: all 6N² columns are solved (a
//   truncated column set would lose the energy the bounces carry into coefficients D̂ lacks),
//   so D̂ is held dense: V·6N²·C floats (N = 32: 24.6 KB per vertex and channel). The bake
//   refuses when that exceeds kMaxHaarInterreflectionBytes; use a smaller --cube (16: 6 KB).
//   The solve costs (6N²/64) BiCGSTAB runs of 64 columns each per channel.
//
// Textured scenes keep the albedo apart as the SH baker does (bake/transfer_baker.h): T holds
// 1/π instead of ρ_v/π (albedo_folded = false), and the interreflected H holds the albedo of each
// hit point (the texture, bilinear) in one block of V columns per channel, solved per channel
// without the receiver's albedo.
//
// Then each vertex is truncated (relative threshold / top M) and quantised (8/16 bit with a
// per-vertex step), per prt/haar/transfer.h. Vertices are computed independently in parallel
// and added in order, so the output is identical for any thread count.
// References: [4], [16] of docs/REFERENCES.md.
#pragma once

#include <cstdint>

#include "prt/formats/haar_transfer_file.h"
#include "prt/formats/transfer_data.h"
#include "prt/haar/transfer.h"
#include "scene/scene.h"

namespace prt::bake {

class ProgressSink;

inline constexpr int kMaxHaarSupersample = 8;
inline constexpr uint64_t kMaxHaarInterreflectionBytes = uint64_t{3} << 30;  // dense D̂

struct HaarBakeOptions {
  // Unshadowed, Shadowed or Interreflected: the light transport the Haar vectors hold.
  prt::TransferKind transport = prt::TransferKind::Shadowed;
  int cube_size = 32;                    // N, a power of two in 8..128
  int supersample = 1;                   // S: S×S directions per texel, 1..kMaxHaarSupersample
  prt::HaarTransferOptions compression;  // threshold / top M / quantisation
  int bounces = -1;                      // interreflected: as BakeOptions::bounces
  double bounce_tolerance = 1e-4;
  int max_solver_iterations = 2000;
  uint64_t seed = 1;          // jitter of the supersampling
  int threads = 0;            // 0 = all hardware threads
  uint64_t memory_limit = 0;  // bytes the bake may hold (prt/core/memory_budget.h); 0: none
};

struct HaarBakeStatistics {
  uint64_t vertices = 0, triangles = 0;
  uint64_t rays = 0;
  double seconds_total = 0, seconds_rays = 0, seconds_solve = 0;
  int solver_iterations = 0;   // summed over column chunks and channels
  double solver_residual = 0;  // max
  bool solver_converged = true;
  uint64_t stored_bytes = 0;  // HaarTransfer::stored_bytes()
  uint64_t dense_bytes = 0;   // HaarTransfer::dense_bytes()
  uint64_t entries = 0;       // kept (vertex, wavelet) pairs
  double mrays_per_second() const {
    return seconds_rays > 0 ? static_cast<double>(rays) / seconds_rays * 1e-6 : 0.0;
  }
};

struct HaarBakeResult {
  prt::HaarTransferFile file;  // ready for prt::write_haar_transfer_file
  HaarBakeStatistics stats;
};

// Bakes Haar transfer for every vertex. Throws BakeError (bad options or scene, one line
// "PATH: problem") or std::runtime_error (Embree). `progress` may be null.
HaarBakeResult bake_haar_transfer(const scene::Scene& scene, const HaarBakeOptions& options,
                                  ProgressSink* progress = nullptr);

}  // namespace prt::bake
