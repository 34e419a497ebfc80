// bake/src/adaptive/cap_sampling.cpp — directions in a union of caps and their weights
// (cap_sampling.h).
#include "bake/adaptive/cap_sampling.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "bake/sampling.h"
#include "sh/constants.h"

namespace prt::bake {
namespace {

using sh::kPi;

}  // namespace

double total_solid_angle(const DirectionCap* caps, int count) {
  double total = 0.0;
  for (int j = 0; j < count; ++j) total += caps[j].solid_angle();
  return total;
}

namespace {

// A cap with its tangent frame and the upper end of its CDF interval, prepared once per vertex
// and packet rather than per sample.
struct CapFrame {
  glm::dvec3 axis, t, b;
  double one_minus_cos = 0.0, cdf_lo = 0.0, cdf_width = 0.0;
};

int prepare_frames(const DirectionCap* caps, int count, double total, CapFrame* frames) {
  double lo = 0.0;
  for (int j = 0; j < count; ++j) {
    CapFrame& f = frames[j];
    f.axis = caps[j].axis;
    f.one_minus_cos = caps[j].one_minus_cos;
    glm::vec3 tf, bf;
    build_orthonormal_basis(glm::vec3(f.axis), tf, bf);
    // Re-orthonormalised in double around the exact axis (the float basis is approximate).
    f.t = glm::normalize(glm::dvec3(tf) - glm::dot(glm::dvec3(tf), f.axis) * f.axis);
    f.b = glm::cross(f.axis, f.t);
    f.cdf_lo = lo;
    f.cdf_width = caps[j].solid_angle() / total;
    lo += f.cdf_width;
  }
  return count;
}

CapSample sample_frames(const CapFrame* frames, int count, double total, const glm::dvec3& n,
                        const glm::dvec2& u) {
  // The cap whose CDF interval holds u.x; u.x rescaled to [0, 1) inside it.
  int j = 0;
  while (j + 1 < count && u.x >= frames[j].cdf_lo + frames[j].cdf_width) ++j;
  const CapFrame& f = frames[j];
  const double u0 = f.cdf_width > 0.0 ? std::clamp((u.x - f.cdf_lo) / f.cdf_width, 0.0, 1.0) : 0.0;
  // Uniform in the cap: 1 − cos θ = u0·(1 − cos α); sin θ = √((1 − cos θ)(1 + cos θ)).
  const double omc = u0 * f.one_minus_cos;
  const double cos_t = 1.0 - omc;
  const double sin_t = std::sqrt(std::max(0.0, omc * (2.0 - omc)));
  const double phi = 2.0 * kPi * u.y;
  CapSample s;
  s.direction =
      glm::normalize(sin_t * (std::cos(phi) * f.t + std::sin(phi) * f.b) + cos_t * f.axis);
  const double cos_n = glm::dot(s.direction, n);
  if (!(cos_n > 0.0)) return s;  // below the horizon: weight 0
  int holders = 1;               // its own cap, whatever the rounding says
  for (int i = 0; i < count; ++i) {
    if (i == j) continue;
    const glm::dvec3 d = s.direction - frames[i].axis;
    if (0.5 * glm::dot(d, d) <= frames[i].one_minus_cos) ++holders;  // DirectionCap::contains
  }
  s.weight = cos_n * total / (kPi * holders);
  return s;
}

}  // namespace

CapSample sample_cap_union(const DirectionCap* caps, int count, double total, const glm::dvec3& n,
                           const glm::dvec2& u) {
  std::vector<CapFrame> frames(static_cast<std::size_t>(count));
  prepare_frames(caps, count, total, frames.data());
  return sample_frames(frames.data(), count, total, n, u);
}

void generate_cap_directions(const DirectionCap* caps, int cap_count, const glm::vec3& n,
                             uint64_t seed, uint64_t vertex, uint32_t first, int count,
                             glm::vec3* dirs, double* weights) {
  const uint64_t vertex_seed = hash_seed(seed, vertex);
  const double total = total_solid_angle(caps, cap_count);
  const glm::dvec3 nd = glm::normalize(glm::dvec3(n));
  std::vector<CapFrame> heap;
  CapFrame local[16];
  CapFrame* frames = local;
  if (cap_count > 16) {
    heap.resize(static_cast<std::size_t>(cap_count));
    frames = heap.data();
  }
  prepare_frames(caps, cap_count, total, frames);
  for (int i = 0; i < count; ++i) {
    const glm::vec2 u = sample_sobol_2d(first + static_cast<uint32_t>(i), vertex_seed);
    const CapSample s = sample_frames(frames, cap_count, total, nd, glm::dvec2(u));
    dirs[i] = glm::vec3(s.direction);
    weights[i] = s.weight;
  }
}

}  // namespace prt::bake
