// Choosing between a diffuse and a glossy lobe with one uniform number, and sampling the diffuse
// lobe (internal header).
#pragma once

#include "numerics/constants.h"
#include "numerics/sampling.h"
#include "prt/brdf/vec3.h"

namespace prt::brdf::detail {

// Probability of sampling the diffuse lobe: proportional to the channel means of the two
// weights (0.5 when both are zero).
inline double diffuse_probability(const Rgb& diffuse, const Rgb& glossy) {
  const double d = channel_mean(diffuse), g = channel_mean(glossy);
  return d + g > 0.0 ? d / (d + g) : 0.5;
}

// Picks a lobe with u and rescales u to [0, 1) within it. Returns true for the diffuse lobe.
inline bool pick_diffuse(double p_diffuse, double& u) {
  if (u < p_diffuse) {
    u = u / p_diffuse;
    return true;
  }
  u = (u - p_diffuse) / (1.0 - p_diffuse);
  if (u >= 1.0) u = numerics::kOneMinusEpsilon;
  return false;
}

// A cosine-weighted direction on the upper hemisphere of the shading frame (pdf cos θ/π):
// numerics::sample_cosine_hemisphere, Malley's method on the concentric disc.
inline Vec3 sample_cosine_direction(double u1, double u2) {
  const numerics::Vec3<double> l = numerics::sample_cosine_hemisphere<double>({u1, u2});
  return {l.x, l.y, l.z};
}

}  // namespace prt::brdf::detail
