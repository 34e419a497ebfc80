// bake/glossy_transfer_baker.h — per-vertex transfer MATRICES for glossy PRT (Sloan, Kautz &
// Snyder 2002, §6; [2] of docs/REFERENCES.md), stored as prt::GlossyTransferData
// (prt/glossy/transfer.h, file: prt/formats/glossy_transfer_file.h).
//
// Conventions: SH of sh/basis.h, order n, K = n². Row index i: SH of the vertex's LOCAL frame
// (scene/tangent_frames.h: +z the normal, +x the tangent, +y = w · cross(n, t)); column j: SH of
// the GLOBAL scene frame (+Y up). M maps lighting coefficients L (radiance, global) to the
// coefficients L' of the radiance arriving at the vertex, in its local frame.
//
// Domain: the UPPER hemisphere of the vertex (local z > 0) only: L' is the projection of
// V(ω)·L(ω)·[ω above the horizon]. No cosine: the BRDF's cos θ_i is in b at runtime
// (b_i(ω_o) = ∫ y_i f cos⁺θ_i, prt/glossy/transfer.h), and f = 0 below the horizon, so nothing
// below it contributes to exit radiance; leaving it at zero (rather than at whatever a ray into
// the surface sees) keeps L' free of radiance the surface cannot reflect.
//
// Shadowed (bounces = 0):
//     M_p,ij = ∫_{H+} y_i(ω_local) V_p(ω) y_j(ω) dω
//            ≈ (2π/N) Σ_s V_p(ω_s) y_i(ω_s,local) y_j(ω_s),
// ω_s uniform on the upper hemisphere (pdf 1/2π): local z = 1 − u₁, φ = 2π u₂ from the
// Owen-scrambled Sobol' points of bake/sampling.h seeded by (seed, vertex) — the same points
// as the diffuse bake, mapped uniformly instead of cosine-weighted (cosine-weighted sampling of
// an integrand without cosine has weight 1/cos θ and infinite variance). V from the Embree
// caster with the diffuse bake's ray start (RayCaster::vertex_origin, docs/RAY_OFFSETS.md).
// Per vertex the 16 rays of a packet are summed in float (y_local ⊗ y_global, a rank-16
// update), then added to a double accumulator.
//
// Interreflected (bounces ≠ 0): a ray that hits the front of triangle (q₀, q₁, q₂) at
// barycentrics β brings the radiance the hit point sends back along −ω_s,
//     L(−ω_s) = Σ_a β_a · b_{q_a}(−ω_s in q_a's frame)ᵀ · M_{q_a} · L,
// b the SH projection of the hit primitive's BRDF (prt::BrdfProjection with
// GlossyBakeOptions::projection, the runtime's own, prt/glossy/brdf_projection.h); for a Lambert
// hit b = ρ(hit)/π · (clamped-cosine zonal row), ρ(hit) = Scene::albedo_at (the texture when there
// is one), exactly as the diffuse bake's bounce. So M = S + G(M),
//     G(M)_p = (2π/N) Σ_{s hits} y_local,p(ω_s) ⊗ L(−ω_s)-row,
// solved by Jacobi bounces M⁽ᵏ⁺¹⁾ = S + G(M⁽ᵏ⁾) from M⁽⁰⁾ = S: `bounces` of them, or (−1) until
// a bounce changes no entry by more than bounce_tolerance × max|S| (at most kMaxGlossyBounces).
// Back faces occlude but reflect nothing (bake/src/hit_side.h, as the diffuse bake).
// Hits: a front-face hit is kept in 8 bytes (bake/compact_gather.h's CompactHit: the triangle and
// β₁, β₂ quantised to 16 bits, the three weights integers summing to 65535), its sample implied
// by a bit per sample and vertex (N/8 bytes a vertex): 8·hits + N/8 bytes a vertex. A weight
// moves by ≤ 1/131070 (β₀ by ≤ 1/65535), so a hit's radiance row by ≤ 3.1e-5 of the largest
// row of its three vertices, and a bounce's gathered part by ≤ 3.1e-5 of its size.
// Channels: 1 for shadowed transfer (M carries no albedo); interreflected: 3 when some vertex
// albedo or some material is coloured (MERL counts as coloured), else 1.
// Materials: ScenePrimitive::brdf, or Lambert with the primitive's albedo; equal materials are
// stored once.
// Memory (GlossyBakeOptions::memory_limit, prt/core/memory_budget.h): before it allocates them
// the bake charges its large buffers — the frames and geometry (about 100 bytes a vertex); then
// shadowed and streamed to a file, the matrices of the blocks in flight; shadowed in memory,
// every vertex's matrices; interreflected in memory, the matrices of two bounces, the direct
// transfer and the Lambert exit rows; interreflected and streamed, ONE bounce of matrices (the
// one the gather reads at random), the Lambert exit rows and the blocks in flight, the direct
// transfer and the bounce being written going to two unlinked scratch files beside the output
// (4·(C·K² + K²) bytes a vertex of disk) — and the hits, block by block as the ray pass keeps
// them. It stops with MemoryBudgetExceeded (one line) when they would exceed the limit.
// Streamed interreflected, per vertex: 4·C·K² + 4·C·K + 8·hits + N/8 bytes (order 5, C = 3,
// N = 256: 7.8 KB + 8·hits); with bounce_precision F16 the first term is 2·C·K² (4.1 KB + 8·hits)
// and the disk 4·(2·C·K² + K²). docs/GLOSSY.md ("Glossy bakes at scale") gives the figures.
// Determinism: vertices in blocks, each vertex from its own samples and the previous bounce's
// matrices in a fixed order: bit-identical for any thread count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bake/transfer_baker.h"
#include "prt/glossy/brdf_projection.h"
#include "prt/glossy/transfer.h"
#include "scene/scene.h"

namespace prt::bake {

inline constexpr int kMaxGlossyBakeOrder = 10;
inline constexpr int kMaxGlossyBounces = 200;

struct GlossyBakeOptions {
  int order = 5;      // 1 .. kMaxGlossyBakeOrder
  int samples = 256;  // per vertex, rounded up to a multiple of 16
  int bounces = 0;    // 0: shadowed; k > 0: k Jacobi bounces; −1: until converged
  double bounce_tolerance = 1e-4;
  uint64_t seed = 1;
  int threads = 0;            // 0 = all hardware threads
  uint64_t memory_limit = 0;  // bytes the bake may hold (prt/core/memory_budget.h); 0: none
  prt::BrdfProjectionOptions projection;  // b(ω_o) for the bounces (prt/glossy/brdf_projection.h)
  prt::Precision precision = prt::Precision::F32;
  // > 0: every bounce gathers from a CPCA compression (bake/cpca/compressor.h, plain metric) of
  // the previous bounce's matrices, bounce_cpca_clusters × bounce_cpca_vectors, instead of from
  // the matrices themselves: the error of bounces that read compressed transfer, the design
  // for bakes whose matrices do not fit in memory (docs/GLOSSY.md, "Glossy bakes at scale").
  // The output is still S + G(compressed M). This bake holds the reconstruction too (it
  // measures the error, it does not save the memory). 0: off.
  uint32_t bounce_cpca_clusters = 0;
  uint32_t bounce_cpca_vectors = 8;
  // The reference for the compact hits: also keep each hit's barycentrics in float (8 more
  // bytes a hit) and let the bounces read those instead of the 16-bit ones. For tests.
  bool exact_hits = false;
  // F16: the bounce the gather reads is held in binary16 (half the memory of the dominant term;
  // rounding 2⁻¹¹ relative, fed through the bounces: docs/GLOSSY.md gives the measured error).
  // The bounces are still computed, compared and written in float. Streamed bakes only
  // (bake_glossy_transfer_to_file), without bounce_cpca_clusters; BakeError otherwise.
  prt::Precision bounce_precision = prt::Precision::F32;
};

struct GlossyBakeStatistics {
  uint64_t vertices = 0;
  uint64_t triangles = 0;
  uint64_t rays = 0;
  uint64_t hits = 0;            // front-face hits kept for the bounces
  uint64_t back_face_hits = 0;  // occlude only
  int samples_per_vertex = 0;
  int bounces = 0;  // bounces done
  // Interreflected: the last bounce changed no entry by more than bounce_tolerance × max|S|
  // (counted or solved bounces alike); shadowed: true (nothing to solve).
  bool converged = true;
  std::vector<double> bounce_change;  // per bounce: max |ΔM| / max |S|
  double seconds_total = 0;
  double seconds_rays = 0;  // sampling pass: rays + accumulation
  double seconds_projection = 0;
  double seconds_bounces = 0;
  uint64_t gather_bytes = 0;  // interreflected: the hits and sample masks kept for the bounces
  uint64_t peak_charged_bytes = 0;  // the most the bake held at once of what it charged
  uint64_t bounce_cpca_bytes = 0;   // bounce_cpca_clusters > 0: the compressed transfer's payload

  double mrays_per_second() const {
    return seconds_rays > 0 ? static_cast<double>(rays) / seconds_rays * 1e-6 : 0.0;
  }
};

struct GlossyBakeResult {
  prt::GlossyTransferData data;
  GlossyBakeStatistics stats;
};

// The materials of the primitives and each vertex's index into them: scene::vertex_materials
// (scene/vertex_materials.h).
void glossy_scene_materials(const scene::Scene& scene, std::vector<brdf::Material>& materials,
                            std::vector<uint32_t>& material_of_vertex);

// Bakes the glossy transfer of every vertex. Throws BakeError (bad scene or options, a material
// make_brdf refuses, bounces that diverge — a change that is not finite, or that exceeds 2 max|S|
// and the change of the bounce before — a texture a material needs that could not be read:
// ScenePrimitive::brdf_texture_problem) or std::runtime_error (Embree). `progress` may be null.
GlossyBakeResult bake_glossy_transfer(const scene::Scene& scene, const GlossyBakeOptions& options,
                                      ProgressSink* progress = nullptr);

// The same bake written to PATH as it goes (prt/formats/glossy_transfer_writer.h): a shadowed
// bake hands each block of vertices' matrices to the file when it is finished and never holds
// more than the blocks in flight; an interreflected one holds one bounce (the rest in scratch
// files in PATH's directory, removed whatever happens) and writes its last bounce block by block.
// The file is byte for byte write_glossy_transfer_file(PATH, bake_glossy_transfer(...).data)
// (same options, same seed, any thread count). Returns everything but the matrices
// (result.data.matrices is empty). On any error — those of bake_glossy_transfer, a file that
// cannot be written (BakeError, "PATH: problem"), MemoryBudgetExceeded — PATH is left as it was
// and no temporary remains.
GlossyBakeResult bake_glossy_transfer_to_file(const scene::Scene& scene,
                                              const GlossyBakeOptions& options,
                                              const std::string& path,
                                              ProgressSink* progress = nullptr);

}  // namespace prt::bake
