// prt/brdf/gltf_pbr.h — glTF 2.0's metallic-roughness BRDF exactly as the specification's
// Appendix B writes it [112].
//
// With h = normalize(ωi + ωo), D the GGX distribution (α_x, α_y:
// prt/brdf/microfacet_distribution.h), V = G2 / (4 cos θi cos θo) with G2 Smith's height-correlated
// masking-shadowing, and the Schlick weight s = (1 − ωo·h)⁵:
//   specular_brdf   = D · V
//   diffuse_brdf    = base / π
//   dielectric_brdf = fresnel_mix = (1 − F_d) · diffuse_brdf + F_d · specular_brdf,
//                     F_d = F0_d + (1 − F0_d) s      (F0_d = 0.04 for ior 1.5)
//   metal_brdf      = conductor_fresnel = F_m · specular_brdf,
//                     F_m = base + (1 − base) s
//   f               = (1 − metallic) · dielectric_brdf + metallic · metal_brdf
// per linear-RGB channel. F0_d is an RGB value so that KHR_materials_ior and
// KHR_materials_specular can set it (the loader's business); f90 is 1. Frame and conventions:
// prt/brdf/brdf.h. Reciprocal (ωo·h = ωi·h). base, F0_d and metallic lie in [0, 1], roughness α
// in [0.001, 1].
// Energy: the (1 − F_d) weight is evaluated at ωo·h, not at the directional albedo of the
// specular layer, so the sum is not exactly bounded by 1; docs/GLOSSY.md measures it.
// Sampling: cosine-weighted for the diffuse layer, GGX visible normals (prt/brdf/microfacet.h)
// for the specular one, chosen with u1 by the channel means of (1 − metallic)·base and of the
// normal-incidence specular reflectance (1 − metallic)·F0_d + metallic·base; the pdf is the
// mixture. Compiles as C++17. References: [112] of docs/REFERENCES.md.
#pragma once

#include "prt/brdf/brdf.h"
#include "prt/brdf/microfacet_distribution.h"
#include "prt/core/status.h"

namespace prt::brdf {

struct GltfPbrParams {
  Rgb base_color = grey(1.0);
  double metallic = 1.0;
  double alpha_x = 1.0;  // roughness², along the tangent
  double alpha_y = 1.0;  // across it
  Rgb f0_dielectric = grey(0.04);
};

class GltfPbr final : public Brdf {
 public:
  static Result<GltfPbr> create(const GltfPbrParams& params);

  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, double u1, double u2) const override;
  double pdf(const Vec3& wo, const Vec3& wi) const override;
  bool reciprocal() const override { return true; }

  const GltfPbrParams& params() const { return params_; }

 private:
  explicit GltfPbr(const GltfPbrParams& p);
  double specular_pdf(const Vec3& wo, const Vec3& wi) const;
  GltfPbrParams params_;
  MicrofacetDistribution ggx_;
  double p_diffuse_;
};

}  // namespace prt::brdf
