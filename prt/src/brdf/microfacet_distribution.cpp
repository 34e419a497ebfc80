// GGX and Beckmann microfacet distributions.
#include "prt/brdf/microfacet_distribution.h"
#include "sh/constants.h"

#include <cmath>

namespace prt::brdf {

namespace {
using sh::kPi;
}

const char* distribution_name(NormalDistribution d) {
  return d == NormalDistribution::kGgx ? "ggx" : "beckmann";
}

double MicrofacetDistribution::d(const Vec3& m) const {
  if (m.z <= 0.0) return 0.0;
  const double ex = m.x / alpha_x, ey = m.y / alpha_y;
  const double e = ex * ex + ey * ey;
  const double z2 = m.z * m.z;
  if (type == NormalDistribution::kBeckmann) {
    return std::exp(-e / z2) / (kPi * alpha_x * alpha_y * z2 * z2);
  }
  const double t = e + z2;
  return 1.0 / (kPi * alpha_x * alpha_y * t * t);
}

double MicrofacetDistribution::lambda(const Vec3& w) const {
  const double z2 = w.z * w.z;
  const double num = alpha_x * alpha_x * w.x * w.x + alpha_y * alpha_y * w.y * w.y;
  if (num <= 0.0) return 0.0;  // along the normal: no masking
  if (z2 <= 0.0) return INFINITY;
  const double a2 = num / z2;
  if (type == NormalDistribution::kGgx) return 0.5 * (-1.0 + std::sqrt(1.0 + a2));
  const double nu = 1.0 / std::sqrt(a2);
  return 0.5 * (std::erf(nu) - 1.0) + std::exp(-nu * nu) / (2.0 * nu * std::sqrt(kPi));
}

Vec3 MicrofacetDistribution::sample_normal(double u1, double u2) const {
  // Azimuth: tan φ = (α_y/α_x) tan(2π u2), in the quadrant of 2π u2.
  const double p = 2.0 * kPi * u2;
  double cx = alpha_x * std::cos(p), cy = alpha_y * std::sin(p);
  const double len = std::sqrt(cx * cx + cy * cy);
  cx /= len;
  cy /= len;
  // 1/α(φ)² = cos²φ/α_x² + sin²φ/α_y².
  const double inv_a2 = cx * cx / (alpha_x * alpha_x) + cy * cy / (alpha_y * alpha_y);
  const double tan2 =
      type == NormalDistribution::kGgx ? u1 / ((1.0 - u1) * inv_a2) : -std::log1p(-u1) / inv_a2;
  const double cos_t = 1.0 / std::sqrt(1.0 + tan2);
  const double sin_t = std::sqrt(std::fmax(0.0, 1.0 - cos_t * cos_t));
  return {sin_t * cx, sin_t * cy, cos_t};
}

}  // namespace prt::brdf
