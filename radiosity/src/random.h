// random.h — the per-patch random streams of the radiosity module and the sampling helpers
// built on them: a stream is a splitmix64-seeded std::mt19937_64 determined by (seed, patch), so
// results do not depend on the thread count.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include <glm/glm.hpp>

#include "radiosity/patches.h"

namespace prt::radiosity::detail {

inline uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// A point uniformly distributed on the patch from two uniforms in [0, 1).
inline glm::dvec3 point_on(const Patch& p, double u1, double u2) {
  const double r = std::sqrt(u1), s = u2;
  return p.corners[0] * (1.0 - r) + p.corners[1] * (r * (1.0 - s)) + p.corners[2] * (r * s);
}

// A direction distributed ∝ cos θ about the unit normal n (Malley's method) from two uniforms.
inline glm::dvec3 cosine_direction(const glm::dvec3& n, double u1, double u2) {
  const double r = std::sqrt(u1), phi = 2.0 * M_PI * u2;
  const glm::dvec3 t = std::abs(n.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  const glm::dvec3 b1 = glm::normalize(glm::cross(t, n)), b2 = glm::cross(n, b1);
  return glm::normalize(b1 * (r * std::cos(phi)) + b2 * (r * std::sin(phi)) +
                        n * std::sqrt(std::max(0.0, 1.0 - u1)));
}

class PatchRandom {
 public:
  PatchRandom(uint64_t seed, uint64_t patch) : engine_(splitmix64(seed ^ splitmix64(patch))) {}
  double uniform() { return std::generate_canonical<double, 53>(engine_); }
  uint32_t word() { return static_cast<uint32_t>(engine_() >> 32); }

  // A point uniformly distributed on the patch.
  glm::dvec3 point_on(const Patch& p) {
    const double u1 = uniform(), u2 = uniform();
    return detail::point_on(p, u1, u2);
  }

  // A direction distributed ∝ cos θ about the unit normal n (Malley's method).
  glm::dvec3 cosine_direction(const glm::dvec3& n) {
    const double u1 = uniform(), u2 = uniform();
    return detail::cosine_direction(n, u1, u2);
  }

 private:
  std::mt19937_64 engine_;
};

}  // namespace prt::radiosity::detail
