// bake/adaptive/cap_sampling.h — Monte Carlo over a union of caps (bake/adaptive/occluder_caps.h)
// instead of the whole cosine-weighted hemisphere.
//
// For a vertex whose blockable directions all lie in caps C_1..C_m, the occluded part of any
// cosine-weighted integral, (1/π) ∫ (1 − V(ω)) f(ω) cos⁺θ dω, is an integral over the union
// only. Directions are drawn from the mixture q(ω) = Σ_j (Ω_j/Ω)(1/Ω_j)[ω ∈ C_j] = k(ω)/Ω
// (Ω_j a cap's solid angle, Ω = Σ_j Ω_j, k(ω) the number of caps holding ω), which is unbiased
// on the union however the caps overlap. A sample's weight is the ratio of the hemisphere's
// pdf cos⁺θ/π to q:
//   w(ω) = cos⁺θ · Ω / (π · k(ω)),   so (1/N) Σ_s w(ω_s)(1 − V(ω_s)) f(ω_s)
// estimates the same quantity as (1/N) Σ_s (1 − V) f under cos/π sampling (w = 1 there).
// Directions below the horizon get w = 0 (no ray need be cast). Since w ≤ Ω/π, the variance is
// at most Ω/π times the hemisphere estimator's second moment: small caps, few rays.
// Points: the cap is chosen by the first coordinate of a 2-D point (its CDF interval, rescaled
// to [0, 1) for reuse), then uniform in the cap: 1 − cos θ = u₀'·(1 − cos α), φ = 2π·u₁.
// Frame: any (the scene's); n is the vertex's unit normal.
#pragma once

#include <glm/glm.hpp>

#include "bake/adaptive/occluder_caps.h"

namespace prt::bake {

struct CapSample {
  glm::dvec3 direction{0.0};  // unit
  double weight = 0.0;        // w(ω) above; 0 below the horizon
};

// Total solid angle Ω of `count` caps.
double total_solid_angle(const DirectionCap* caps, int count);

// The sample for the point u ∈ [0, 1)² (count ≥ 1, total = total_solid_angle(caps, count)).
CapSample sample_cap_union(const DirectionCap* caps, int count, double total, const glm::dvec3& n,
                           const glm::dvec2& u);

// Fills dirs/weights[0 .. count) for points first .. first + count of the vertex's Owen-
// scrambled Sobol' sequence (bake/sampling.h: same seeding as generate_cosine_directions).
void generate_cap_directions(const DirectionCap* caps, int cap_count, const glm::vec3& n,
                             uint64_t seed, uint64_t vertex, uint32_t first, int count,
                             glm::vec3* dirs, double* weights);

}  // namespace prt::bake
