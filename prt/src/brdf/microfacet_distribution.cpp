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

Vec3 MicrofacetDistribution::sample_visible_normal(const Vec3& wo, double u1, double u2) const {
  // In the stretched configuration (α = 1) the visible normals are those of a hemisphere seen
  // from v: uniform on its projected disc, which is the unit disc with its far half squashed
  // onto the visible ellipse.
  const Vec3 v = normalize({alpha_x * wo.x, alpha_y * wo.y, wo.z});
  const double len2 = v.x * v.x + v.y * v.y;
  const Vec3 t1 = len2 > 0.0 ? (1.0 / std::sqrt(len2)) * Vec3{-v.y, v.x, 0.0} : Vec3{1.0, 0.0, 0.0};
  const Vec3 t2{v.y * t1.z - v.z * t1.y, v.z * t1.x - v.x * t1.z, v.x * t1.y - v.y * t1.x};
  const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
  const double p1 = r * std::cos(phi);
  const double s = 0.5 * (1.0 + v.z);
  const double p2 = (1.0 - s) * std::sqrt(std::fmax(0.0, 1.0 - p1 * p1)) + s * r * std::sin(phi);
  const double pz = std::sqrt(std::fmax(0.0, 1.0 - p1 * p1 - p2 * p2));
  const Vec3 n = p1 * t1 + p2 * t2 + pz * v;
  // Unstretch.
  return normalize({alpha_x * n.x, alpha_y * n.y, std::fmax(1e-12, n.z)});
}

}  // namespace prt::brdf
