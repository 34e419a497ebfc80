// bake/subsurface/dipole_gather.h — the subsurface sum of the dipole BSSRDF over a surface's
// irradiance samples: for each receiving sample o of a translucent material m,
//
//     X_o,c = Σ_{i ∈ m} w_c(o, i) · S_i,   w_c(o, i) = A_i R_d,c(|x_o − x_i|)  (i ≠ o),
//                                           w_c(o, o) = R_total,c − tail_c(√(A_o/π)),
//
// S_i the sample's transfer vector (K SH coefficients of shadowed irradiance / π, grey), A_i its
// area, R_d,c the dipole profile of channel c (prt/subsurface/dipole.h) in scene units. The
// receiver's own term integrates R_d exactly over a disc of its own area (the closed-form tail),
// because the profile is sharply peaked (z_r = 1/σ_t′, a fraction of a millimetre) compared with
// the sample spacing. Distances are straight lines through space (JMLH 2001), not geodesics:
// a thin part passes light from its back to its front.
// Exit radiance L_o,c = Σ_k X_o,c,k L_k: the normalisation that makes a large flat slab under
// uniform light give L = R_total·E/π is derived in docs/SUBSURFACE.md.
//
// Energy clamp (on by default): with W_c(o) = Σ_i w_c(o, i) (the receiver's response to
// uniform irradiance), X_o,c is scaled by R_total,c/W_c(o) when W_c(o) > R_total,c. On a sphere
// W ≤ R_total exactly (the area within chord r of a point is πr²); on thin parts straight-line
// distances count both faces and W can exceed what the semi-infinite dipole allows.
//
// Two evaluations: the direct O(n²) sum (the slow reference) and the hierarchical one of Jensen
// & Buhler 2002: an octree per material over the samples, each node holding its area A, its
// area-weighted centroid P and Σ A_i S_i; a node is used as one sample when the receiver lies
// outside its bounds and its solid-angle measure A/|x_o − P|² < ε, else its children are opened
// (leaves hold ≤ 8 samples, summed directly). O(n log n) for fixed ε.
// Determinism: every receiver is computed independently in a fixed order; bit-identical for any
// thread count.
// References: Jensen, Marschner, Levoy & Hanrahan 2001; Jensen & Buhler, "A Rapid Hierarchical
// Rendering Technique for Translucent Materials", SIGGRAPH 2002.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "prt/subsurface/dipole.h"

namespace prt::bake {

struct SubsurfaceSamples {
  std::vector<glm::dvec3> positions;  // scene units
  std::vector<double> areas;          // scene units², > 0
  std::vector<int32_t> material;      // index into the materials, −1: not translucent
  std::vector<double> transfer;       // samples × K (S_i), grey
  int K = 1;
};

struct SubsurfaceGatherOptions {
  double epsilon = 0.05;   // solid-angle criterion of the hierarchy (ignored by the reference)
  bool reference = false;  // the direct O(n²) sum
  bool energy_clamp = true;
};

struct SubsurfaceGatherStats {
  uint64_t nodes = 0;             // octree nodes over every material
  uint64_t node_evaluations = 0;  // aggregates used
  uint64_t sample_evaluations = 0;
  uint64_t clamped_receivers = 0;  // receivers scaled by the energy clamp in any channel
};

// X: samples × 3 × K (channel-major within a sample, the .prt layout); zero rows for samples
// with material −1. `materials` are in scene units (prt::subsurface::scale_coefficients).
// Runs in parallel over receivers (TBB, the caller's thread limit).
std::vector<double> gather_subsurface(const SubsurfaceSamples& samples,
                                      const std::vector<subsurface::DipoleMaterial>& materials,
                                      const SubsurfaceGatherOptions& options,
                                      SubsurfaceGatherStats* stats = nullptr);

// The response to uniform irradiance, W_c(o) = Σ_i w_c(o, i) (before the clamp), samples × 3,
// by the same evaluation as gather_subsurface (for tests and diagnostics).
std::vector<double> subsurface_response(const SubsurfaceSamples& samples,
                                        const std::vector<subsurface::DipoleMaterial>& materials,
                                        const SubsurfaceGatherOptions& options);

}  // namespace prt::bake
