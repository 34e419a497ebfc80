// prt/brdf/microfacet.h — the Torrance–Sparrow / Cook–Torrance microfacet specular BRDF.
//
//   f(ωi, ωo) = D(h) G2(ωi, ωo) F(ωi·h) / (4 cos θi cos θo),   h = normalize(ωi + ωo)
// with D the GGX or Beckmann distribution (isotropic or anisotropic, α_x along the tangent,
// α_y along the bitangent), G2 Smith's height-correlated masking-shadowing
// (prt/brdf/microfacet_distribution.h) and F one of:
//   kNone       F = 1 (a perfect-mirror microsurface: the white-furnace configuration),
//   kSchlick    Schlick's approximation with the given RGB reflectance at normal incidence,
//   kDielectric the exact unpolarised dielectric Fresnel with relative index η (grey).
// Frame and conventions: prt/brdf/brdf.h. Single scattering only: light that bounces more
// than once between microfacets is lost, so the albedo falls below 1 at high roughness even
// with F = 1 (measured in docs/BRDF.md). Reciprocal.
// Sampling reflects ωo about a sampled micro-normal. GGX samples the normals visible from ωo
// [42]: pdf(ωi) = G1(ωo) D(h) / (4 cos θo), so f cos θi / pdf = F G2/G1(ωo) ≤ 1. Beckmann (no
// closed-form visible-normal sampler) draws h with density D(h) h_z: pdf(ωi) = D(h) h_z /
// (4 ωo·h), whose weights grow at grazing ωo (docs/BRDF.md compares the two).
// Draws whose ωi falls below the horizon (or whose m faces away from ωo) are discarded (brdf.h);
// their share grows with roughness and with grazing ωo. Roughness must lie in [0.001, 1]. Compiles
// as C++17. References: [28]-[31], [33], [34], [42] of docs/REFERENCES.md.
#pragma once

#include "prt/brdf/brdf.h"
#include "prt/brdf/microfacet_distribution.h"
#include "prt/core/status.h"

namespace prt::brdf {

enum class FresnelMode { kNone, kSchlick, kDielectric };

struct MicrofacetParams {
  NormalDistribution distribution = NormalDistribution::kGgx;
  double alpha_x = 0.5;
  double alpha_y = 0.5;
  FresnelMode fresnel = FresnelMode::kNone;
  Rgb f0 = grey(0.04);  // kSchlick: reflectance at normal incidence, each channel in [0, 1]
  double eta = 1.5;     // kDielectric: relative index of refraction, in [1.0001, 10]
};

class Microfacet final : public Brdf {
 public:
  static Result<Microfacet> create(const MicrofacetParams& params);

  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, double u1, double u2) const override;
  double pdf(const Vec3& wo, const Vec3& wi) const override;
  bool reciprocal() const override { return true; }

  const MicrofacetParams& params() const { return params_; }
  const MicrofacetDistribution& distribution() const { return dist_; }

 private:
  explicit Microfacet(const MicrofacetParams& p);
  Rgb fresnel(double cos_d) const;
  MicrofacetParams params_;
  MicrofacetDistribution dist_;
};

// The density of ωi = reflect(ωo, m) when m has density D(m) m_z: D(h) h_z / (4 |ωo·h|)
// with h = normalize(ωi + ωo); 0 when ωo or ωi is below the horizon.
double reflected_normal_pdf(const MicrofacetDistribution& dist, const Vec3& wo, const Vec3& wi);

}  // namespace prt::brdf
