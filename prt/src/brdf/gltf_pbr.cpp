// glTF 2.0's metallic-roughness BRDF (Appendix B).
#include "prt/brdf/gltf_pbr.h"

#include <cmath>

#include "brdf/lobe_mix.h"
#include "brdf/parameter_check.h"
#include "numerics/constants.h"

namespace prt::brdf {

Result<GltfPbr> GltfPbr::create(const GltfPbrParams& p) {
  Status s = detail::check_rgb("gltf", "base colour", p.base_color);
  if (s) s = detail::check_range("gltf", "metallic", p.metallic, 0.0, 1.0);
  if (s) s = detail::check_roughness("gltf", "alpha_x", p.alpha_x);
  if (s) s = detail::check_roughness("gltf", "alpha_y", p.alpha_y);
  if (s) s = detail::check_rgb("gltf", "dielectric f0", p.f0_dielectric);
  if (!s) return s;
  return GltfPbr(p);
}

GltfPbr::GltfPbr(const GltfPbrParams& p)
    : params_(p), ggx_{NormalDistribution::kGgx, p.alpha_x, p.alpha_y} {
  const double m = p.metallic;
  const Rgb diffuse = (1.0 - m) * p.base_color;
  const Rgb specular = (1.0 - m) * p.f0_dielectric + m * p.base_color;
  p_diffuse_ = detail::diffuse_probability(diffuse, specular);
}

Rgb GltfPbr::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0.0 || wo.z <= 0.0) return {};
  const Vec3 h = normalize(wi + wo);
  const double vh = std::fmax(0.0, dot(wo, h));
  const double s = std::pow(1.0 - vh, 5.0);
  const double specular = h.z > 0.0 ? ggx_.d(h) * ggx_.g2(wi, wo) / (4.0 * wi.z * wo.z) : 0.0;
  const double m = params_.metallic;
  const double base[3] = {params_.base_color.r, params_.base_color.g, params_.base_color.b};
  const double f0[3] = {params_.f0_dielectric.r, params_.f0_dielectric.g, params_.f0_dielectric.b};
  double f[3];
  for (int c = 0; c < 3; ++c) {
    const double fd = f0[c] + (1.0 - f0[c]) * s;
    const double fm = base[c] + (1.0 - base[c]) * s;
    const double dielectric = (1.0 - fd) * base[c] * numerics::kInvPi + fd * specular;
    f[c] = (1.0 - m) * dielectric + m * fm * specular;
  }
  return {f[0], f[1], f[2]};
}

double GltfPbr::specular_pdf(const Vec3& wo, const Vec3& wi) const {
  // Visible normals: G1(ωo) D(h) / (4 ωo_z) (prt/brdf/microfacet.h).
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  const Vec3 sum = wi + wo;
  if (dot(sum, sum) <= 1e-24) return 0.0;
  return ggx_.g1(wo) * ggx_.d(normalize(sum)) / (4.0 * wo.z);
}

double GltfPbr::pdf(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  return p_diffuse_ * wi.z * numerics::kInvPi + (1.0 - p_diffuse_) * specular_pdf(wo, wi);
}

BrdfSample GltfPbr::sample(const Vec3& wo, double u1, double u2) const {
  if (wo.z <= 0.0) return {};
  BrdfSample s;
  if (detail::pick_diffuse(p_diffuse_, u1)) {
    s.wi = detail::sample_cosine_direction(u1, u2);
  } else {
    const Vec3 m = ggx_.sample_visible_normal(wo, u1, u2);
    if (dot(wo, m) <= 0.0) return {};
    s.wi = reflect(wo, m);
  }
  if (s.wi.z <= 0.0) return {};
  s.pdf = pdf(wo, s.wi);
  if (!(s.pdf > 0.0)) return {};
  s.f = eval(s.wi, wo);
  return s;
}

}  // namespace prt::brdf
