// bake/glossy_emitter_gather.h — the incident radiance of a scene's emitters at the vertices of a
// glossy transfer file, in each vertex's local SH frame, gathered from a radiosity solution
// (prt/emitters/glossy_emitter_radiance.h holds the result and shades it).
//
// For vertex p and emitting material e of a per-emitter radiosity responses file (.prte,
// prt/emitters/emitter_responses.h: R_e,q the exit radiance of vertex q when e alone emits unit
// white radiance, emission included):
//     G_e,p,c,i = ∫_{H+(p)} y_i(R_p ω) R_e,c(hit_p(ω)) dω
// over the upper hemisphere of p's local frame (glossy_vertex_frame: the frame the glossy file
// is shaded in), estimated by two sample sets combined with the balance heuristic (Veach 1997):
// - N_h directions uniform on it (p_h = 1/2π) from the Owen-scrambled Sobol' points the glossy
//   bake uses (bake/sampling.h, seeded by (seed, vertex)); a ray that meets the FRONT of
//   triangle (q₀, q₁, q₂) at barycentrics β brings the responses Σ_a β_a R_e,q_a interpolated
//   there; a miss or a back face brings nothing (the environment is the glossy file's part;
//   radiosity surfaces are one-sided);
// - N_a points per emitter uniform by area on its own surface (the triangles whose vertices all
//   lie on it; p_a = r² / (cos θ_l · A_e) in solid angle), visible from p and in front of both.
// The emitter's unit emission, seen directly, is weighted 1 / (N_h p_h + N_a p_a) in both sets;
// everything else a hemisphere ray brings (the reflected light, the emitter's response minus its
// own emission on its surface) 1 / (N_h p_h). Rays leave RayCaster::vertex_origin(p), as in the
// glossy bake. Small lamps, which few hemisphere directions meet, are then seen by every vertex.
// So every bounce the radiosity solve made (diffuse, with the scene's albedos) is in G; light
// that a glossy surface reflects toward another is taken as the radiosity's diffuse estimate of
// it (the .prte treats every surface as Lambert with its albedo).
// emitter_of_vertex: the vertices of the primitives whose material carries an emitter's name
// (primitives without a material name and with a non-zero emission for "<none>", radiosity's
// grouping), so that the emitters' surfaces show their emission.
// Preconditions: `scene`, `glossy` and `responses` hold the same vertices in the same order and
// the same triangles (the caller checks fingerprints; this checks counts and triangles).
// Determinism: each vertex from its own samples, accumulated in double: bit-identical for any
// thread count.
#pragma once

#include <cstdint>

#include "prt/emitters/emitter_responses.h"
#include "prt/emitters/glossy_emitter_radiance.h"
#include "prt/glossy/transfer.h"
#include "scene/scene.h"

namespace prt::bake {

struct GlossyEmitterGatherOptions {
  int samples = 1024;  // hemisphere directions per vertex, rounded up to a multiple of 16; ≤ 2^24
  // Points on each emitter's surface per vertex (rounded up to a multiple of 16; 0: none, the
  // hemisphere directions alone), combined with them by the balance heuristic.
  int emitter_samples = 256;
  uint64_t seed = 1;
  int threads = 0;  // 0 = all hardware threads
};

struct GlossyEmitterGatherStatistics {
  uint64_t rays = 0;
  uint64_t front_hits = 0;  // rays that brought radiosity
  double seconds = 0;
};

// G for every vertex of `glossy` at its order. Throws BakeError (bake/transfer_baker.h) when the
// three do not hold the same mesh, the options are out of range, or a frame is degenerate;
// std::runtime_error from Embree.
prt::GlossyEmitterRadiance gather_glossy_emitters(const scene::Scene& scene,
                                                  const prt::GlossyTransferData& glossy,
                                                  const prt::EmitterResponses& responses,
                                                  const GlossyEmitterGatherOptions& options = {},
                                                  GlossyEmitterGatherStatistics* stats = nullptr);

}  // namespace prt::bake
