// The microfacet specular BRDF.
#include "prt/brdf/microfacet.h"

#include <cmath>

#include "brdf/parameter_check.h"
#include "prt/brdf/fresnel.h"

namespace prt::brdf {

Result<Microfacet> Microfacet::create(const MicrofacetParams& p) {
  Status s = detail::check_roughness("microfacet", "alpha_x", p.alpha_x);
  if (s) s = detail::check_roughness("microfacet", "alpha_y", p.alpha_y);
  if (s && p.fresnel == FresnelMode::kSchlick) s = detail::check_rgb("microfacet", "f0", p.f0);
  if (s && p.fresnel == FresnelMode::kDielectric) {
    s = detail::check_range("microfacet", "eta", p.eta, 1.0001, 10.0);
  }
  if (!s) return s;
  return Microfacet(p);
}

Microfacet::Microfacet(const MicrofacetParams& p)
    : params_(p), dist_{p.distribution, p.alpha_x, p.alpha_y} {}

Rgb Microfacet::fresnel(double cos_d) const {
  switch (params_.fresnel) {
    case FresnelMode::kSchlick:
      return {fresnel_schlick(cos_d, params_.f0.r), fresnel_schlick(cos_d, params_.f0.g),
              fresnel_schlick(cos_d, params_.f0.b)};
    case FresnelMode::kDielectric:
      return grey(fresnel_dielectric(cos_d, params_.eta));
    case FresnelMode::kNone:
      break;
  }
  return grey(1.0);
}

Rgb Microfacet::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0.0 || wo.z <= 0.0) return {};
  const Vec3 h = normalize(wi + wo);
  if (h.z <= 0.0) return {};
  const double v = dist_.d(h) * dist_.g2(wi, wo) / (4.0 * wi.z * wo.z);
  return v * fresnel(dot(wi, h));
}

double reflected_normal_pdf(const MicrofacetDistribution& dist, const Vec3& wo, const Vec3& wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  const Vec3 sum = wi + wo;
  if (dot(sum, sum) <= 1e-24) return 0.0;
  const Vec3 h = normalize(sum);
  const double oh = dot(wo, h);
  if (oh <= 0.0) return 0.0;
  return dist.d(h) * h.z / (4.0 * oh);
}

BrdfSample Microfacet::sample(const Vec3& wo, double u1, double u2) const {
  if (wo.z <= 0.0) return {};
  const bool visible = params_.distribution == NormalDistribution::kGgx;
  const Vec3 m = visible ? dist_.sample_visible_normal(wo, u1, u2) : dist_.sample_normal(u1, u2);
  if (dot(wo, m) <= 0.0) return {};  // a back-facing micro-normal: no sample
  BrdfSample s;
  s.wi = reflect(wo, m);
  if (s.wi.z <= 0.0) return {};  // below the horizon: discarded
  s.pdf = pdf(wo, s.wi);
  s.f = eval(s.wi, wo);
  return s;
}

double Microfacet::pdf(const Vec3& wo, const Vec3& wi) const {
  if (params_.distribution != NormalDistribution::kGgx) return reflected_normal_pdf(dist_, wo, wi);
  // Visible normals: D_ωo(h) / (4 ωo·h) = G1(ωo) D(h) / (4 ωo_z).
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  const Vec3 sum = wi + wo;
  if (dot(sum, sum) <= 1e-24) return 0.0;
  return dist_.g1(wo) * dist_.d(normalize(sum)) / (4.0 * wo.z);
}

}  // namespace prt::brdf
