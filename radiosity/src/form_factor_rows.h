// form_factor_rows.h — the pieces of form-factor rows that the full computation and the partial
// update after a move share (radiosity/form_factors.h, radiosity/form_factor_update.h), so that
// an entry or row recomputed by the update is bit-identical to the full computation's.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/form_factors.h"

namespace prt::radiosity::detail {

// The quadrature points of a triangle: its centroid (1 point), or the degree-2 rule with
// barycentrics (2/3, 1/6, 1/6) and their permutations (3 points, equal weights).
std::vector<glm::dvec3> quadrature_points(const Patch& p, int count);

// Sender i of the analytic method: its quadrature points and their ray origins.
class AnalyticSender {
 public:
  AnalyticSender(const std::vector<Patch>& patches, const scene::RayCaster& caster, uint32_t i,
                 int points);
  // F_ij before the row's normalisation (point-to-polygon values times sampled visibility).
  // Not thread-safe (one sender per thread).
  float entry(uint32_t j);

 private:
  const std::vector<Patch>& patches_;
  const scene::RayCaster& caster_;
  uint32_t i_;
  int points_;
  std::vector<glm::dvec3> xs_;
  std::vector<glm::vec3> origins_;
  std::vector<glm::dvec3> polygon_;  // scratch
};

// Rays leaving patch p for the ray method.
inline int rays_of(const Patch& p, const FormFactorOptions& options) {
  const bool emits = p.emission != glm::dvec3(0.0);
  return emits && options.emitter_rays_per_patch > 0 ? options.emitter_rays_per_patch
                                                     : options.rays_per_patch;
}

// Scales an analytic row that sums above 1 to sum to 1 (sums in double).
void normalise_row(float* row, std::size_t n);

// Row i of any method into `row` (n floats, zero on entry).
void row_into(const std::vector<Patch>& patches, const scene::RayCaster& caster, uint32_t i,
              const FormFactorOptions& options, float* row);

}  // namespace prt::radiosity::detail
