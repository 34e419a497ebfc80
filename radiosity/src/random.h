// random.h — the per-patch random streams of the radiosity module and the sampling helpers
// built on them: a stream is a std::mt19937_64 seeded with splitmix64(seed ⊕ splitmix64(patch))
// (numerics/hash.h), so results do not depend on the thread count. The warps are
// numerics/sampling.h's: a uniform point on a triangle and Malley's cosine-weighted direction on
// the concentric disc, about the normal with Duff et al.'s orthonormal basis.
#pragma once

#include <cstdint>
#include <random>

#include <glm/glm.hpp>

#include "numerics/hash.h"
#include "numerics/sampling.h"
#include "radiosity/patches.h"

namespace prt::radiosity::detail {

// A point uniformly distributed on the patch from two uniforms in [0, 1).
inline glm::dvec3 point_on(const Patch& p, double u1, double u2) {
  const numerics::Vec3<double> w = numerics::sample_uniform_triangle<double>({u1, u2});
  return p.corners[0] * w.x + p.corners[1] * w.y + p.corners[2] * w.z;
}

// A direction distributed ∝ cos θ about the unit normal n from two uniforms.
inline glm::dvec3 cosine_direction(const glm::dvec3& n, double u1, double u2) {
  const numerics::Vec3<double> nn{n.x, n.y, n.z};
  numerics::Vec3<double> t, b;
  numerics::build_orthonormal_basis(nn, &t, &b);
  const numerics::Vec3<double> l = numerics::sample_cosine_hemisphere<double>({u1, u2});
  return glm::normalize(glm::dvec3(t.x, t.y, t.z) * l.x + glm::dvec3(b.x, b.y, b.z) * l.y +
                        n * l.z);
}

class PatchRandom {
 public:
  PatchRandom(uint64_t seed, uint64_t patch)
      : engine_(numerics::splitmix64(seed ^ numerics::splitmix64(patch))) {}
  double uniform() { return std::generate_canonical<double, 53>(engine_); }

  // A point uniformly distributed on the patch.
  glm::dvec3 point_on(const Patch& p) {
    const double u1 = uniform(), u2 = uniform();
    return detail::point_on(p, u1, u2);
  }

  // A direction distributed ∝ cos θ about the unit normal n.
  glm::dvec3 cosine_direction(const glm::dvec3& n) {
    const double u1 = uniform(), u2 = uniform();
    return detail::cosine_direction(n, u1, u2);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace prt::radiosity::detail
