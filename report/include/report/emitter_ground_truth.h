// report/emitter_ground_truth.h — an independent reference for scenes lit by their own emitters:
// a path tracer for Lambertian scenes with emissive triangles, giving the area-averaged exit
// radiance of each patch (scene triangle) — the quantity L_i of the radiosity equation
// (radiosity/solver.h) — with its standard error. It shares no code with prt_radiosity (no form
// factors, no solver); report/radiosity_report.h measures radiosity solutions against it.
//
// Scene model (the radiosity model of radiosity/patches.h): a triangle is one-sided, its front the
// side its counter-clockwise winding faces (geometric normal; vertex normals are not used); a
// front face emits ScenePrimitive::emission (exit radiance, Lambertian) and reflects with albedo
// ρ_t = the mean of its corners' Scene::albedo; a back face absorbs everything (occludes, emits and
// reflects nothing). Nothing lies outside the scene (rays that leave it carry no light).
// Frame and units: the Scene's; radiance in the units of the emission.
//
// Estimator, per sample of patch t: a point x uniform on t (area measure), then
//   L_t(x) = E_t + ρ_t/π ∫_H L_in(x, ω) cos θ dω,
// E_t added exactly, the integral by a path from x (Veach & Guibas 1995, [13] of
// docs/REFERENCES.md), at every path vertex:
//   * next-event estimation: an emitting triangle e drawn with probability P_e ∝ A_e · Y(E_e)
//     (Y = Rec. 709 luminance, floored at 1e-3 of the channel sum so coloured emitters count),
//     then a point y uniform on it; its solid-angle pdf is P_e / A_e · |x − y|² / cos θ_y; a
//     shadow ray tests the segment; y's front must face x;
//   * a cosine-distributed direction (pdf cos θ/π) traced to its closest hit: a front face
//     that emits adds its emission; the path continues from a front hit (throughput × ρ_hit) and
//     ends at a back face or an escape;
//   * the two estimates of emitted light are combined by the power heuristic (β = 2).
// Path length: Russian roulette from the third path vertex on (survival = the hit's largest
// albedo channel, clamped to [0.05, 0.99]; the throughput is divided by it, so no bias), and a
// hard cap of `max_bounces` reflections after x, whose truncation is the only bias: at most
// ρ_max^(cap+1)/(1 − ρ_max) of L relative (ρ_max = 0.99 clamps survival; for the Cornell box's
// ρ ≤ 0.73 walls and the default cap 256 it is below 1e-30; docs/RADIOSITY.md measures it).
// Accumulation in double. Random numbers of sample s of patch t come from hash(seed, t, s) only,
// so the result is bit-identical for any thread count (TBB, parallel over patches).
// Standard error: every sample is an independent estimate of L_t (RGB); SE_t,c = sample standard
// deviation / √N. Summary: the area-weighted relative RMS standard error over the integrated
// patches that do not emit,
//     s = √(Σ_t A_t Σ_c SE_t,c²) / √(Σ_t A_t Σ_c L_t,c²).
// Errors: std::invalid_argument "LABEL: problem" for an empty scene, albedo outside [0, 1],
// negative or non-finite emission, a bad option or a patch index out of range.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::report {

struct EmitterGroundTruthOptions {
  int samples = 1024;     // per patch (or per point)
  int max_bounces = 256;  // reflections after the first point (0: direct light only)
  uint64_t seed = 1;
  int threads = 0;  // 0 = all hardware threads
  // Only these triangles are integrated (empty: all); the others keep radiance and SE 0.
  std::vector<uint32_t> patches;
};

struct EmitterGroundTruthResult {
  std::vector<glm::dvec3> radiance;        // per triangle: area-averaged exit radiance L_t
  std::vector<glm::dvec3> standard_error;  // per triangle, per channel
  std::vector<uint32_t> patches;           // the triangles integrated, ascending
  int samples = 0;                         // per patch
  double relative_rms_se = 0;              // s of the header (non-emitting patches)
  uint64_t rays = 0;                       // shadow + closest-hit rays
  double seconds = 0;                      // wall time
};

// Area-averaged exit radiance of the scene's patches (see header).
EmitterGroundTruthResult compute_emitter_ground_truth(const scene::Scene& scene,
                                                      const EmitterGroundTruthOptions& options);

// The reflected exit radiance ρ/π ∫ L_in cos θ dω of a free receiving point x with unit normal n
// and albedo rho (the point is not part of the scene: nothing of it occludes), by the same
// estimator: the mean over options.samples paths, and its standard error in *standard_error
// when not null. With rho = 1 and one emitter of emission E in view this is E · F(x → emitter).
glm::dvec3 point_reflected_radiance(const scene::Scene& scene, const glm::dvec3& x,
                                    const glm::dvec3& n, const glm::dvec3& rho,
                                    const EmitterGroundTruthOptions& options,
                                    glm::dvec3* standard_error = nullptr);

}  // namespace prt::report
